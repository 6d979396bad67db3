#include "SemiImplicitEuler.h"

#include <algorithm>
#include <cmath>

namespace fascia::mechanics {

void SemiImplicitEuler::step(core::MechanicalGroup& g, double t, double dt) {
    const double alpha = m_damping.get();
    auto it = std::find_if(m_lastDt.begin(), m_lastDt.end(), [&](const auto& s) { return s.first == g.state; });
    double kick = dt;
    if (it == m_lastDt.end()) {
        m_lastDt.emplace_back(g.state, dt);
        if (m_halfStepStart.get()) kick = 0.5 * dt;
    } else {
        // staggered velocities v(t - dt_old/2) reach v(t + dt/2) over (dt_old + dt)/2 (the variable-step
        // leapfrog), so that a change of dt keeps the scheme second order
        if (m_halfStepStart.get()) kick = 0.5 * (it->second + dt);
        it->second = dt;
    }
    forcesThenUpdate(g, t, [=](double& x, double& v, double f, double invMass) {
        v += kick * (invMass * f - alpha * v);  // HEML eq. (32), first line
        x += dt * v;                            // HEML eq. (32), second line
    });
    g.projectState(t + dt);
}

void SemiImplicitEuler::saveState(core::StateWriter& out) const {
    out.put("states", long(m_lastDt.size()));
    for (const auto& [state, dt] : m_lastDt) {
        out.put("state", state->path());
        out.put("lastDt", dt);
    }
}

void SemiImplicitEuler::restoreState(core::StateReader& in) {
    m_lastDt.clear();
    const long n = in.getLong("states");
    for (long k = 0; k < n; ++k) {
        const auto& s = savedState(*this, in, in.getText("state"));
        m_lastDt.emplace_back(&s, in.getDouble("lastDt"));
    }
}

double SemiImplicitEuler::stableTimeStep(double critical, std::string&) const {
    const double alpha = m_damping.get();
    if (alpha == 0.0) return critical;
    const double omega = 2.0 / critical;  // 0 when no force field limits the step
    return 4.0 / (alpha + std::sqrt(alpha * alpha + 4.0 * omega * omega));
}

} // namespace fascia::mechanics
