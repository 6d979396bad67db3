#include "fascia/sim/Mechanics.h"
#include "fascia/base/Error.h"
#include "fascia/base/StateIO.h"
#include "fascia/scene/Node.h"
#include "fascia/sim/ThreadedStep.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace fascia::core {

void BaseMechanicalState::resize(size_t n) {
    waitForLateTasks();  // (a block's late run may still read x: fascia/sim/StepTeam.h)
    m_x0.resize(n, Vec3::Zero());
    m_x = m_x0;
    m_v.assign(n, Vec3::Zero());
    m_f.assign(n, Vec3::Zero());
    m_reaction.assign(n, Vec3::Zero());
    m_external.assign(n, Vec3::Zero());
}

void BaseMechanicalState::saveState(StateWriter& out) const {
    out.put("x", m_x);
    out.put("v", m_v);
    out.put("f", m_f);
    out.put("x0", m_x0);
    out.put("reaction", m_reaction);
    out.put("externalForce", m_external);
}

void BaseMechanicalState::restoreState(StateReader& in) {
    in.getInto("x", m_x);
    in.getInto("v", m_v);
    in.getInto("f", m_f);
    in.getInto("x0", m_x0);
    in.getInto("reaction", m_reaction);
    in.getInto("externalForce", m_external);
}

MechanicalGroup::ForceStart MechanicalGroup::forceStart(double t) const {
    ForceStart s;
    const size_t n = state->f().size();
    s.ext = state->externalForce().size() == n;
    s.gravity = !gravity.isZero() && mass.size() >= n;
    const double c = gravityCurve ? gravityCurve->value(t) : 1.0;
    for (int k = 0; k < 3; ++k) s.g[k] = c * gravity[k];
    return s;
}

void MechanicalGroup::initialForces(const ForceStart& s, long lo, long hi) {
    double* __restrict fp = flat(state->f());
    const double* __restrict ep = flat(state->externalForce());
    const double* __restrict m = mass.data();
    const double* g = s.g;
    if (s.ext && s.gravity) {
        for (long i = lo; i < hi; ++i)
            for (int c = 0; c < 3; ++c) fp[3 * i + c] = ep[3 * i + c] + m[i] * g[c];
    } else if (s.gravity) {
        for (long i = lo; i < hi; ++i)
            for (int c = 0; c < 3; ++c) fp[3 * i + c] = m[i] * g[c];
    } else if (s.ext) {
        std::copy(ep + 3 * lo, ep + 3 * hi, fp + 3 * lo);
    } else {
        std::fill(fp + 3 * lo, fp + 3 * hi, 0.0);
    }
}

void MechanicalGroup::prepareReactions() {
    // one reaction per node, whatever the number of constraints acting on it: minus what the
    // constraints removed, recorded at the constrained nodes only (a node listed twice is harmless)
    Positions& r = state->reaction();
    for (int i : reactionNodes)  // (the set may change between steps, the state may have shrunk)
        if (size_t(i) < r.size()) r[size_t(i)] = Vec3::Zero();
    reactionNodes.clear();
    for (auto* c : constraints) {
        const IndexList& nodes = c->constrainedNodes();
        reactionNodes.insert(reactionNodes.end(), nodes.begin(), nodes.end());
    }
}

void MechanicalGroup::applyConstraints() {
    Positions& f = state->f();
    Positions& r = state->reaction();
    beforeConstraints.resize(reactionNodes.size());
    for (size_t k = 0; k < reactionNodes.size(); ++k) beforeConstraints[k] = f[size_t(reactionNodes[k])];
    for (auto* c : constraints) {
        ScopedTimer timer(c->timer());
        c->projectForces(*state);
    }
    for (size_t k = 0; k < reactionNodes.size(); ++k) {
        const size_t i = size_t(reactionNodes[k]);
        r[i] = f[i] - beforeConstraints[k];
    }
}

void MechanicalGroup::computeForces(double t) {
    chunkReady.clear();
    Positions& f = state->f();
    // f starts from the body and external forces (one pass), then every force field adds its own
    const ForceStart start = forceStart(t);
    forEachNodeRange(static_cast<long>(f.size()), [&](long lo, long hi) { initialForces(start, lo, hi); });
    for (auto* ff : forceFields) {
        ScopedTimer timer(ff->timer());
        ff->addForce(*state, f, t);
    }
    if (constraints.empty()) return;
    prepareReactions();
    applyConstraints();
}

double MechanicalGroup::residualNorm(double t) {
    // the forces of a step at t, then f, the reactions and their node list put back as they were
    const Positions f0 = state->f(), r0 = state->reaction();
    const IndexList nodes0 = reactionNodes;
    computeForces(t);
    double sum = 0;  // in node order: the same sum for any thread count
    for (const Vec3& fi : state->f()) sum += fi.squaredNorm();
    state->f() = f0;
    state->reaction() = r0;
    reactionNodes = nodes0;
    return std::sqrt(sum);
}

void MechanicalGroup::projectState(double t) {
    for (auto* c : constraints) {
        ScopedTimer timer(c->timer());
        c->projectPositions(*state, t);
        c->projectVelocities(*state, t);
    }
}

namespace {
/// sum of 0 a_j + 0 b_j over j < m: 0 if every value is finite, NaN otherwise (0 * inf = NaN). Eight
/// independent sums, so that the loop vectorises (one sum is a chain of dependent additions;
/// docs/performance.md, lesson 3).
double finiteProbe(const double* __restrict a, const double* __restrict b, long m) {
    double acc[8] = {0, 0, 0, 0, 0, 0, 0, 0};
    long j = 0;
    for (; j + 8 <= m; j += 8)
        for (int k = 0; k < 8; ++k) acc[k] += 0.0 * a[j + k] + 0.0 * b[j + k];
    double p = 0;
    for (; j < m; ++j) p += 0.0 * a[j] + 0.0 * b[j];
    for (double s : acc) p += s;
    return p;
}

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

void MechanicalGroup::checkChunk(long c, long lo, long hi) {
    const long n = static_cast<long>(std::min(state->x().size(), state->v().size()));
    const double* xp = flat(state->x());
    const double* vp = flat(state->v());
    const double* mp = mass.size() >= size_t(n) ? mass.data() : nullptr;
    double* sums = chunkSums.data();
    sums[2 * c] = finiteProbe(xp + 3 * lo, vp + 3 * lo, 3 * (hi - lo));
    double e[4] = {0, 0, 0, 0};
    if (mp)
        for (long i = lo; i < hi; ++i)
            e[i & 3] += mp[i] * (vp[3 * i] * vp[3 * i] + vp[3 * i + 1] * vp[3 * i + 1] + vp[3 * i + 2] * vp[3 * i + 2]);
    sums[2 * c + 1] = 0.5 * ((e[0] + e[1]) + (e[2] + e[3]));
}

void MechanicalGroup::checkStep(double t) {
    // one pass over x, v and the masses: per chunk the finite probe of x and v and the kinetic energy
    const long n = static_cast<long>(std::min(state->x().size(), state->v().size()));
    const long chunks = (n + kNodeChunk - 1) / kNodeChunk;
    const double* sums = chunkSums.data();
    if (chunkReady.size() == size_t(chunks) && chunkSums.size() == 2 * size_t(chunks)) {
        // the threaded step computed the sums of the chunks no constraint touches; here the others,
        // after the constraints' projection (ThreadedStep.h)
        for (long c = 0; c < chunks; ++c)
            if (!chunkReady[size_t(c)]) checkChunk(c, c * kNodeChunk, std::min(n, (c + 1) * kNodeChunk));
    } else {
        chunkSums.assign(2 * size_t(chunks), 0.0);
        sums = chunkSums.data();
        forEachNodeRange(n, [&](long lo, long hi) { checkChunk(lo / kNodeChunk, lo, hi); });
    }
    chunkReady.clear();
    double probe = 0, ke = 0;
    for (long c = 0; c < chunks; ++c) probe += sums[2 * c], ke += sums[2 * c + 1];  // in chunk order
    if (!std::isfinite(probe) || state->x().size() != state->v().size()) checkFinite(t);
    // the growth rule (Mechanics.h): kGrowthSteps consecutive steps above kGrowthFactor times every earlier one
    const double before = kineticMax;
    kineticGrowth = (ke > 0 && ke > kGrowthFactor * kineticMax) ? kineticGrowth + 1 : 0;
    kinetic = ke;
    kineticMax = std::max(kineticMax, ke);
    if (kineticGrowth >= kGrowthSteps) {
        std::ostringstream os;
        os.precision(3);
        os << "[" << state->path() << "] step " << stepIndex << ": the kinetic energy grew more than " << kGrowthFactor
           << " times its largest earlier value at each of the last " << kGrowthSteps << " steps, to " << ke << " J ("
           << (before > 0 ? ke / before : INFINITY) << " times the " << before << " J before this step) after "
           << integrator->className() << " '" << integrator->name()
           << "': the simulation diverges (time step above the critical one, or an exploding force); "
              "try a smaller dt or dt=\"auto\"";
        throwSimulationError(os.str());
    }
}

void MechanicalGroup::checkFinite(double t) {
    // fast test: one pass over x and v (0 * a non-finite value is NaN, 0 * a finite one is 0); the
    // slow one below only when it fails
    const Positions& x = state->x();
    const Positions& v = state->v();
    const long n = static_cast<long>(std::min(x.size(), v.size()));
    const double* xp = flat(x);
    const double* vp = flat(v);
    const double probe = sumNodeRange(n, [&](long lo, long hi) { return finiteProbe(xp + 3 * lo, vp + 3 * lo, 3 * (hi - lo)); });
    if (std::isfinite(probe) && x.size() == v.size()) return;
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

namespace {
std::atomic<TaskHook> g_taskHook{nullptr};
bool threadedDefault() {
    const char* e = std::getenv("FASCIA_THREADED_STEP");
    return !(e && e[0] == '0');
}
std::atomic<bool> g_threaded{threadedDefault()};
} // namespace

namespace {
bool adaptiveDefault() {
    const char* e = std::getenv("FASCIA_ADAPTIVE_TEAM");
    return !(e && e[0] == '0');
}
std::atomic<bool> g_adaptive{adaptiveDefault()};
} // namespace

void setAdaptiveTeam(bool on) { g_adaptive.store(on); }
bool adaptiveTeamEnabled() { return g_adaptive.load(std::memory_order_relaxed); }

int TeamChoice::choose() {
    ++step;
    if (probing == 0 && step >= nextProbe) {
        probing = kProbe;
        count[1 - current] = 0;  // the probe's own steps only: the load may have changed since the last
    }
    return probing > 0 ? 1 - current : current;
}

void TeamChoice::record(int t, double s) {
    seconds[t][count[t] % kKeep] = s;
    ++count[t];
    if (t == current) {
        if (probing > 0 || count[1 - t] == 0) return;
        // a collapsed step of the team (another process took a core back), or a team slower than the
        // other's typical step for kKeep steps (a lasting slowdown): probe at once
        const double other = median(1 - t);
        if (s > 2 * other || (count[t] >= kKeep && step - lastProbe >= kKeep && mean(t) > 1.25 * other))
            nextProbe = std::min(nextProbe, step + 1);
        return;
    }
    if (probing == 0) return;
    // a probe step twice as slow as the current team's steps: no need for the rest of the probe
    if (count[t] == 1 && s > 2 * mean(current)) probing = 1;
    if (--probing > 0) return;
    lastProbe = step;
    // the end of a probe: switch when the other team's recent steps are 10 % faster on average
    if (mean(t) < 0.9 * mean(current)) {
        current = t;
        interval = 16;
    } else {
        // a probe 3 times slower (a collapsed team, most likely): the next one much later
        interval = std::min((mean(t) > 3 * mean(current) ? 4 : 2) * interval, 1024L);
    }
    nextProbe = step + interval;
}

double TeamChoice::median(int t) const {
    const int n = std::min(count[t], kKeep);
    if (n == 0) return INFINITY;
    double v[kKeep];
    std::copy(seconds[t], seconds[t] + n, v);
    // (an insertion sort of the at most kKeep samples: std::sort's 16-element threshold made GCC 12
    // warn about bounds it never reaches)
    for (int i = 1; i < n; ++i)
        for (int j = i; j > 0 && v[j - 1] > v[j]; --j) std::swap(v[j - 1], v[j]);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double TeamChoice::mean(int t) const {
    // the mean, not the median: a descheduled thread makes a few steps very slow, and those set the
    // throughput (a median of them looked fine while the mean was ten times the one-thread step)
    const int n = std::min(count[t], kKeep);
    if (n == 0) return INFINITY;
    double sum = 0;
    for (int i = 0; i < n; ++i) sum += seconds[t][i];
    return sum / n;
}

void setTaskHook(TaskHook hook) { g_taskHook.store(hook); }
TaskHook taskHook() { return g_taskHook.load(std::memory_order_relaxed); }
void setThreadedStep(bool on) { g_threaded.store(on); }
bool threadedStepEnabled() { return g_threaded.load(std::memory_order_relaxed); }

} // namespace fascia::core
