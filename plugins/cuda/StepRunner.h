#pragma once
/// One device step's data and launches: on a GPU (CudaRunner.cu) or emulated on the CPU
/// (EmulatedRunner.h), both built from the same StepSetup and its StepArraysHost, so the emulation
/// checks the layout, the indexing and the host-side setup the GPU runs.
#include "DeviceLaws.h"
#include "StepSetup.h"

#include <memory>
#include <string>
#include <vector>

namespace fascia::cuda {

class StepRunner {
public:
    virtual ~StepRunner() = default;
    /// Uploads displacements u = x - X and velocities (3 per node, double), and clears the record
    /// of a state that was not finite (a restore, a replay).
    virtual void setState(const std::vector<double>& u, const std::vector<double>& v) = 0;
    /// Downloads them, after every step launched so far, with the reactions of the last node pass
    /// (StepArrays::react, 3 per node).
    virtual void getState(std::vector<double>& u, std::vector<double>& v, std::vector<double>& r) = 0;
    /// CentralDifference's increments u(n) - u(n-1) (StepArrays::du), 3 per node: down and up.
    virtual void getIncrements(std::vector<double>& du) = 0;
    virtual void setIncrements(const std::vector<double>& du) = 0;
    /// The Prony states (StepArrays Y, then hY), as doubles: down and up (checkpoints).
    virtual void getPronyStates(std::vector<double>& Y) = 0;
    virtual void setPronyStates(const std::vector<double>& Y) = 0;
    /// The element kernels over every tetrahedron and every hexahedron, those of each material
    /// group over its elements, then the face kernel over the faces under pressure (launched; the
    /// GPU runs them in order with the rest, and the host does not wait; each advances its Prony
    /// states, StepArrays Y, once).
    virtual void elementPass() = 0;
    /// The coefficients A_i, B_i of the Prony series for the next element passes (TLED eq. (30)),
    /// term by term, the series in order (pronyCoefficients); until the first call the series relax
    /// nothing (A = B = 0). Set when they change (CudaStep: the first step, a change of dt).
    virtual void setRelaxation(const std::vector<double>& A, const std::vector<double>& B) = 0;
    /// The pressures of the SurfacePressure components for the next element passes (faceParams).
    virtual void setPressures(const FaceParams<double>& q) = 0;
    /// Uploads the targets of the next node pass (StepArrays tu, tv; motionTargets), asynchronously.
    virtual void setTargets(const std::vector<double>& tu, const std::vector<double>& tv) = 0;
    /// The node kernel of the setup's integrator over every node (after an element pass).
    virtual void nodePass(const NodeParams<double>& p) = 0;
    /// The internal nodal forces of the last element pass, each node's slots summed (3 per node;
    /// for tests).
    virtual void internalForces(std::vector<double>& f) = 0;
    /// The first step (NodeParams::step) whose node pass left a u or v that is not finite, or -1;
    /// after every step launched so far (one number comes back).
    virtual long firstBadStep() = 0;
    /// Waits until every step launched so far is done.
    virtual void wait() = 0;
    /// What in the arrays on the device (the emulation's "device" copy) does not match the table of
    /// StepLayout.h for s, the runner's setup (checkLayout, StepSetup.h): none, which a runner checks
    /// once it uploaded them (requireLayout).
    virtual std::vector<std::string> layoutErrors(const StepSetup& s) = 0;
};

/// Which scalar the device step computes in.
enum class Precision { Double, Float };

/// f(law, g) for each material group g of s, with its law as the element kernels take it (g.material
/// a materials::Material<Law> of DeviceMaterials); any other material is a located error naming it
/// (buildStepSetup refuses it first). The runners build their element passes, one per group, so.
template <class F>
void forEachGroupLaw(const StepSetup& s, F&& f) {
    for (const StepSetup::Group& g : s.groups)
        selectDeviceLaw(g.material, [&](auto tag, const materials::BaseMaterial* m) {
            using Law = typename decltype(tag)::type;
            if constexpr (std::is_same_v<Law, elements::GenericLaw>)
                m->fail("the material " + m->className() + " is not on the GPU step (it runs " + deviceLawNames() + ")");
            else
                f(elements::lawOf<Law>(m), g);
        });
}

/// The emulated runner of s's material groups (their laws in DeviceMaterials) in precision p.
std::unique_ptr<StepRunner> makeEmulatedRunner(const StepSetup& s, Precision p);

/// The same on the GPU, threads per block `block`. Throws a core::Error naming the CUDA error when
/// an allocation, copy or launch fails.
std::unique_ptr<StepRunner> makeCudaRunner(const StepSetup& s, Precision p, int block);

/// The number of usable CUDA devices (0 when none); `why` says why there is none (the CUDA error
/// of cudaGetDeviceCount, or "no CUDA device"), and names device 0 otherwise.
int cudaDevices(std::string& why);

} // namespace fascia::cuda
