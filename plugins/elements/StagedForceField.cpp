#include "fascia/elements/StagedForceField.h"

namespace fascia::elements {

StagedForceField::~StagedForceField() = default;

void StagedForceField::addForce(core::BaseMechanicalState& state, Positions& f, double t) {
    const long n = forceNodes(state, f);
    beginForces(state, t);
    // one job of the step team: the node pass, the blocks, then the sum of the block buffers
    core::runThreadedForces(*this, core::flat(f), n);
}

} // namespace fascia::elements
