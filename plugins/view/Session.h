#pragma once
/// A scene running for a viewer: the simulation steps on its own thread (or, in tests and for
/// pictures, on the caller's) while a render thread takes frames between steps. The render side
/// only posts commands (play, pause, step, reset, grab a node, move a tool) and takes the latest
/// frame; the simulation side applies the commands between two steps and copies a frame out only
/// when one was asked for since the last, so the simulation runs at its own rate, never at the
/// frame rate (docs/viewer.md).
#include "Frame.h"

#include <atomic>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

namespace fascia::view {

struct SessionOptions {
    std::string scene;
    core::LoadOptions load;
    Field field = Field::Displacement;
    std::string surface;          ///< the surface to show ("" every body's)
    /// The grab spring's stiffness (N/m); 0: a quarter of the grabbed node's mass over dt^2 (stiff
    /// enough to pull the node with the cursor, far from the explicit stability limit 4 m/dt^2).
    double grabStiffness = 0;
};

struct SessionStats {
    double msPerStep = 0;         ///< wall time per step over the last second of stepping
    double realTimeFactor = 0;    ///< simulated time over wall time, same window
    double stepsPerFrame = 0;     ///< steps between the last two frames taken
    bool playing = false;
    long steps = 0;               ///< steps since the session (or its last reset) began
    double stepWall = 0;          ///< their wall time (s)
    std::string error;            ///< the message of a failed step (the session then pauses)
};

class Session {
public:
    /// Loads the scene (a located core::Error when it is bad) and captures the first frame.
    explicit Session(const SessionOptions& options);
    ~Session();

    // ---- the render side (any thread)
    void play(bool on);
    bool playing() const { return m_playing; }
    void stepOnce();
    /// Reloads the scene from its file at the next turn of the simulation loop.
    void reset();
    /// Grabs surface point `point` of body `body` with a spring towards `target`.
    void grab(int body, int point, const Vec3& target);
    void moveGrab(const Vec3& target);
    void release();
    /// Moves tool k (FrameSource::tools order) to `pose` before the next step.
    void moveTool(size_t k, const core::Pose& pose);
    /// The newest frame, swapped into `out` when there is one newer than the last taken; asks the
    /// simulation side for the next one. False when none is newer.
    bool takeFrame(Frame& out);
    SessionStats stats() const;
    size_t toolCount() const { return m_toolCount; }
    std::string toolName(size_t k) const;

    // ---- the simulation side
    /// Starts the simulation thread (play() then runs it).
    void start();
    /// Stops and joins the simulation thread (the destructor does too).
    void stop();
    /// Runs n steps on the calling thread (no simulation thread running), applying the pending
    /// commands before each, then publishes a frame. Tests and pictures use it.
    void advance(long n);
    /// The simulation (call only when no simulation thread runs, or from it).
    core::Simulation& simulation() { return *m_sim; }
    /// The grab force of the last step (N), zero without a grab.
    Vec3 grabForce() const;

private:
    void load();
    void loop();
    /// Applies the commands posted since the last turn (reset, tool poses, the grab spring).
    void applyCommands();
    /// One step, timed; a failed step pauses and records its message. False when it failed.
    bool stepTimed();
    void publish();

    SessionOptions m_options;
    std::unique_ptr<core::Simulation> m_sim;
    std::unique_ptr<FrameSource> m_source;
    size_t m_toolCount = 0;
    std::vector<std::string> m_toolNames;

    mutable std::mutex m_mutex;        ///< guards everything below shared by the two sides
    std::condition_variable m_wake;
    bool m_quit = false, m_resetAsked = false;
    long m_stepsAsked = 0;
    std::atomic<bool> m_playing{false};
    std::atomic<bool> m_frameAsked{true};
    struct Grab {
        bool active = false;
        int body = -1, point = -1;
        Vec3 target = Vec3::Zero();
    } m_grab;
    std::vector<std::optional<core::Pose>> m_poses;
    Frame m_front, m_back;
    long m_frameVersion = 0, m_takenVersion = 0;
    long m_stepsAtLastFrame = 0;
    SessionStats m_stats;

    // the simulation side's own
    Grab m_applied;                    ///< the grab the last step applied
    Vec3 m_grabForce = Vec3::Zero(), m_savedExternal = Vec3::Zero();
    int m_grabNode = -1;               ///< the state node the spring pulls (-1 none)
    double m_windowWall = 0, m_windowSim = 0;
    long m_windowSteps = 0;
    std::thread m_thread;
};

} // namespace fascia::view
