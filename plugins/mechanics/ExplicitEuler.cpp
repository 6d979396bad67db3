#include "ExplicitEuler.h"

namespace fascia::mechanics {

void ExplicitEuler::step(core::MechanicalGroup& g, double t, double dt) {
    g.computeForces(t);
    Positions& x = g.state->x();
    Positions& v = g.state->v();
    const Positions& f = g.state->f();
    const double alpha = m_damping.get();
    const size_t n = x.size();
    core::forEachNode(static_cast<long>(n), [&](long l) {
        const size_t i = static_cast<size_t>(l);
        x[i] += dt * v[i];                                    // HEML eq. (31), with v(t)
        v[i] += dt * (g.invMass[i] * f[i] - alpha * v[i]);
    });
    g.projectState(t + dt);
}

} // namespace fascia::mechanics
