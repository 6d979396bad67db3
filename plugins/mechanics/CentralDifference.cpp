#include "CentralDifference.h"

namespace fascia::mechanics {

void CentralDifference::saveState(core::StateWriter& out) const {
    out.put("states", long(m_history.size()));
    for (const auto& [state, h] : m_history) {
        out.put("state", state->path());
        out.put("prev", h.prev);
        out.put("dt", h.dt);
        out.put("steps", h.steps);
    }
}

void CentralDifference::restoreState(core::StateReader& in) {
    m_history.clear();
    const long n = in.getLong("states");
    for (long k = 0; k < n; ++k) {
        auto& s = savedState(*this, in, in.getText("state"));
        History& h = m_history[&s];
        h.prev.resize(s.size());
        in.getInto("prev", h.prev);
        h.dt = in.getDouble("dt");
        h.steps = in.getLong("steps");
    }
}

void CentralDifference::step(core::MechanicalGroup& g, double t, double dt) {
    Positions& x = g.state->x();
    Positions& v = g.state->v();
    const Positions& f = g.state->f();
    const double alpha = m_damping.get();
    const size_t n = x.size();
    History& h = m_history[g.state];
    const double c1 = 1.0 / (1.0 + 0.5 * alpha * dt), c2 = 1.0 - 0.5 * alpha * dt, dt2 = dt * dt;
    auto update = [&](long lo, long hi) {
        const bool haveTwo = h.steps > 0;
        for (long l = lo; l < hi; ++l) {
            const size_t i = static_cast<size_t>(l);
            const Vec3 xn = x[i];
            const Vec3 next = c1 * (2.0 * xn - c2 * h.prev[i] + dt2 * g.invMass[i] * f[i]);
            // velocity at n+1: second-order backward difference once two steps exist, else the
            // exact value for constant acceleration over the first step
            v[i] = haveTwo ? Vec3((3.0 * next - 4.0 * xn + h.prev[i]) / (2.0 * dt))
                           : Vec3(c1 * ((next - xn) / dt + 0.5 * dt * g.invMass[i] * f[i]));
            h.prev[i] = xn;
            x[i] = next;
        }
    };
    // with a history for this dt, the update is node by node: in one region with the forces
    const bool started = h.prev.size() == n && h.dt == dt;
    if (!started || !core::stepThreaded(g, t, update)) {
        g.computeForces(t);
        if (!started) {
            // consistent start (x(-1) from x(0), v(0), a(0)); also after a change of dt, since the
            // history holds x(n-1) for the old step
            h.prev.resize(n);
            for (size_t i = 0; i < n; ++i)
                h.prev[i] = x[i] - dt * v[i] + 0.5 * dt * dt * (g.invMass[i] * f[i] - alpha * v[i]);
            h.dt = dt;
            h.steps = 0;
        }
        core::forEachNodeRange(static_cast<long>(n), update);
    }
    ++h.steps;
    g.projectState(t + dt);
}

} // namespace fascia::mechanics
