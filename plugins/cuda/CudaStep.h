#pragma once
/// The GPU step, chosen in one place: `<CudaStep/>` in the root node runs the whole step of every
/// body on a CUDA device (docs/design.md, section 4.7): TLEDForceField's element kernels on
/// tetrahedra and hexahedra (every built-in law, DeviceLaws.h, relaxed by its ViscoelasticProny
/// series as TLEDForceField relaxes it, the states on the device), then a node kernel that sums each
/// node's element forces in a fixed order, adds ConstantForce and gravity, integrates with
/// SemiImplicitEuler (HEML eq. (32)) or CentralDifference and puts the axes of FixedConstraint and
/// PrescribedDisplacement where they hold them, in float or double. A component it cannot run is
/// a located error naming it; no device is a located error too (exit 2): it never falls back to
/// the host. emulate="true" runs the same kernel bodies over the same layout on the CPU (tests).
/// This slice copies x and v back after every step, so that observers and the finite check read
/// them as on the CPU (and PrescribedDisplacement's targets are read from the host state after
/// projectState, motionTargets). The Prony history advances once a step, over the time the host's
/// HistoryClock gives (the coefficients of dt, as TLEDForceField's forces at the start of each step).
#include "StepRunner.h"
#include "fascia/sim/Mechanics.h"
#include "fascia/viscoelastic/HistoryClock.h"

#include <memory>
#include <vector>

namespace fascia::cuda {

class CudaStep : public core::BaseStepBackend {
public:
    void adopt(core::MechanicalGroup& group) override;
    void step(core::MechanicalGroup& group, double t, double dt) override;

    core::Param<std::string> m_precision{this, core::ParamSpec("precision").choices({"double", "float"}).help(
        "scalar of the device step: double, or float (about twice the speed on a GPU; forces to about 1e-6 relative)"), "double"};
    core::Param<bool> m_emulate{this, core::ParamSpec("emulate").help(
        "run the device step's kernel bodies on the CPU, one thread, over the same data layout (for tests without a GPU; slow)"), false};
    core::Param<int> m_blockSize{this, core::ParamSpec("blockSize").min(32).max(1024).help(
        "threads per block of the kernel launches (performance only: the result is the same for any value)"), 256};

private:
    struct Body {
        const core::BaseMechanicalState* state = nullptr;
        StepSetup setup;
        std::unique_ptr<StepRunner> runner;
        KickRule kick;
        CentralRule central;
        std::vector<double> tu, tv;  ///< the targets of the step (motionTargets)
        std::vector<double> u, v;
        viscoelastic::HistoryClock clock;  ///< when the Prony history advances, over what time (as TLEDForceField)
        std::vector<double> A, B;          ///< the Prony coefficients the runner holds
        std::vector<double> nextA, nextB;  ///< those of the step
    };
    std::vector<Body> m_bodies;
};

} // namespace fascia::cuda
