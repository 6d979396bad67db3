#pragma once
/// The GPU step, chosen in one place: `<CudaStep/>` in the root node runs the whole step of every
/// body on a CUDA device (docs/design.md, section 4.7): TLEDForceField's element kernels on
/// tetrahedra and hexahedra (every built-in law, DeviceLaws.h, one material or one per mesh group
/// with groupMaterials, fibre directions per material or per element with fibreArray and
/// fibreArray2, relaxed by its ViscoelasticProny series as TLEDForceField relaxes it, the states on
/// the device), then a node kernel that sums each node's element forces (and the follower loads of
/// SurfacePressure's faces, a face kernel) in a fixed order, adds ConstantForce (on its load curve)
/// and gravity, integrates with SemiImplicitEuler (HEML eq. (32)) or CentralDifference and puts the
/// axes of FixedConstraint and PrescribedDisplacement where they hold them, in float or double. A
/// component it cannot run is a located error naming it; no device is a located error too (exit 2):
/// it never falls back to the host. emulate="true" runs the same kernel bodies over the same layout on the CPU (tests).
/// The state stays on the device: the host queues the steps without waiting for them, and x and v
/// come back only when something reads them (core::BaseStepBackend::fetch: observers that record
/// the step, Simulation::state, checkpoints). What a program writes into x and v after such a read
/// is taken up by the next step. The device keeps the first step that left a state that is not
/// finite; the host reads it every checkEvery steps and at every fetch. The Prony history advances
/// once a step, over the time the host's HistoryClock gives (the coefficients of dt, as
/// TLEDForceField's forces at the start of each step).
#include "StepRunner.h"
#include "fascia/sim/LayoutBytes.h"
#include "fascia/sim/Mechanics.h"
#include "fascia/viscoelastic/ElementHistory.h"

#include <memory>
#include <vector>

namespace fascia::cuda {

class CudaStep : public core::BaseStepBackend, public core::LayoutReport {
public:
    void adopt(core::MechanicalGroup& group) override;
    void step(core::MechanicalGroup& group, double t, double dt) override;
    void fetch(core::MechanicalGroup& group) override;
    void push(core::MechanicalGroup& group) override;
    /// The device's state per body: u and v as the device holds them (x - X in double would not give
    /// u back bitwise), SemiImplicitEuler's kick, CentralDifference's restart rule and increments,
    /// the Prony states, clock and coefficients.
    void saveState(core::StateWriter& out) const override;
    void restoreState(core::StateReader& in) override;
    void wait() override;
    /// What one step moves through the device's memory, counted from the layout (StepLayout.h) as
    /// core::LayoutBytes counts a force field's: fascia-bench's bytes per element-step.
    core::LayoutBytes layoutBytes() const override;

    core::Param<std::string> m_precision{this, core::ParamSpec("precision").choices({"double", "float"}).help(
        "scalar of the device step: double, or float (about twice the speed on a GPU; forces to about 1e-6 relative)"), "double"};
    core::Param<bool> m_emulate{this, core::ParamSpec("emulate").help(
        "run the device step's kernel bodies on the CPU, one thread, over the same data layout (for tests without a GPU; slow)"), false};
    core::Param<int> m_blockSize{this, core::ParamSpec("blockSize").min(32).max(1024).help(
        "threads per block of the kernel launches, or fewer where a kernel's registers allow fewer (performance only: the result is the same for any value)"), 256};
    core::Param<std::string> m_forceOrder{this, core::ParamSpec("forceOrder").choices({"element", "node"}).help(
        "where the element kernels write their corner forces: by element (the node kernel gathers them from scattered records), "
        "or in node order (each element scatters its corners, the node kernel reads one contiguous run); the same bits either "
        "way, a choice of speed for a GPU to measure"), "element"};
    core::Param<int> m_checkEvery{this, core::ParamSpec("checkEvery").min(1).help(
        "the host reads the device's record of a state that is not finite every N steps (and whenever it reads the state); "
        "each read waits for the queued steps, so 1 costs speed on small meshes"), 100};

private:
    struct Body {
        const core::BaseMechanicalState* state = nullptr;
        StepSetup setup;
        std::unique_ptr<StepRunner> runner;
        KickRule kick;
        CentralRule central;
        std::vector<double> tu, tv;  ///< the targets of the step (motionTargets)
        std::vector<double> u, v, du;  ///< the device's state when the host holds it, and the increments
        std::vector<double> r;          ///< the reactions of the last fetch (StepArrays::react)
        std::vector<double> Y;          ///< the Prony states read from a checkpoint (push uploads them)
        viscoelastic::HistoryClock clock;  ///< when the Prony history advances, over what time (as TLEDForceField)
        /// the element force field, which takes the Prony states back at a fetch for its stress
        /// output (null without a series)
        viscoelastic::ElementHistory* history = nullptr;
        std::vector<double> A, B;          ///< the Prony coefficients the runner holds
        std::vector<double> nextA, nextB;  ///< those of the step
        bool restored = false;          ///< u, v and du come from a checkpoint: push uploads them as they are
        Precision precision = Precision::Double;
        /// the host's x and v hold the state (after an upload or a fetch, until the next step): a
        /// program may write them before that step, which then uploads what it finds
        bool onHost = true;
        Positions xSeen, vSeen;  ///< what the host held then, to see such a write
    };
    Body& body(const core::MechanicalGroup& g);
    /// The host's x and v to the device.
    void upload(Body& b, const core::MechanicalGroup& g);
    /// A simulation error when the device kept a step whose state was not finite.
    void check(Body& b, core::MechanicalGroup& g);
    std::vector<Body> m_bodies;
};

} // namespace fascia::cuda
