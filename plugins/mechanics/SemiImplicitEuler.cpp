#include "SemiImplicitEuler.h"

#include <algorithm>

namespace fascia::mechanics {

void SemiImplicitEuler::step(core::MechanicalGroup& g, double t, double dt) {
    g.computeForces(t);
    const double alpha = m_damping.get();
    double kick = dt;
    if (std::find(m_started.begin(), m_started.end(), g.state) == m_started.end()) {
        m_started.push_back(g.state);
        if (m_halfStepStart.get()) kick = 0.5 * dt;
    }
    updateNodes(g, [=](double& x, double& v, double f, double invMass) {
        v += kick * (invMass * f - alpha * v);  // HEML eq. (32), first line
        x += dt * v;                            // HEML eq. (32), second line
    });
    g.projectState(t + dt);
}

} // namespace fascia::mechanics
