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

#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace fascia::core {

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
    /// On a run that has not stepped yet, a dt larger than T - time() is a located error
    /// (checkEndTime). Nothing happens when T <= time().
    void runUntil(double T);
    /// One step toward T: a step of dt, or the last one, shortened to end on T exactly when T is less
    /// than one dt away (a whole step when T is a multiple of dt up to 1e-9 dt).
    void stepToward(double T);
    /// The number of steps runUntil(T) takes from the current time.
    long stepsUntil(double T) const;
    /// The located error for an end time T shorter than one step (dt > T - time()).
    void checkEndTime(double T) const;
    /// Lets every observer record the final state (whatever its `every`), then calls every
    /// component's cleanup (once). After a failed step the observers record nothing more.
    void finish();

    double time() const { return m_time; }
    long stepCount() const { return m_step; }
    double dt() const { return m_dt; }
    void setDt(double dt);
    /// Folder observers write into (default: the current directory).
    void setOutputDir(const std::string& dir);
    const std::string& outputDir() const;

    Node& root() { return *m_root; }
    /// A mechanical state by name or path ("organ", "/root/liver/mo"); throws when there is none.
    BaseMechanicalState& state(const std::string& nameOrPath);
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

private:
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
    /// Sets dt, warning above the critical step when asked; every component hears it.
    void applyDt(double dt, bool warnAboveCritical);
    /// One step of dt; when `end` is a number, the time after it is exactly `end` (a run's last step).
    void advance(double end);
    std::unique_ptr<Node> m_root;
    std::vector<MechanicalGroup> m_groups;
    std::vector<BaseObserver*> m_observers;
    std::vector<Component*> m_all;
    double m_time = 0.0, m_dt = 0.0, m_dtOverride = 0.0;
    long m_step = 0;
    double m_timeAtDtChange = 0.0;  ///< time and step of the last dt change: time = t0 + (step - s0) dt
    long m_stepAtDtChange = 0;
    bool m_initialised = false, m_started = false, m_finished = false, m_failed = false;
};

} // namespace fascia::core
