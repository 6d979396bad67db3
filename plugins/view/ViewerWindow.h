#pragma once
/// fascia-view's window: a Session's frames drawn by a SceneRenderer at up to 60 frames a second on
/// the thread that runs the window (the simulation steps on the session's own), the keys, and the
/// mouse on the tissue (docs/viewer.md):
/// - left drag turns the camera, the wheel zooms, shift-left on the surface grabs the nearest node
///   with a spring and dragging pulls it (shift-left off the body pans);
/// - t selects the next tool (none after the last), ctrl-left drag then moves it in the view plane.
#include "SceneRenderer.h"
#include "Session.h"

#include <chrono>
#include <memory>

class vtkRenderWindowInteractor;

namespace fascia::view {

class ViewerWindow {
public:
    ViewerWindow(Session& session, const RenderOptions& options);
    ~ViewerWindow();
    /// One tick of the window: takes the session's newest frame, shows it with the status, renders.
    /// False when there was nothing new (nothing drawn).
    bool pump();
    /// Runs the window until it is closed (q, Escape or the close button), or for `quitAfter`
    /// seconds of wall time when positive (benchmarks): the session's thread runs meanwhile,
    /// paused or playing as asked.
    void run(double quitAfter = 0);
    /// The frames drawn since run() began, and their mean render time (ms).
    long frames() const { return m_frames; }
    double meanFrameMs() const { return m_frames ? m_totalFrameMs / double(m_frames) : 0.0; }

    SceneRenderer& renderer() { return m_renderer; }
    vtkRenderWindowInteractor* interactor();
    /// The tool ctrl-drag moves (-1: none).
    int selectedTool() const { return m_tool; }
    void selectTool(int k);
    /// The status text drawn in the last pump.
    const std::string& status() const { return m_status; }
    /// The render time of the last frame (ms).
    double frameMs() const { return m_frameMs; }
    /// The key help, bottom left.
    static const char* help();

    // what the interactor style calls (and tests, through VTK's events)
    bool beginGrab(int x, int y);
    bool beginToolDrag(int x, int y);
    void drag(int x, int y);
    /// Ends a grab or a tool drag; false when neither was on.
    bool endDrag();
    void key(const std::string& sym);

private:
    void updateStatus();
    Session& m_session;
    SceneRenderer m_renderer;
    Frame m_frame;
    std::string m_status;
    int m_tool = -1;
    enum class Drag { None, Grab, Tool } m_drag = Drag::None;
    Vec3 m_depth = Vec3::Zero();       ///< the world point whose depth a drag keeps
    Vec3 m_dragStart = Vec3::Zero();   ///< the cursor's world point where a tool drag began
    core::Pose m_toolStart;
    double m_frameMs = 0, m_totalFrameMs = 0, m_quitAfter = 0;
    long m_frames = 0;
    std::chrono::steady_clock::time_point m_runStart;
    struct Vtk;
    std::unique_ptr<Vtk> m_vtk;
};

} // namespace fascia::view
