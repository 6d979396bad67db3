#pragma once
/// The roles a component plays in the simulation loop. Plugins derive from these; the core knows
/// nothing of any physics beyond them.
#include "fascia/base/Component.h"
#include "fascia/sim/LoadCurve.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace fascia::core {

/// A mesh source (MeshLoader, GridMesh ...): states, masses and force fields in its context
/// take their points and elements from it when not linked explicitly.
class BaseTopology : public Component {
public:
    virtual const MeshData& meshData() const = 0;
    /// The boundary of the volume elements: the faces that only one tetrahedron or hexahedron has,
    /// turned outwards (normal (b - a) x (c - a) out of the body; a hexahedron's quadrilateral split
    /// in two), node indices of meshData().points. Filled by the mesh source's init; empty before.
    /// The body's surface for rendering and output (Simulation::surface, VTKExporter surface="true").
    const Triangles& boundaryTriangles() const { return m_boundary; }
    /// A mesh source reads files or parameters only.
    std::vector<Component*> dependencies() const override { return {}; }

protected:
    Triangles m_boundary;
};

/// Node data of one deformable body: positions, rest positions, velocities, forces, reactions.
/// Storage lives here so the loop reads it without virtual calls.
class BaseMechanicalState : public Component {
public:
    size_t size() const { return m_x.size(); }
    Positions& x() { return m_x; }               ///< current positions (m)
    Positions& v() { return m_v; }               ///< velocities (m/s)
    Positions& f() { return m_f; }               ///< accumulated forces (N)
    Positions& x0() { return m_x0; }             ///< rest positions (m)
    Positions& reaction() { return m_reaction; } ///< reaction forces on constrained nodes (N)
    /// External forces (N) added to every step's forces until changed: what an embedding program
    /// (a haptic loop) writes between steps. Zero unless written.
    Positions& externalForce() { return m_external; }
    const Positions& x() const { return m_x; }
    const Positions& v() const { return m_v; }
    const Positions& f() const { return m_f; }
    const Positions& x0() const { return m_x0; }
    const Positions& reaction() const { return m_reaction; }
    const Positions& externalForce() const { return m_external; }
    /// Resizes every array to n nodes (positions copied from rest, velocities and forces zero).
    void resize(size_t n);
    /// x, v, f, x0, the reactions and the external forces (records of the state's size: a restore
    /// into a state of another size is an error naming the record). The force and reaction of the
    /// last step are saved too: exporters write them.
    void saveState(StateWriter& out) const override;
    void restoreState(StateReader& in) override;

protected:
    Positions m_x, m_v, m_f, m_x0, m_reaction, m_external;
};

/// A per-element field a force field offers to exporters and monitors.
struct CellField {
    std::string name;            ///< "J", "vonMises", "S" ...
    int components = 1;          ///< 1 scalar, 6 symmetric tensor (xx yy zz xy yz xz), 9 tensor
    std::string unit;
    std::vector<double> values;  ///< components * elements
};

/// One element of a force field, for the messages of a diverging run (BaseForceField::worstElement).
struct ElementReport {
    long index = -1;                 ///< element number (the force field's cell order: tetrahedra, then hexahedra)
    double J = 0;                    ///< volume ratio det F at the current positions (NaN when they are not finite)
    Vec3 centroid = Vec3::Zero();    ///< centroid of its rest positions (m)
};

/// True when element a is a worse culprit of a divergence than b: a non-finite J first, then the
/// smaller J of two inverted or flat ones (J <= 0), then the larger |ln J|.
inline bool worseElement(const ElementReport& a, const ElementReport& b) {
    auto rank = [](double J) { return !std::isfinite(J) ? 2 : J <= 0 ? 1 : 0; };
    const int ra = rank(a.J), rb = rank(b.J);
    if (ra != rb) return ra > rb;
    if (ra == 2) return false;
    if (ra == 1) return a.J < b.J;
    return std::abs(std::log(a.J)) > std::abs(std::log(b.J));
}

/// Nodal masses (kg) for the state in its context.
class BaseMass : public Component {
public:
    const std::vector<double>& nodalMasses() const { return m_masses; }
    /// Mass density (kg/m^3) where the mass comes from one, else NaN (force fields use it for wave speeds).
    virtual double density() const { return std::numeric_limits<double>::quiet_NaN(); }
protected:
    std::vector<double> m_masses;
};

/// Adds forces to the state in its context (internal elastic forces, loads).
class BaseForceField : public Component {
public:
    /// f += forces at the state's current positions and velocities at time t.
    virtual void addForce(BaseMechanicalState& state, Positions& f, double t) = 0;
    /// Potential (strain) energy at the current positions, J; NaN when not offered.
    virtual double potentialEnergy(const BaseMechanicalState& state) const {
        return std::numeric_limits<double>::quiet_NaN();
    }
    /// Largest stable explicit time step (s); infinity when it imposes none.
    virtual double stableTimeStep(const BaseMechanicalState& state) const {
        return std::numeric_limits<double>::infinity();
    }
    /// Per-element data for exporters (J, stresses ...), computed at the current state.
    virtual void cellData(const BaseMechanicalState& state, std::vector<CellField>& out) const {}
    /// Number of elements cellData refers to.
    virtual size_t elementCount() const { return 0; }
    /// The element most likely to have caused a divergence, at the state's current positions: one
    /// whose J is not finite, else the smallest J when one is inverted or flat (J <= 0), else the one
    /// with the largest |ln J|. False when it has no elements (the default). Element force fields
    /// implement it with elements::worstTetrahedron / worstElement (fascia/elements/Geometry.h).
    virtual bool worstElement(const BaseMechanicalState& state, ElementReport& out) const { return false; }
    /// True for the element force fields whose elements exporters write as cells.
    virtual const Tetrahedra* tetrahedra() const { return nullptr; }
    virtual const Hexahedra* hexahedra() const { return nullptr; }
};

/// Boundary conditions on the state in its context.
class BaseConstraint : public Component {
public:
    /// Imposes positions at time t (prescribed motion); fixed nodes keep their rest positions.
    virtual void projectPositions(BaseMechanicalState& s, double t) {}
    /// Imposes velocities at time t.
    virtual void projectVelocities(BaseMechanicalState& s, double t) {}
    /// Zeroes the constrained force components, of constrainedNodes() only. The group records the
    /// reactions (minus the removed force, summed over every constraint) itself, at those nodes.
    virtual void projectForces(BaseMechanicalState& s) {}
    /// Nodes this constraint acts on (for the reactions and reaction-force monitors).
    virtual const IndexList& constrainedNodes() const = 0;
    /// Axes it holds (x, y, z): a monitor of its reaction sums only these components.
    virtual std::array<bool, 3> constrainedAxes() const { return {true, true, true}; }
    /// True when it moves its nodes along a prescribed path (PrescribedDisplacement), false when it
    /// holds them at rest (FixedConstraint). Two constraints on one node and axis are an input error
    /// (Simulation::init) when either prescribes motion; two that hold it at rest agree.
    virtual bool prescribesMotion() const { return false; }
};

struct MechanicalGroup;

/// Node loops of the framework (forces, integrators, checks) run on the OpenMP threads above this
/// many nodes; below it a parallel region costs more than it saves (docs/performance.md, lesson 13).
constexpr long kParallelNodes = 2048;

/// Nodes per chunk of forEachNodeRange: fixed (never the thread count), so that every node goes
/// through the same code path (vector body or remainder) for any number of threads.
constexpr long kNodeChunk = 1024;

/// Runs body(lo, hi) over [0, n) in chunks of kNodeChunk nodes, on the OpenMP threads above
/// kParallelNodes. For node loops written over the flat arrays (flat()): GCC vectorises those
/// better than loops of Eigen Vec3 expressions (docs/performance.md, lesson 13).
template <class Body>
inline void forEachNodeRange(long n, Body&& body) {
    const long chunks = (n + kNodeChunk - 1) / kNodeChunk;
    if (n > kParallelNodes) {
#pragma omp parallel for schedule(static)
        for (long c = 0; c < chunks; ++c) body(c * kNodeChunk, std::min(n, (c + 1) * kNodeChunk));
    } else {
        for (long c = 0; c < chunks; ++c) body(c * kNodeChunk, std::min(n, (c + 1) * kNodeChunk));
    }
}

/// The sum of body(lo, hi) over the same chunks as forEachNodeRange, on the OpenMP threads above
/// kParallelNodes (a reduction: for checks over every node, not for results that must be bitwise
/// reproducible).
template <class Body>
inline double sumNodeRange(long n, Body&& body) {
    const long chunks = (n + kNodeChunk - 1) / kNodeChunk;
    double sum = 0;
    if (n > kParallelNodes) {
#pragma omp parallel for schedule(static) reduction(+ : sum)
        for (long c = 0; c < chunks; ++c) sum += body(c * kNodeChunk, std::min(n, (c + 1) * kNodeChunk));
    } else {
        for (long c = 0; c < chunks; ++c) sum += body(c * kNodeChunk, std::min(n, (c + 1) * kNodeChunk));
    }
    return sum;
}

/// Runs body(i) for i in [0, n), chunk by chunk through forEachNodeRange (on the OpenMP threads
/// above kParallelNodes; below it no parallel region at all: even an inactive one costs more than a
/// small loop, docs/performance.md, lesson 13).
template <class Body>
inline void forEachNode(long n, Body&& body) {
    forEachNodeRange(n, [&](long lo, long hi) {
        for (long i = lo; i < hi; ++i) body(i);
    });
}

static_assert(sizeof(Vec3) == 3 * sizeof(double), "node arrays are read as 3 doubles per node");
/// The node array as 3 n doubles (x y z of node i at 3 i).
inline double* flat(Positions& p) { return p.empty() ? nullptr : p.data()->data(); }
inline const double* flat(const Positions& p) { return p.empty() ? nullptr : p.data()->data(); }

/// Advances the states of its subtree by one step.
class BaseIntegrator : public Component {
public:
    virtual void step(MechanicalGroup& group, double t, double dt) = 0;
    /// One line on what the run did, for fascia-run's summary ("" when there is nothing to say,
    /// as for the explicit integrators; a static solver reports its load steps and iterations).
    virtual std::string runSummary() const { return {}; }
    /// True when the run did not do what it was asked (a static solver with a load step that did
    /// not converge): fascia-run then exits 3 after writing its files.
    virtual bool runFailed() const { return false; }
    /// The largest time step (s) for which it is stable on a group whose force fields give the
    /// critical step `critical` (the smallest BaseForceField::stableTimeStep, central difference's
    /// limit 2 / omega_max; infinity when no force field limits the step). dt="auto" is the smallest
    /// over the groups times dtSafety, and a larger dt is warned. Default: critical. 0 when no step is
    /// stable (forward Euler without damping); `why` then says why and what to do. Infinity for a
    /// solver that does not integrate in time (a static solver, whose dt is a load step): its group's
    /// dt is then checked against neither this nor the force fields' critical step.
    virtual double stableTimeStep(double critical, std::string& why) const { return critical; }
};

/// Reads the scene after each step (exporters, monitors).
class BaseObserver : public Component {
public:
    /// Called once after init with the initial state, then after every step.
    virtual void observe(double t, long step) = 0;
    /// Called once at the end of a run (Simulation::finish) with the final state, whatever the steps
    /// observe() skipped: an observer that records only some steps records this one too, unless it
    /// already did at this step.
    virtual void observeFinal(double t, long step) {}
    /// Whether observe(t, step) reads the state at this step (an observer with `every` skips
    /// steps): a step backend that keeps the state on a device (BaseStepBackend::fetch) brings it
    /// to the host only for steps that some observer records. Default: every step.
    virtual bool records(long step) const { return true; }
};

class BaseStepBackend;

/// A triangle surface that moves with a body, updated after every step as an observer: a finer
/// visual surface mapped onto the body (meshio's BarycentricSurfaceMapping). Read it between steps
/// through Simulation::surface. Storage lives here so that readers need no plugin header.
class BaseVisualSurface : public BaseObserver {
public:
    const Positions& points() const { return m_points; }      ///< current vertex positions (m)
    const Triangles& triangles() const { return m_triangles; }  ///< vertex indices, turned outwards
    /// The state the surface follows (null before init).
    virtual const BaseMechanicalState* body() const = 0;

protected:
    Positions m_points;
    Triangles m_triangles;
};

/// The team of the threaded step (ThreadedStep.h), chosen from the measured steps: all the OpenMP
/// threads, or one thread when the steps measured on one are faster (another process holds a core:
/// a thread preempted while it holds a task of the step team stalls the step, StepTeam.h,
/// docs/performance.md, lesson 17). The
/// results are bitwise the same either way (principle 5), so switching costs nothing but the probes:
/// every `interval` steps it runs kProbe steps on the other team, and switches when the mean of
/// those steps is 10 % below the mean of the current team's recent steps; the interval doubles (up to 1,024 steps) while the choice stands.
/// Four things keep a loaded run from paying for many slow steps before it switches: the first
/// probe comes after kFirstProbe steps; a probe whose first step takes twice the current team's
/// mean ends there (the other team is clearly slower); a step of the current team that takes more
/// than twice the median of the other team's last steps brings the next probe forward to the next
/// step (the load came back); and so does a current team whose last kKeep steps take on average
/// more than 1.25 times that median (a lasting slowdown, such as a scheduler that put the threads
/// on the loaded core), at most once every kKeep steps. Medians, not means, of the other team:
/// one stalled step in a probe of three (a worker preempted while it held a task) no longer hides
/// that team for the rest of the run (docs/performance.md, "a step team of our own", its two
/// traces). After a probe 3 times slower than the current team the interval grows 4 times instead
/// of 2 (each such probe step costs milliseconds).
struct TeamChoice {
    static constexpr int kKeep = 8, kProbe = 3, kFirstProbe = 4;
    double seconds[2][kKeep] = {};  ///< recent step times (s) per team: [0] one thread, [1] all
    int count[2] = {0, 0};          ///< samples recorded per team (the ring holds the last kKeep)
    int current = 1;                ///< the team of ordinary steps
    long step = 0, nextProbe = kFirstProbe, interval = 16;
    int probing = 0;                ///< probe steps left
    long lastProbe = 0;             ///< the step the last probe ended
    /// The team of the next step: 0 one thread, 1 all.
    int choose();
    /// The time of a step just run on team `team` (as choose() gave it).
    void record(int team, double s);
    double mean(int team) const;
    double median(int team) const;
};
/// Whether the threaded step picks its team from measured steps (TeamChoice; default true,
/// FASCIA_ADAPTIVE_TEAM=0 in the environment turns it off): off, it always runs on all threads.
void setAdaptiveTeam(bool on);
bool adaptiveTeamEnabled();

/// One state with everything acting on it, as assembled by the simulation for its integrator.
struct MechanicalGroup {
    BaseIntegrator* integrator = nullptr;
    BaseMechanicalState* state = nullptr;
    std::vector<BaseForceField*> forceFields;
    std::vector<BaseMass*> masses;
    std::vector<BaseConstraint*> constraints;
    Vec3 gravity = Vec3::Zero();
    const Curve* gravityCurve = nullptr;  ///< scales gravity: g(t) = c(t) gravity (null: 1)
    std::vector<double> mass;      ///< summed nodal masses
    std::vector<double> invMass;   ///< 1/mass (0 where the mass is 0)
    long stepIndex = 0;            ///< the step being computed (for messages)

    /// f = sum of force fields + c(t) m gravity + external forces, then constraints project it; the
    /// reaction of a constrained node is minus the force the constraints removed (the static
    /// support force: the inertia of prescribed motion is not included).
    void computeForces(double t);
    Positions beforeConstraints;   ///< scratch for the reactions: f at reactionNodes before the constraints
    IndexList reactionNodes;       ///< the constrained nodes of the last computeForces
    /// The norm |f| of the free nodal forces at the current positions and time t: what
    /// computeForces leaves in f (every force, the constrained components removed), 0 at an
    /// equilibrium. Evaluates the forces once more; the state's f and reactions are left as they were.
    double residualNorm(double t);
    /// Applies the constraints' positions and velocities at time t.
    void projectState(double t);
    /// Throws a simulation error naming the step and the component when x, v or f holds NaN/inf.
    void checkFinite(double t);

    /// The divergence check after each step: checkFinite's test, and the kinetic energy
    /// 1/2 sum m |v|^2 (summed over fixed chunks in order: the same for any thread count) against
    /// the growth rule. A run diverges when the kinetic energy exceeds kGrowthFactor times its largest
    /// value of every earlier step at kGrowthSteps consecutive steps (a growth of 10^4 in 4 steps):
    /// an explicit step above the critical one multiplies it by about (omega dt)^4 per step (some 10^3
    /// at three times the critical step), while a load from rest cannot: a force ramping up from rest
    /// as t^3 (the 3-4-5 smooth curve) gives a kinetic energy growing as t^8, whose ratio
    /// ((n + 1) / n)^8 is below 10 from the fourth step on. A kinetic energy of 0 never counts.
    /// Throws a simulation error naming the state, the step and the growth.
    void checkStep(double t);
    static constexpr double kGrowthFactor = 10.0;
    static constexpr int kGrowthSteps = 4;
    double kinetic = 0;          ///< kinetic energy after the last step (J)
    double kineticMax = 0;       ///< its largest value over the earlier steps (J)
    int kineticGrowth = 0;       ///< consecutive steps it grew past kGrowthFactor kineticMax
    std::vector<double> chunkSums; ///< scratch of checkStep: per chunk of nodes, the finite probe and the energy
    /// Runs the group's whole step instead of the integrator (a GPU backend, BaseStepBackend), or
    /// null. The integrator still gives the group's stable time step and its parameters. (Last, so
    /// that the members plugins built before it read keep their offsets.)
    BaseStepBackend* backend = nullptr;
    /// Set by a backend that checks the state on its device only every few steps: the first step
    /// whose result was not finite (-1: none). The last good state is then the start of that step.
    long firstBadStep = -1;

    // The pieces of computeForces and checkStep that the threaded step (ThreadedStep.h) runs by chunks.
    /// What f starts from at time t: the external forces and c(t) g where present.
    struct ForceStart {
        bool ext = false, gravity = false;
        double g[3] = {0, 0, 0};
    };
    ForceStart forceStart(double t) const;
    /// f = external forces + m c(t) g at the nodes [lo, hi).
    void initialForces(const ForceStart& s, long lo, long hi);
    /// The constrained nodes of this step (reactionNodes, from every constraint's list), their old reactions zeroed.
    void prepareReactions();
    /// Every constraint's projectForces, and the reactions at reactionNodes (what it removed).
    void applyConstraints();
    /// checkStep's sums over chunk c (nodes [lo, hi)): the finite probe of x and v and the kinetic energy.
    void checkChunk(long c, long lo, long hi);
    /// Per chunk of kNodeChunk nodes: 1 where the threaded step already computed checkStep's sums
    /// (chunkSums); empty otherwise. checkStep computes the others and empties it.
    std::vector<char> chunkReady;
    TeamChoice team;  ///< the threaded step's team
};

/// Runs whole steps of mechanical groups elsewhere than in the integrators' host loops (the cuda
/// plugin's CudaStep: forces, constraints and the update on a GPU). At most one, in the root node,
/// so that the device is chosen in one place (docs/design.md, section 4.7). After the groups are
/// assembled and their masses summed, Simulation::init calls adopt() for each group; a backend that
/// cannot run a component of the group fails located at that component (never a silent fallback
/// to the host). Then step() replaces integrator->step() for that group. The integrator stays the
/// group's: it still gives the stable time step, and its parameters say what to run.
/// A backend may keep the state on its device between steps. The Simulation then calls fetch()
/// before anything on the host reads x and v (observers that record the step, within the step;
/// Simulation::state and surface; checkpoints and snapshots; finish) and push() after it wrote them
/// (a restore, a replay). The backend checks the state it runs for divergence itself (the host's
/// checkStep is not run on its groups): a state that is not finite is a simulation error from
/// step() or fetch(), with MechanicalGroup::firstBadStep set when it was found steps late.
class BaseStepBackend : public Component {
public:
    virtual void adopt(MechanicalGroup& group) = 0;
    virtual void step(MechanicalGroup& group, double t, double dt) = 0;
    /// Brings the device's state to the group's host x and v (nothing when they are current). A
    /// program may then write x and v between steps: the next step takes what it finds there.
    virtual void fetch(MechanicalGroup& group) {}
    /// The host state was set (a restore or a replay from a snapshot): the device takes it.
    virtual void push(MechanicalGroup& group) {}
    /// Waits until the steps it queued on its device are done (a benchmark's timing window).
    virtual void wait() {}
};

} // namespace fascia::core
