#pragma once
/// StagedForceField: the base of the element force fields whose addForce runs in stages on the step
/// team (HEMLForceField, TLEDForceField): what the core sees of them (core::BaseForceField,
/// core::ThreadedForces, core::LayoutReport) with the stages' contract written once, and addForce
/// written once on top of them (StagedForceField.cpp).
///
/// The stages (fascia/sim/ThreadedStep.h runs them as the phases of one job of the step team):
///   beginForces    serially, first: the checks, the viscous history's clock and coefficients (a new
///                  time advances the history, viscoelastic/HistoryClock.h), the state the next
///                  stages read; may throw
///   prepareRange   the node pass over [lo, lo + prepareNodes()) by chunks, in the force field's own
///                  numbering (TLED: u = x - X; HEML: the positions in internal order)
///   runForceBlock  block b (of blockCount(), fixed by the mesh, never by the thread count) into its
///                  own node buffer, after every node chunk; any thread, must not throw. When
///                  rerunnableBlocks(), it computes into its thread's scratch (elements::BlockScratch)
///                  and writes its buffer only when core::claimTask() says so (a block taken over
///                  from a descheduled thread runs twice, fascia/sim/StepTeam.h)
///   sumForceRange  f += the buffers' sum per node in block order over state nodes [lo, hi), after
///                  every block; clears what the next evaluation needs cleared
/// Each task's result depends on the task only, so the forces are bitwise the same for any thread
/// count and any schedule (docs/design.md, principle 5).
///
/// A derived class's destructor calls core::waitForLateTasks() before its data goes (a block's late
/// run may still read it); its components' parameters (core::Param) stay its own, in their order.
#include "fascia/sim/LayoutBytes.h"
#include "fascia/sim/Mechanics.h"
#include "fascia/sim/ThreadedStep.h"

#include <cstddef>

namespace fascia::elements {

class StagedForceField : public core::BaseForceField, public core::LayoutReport, public core::ThreadedForces {
public:
    ~StagedForceField() override;

    /// f += forces at the state's positions at time t: forceNodes' check of f, beginForces, then the
    /// stages as one job of the step team over the nodes forceNodes returns (core::runThreadedForces).
    void addForce(core::BaseMechanicalState& state, Positions& f, double t) final;

    // the stages (see above)
    void beginForces(core::BaseMechanicalState& state, double t) override = 0;
    long prepareNodes() const override = 0;
    void prepareRange(long lo, long hi) override = 0;
    /// blockCount()
    long forceBlocks() const final { return static_cast<long>(blockCount()); }
    bool rerunnableBlocks() const override = 0;
    void runForceBlock(long b, int thread) override = 0;
    void sumForceRange(double* f, long lo, long hi) override = 0;

    /// Number of fixed element blocks (set at init from the mesh, never from the thread count; 0
    /// before init).
    virtual size_t blockCount() const = 0;
    /// True when every element group runs the inlined loop of a built-in law (materials::BuiltinMaterials;
    /// false: some group's material runs the generic loop, one virtual evaluate() per batch).
    virtual bool usesFastPath() const = 0;

protected:
    /// addForce's check of the force array against the state (throws on a mismatch); the state
    /// nodes [0, n) whose forces the sum adds.
    virtual long forceNodes(const core::BaseMechanicalState& state, const Positions& f) const = 0;
};

} // namespace fascia::elements
