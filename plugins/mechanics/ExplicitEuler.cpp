#include "ExplicitEuler.h"

namespace fascia::mechanics {

void ExplicitEuler::step(core::MechanicalGroup& g, double t, double dt) {
    g.computeForces(t);
    const double alpha = m_damping.get();
    updateNodes(g, [=](double& x, double& v, double f, double invMass) {
        x += dt * v;  // HEML eq. (31), with v(t)
        v += dt * (invMass * f - alpha * v);
    });
    g.projectState(t + dt);
}

} // namespace fascia::mechanics
