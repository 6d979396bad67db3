#include "SemiImplicitEuler.h"

#include <algorithm>

namespace fascia::mechanics {

void SemiImplicitEuler::step(core::MechanicalGroup& g, double t, double dt) {
    g.computeForces(t);
    Positions& x = g.state->x();
    Positions& v = g.state->v();
    const Positions& f = g.state->f();
    const double alpha = m_damping.get();
    const size_t n = x.size();
    double kick = dt;
    if (std::find(m_started.begin(), m_started.end(), g.state) == m_started.end()) {
        m_started.push_back(g.state);
        if (m_halfStepStart.get()) kick = 0.5 * dt;
    }
    const double* invMass = g.invMass.data();
    core::forEachNode(static_cast<long>(n), [&](long l) {
        const size_t i = static_cast<size_t>(l);
        v[i] += kick * (invMass[i] * f[i] - alpha * v[i]);  // HEML eq. (32), first line
        x[i] += dt * v[i];                                  // HEML eq. (32), second line
    });
    g.projectState(t + dt);
}

} // namespace fascia::mechanics
