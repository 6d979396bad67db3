#include "AxisConstraint.h"

namespace fascia::mechanics {

void AxisConstraint::init() {
    auto& s = contextState(*this);
    m_nodes = m_select.resolve(*this, s);
    m_mask = readAxisMask(*this, m_directions);
    projectPositions(s, 0);
    projectVelocities(s, 0);
}

void AxisConstraint::projectPositions(core::BaseMechanicalState& s, double t) {
    const Vec3 u = offset(t);
    auto& x = s.x();
    const auto& x0 = s.x0();
    for (int i : m_nodes)
        for (int a = 0; a < 3; ++a)
            if (m_mask[a]) x[i][a] = x0[i][a] + u[a];
}

void AxisConstraint::projectVelocities(core::BaseMechanicalState& s, double t) {
    const Vec3 w = rate(t);
    auto& v = s.v();
    for (int i : m_nodes)
        for (int a = 0; a < 3; ++a)
            if (m_mask[a]) v[i][a] = w[a];
}

void AxisConstraint::projectForces(core::BaseMechanicalState& s) {
    auto& f = s.f();
    for (int i : m_nodes)
        for (int a = 0; a < 3; ++a)
            if (m_mask[a]) f[i][a] = 0;
}

} // namespace fascia::mechanics
