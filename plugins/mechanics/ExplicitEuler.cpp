#include "ExplicitEuler.h"

#include <algorithm>

namespace fascia::mechanics {

void ExplicitEuler::step(core::MechanicalGroup& g, double t, double dt) {
    const double alpha = m_damping.get();
    forcesThenUpdate(g, t, [=](double& x, double& v, double f, double invMass) {
        x += dt * v;  // HEML eq. (31), with v(t)
        v += dt * (invMass * f - alpha * v);
    });
    g.projectState(t + dt);
}

double ExplicitEuler::stableTimeStep(double critical, std::string& why) const {
    const double alpha = m_damping.get();
    const double omega = 2.0 / critical;  // 0 when no force field limits the step
    if (omega == 0.0) return alpha > 0 ? 2.0 / alpha : critical;
    if (!(alpha > 0)) {
        why = "forward Euler (HEML eq. (31)) without damping amplifies every vibration, whatever the time step, so "
              "no dt is stable; give damping > 0 (then dt=\"auto\" takes min(2/damping, damping/omega^2) with omega = "
              "2 / the force fields' critical step), or use SemiImplicitEuler or CentralDifference";
        return 0.0;
    }
    return std::min(2.0 / alpha, alpha / (omega * omega));
}

} // namespace fascia::mechanics
