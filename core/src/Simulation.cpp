#include "fascia/sim/Simulation.h"
#include "fascia/base/ErrorList.h"
#include "fascia/base/Format.h"
#include "fascia/scene/SceneLoader.h"
#include "fascia/sim/Tool.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <set>
#include <unordered_map>

namespace fascia::core {

std::unique_ptr<Simulation> Simulation::fromFile(const std::string& path, const LoadOptions& options) {
    auto root = buildScene(parseSceneFile(path));
    root->context().sceneFile = path;
    auto sim = std::make_unique<Simulation>(std::move(root));
    sim->configure(options);
    sim->init();
    return sim;
}

std::unique_ptr<Simulation> Simulation::fromString(const std::string& xml, const std::string& virtualName,
                                                   const std::string& baseDir, const LoadOptions& options) {
    auto root = buildScene(parseSceneString(xml, virtualName, baseDir));
    auto sim = std::make_unique<Simulation>(std::move(root));
    sim->configure(options);
    sim->init();
    return sim;
}

Simulation::Simulation(std::unique_ptr<Node> root) : m_root(std::move(root)) {}

void Simulation::configure(const LoadOptions& options) {
    if (!options.outputDir.empty()) setOutputDir(options.outputDir);
    if (options.dt > 0) m_dtOverride = options.dt;
}

Simulation::~Simulation() {
    try {
        finish();
    } catch (...) {
    }
}

/// Marks a component initialised (Component befriends it).
class SceneInit {
public:
    static void markInitialised(Component& c) { c.m_initialised = true; }
};

namespace {

void collect(Node& n, std::vector<Component*>& out) {
    for (auto& c : n.components()) out.push_back(c.get());
    for (auto& ch : n.children()) collect(*ch, out);
}

/// A node has one integrator: its states find the first, so a second one would never be called.
/// Each node's error is kept in errors, under the index (in all) of its second integrator.
std::vector<Component*> checkOneIntegratorPerNode(const Node& root, const std::vector<Component*>& all, ErrorList& errors) {
    std::vector<Component*> second;
    root.visit([&](const Node& n) {
        const auto integrators = n.findAllLocal<BaseIntegrator>();
        if (integrators.size() < 2) return;
        second.push_back(integrators[1]);
        const BaseIntegrator* first = integrators[0];
        const size_t at = size_t(std::find(all.begin(), all.end(), integrators[1]) - all.begin());
        errors.attempt(at, [&] {
            integrators[1]->fail("a second integrator in node '" + n.name() + "', which has " + first->className() + " '" +
                                     first->name() + "'" + (first->loc().empty() ? "" : " (" + first->loc().str() + ")") +
                                     ": only the first would be called",
                                 {"keep one integrator per node; a state in a child node may have its own"});
        });
    });
    return second;
}

/// Two constraints on one node and axis, either of which prescribes its motion, fight over it: an
/// input error at the later one naming the earlier and the first such node. (Two that hold a node at
/// rest agree, e.g. rollers on two faces that share an edge.)
void checkConstraintConflicts(const MechanicalGroup& g) {
    const size_t n = g.state->size();
    std::vector<int> owner(3 * n, -1);  // per node and axis: the first constraint holding it
    static const char* kAxis[3] = {"x", "y", "z"};
    for (size_t c = 0; c < g.constraints.size(); ++c) {
        const BaseConstraint* k = g.constraints[c];
        const std::array<bool, 3> axes = k->constrainedAxes();
        for (int i : k->constrainedNodes()) {
            if (i < 0 || size_t(i) >= n) continue;  // each constraint checks its own indices
            for (int a = 0; a < 3; ++a) {
                if (!axes[size_t(a)]) continue;
                int& o = owner[3 * size_t(i) + size_t(a)];
                if (o < 0) {
                    o = int(c);
                    continue;
                }
                const BaseConstraint* other = g.constraints[size_t(o)];
                if (other == k || (!k->prescribesMotion() && !other->prescribesMotion())) continue;
                k->fail("node " + std::to_string(i) + " axis " + kAxis[a] + " is also constrained by " + other->className() +
                            " '" + other->path() + "'" + (other->loc().empty() ? "" : " (" + other->loc().str() + ")") +
                            ", and " + (k->prescribesMotion() ? "this one" : "that one") +
                            " prescribes its motion: a node's axis can follow one constraint only",
                        {"remove the node from one of them, or let them hold different axes (directions=\"1 1 0\" ...)"});
            }
        }
    }
}

/// Runs every component's init, after the components it links to and those it lists in
/// dependencies(), and keeps the errors of independent components (docs/design.md, section 7). A
/// component whose init failed or did not run leaves uninitialised, without a word, the components
/// that may read it: those that link to it or list it, and those of its node, of the nodes above it
/// and of the nodes below it (a component may read its context or its subtree at init without listing
/// them). Components elsewhere (a body in a sibling node) still run, and report their own errors.
struct InitOrder {
    const std::vector<Component*>& all;
    ErrorList& errors;
    std::set<Component*> done, stopped, active;
    std::set<const Node*> stoppedIn;  ///< the nodes of the components stopped
    std::set<const Node*> above;      ///< those nodes and every node above them
    std::unordered_map<const Component*, size_t> index;  ///< the place of each component in `all`

    /// Whether a component stopped in n's node, in a node above it or in a node below it.
    bool nearStopped(const Node* n) const {
        if (above.count(n)) return true;
        for (; n; n = n->parent())
            if (stoppedIn.count(n)) return true;
        return false;
    }
    void stop(Component* c) {
        stopped.insert(c);
        stoppedIn.insert(c->node());
        for (const Node* n = c->node(); n && above.insert(n).second; n = n->parent()) {}
    }
    size_t orderOf(Component* c) {
        if (index.empty())
            for (size_t i = 0; i < all.size(); ++i) index.emplace(all[i], i);
        const auto it = index.find(c);
        return it == index.end() ? all.size() : it->second;
    }

    /// Whether c is initialised after the call.
    bool run(Component* c) {
        if (done.count(c)) return true;
        if (stopped.count(c)) return false;
        if (active.count(c)) {
            errors.attempt(orderOf(c), [&] { c->fail("link cycle: " + c->path() + " depends, through its links, on itself"); });
            return false;  // (the frames of the cycle stop, as dependents of it)
        }
        active.insert(c);
        bool ready = true;  // every dependency is run, so that an independent error among them is found
        for (BaseParam* p : c->params())
            if (auto* t = dynamic_cast<Component*>(p->linkTarget())) ready = run(t) && ready;
        for (Component* d : c->dependencies()) ready = run(d) && ready;
        active.erase(c);
        ready = ready && !nearStopped(c->node());
        // a value that came through a data link is known only now, and one set from code (the C++
        // API: Param::set) was never checked: check their ranges and choices here, for every
        // component alike (an XML value was checked when read; checking it again costs nothing)
        ready = ready && errors.attempt(orderOf(c), [&] {
            for (BaseParam* p : c->params())
                if (!p->isComponentLink() && (p->linkTarget() || p->isSet())) p->checkValue();
            c->init();
        });
        if (!ready) {
            stop(c);
            return false;
        }
        SceneInit::markInitialised(*c);
        done.insert(c);
        return true;
    }
};

/// The step backend (BaseStepBackend, e.g. the cuda plugin's CudaStep) takes over every group: at
/// most one, and in the root node only, so that the device is chosen in one place.
void adoptBackend(const Node& root, const std::vector<Component*>& all, std::vector<MechanicalGroup>& groups) {
    BaseStepBackend* backend = nullptr;
    for (Component* c : all)
        if (auto* b = dynamic_cast<BaseStepBackend*>(c)) {
            if (c->node() != &root)
                c->fail("a step backend must be in the root node: it runs the step of every body",
                        {"move it to the root node"});
            if (backend) c->fail("a second step backend: " + backend->className() + " '" + backend->name() + "' is one already");
            backend = b;
        }
    if (!backend) return;
    for (auto& g : groups) {
        backend->adopt(g);
        g.backend = backend;
    }
}

/// One group per state that an integrator moves (the first in its context); a state without one
/// is warned about and left out.
std::vector<MechanicalGroup> groupsOfStates(const std::vector<Component*>& all) {
    std::vector<MechanicalGroup> groups;
    for (Component* c : all) {
        auto* s = dynamic_cast<BaseMechanicalState*>(c);
        if (!s) continue;
        auto* integ = s->node()->findInContext<BaseIntegrator>();
        if (!integ) {
            s->warn("no integrator in its context: it will not move (add SemiImplicitEuler to its node or a parent)");
            continue;
        }
        MechanicalGroup g;
        g.integrator = integ;
        g.state = s;
        g.gravity = s->node()->contextGravity();
        g.gravityCurve = &s->node()->contextGravityCurve();
        groups.push_back(std::move(g));
    }
    return groups;
}

/// Every force field, mass and constraint into the group of the state in its context (a tool's:
/// the body it names); one without a group is warned about.
void assignToGroups(const std::vector<Component*>& all, std::vector<MechanicalGroup>& groups) {
    for (Component* c : all) {
        auto* ff = dynamic_cast<BaseForceField*>(c);
        auto* m = dynamic_cast<BaseMass*>(c);
        auto* k = dynamic_cast<BaseConstraint*>(c);
        if (!ff && !m && !k) continue;
        auto* s = c->node()->findInContext<BaseMechanicalState>();
        if (auto* tool = dynamic_cast<BaseTool*>(c); tool && tool->body()) s = tool->body();  // a tool names its body
        auto it = std::find_if(groups.begin(), groups.end(), [&](auto& g) { return g.state == s; });
        if (it == groups.end()) {
            c->warn(s ? "its state '" + s->name() + "' has no integrator: it will not act"
                      : "no MechanicalObject in its context: it will not act");
            continue;
        }
        if (ff) it->forceFields.push_back(ff);
        if (m) it->masses.push_back(m);
        if (k) it->constraints.push_back(k);
    }
}

/// The group's nodal masses (the sum of its masses) and their inverses (0 for a massless node),
/// checked against the state's size; a group that needs a mass and has none fails.
void sumMasses(MechanicalGroup& g) {
    const size_t n = g.state->size();
    g.mass.assign(n, 0.0);
    for (auto* m : g.masses) {
        const auto& mm = m->nodalMasses();
        if (mm.size() != n)
            m->fail("has " + std::to_string(mm.size()) + " nodal masses but its state '" + g.state->name() + "' has " +
                    std::to_string(n) + " nodes");
        for (size_t i = 0; i < n; ++i) g.mass[i] += mm[i];
    }
    if (g.masses.empty() && n > 0 && (!g.forceFields.empty() || !g.gravity.isZero()))
        g.state->fail("no mass in its context: add a LumpedMass next to it");
    g.invMass.resize(n);
    size_t massless = 0;
    for (size_t i = 0; i < n; ++i) {
        g.invMass[i] = g.mass[i] > 0 ? 1.0 / g.mass[i] : 0.0;
        massless += g.mass[i] > 0 ? 0 : 1;
    }
    if (massless && !g.masses.empty())
        g.state->warn(std::to_string(massless) + " node(s) have no mass (no element uses them): they will stay where they are");
}

} // namespace

void Simulation::init() {
    if (m_initialised) return;
    m_all.clear();
    collect(*m_root, m_all);
    // the init phase: its errors are thrown together, in scene order, before anything else is checked
    ErrorList errors({m_root->loc().file, 0});
    InitOrder order{m_all, errors, {}, {}, {}, {}, {}, {}};
    // a node with two integrators is not initialised: its components would run with the wrong one
    for (Component* second : checkOneIntegratorPerNode(*m_root, m_all, errors)) order.stop(second);
    for (Component* c : m_all) order.run(c);
    errors.throwIfAny();

    // assemble one group per state: a state belongs to the integrator in its context, and every
    // force field, mass and constraint to the state in its context
    m_groups = groupsOfStates(m_all);
    assignToGroups(m_all, m_groups);
    for (auto& g : m_groups) {
        sumMasses(g);
        checkConstraintConflicts(g);
    }
    adoptBackend(*m_root, m_all, m_groups);
    chooseDt();

    for (Component* c : m_all)
        if (auto* o = dynamic_cast<BaseObserver*>(c)) m_observers.push_back(o);
    m_initialised = true;
    SceneContext& ctx = m_root->context();
    ctx.time = m_time;
    ctx.step = m_step;
    ctx.groups = &m_groups;
}

void Simulation::chooseDt() {
    const TimeStep& ts = m_root->dt.get();
    if (m_dtOverride > 0) {
        m_dt = m_dtOverride;
    } else if (ts.automatic) {
        const auto [crit, limiting] = limitingForceField();
        if (!limiting)
            m_root->fail(m_root->dt, "dt=\"auto\" but no force field reports a stable time step; give dt in seconds");
        if (!(crit > 0) || !std::isfinite(crit * m_root->dtSafety.get()))
            limiting->fail("dt=\"auto\" but the stable time step it computes is " + formatNumber(crit, 6) +
                               " s, not a positive number: the wave speed of its material is not finite",
                           {"check the moduli (mu, E, bulk modulus) and the density: a modulus near the largest "
                            "double (1e308) overflows, and a zero density has no wave speed",
                            "or give dt in seconds on the root node"});
        // the integrators' own limits (ExplicitEuler's is not central difference's)
        const IntegratorLimit lim = integratorLimit();
        if (lim.integrator && !(lim.step > 0)) lim.integrator->fail("dt=\"auto\" finds no stable time step: " + lim.why);
        m_dt = std::min(crit, lim.step) * m_root->dtSafety.get();
    } else if (ts.value > 0) {
        m_dt = ts.value;
    }
    if (m_dt > 0) setDt(m_dt);
}

void Simulation::start() {
    if (!m_initialised) init();
    if (m_started) return;
    createOutputDir();
    m_started = true;
    fetchState();
    for (auto* o : m_observers) {
        ScopedTimer t(o->timer());
        o->observe(m_time, m_step);
    }
}

void Simulation::fetchState() const {
    // (a copy from the device into the host state: what the simulation is does not change)
    for (auto& g : const_cast<std::vector<MechanicalGroup>&>(m_groups))
        if (g.backend) g.backend->fetch(g);
}

double Simulation::criticalTimeStep() const { return limitingForceField().first; }

std::pair<double, const BaseForceField*> Simulation::limitingForceField() const {
    double crit = std::numeric_limits<double>::infinity();
    const BaseForceField* limiting = nullptr;
    for (auto& g : m_groups)
        for (auto* ff : g.forceFields)
            if (const double c = ff->stableTimeStep(*g.state); c < crit || (std::isnan(c) && !std::isnan(crit)))
                crit = c, limiting = ff;  // a NaN step is the worst: init names its force field
    return {crit, limiting};
}

Simulation::IntegratorLimit Simulation::integratorLimit() const {
    IntegratorLimit out;
    for (auto& g : m_groups) {
        double crit = std::numeric_limits<double>::infinity();
        for (auto* ff : g.forceFields) crit = std::min(crit, ff->stableTimeStep(*g.state));
        std::string why;
        const double s = g.integrator->stableTimeStep(crit, why);
        if (s < out.step || !(s > 0)) {
            out.step = s;
            out.integrator = g.integrator;
            out.why = why;
            if (!(s > 0)) break;
        }
    }
    return out;
}

void Simulation::setDt(double dt) { applyDt(dt, true); }

void Simulation::applyDt(double dt, bool warnAboveCritical) {
    if (!(dt > 0) || !std::isfinite(dt))
        throwInputError({}, "time step " + std::to_string(dt) + " s is not a positive number");
    m_dt = dt;
    m_snapshotStep = -1;  // a snapshot replays steps of one dt: the next step takes a new one
    m_snapshots.clear();
    m_timeAtDtChange = m_time;
    m_stepAtDtChange = m_step;
    m_root->context().dt = dt;
    // the force fields' critical step, over the groups whose integrator steps in time: a solver whose
    // stable step is infinite (DynamicRelaxation: dt is a load step, its iterations have their own
    // fictitious masses) is not warned
    double crit = std::numeric_limits<double>::infinity();
    const BaseForceField* limiting = nullptr;
    for (auto& g : m_groups) {
        double c = std::numeric_limits<double>::infinity();
        const BaseForceField* l = nullptr;
        for (auto* ff : g.forceFields)
            if (const double s = ff->stableTimeStep(*g.state); s < c) c = s, l = ff;
        std::string why;
        if (l && c < crit && g.integrator->stableTimeStep(c, why) < std::numeric_limits<double>::infinity()) crit = c, limiting = l;
    }
    if (warnAboveCritical && dt > crit)
        m_root->warn("dt = " + std::to_string(dt) + " s is above the critical time step " + std::to_string(crit) +
                     " s of " + limiting->className() + " '" + limiting->path() +
                     "': the explicit integration will likely be unstable (dt=\"auto\" picks a stable one)");
    else if (const IntegratorLimit lim = integratorLimit(); warnAboveCritical && lim.integrator && dt > lim.step)
        lim.integrator->warn(lim.step > 0 ? "dt = " + formatNumber(dt, 6) + " s is above its stable time step " + formatNumber(lim.step, 6) +
                                                " s (with its damping): the integration will likely be unstable (dt=\"auto\" picks a stable one)"
                                          : "no time step is stable: " + lim.why);
    for (Component* c : m_all) c->dtChanged(dt);
}

void Simulation::setOutputDir(const std::string& dir) {
    namespace fs = std::filesystem;
    std::error_code ec;
    // checked now, created by start(): a scene found invalid after loading leaves no folder behind
    if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
        throwOutputError({dir, 0}, "output folder '" + dir + "' is a file, not a folder", {"give --output a folder (it is created when missing)"});
    if (fs::exists(dir, ec)) {
        if (::access(dir.c_str(), W_OK | X_OK) != 0)
            throwOutputError({dir, 0}, "cannot write into output folder '" + dir + "': " + std::strerror(errno));
    } else {
        fs::path up = fs::absolute(dir, ec).parent_path();
        while (!up.empty() && !fs::exists(up, ec) && up != up.parent_path()) up = up.parent_path();
        if (!fs::is_directory(up, ec))
            throwOutputError({dir, 0}, "cannot create output folder '" + dir + "': " + std::strerror(ENOTDIR));
        if (::access(up.c_str(), W_OK | X_OK) != 0)
            throwOutputError({dir, 0}, "cannot create output folder '" + dir + "': " + std::strerror(errno));
    }
    m_root->context().outputDir = dir;
}

void Simulation::createOutputDir() const {
    const std::string& dir = m_root->context().outputDir;
    if (dir.empty()) return;
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throwOutputError({dir, 0}, "cannot create output folder '" + dir + "': " + ec.message());
}

const std::string& Simulation::outputDir() const { return m_root->context().outputDir; }

void Simulation::requireDt() const {
    if (!(m_dt > 0))
        throwInputError(m_root->loc(), "no time step: set dt on the root node (seconds or \"auto\") or pass --dt");
}

void Simulation::step() { advance(std::numeric_limits<double>::quiet_NaN()); }

void Simulation::advance(double end) {
    if (!m_initialised) init();
    requireDt();
    start();
    SceneContext& ctx = m_root->context();
    // observers that record the end of this step read the state: a device brings it back (and
    // checks it) within the step
    const bool recorded = !m_replaying && std::any_of(m_observers.begin(), m_observers.end(),
                                                      [&](const BaseObserver* o) { return o->records(m_step + 1); });
    try {
        // the divergence check's snapshot (the last good state is rebuilt from it: saveLastGoodState)
        if (!m_replaying && m_snapshotEvery > 0 && (m_snapshotStep < 0 || m_step - m_snapshotStep >= m_snapshotEvery))
            takeSnapshot();
        for (Component* c : m_all) c->beginStep(m_time, m_dt);
        for (auto& g : m_groups) {
            g.stepIndex = m_step + 1;
            if (g.backend) {
                ScopedTimer t(g.backend->timer());
                g.backend->step(g, m_time, m_dt);
                if (recorded) g.backend->fetch(g);
            } else {
                ScopedTimer t(g.integrator->timer());
                g.integrator->step(g, m_time, m_dt);
            }
            // (a backend checks the state it runs itself, on its device: BaseStepBackend)
            if (!g.backend) checkGroup(g);
        }
    } catch (const Error& e) {
        m_failed = true;  // finish() then records no final state
        if (!m_replaying && e.kind() == ErrorKind::Simulation) {
            // the last good state: before the run of growing steps that led here (checkStep's rule),
            // or before the first bad step a device found late (MechanicalGroup::firstBadStep)
            int back = 0;
            long bad = m_step + 1;
            for (const auto& g : m_groups) {
                back = std::max(back, std::min(g.kineticGrowth, MechanicalGroup::kGrowthSteps - 1));
                if (g.firstBadStep > 0) bad = std::min(bad, g.firstBadStep);
            }
            m_failedStep = bad;
            m_lastGoodStep = std::max(0L, std::min(m_step - long(back), bad - 1));
        }
        throw;
    } catch (...) {
        m_failed = true;
        throw;
    }
    ++m_step;
    m_time = m_timeAtDtChange + double(m_step - m_stepAtDtChange) * m_dt;  // no drift from summing dt
    if (!std::isnan(end)) {  // a run's last step ends on its end time exactly; later steps count from it
        m_time = end;
        m_timeAtDtChange = end;
        m_stepAtDtChange = m_step;
    }
    ctx.time = m_time;
    ctx.step = m_step;
    if (m_replaying) return;
    for (auto* o : m_observers) {
        ScopedTimer t(o->timer());
        o->observe(m_time, m_step);
    }
}

void Simulation::run(long steps) {
    if (!m_initialised) init();
    if (steps > 0) requireDt();  // before the observers write the initial state
    start();
    for (long i = 0; i < steps; ++i) step();
}

namespace {
/// Two times closer than this many steps are one (round-off of t0 + n dt).
constexpr double kTimeTolerance = 1e-9;
} // namespace

void Simulation::checkEndTime(double T) const {
    requireDt();
    // the end time itself, not the time left: a run that has less than one dt left to T takes one
    // shortened step, so the rule is the same before the first step and after any (a restart included)
    if (m_dt > T * (1 + kTimeTolerance))
        m_root->fail(m_root->dt.isSet() ? static_cast<const BaseParam&>(m_root->dt) : m_root->endTime,
                     "dt = " + formatNumber(m_dt, 6) + " s is larger than the end time " + formatNumber(T, 6) +
                         " s: not even one step fits",
                     {"make dt smaller than the end time, or the end time (endTime, --time) longer"});
}

long Simulation::stepsUntil(double T) const {
    if (!(m_dt > 0) || !(T > m_time)) return 0;
    const double n = std::ceil((T - m_time) / m_dt - kTimeTolerance);
    return n < 1 ? 0 : n > 9e18 ? std::numeric_limits<long>::max() : long(n);
}

void Simulation::stepToward(double T) {
    if (!m_initialised) init();
    requireDt();
    const double left = T - m_time, dt = m_dt;
    if (!(left > kTimeTolerance * dt)) return;
    if (left > dt * (1 + kTimeTolerance)) return step();
    // the last step: shortened to end on T, or a whole one when T is a multiple of dt up to round-off
    const bool shorten = left < dt * (1 - kTimeTolerance);
    if (shorten) applyDt(left, false);
    advance(T);
    if (shorten) applyDt(dt, false);
}

void Simulation::runUntil(double T) {
    if (!m_initialised) init();
    requireDt();
    if (!std::isfinite(T)) throwInputError({}, "end time " + std::to_string(T) + " s is not a finite number");
    checkEndTime(T);  // at every call (before the observers write the initial state on the first)
    start();
    while (T - m_time > kTimeTolerance * m_dt) stepToward(T);
}

void Simulation::finish() {
    if (m_finished || !m_initialised) return;
    m_finished = true;
    // the final state, whatever the observers' `every` (not after a failed step: its state is not one)
    if (m_started && !m_failed) {
        try {
            fetchState();  // (a device's state found not finite here is a failed run: no final state)
        } catch (...) {
            m_failed = true;
            for (Component* c : m_all) c->cleanup();
            throw;
        }
        for (auto* o : m_observers) {
            ScopedTimer t(o->timer());
            o->observeFinal(m_time, m_step);
        }
    }
    for (Component* c : m_all) c->cleanup();
}

BaseMechanicalState& Simulation::state(const std::string& nameOrPath) {
    auto* s = dynamic_cast<BaseMechanicalState*>(find(nameOrPath));
    if (!s) throwInputError({}, "no mechanical state '" + nameOrPath + "' in the scene");
    fetchState();
    return *s;
}

SurfaceView Simulation::surface(const std::string& nameOrPath) {
    Component* c = find(nameOrPath);
    fetchState();
    if (auto* v = dynamic_cast<BaseVisualSurface*>(c)) return {&v->points(), &v->triangles(), v->body()};
    auto* s = dynamic_cast<BaseMechanicalState*>(c);
    if (!s) throwInputError({}, "no mechanical state or visual surface '" + nameOrPath + "' in the scene");
    const BaseTopology* topo = s->node()->findInContext<BaseTopology>();
    if (!topo || topo->meshData().points.size() != s->size() || topo->boundaryTriangles().empty())
        throwInputError({}, "mechanical state '" + nameOrPath + "' has no boundary surface: it needs a mesh source with "
                                                            "volume elements and as many nodes in its context (MeshLoader, GridMesh)");
    return {&s->x(), &topo->boundaryTriangles(), s};
}

BaseTool& Simulation::tool(const std::string& nameOrPath) {
    Component* c = find(nameOrPath);
    auto* t = dynamic_cast<BaseTool*>(c);
    if (!t)
        throwInputError({}, c ? "the component '" + nameOrPath + "' is a " + c->className() + ", not a tool"
                              : "no tool '" + nameOrPath + "' in the scene",
                        {"a tool is a PlaneTool, SphereTool, CapsuleTool or SurfaceTool (plugin contact)"});
    return *t;
}

Component* Simulation::find(const std::string& nameOrPath) const { return m_root->findUnique(nameOrPath); }

std::vector<TimerRow> Simulation::timers() const {
    std::vector<TimerRow> rows;
    for (Component* c : m_all) rows.push_back({c->path(), c->className(), c->timer().seconds, c->timer().calls});
    std::sort(rows.begin(), rows.end(), [](const TimerRow& a, const TimerRow& b) { return a.path < b.path; });
    return rows;
}

} // namespace fascia::core
