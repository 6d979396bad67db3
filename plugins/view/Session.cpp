#include "Session.h"

#include "fascia/base/Error.h"

#include <chrono>

namespace fascia::view {

Session::Session(const SessionOptions& options) : m_options(options) {
    load();
    m_source->capture(m_front, m_sim->time(), m_sim->stepCount());
    m_front.grab = {};
    m_frameVersion = 1;
}

Session::~Session() { stop(); }

void Session::load() {
    // the new scene is built before the old one goes: a reset that fails keeps the running one
    auto sim = core::Simulation::fromFile(m_options.scene, m_options.load);
    if (!(sim->dt() > 0)) core::throwInputError({m_options.scene, sim->root().loc().line}, "no time step: set dt on the root node or pass --dt");
    auto source = std::make_unique<FrameSource>(sim->root(), m_options.field, m_options.surface);
    sim->start();
    m_source = std::move(source);
    m_sim = std::move(sim);
    m_toolCount = m_source->tools().size();
    m_toolNames.clear();
    for (auto* t : m_source->tools()) m_toolNames.push_back(t->name());
    m_poses.assign(m_toolCount, std::nullopt);
    m_grabNode = -1;
    m_applied = {};
}

void Session::play(bool on) {
    m_playing = on;
    m_wake.notify_all();
}

void Session::stepOnce() {
    std::lock_guard<std::mutex> lock(m_mutex);
    ++m_stepsAsked;
    m_wake.notify_all();
}

void Session::reset() {
    std::lock_guard<std::mutex> lock(m_mutex);
    m_resetAsked = true;
    m_wake.notify_all();
}

void Session::grab(int body, int point, const Vec3& target) {
    std::lock_guard<std::mutex> lock(m_mutex);
    m_grab = {true, body, point, target};
}

void Session::moveGrab(const Vec3& target) {
    std::lock_guard<std::mutex> lock(m_mutex);
    m_grab.target = target;
}

void Session::release() {
    std::lock_guard<std::mutex> lock(m_mutex);
    m_grab.active = false;
}

void Session::moveTool(size_t k, const core::Pose& pose) {
    std::lock_guard<std::mutex> lock(m_mutex);
    if (k < m_poses.size()) m_poses[k] = pose;
}

std::string Session::toolName(size_t k) const { return k < m_toolNames.size() ? m_toolNames[k] : ""; }

bool Session::takeFrame(Frame& out) {
    std::lock_guard<std::mutex> lock(m_mutex);
    m_frameAsked = true;
    if (m_frameVersion == m_takenVersion) return false;
    std::swap(out, m_front);
    m_takenVersion = m_frameVersion;
    return true;
}

SessionStats Session::stats() const {
    std::lock_guard<std::mutex> lock(m_mutex);
    SessionStats s = m_stats;
    s.playing = m_playing;
    return s;
}

Vec3 Session::grabForce() const {
    std::lock_guard<std::mutex> lock(m_mutex);
    return m_grabForce;
}

void Session::applyCommands() {
    Grab grab;
    std::vector<std::optional<core::Pose>> poses;
    bool reset;
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        reset = m_resetAsked;
        m_resetAsked = false;
        grab = m_grab;
        poses.swap(m_poses);
        m_poses.assign(m_toolCount, std::nullopt);
    }
    if (reset) {
        try {
            load();
            std::lock_guard<std::mutex> lock(m_mutex);
            m_stats.error.clear();
            m_stats.steps = 0;
            m_stats.stepWall = 0;
            m_grab.active = false;
            m_frameAsked = true;
            return;
        } catch (const core::Error& e) {
            std::lock_guard<std::mutex> lock(m_mutex);
            m_stats.error = std::string("reset failed, the scene runs on: ") + e.what();
        }
    }
    for (size_t k = 0; k < poses.size() && k < m_source->tools().size(); ++k)
        if (poses[k]) m_source->tools()[k]->setPose(*poses[k]);
    // the grab spring: an external force on one node, k (target - x), restored on release
    core::BaseMechanicalState* state =
        grab.body >= 0 && size_t(grab.body) < m_source->bodyCount() && m_source->grabbable(grab.body) ? &m_source->state(grab.body) : nullptr;
    if (m_grabNode >= 0 && (!grab.active || grab.body != m_applied.body || grab.point != m_applied.point)) {
        m_source->state(m_applied.body).externalForce()[m_grabNode] = m_savedExternal;
        m_grabNode = -1;
    }
    m_applied = grab;
    Vec3 force = Vec3::Zero();
    if (grab.active && state) {
        const int node = m_source->stateNode(grab.body, grab.point);
        if (m_grabNode < 0) m_savedExternal = state->externalForce()[node], m_grabNode = node;
        double k = m_options.grabStiffness;
        if (!(k > 0)) k = 0.25 * m_source->nodeMass(grab.body, node) / (m_sim->dt() * m_sim->dt());
        force = k * (grab.target - state->x()[node]);
        state->externalForce()[node] = m_savedExternal + force;
    }
    std::lock_guard<std::mutex> lock(m_mutex);
    m_grabForce = force;
}

bool Session::stepTimed() {
    const auto t0 = std::chrono::steady_clock::now();
    const double sim0 = m_sim->time();
    try {
        m_sim->step();
    } catch (const core::Error& e) {
        m_playing = false;
        std::lock_guard<std::mutex> lock(m_mutex);
        m_stats.error = std::string("the step failed, paused: ") + e.what() + " (press r to reset)";
        return false;
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    m_windowWall += wall;
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        ++m_stats.steps;
        m_stats.stepWall += wall;
    }
    m_windowSim += m_sim->time() - sim0;
    ++m_windowSteps;
    if (m_windowWall > 0.5) {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_stats.msPerStep = 1e3 * m_windowWall / double(m_windowSteps);
        m_stats.realTimeFactor = m_windowSim / m_windowWall;
        m_windowWall = m_windowSim = 0;
        m_windowSteps = 0;
    }
    return true;
}

void Session::publish() {
    m_sim->fetchState();
    m_source->capture(m_back, m_sim->time(), m_sim->stepCount());
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_back.grab.active = m_applied.active && m_grabNode >= 0;
        if (m_back.grab.active) {
            m_back.grab.node = m_source->state(m_applied.body).x()[m_grabNode];
            m_back.grab.target = m_applied.target;
            m_back.grab.force = m_grabForce;
        }
        std::swap(m_front, m_back);
        ++m_frameVersion;
        m_stats.stepsPerFrame = double(m_sim->stepCount() - m_stepsAtLastFrame);
        m_stepsAtLastFrame = m_sim->stepCount();
    }
    m_frameAsked = false;
}

void Session::advance(long n) {
    for (long i = 0; i < n; ++i) {
        applyCommands();
        if (!stepTimed()) break;
    }
    publish();
}

void Session::loop() {
    for (;;) {
        bool step = false;
        {
            std::unique_lock<std::mutex> lock(m_mutex);
            // asleep while paused with nothing asked; a frame request wakes it within 20 ms
            m_wake.wait_for(lock, std::chrono::milliseconds(20),
                            [&] { return m_quit || m_playing || m_stepsAsked > 0 || m_resetAsked; });
            if (m_quit) return;
            if (m_stepsAsked > 0) --m_stepsAsked, step = true;
        }
        applyCommands();
        if (m_playing || step) stepTimed();
        if (m_frameAsked) publish();
    }
}

void Session::start() {
    if (m_thread.joinable()) return;
    m_quit = false;
    m_thread = std::thread([this] { loop(); });
}

void Session::stop() {
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_quit = true;
    }
    m_wake.notify_all();
    if (m_thread.joinable()) m_thread.join();
}

} // namespace fascia::view
