#include "FixedConstraint.h"

namespace fascia::mechanics {

void FixedConstraint::init() {
    auto& s = contextState(*this);
    m_nodes = m_select.resolve(*this, s);
    m_mask = readAxisMask(*this, m_directions);
    projectPositions(s, 0);
    projectVelocities(s, 0);
}

void FixedConstraint::projectPositions(core::BaseMechanicalState& s, double) {
    auto& x = s.x();
    const auto& x0 = s.x0();
    for (int i : m_nodes)
        for (int a = 0; a < 3; ++a)
            if (m_mask[a]) x[i][a] = x0[i][a];
}

void FixedConstraint::projectVelocities(core::BaseMechanicalState& s, double) {
    auto& v = s.v();
    for (int i : m_nodes)
        for (int a = 0; a < 3; ++a)
            if (m_mask[a]) v[i][a] = 0;
}

void FixedConstraint::projectForces(core::BaseMechanicalState& s) {
    auto& f = s.f();
    for (int i : m_nodes)
        for (int a = 0; a < 3; ++a)
            if (m_mask[a]) f[i][a] = 0;
}

} // namespace fascia::mechanics
