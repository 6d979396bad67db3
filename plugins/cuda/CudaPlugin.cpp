#include "CudaStep.h"

#include "fascia/plugin/Plugin.h"

static void registerAll(fascia::core::Registry& r) {
    // --list shows whether the device step can run here (one cudaGetDeviceCount at load)
    std::string why;
    const int n = fascia::cuda::cudaDevices(why);
    r.add<fascia::cuda::CudaStep>(
        "CudaStep", "runs the whole step on a CUDA GPU (TLED tetrahedra and hexahedra, HEML tetrahedra and its mass-spring mode, groupMaterials, fibre arrays, ViscoelasticProny, FixedConstraint, PrescribedDisplacement, ConstantForce with its load curve, SurfacePressure, gravity, SemiImplicitEuler, CentralDifference); " +
                        std::string(n > 0 ? "available here: " + std::to_string(n) + " device(s), " + why
                                          : "not available here: " + why));
}

FASCIA_PLUGIN("fascia.cuda", "0.1.0", "the explicit step on a CUDA GPU (TLED T4 and H8, HEML T4, float and double), and its CPU emulation", registerAll)
