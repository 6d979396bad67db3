#include "fascia/sim/Mechanics.h"
#include "fascia/scene/Node.h"

#include <cmath>
#include <sstream>

namespace fascia::core {

void BaseMechanicalState::resize(size_t n) {
    m_x0.resize(n, Vec3::Zero());
    m_x = m_x0;
    m_v.assign(n, Vec3::Zero());
    m_f.assign(n, Vec3::Zero());
    m_reaction.assign(n, Vec3::Zero());
    m_external.assign(n, Vec3::Zero());
}

void MechanicalGroup::computeForces(double t) {
    Positions& f = state->f();
    std::fill(f.begin(), f.end(), Vec3::Zero());
    for (auto* ff : forceFields) {
        ScopedTimer timer(ff->timer());
        ff->addForce(*state, f, t);
    }
    const size_t n = f.size();
    if (!gravity.isZero())
        for (size_t i = 0; i < n; ++i) f[i] += mass[i] * gravity;
    const Positions& ext = state->externalForce();
    if (ext.size() == n)
        for (size_t i = 0; i < n; ++i) f[i] += ext[i];
    if (constraints.empty()) return;
    beforeConstraints = f;
    for (auto* c : constraints) {
        ScopedTimer timer(c->timer());
        c->projectForces(*state);
    }
    // one reaction per node, whatever the number of constraints acting on it
    Positions& r = state->reaction();
    for (size_t i = 0; i < n; ++i) r[i] = f[i] - beforeConstraints[i];
}

void MechanicalGroup::projectState(double t) {
    for (auto* c : constraints) {
        ScopedTimer timer(c->timer());
        c->projectPositions(*state, t);
        c->projectVelocities(*state, t);
    }
}

namespace {
long firstNonFinite(const Positions& p) {
    const size_t n = p.size();
    for (size_t i = 0; i < n; ++i)
        if (!std::isfinite(p[i][0] + p[i][1] + p[i][2])) return long(i);
    return -1;
}
std::string vecText(const Vec3& v) {
    std::ostringstream os;
    os << v[0] << " " << v[1] << " " << v[2];
    return os.str();
}
} // namespace

void MechanicalGroup::checkFinite(double t) {
    const long bad = firstNonFinite(state->x());
    const long badV = firstNonFinite(state->v());
    if (bad < 0 && badV < 0) return;
    // find the culprit: recompute each force field alone at the previous... current positions
    std::string stepText = "[" + state->path() + "] step " + std::to_string(stepIndex) + ": ";
    Positions tmp(state->size());
    for (auto* ff : forceFields) {
        std::fill(tmp.begin(), tmp.end(), Vec3::Zero());
        try {
            ff->addForce(*state, tmp, t);
        } catch (...) {
        }
        const long i = firstNonFinite(tmp);
        if (i >= 0 && firstNonFinite(state->x()) < 0)
            throwSimulationError("[" + ff->path() + "] step " + std::to_string(stepIndex) + ": non-finite force (" +
                                 vecText(tmp[i]) + ") at node " + std::to_string(i));
    }
    // the step's forces are still in f: a non-finite one names its force field (or lists them)
    const long badF = firstNonFinite(state->f());
    if (badF >= 0 && !forceFields.empty()) {
        std::string others;
        if (forceFields.size() > 1)
            for (auto* ff : forceFields) others += (others.empty() ? " from one of " : ", ") + ff->path();
        throwSimulationError("[" + (forceFields.size() == 1 ? forceFields[0]->path() : state->path()) + "] step " +
                             std::to_string(stepIndex) + ": non-finite force (" + vecText(state->f()[size_t(badF)]) +
                             ") at node " + std::to_string(badF) + others);
    }
    const long node = bad >= 0 ? bad : badV;
    throwSimulationError(stepText + "node " + std::to_string(node) + " has a non-finite " +
                         (bad >= 0 ? "position" : "velocity") + " after " + integrator->className() + " '" +
                         integrator->name() +
                         "': the simulation is unstable (time step above the critical one, or an exploding force); "
                         "try a smaller dt or dt=\"auto\"");
}

} // namespace fascia::core
