#pragma once
/// The embedding API: load a scene, step it, read and write a state between steps.
///
/// ```
/// auto sim = fascia::core::Simulation::fromFile("scenes/heml/abdomen.xml");
/// auto& organ = sim->state("organ");          // a MechanicalObject by name or path
/// for (int i = 0; i < 500; ++i) {             // a haptic loop
///     organ.x()[tool] = devicePosition;       // write positions between steps
///     sim->step();
///     feedback = organ.reaction()[tool];      // read forces
/// }
/// auto skin = sim->surface("organ");          // the body's boundary triangles, for rendering
/// draw(*skin.points, *skin.triangles);        // (or a visual surface: sim->surface("visual"))
/// ```
#include "fascia/scene/Node.h"
#include "fascia/sim/Mechanics.h"

#include <cstdint>
#include <deque>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace fascia::core {

class StateWriter;
class StateReader;
class BaseTool;

/// A triangle surface to draw or export, valid until the scene changes: points (m) and triangles
/// indexing them, turned outwards. Read it between steps.
struct SurfaceView {
    const Positions* points = nullptr;
    const Triangles* triangles = nullptr;
    const BaseMechanicalState* body = nullptr;  ///< the state it moves with
};

struct TimerRow {
    std::string path, type;
    double seconds;
    long calls;
};

/// Settings applied before init (they change what init does).
struct LoadOptions {
    std::string outputDir;  ///< folder observers write into ("" = current directory)
    double dt = 0;          ///< overrides the root node's dt when > 0
};

class Simulation {
public:
    /// Builds and initialises the scene of a file; input errors are located fascia::core::Error.
    static std::unique_ptr<Simulation> fromFile(const std::string& path, const LoadOptions& options = {});
    /// Same from an XML string; locations use virtualName, relative paths baseDir.
    static std::unique_ptr<Simulation> fromString(const std::string& xml, const std::string& virtualName = "<string>",
                                                  const std::string& baseDir = ".", const LoadOptions& options = {});
    /// Takes a graph built in code; call init() before stepping.
    explicit Simulation(std::unique_ptr<Node> root);
    ~Simulation();

    /// Initialises every component (dependencies first), assembles the mechanical groups and
    /// resolves dt="auto". Writes nothing: observers see the initial state in start().
    void init();
    /// Lets the observers record the initial state (once; init() first when needed). step() and
    /// run() call it, so a scene found invalid after init (no dt, too many steps) leaves no file.
    void start();
    /// Applies options (call before init).
    void configure(const LoadOptions& options);
    /// One step of dt: for each group: clear forces, forces, constraints, integrate; then observers.
    void step();
    void run(long steps);
    /// Runs to the time T exactly: steps of dt, the last one shortened to end on T (every component
    /// hears the shorter dt through dtChanged, and dt again after it), so that time() == T after it.
    /// A dt larger than T itself is a located error at every call (checkEndTime); with less than one
    /// dt left to T it takes one shortened step. Nothing else happens when T <= time().
    void runUntil(double T);
    /// One step toward T: a step of dt, or the last one, shortened to end on T exactly when T is less
    /// than one dt away (a whole step when T is a multiple of dt up to 1e-9 dt).
    void stepToward(double T);
    /// The number of steps runUntil(T) takes from the current time.
    long stepsUntil(double T) const;
    /// The located error for an end time T shorter than one step (dt > T), whatever time() is.
    void checkEndTime(double T) const;
    /// Lets every observer record the final state (whatever its `every`), then calls every
    /// component's cleanup (once). After a failed step the observers record nothing more.
    void finish();

    double time() const { return m_time; }
    long stepCount() const { return m_step; }
    double dt() const { return m_dt; }
    void setDt(double dt);
    /// Folder observers write into (default: the current directory). Checked at once (an output error
    /// at {dir, 0} when it is a file, or cannot be written or created), created by start().
    void setOutputDir(const std::string& dir);
    const std::string& outputDir() const;

    Node& root() { return *m_root; }
    /// A mechanical state by name or path ("organ", "/root/liver/mo"); throws when there is none.
    /// With a step backend that keeps the state on a device (CudaStep), it first brings every state
    /// to the host (fetchState).
    BaseMechanicalState& state(const std::string& nameOrPath);
    /// Brings every group's x and v to the host when a step backend keeps them on a device
    /// (BaseStepBackend::fetch; nothing otherwise). state() and surface() call it, and so do the
    /// observers' steps, checkpoints and finish(); a program that keeps a reference to a state and
    /// reads it after later steps calls it first. What it then writes into x and v between steps
    /// is what the next step starts from, as on the host.
    void fetchState() const;
    /// A surface by name or path: for a mechanical state, its boundary (points: the state's x(),
    /// triangles: the boundary triangles of the mesh source in its context,
    /// BaseTopology::boundaryTriangles); for a visual surface (BaseVisualSurface, e.g.
    /// BarycentricSurfaceMapping), its moved vertices and triangles. Throws when there is none.
    SurfaceView surface(const std::string& nameOrPath);
    /// A rigid tool (fascia/sim/Tool.h) by name or path ("probe", "/root/probe"); throws an input
    /// error when there is none or the component of that name is no tool.
    BaseTool& tool(const std::string& nameOrPath);
    /// Any component by name or path; null when there is none.
    Component* find(const std::string& nameOrPath) const;
    const std::vector<MechanicalGroup>& groups() const { return m_groups; }
    /// Smallest stable time step of every force field (infinity when none).
    double criticalTimeStep() const;

    /// Time spent in each component, sorted by path.
    std::vector<TimerRow> timers() const;

    // ---- checkpoint and restart (core/src/SimulationState.cpp; the format: docs/design.md, section 1)

    /// Writes the whole state between steps to `path`, atomically (written to `path.tmp` in the same
    /// folder, fsync'ed, renamed over `path`): the time, the step, dt and the origin of the time
    /// (the last dt change), every component's saveState() records (positions, velocities, forces,
    /// integrator histories, Prony states, observer counters ...) and the scene hash. A file that
    /// cannot be written is an output error (exit 1).
    void save(const std::string& path) const;
    /// Loads a checkpoint that save() wrote, into this simulation: call it after init() (fromFile and
    /// fromString do it) and before the first step. It checks the magic, the format version, the byte
    /// order, the size, the checksum, the scene hash (the same scene: every component's parameters and
    /// every mesh file's content), then each component's records by name and size, and that every
    /// record was read; each failure is an input error (exit 2) naming the file and, where known, the
    /// component and the record. Nothing is written: the observers continue their files (the .pvd
    /// lists the earlier files, a Monitor's CSV is cut back to its length at the checkpoint and
    /// appended to) at their next record, and start() records no initial state. The run then goes
    /// on bitwise as the one that wrote the checkpoint. When this scene's dt differs from the saved one
    /// (another dt attribute, --dt, dt="auto" with another dtSafety), the run continues with the new dt
    /// from the checkpoint's time, as after setDt. A failed restore leaves the simulation unusable.
    void restore(const std::string& path);
    /// The scene hash a checkpoint carries: hashBytes (fascia/base/StateIO.h) over, for every node
    /// and component in scene order, its path, class and parameters (name and value as text, or the
    /// link "@..." it reads; output parameters left out; the root's dt, dtSafety and endTime left out,
    /// since a restart may change how far and with which step it runs), and for a file parameter
    /// (MeshLoader's filename) the content of the file. Computed once.
    std::uint64_t sceneHash() const;

    /// The divergence check keeps a snapshot of the state (in memory, the checkpoint's records minus
    /// the observers') every `steps` steps (default kSnapshotEvery; 0: none, and no last good state),
    /// and after any dt change. After a step fails (a simulation error: NaN, a kinetic energy growing
    /// without bound, an integrator or force field that gives up), saveLastGoodState() rebuilds the state
    /// at the start of the failing step by restoring the snapshot and replaying the steps since it
    /// with the observers muted (bitwise the same steps: docs/design.md, principle 5). Cost: one
    /// serialisation per `steps` steps instead of a copy per step. An embedding program that writes
    /// the state between steps (positions, external forces) makes the replay differ: it sets 1 (a
    /// snapshot before every step, no replay).
    void setSnapshotEvery(long steps);
    static constexpr long kSnapshotEvery = 100;
    static constexpr size_t kSnapshotsKept = 5;
    /// After a failed step: writes the last good state as a checkpoint to `path` (see save) and
    /// returns its step number; the simulation is then at that state. The last good state is the
    /// start of the failing step, or, when the kinetic energy was growing past the growth rule's
    /// factor at the steps before it, the start of the first of them (a state the unstable mode has
    /// not yet amplified: MechanicalGroup::checkStep); no earlier than the oldest snapshot kept (the
    /// last kSnapshotsKept). -1 when there is no failed step or no snapshot (setSnapshotEvery(0)).
    long saveLastGoodState(const std::string& path);
    /// The step that failed (1-based), -1 when none.
    long failedStep() const { return m_failedStep; }

private:
    /// Creates the output folder (start() does, when the scene is known to be valid).
    void createOutputDir() const;
    /// The smallest stable time step and the force field that sets it (null when none does).
    std::pair<double, const BaseForceField*> limitingForceField() const;
    /// The smallest integrator step (BaseIntegrator::stableTimeStep) over the groups, the integrator
    /// giving it (null without groups) and, for a step of 0, why none is stable.
    struct IntegratorLimit {
        double step = std::numeric_limits<double>::infinity();
        const BaseIntegrator* integrator = nullptr;
        std::string why;
    };
    IntegratorLimit integratorLimit() const;
    /// The located "no time step" error when dt is not set.
    void requireDt() const;
    /// init's time step, set with setDt: the load options' dt, else for dt="auto" the smallest stable
    /// step of the force fields and integrators times dtSafety, else the root's dt (none: unset).
    void chooseDt();
    /// Sets dt, warning above the critical step when asked; every component hears it.
    void applyDt(double dt, bool warnAboveCritical);
    /// One step of dt; when `end` is a number, the time after it is exactly `end` (a run's last step).
    void advance(double end);
    /// The checks after a group's step (MechanicalGroup::checkStep), their error completed with the
    /// time, the worst element and a stable dt.
    void checkGroup(MechanicalGroup& g);
    /// "; at t = ...; worst element ...; a stable dt: ..." for a group that diverged.
    std::string divergenceDiagnosis(const MechanicalGroup& g) const;
    /// The state records (the Simulation's and every component's, observers too unless `observers` is
    /// false) into w.
    void writeState(StateWriter& w, bool observers) const;
    /// Reads what writeState wrote (`observers` as it was written).
    void readState(StateReader& r, bool observers);
    void takeSnapshot();
    std::unique_ptr<Node> m_root;
    std::vector<MechanicalGroup> m_groups;
    std::vector<BaseObserver*> m_observers;
    std::vector<Component*> m_all;
    double m_time = 0.0, m_dt = 0.0, m_dtOverride = 0.0;
    long m_step = 0;
    double m_timeAtDtChange = 0.0;  ///< time and step of the last dt change: time = t0 + (step - s0) dt
    long m_stepAtDtChange = 0;
    bool m_initialised = false, m_started = false, m_finished = false, m_failed = false;
    bool m_replaying = false;           ///< saveLastGoodState's replay: observers muted
    long m_snapshotEvery = kSnapshotEvery, m_snapshotStep = -1, m_failedStep = -1, m_lastGoodStep = -1;
    /// the last kSnapshotsKept snapshots (step, records of writeState(.., false)), oldest first
    std::deque<std::pair<long, std::string>> m_snapshots;
    mutable std::uint64_t m_sceneHash = 0;
    mutable std::string m_sceneLines;   ///< "path hash" per node and component, for the mismatch message
    mutable bool m_haveSceneHash = false;
};

} // namespace fascia::core
