#include "ViewerWindow.h"

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkCamera.h>
#include <vtkInteractorStyle.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>

#include <chrono>
#include <cmath>
#include <cstdio>

namespace fascia::view {

namespace {

/// A trackball camera (left drag turns about the focal point, middle drag pans, right drag and the
/// wheel zoom), with the viewer's modified clicks and keys first. Our own rather than VTK's
/// InteractionStyle module, which brings MPI into the link on Debian.
class ViewerStyle : public vtkInteractorStyle {
public:
    static ViewerStyle* New();
    vtkTypeMacro(ViewerStyle, vtkInteractorStyle)
    ViewerWindow* viewer = nullptr;

    void OnLeftButtonDown() override {
        const int* p = Interactor->GetEventPosition();
        if (Interactor->GetShiftKey() && viewer->beginGrab(p[0], p[1])) return;
        if (Interactor->GetControlKey() && viewer->beginToolDrag(p[0], p[1])) return;
        begin(Interactor->GetShiftKey() ? Motion::Pan : Motion::Turn);
    }
    void OnLeftButtonUp() override { viewer->endDrag() || end(); }
    void OnMiddleButtonDown() override { begin(Motion::Pan); }
    void OnMiddleButtonUp() override { end(); }
    void OnRightButtonDown() override { begin(Motion::Zoom); }
    void OnRightButtonUp() override { end(); }
    void OnMouseWheelForward() override { zoom(1.1); }
    void OnMouseWheelBackward() override { zoom(1 / 1.1); }
    void OnMouseMove() override {
        const int* p = Interactor->GetEventPosition();
        viewer->drag(p[0], p[1]);
        if (m_motion == Motion::None) return;
        const int dx = p[0] - m_last[0], dy = p[1] - m_last[1];
        m_last[0] = p[0], m_last[1] = p[1];
        vtkCamera* cam = viewer->renderer().renderer()->GetActiveCamera();
        const int* size = Interactor->GetRenderWindow()->GetSize();
        if (m_motion == Motion::Turn) {
            cam->Azimuth(-200.0 * dx / size[0]);
            cam->Elevation(-200.0 * dy / size[1]);
            cam->OrthogonalizeViewUp();
        } else if (m_motion == Motion::Pan) {
            const Vec3 focal(cam->GetFocalPoint());
            const Vec3 a = viewer->renderer().displayToWorld(p[0] - dx, p[1] - dy, focal);
            const Vec3 b = viewer->renderer().displayToWorld(p[0], p[1], focal);
            const Vec3 move = a - b;
            const Vec3 position(cam->GetPosition());
            const Vec3 newFocal = focal + move, newPosition = position + move;
            cam->SetFocalPoint(newFocal.data());
            cam->SetPosition(newPosition.data());
        } else {
            zoom(std::pow(1.01, dy));
            return;
        }
        viewer->renderer().renderer()->ResetCameraClippingRange();
        Interactor->Render();
    }
    void OnChar() override {
        const char* sym = Interactor->GetKeySym();
        const char c = Interactor->GetKeyCode();
        viewer->key(sym && *sym ? std::string(sym) : std::string(1, c));
    }

private:
    enum class Motion { None, Turn, Pan, Zoom } m_motion = Motion::None;
    int m_last[2] = {0, 0};
    void begin(Motion m) {
        m_motion = m;
        const int* p = Interactor->GetEventPosition();
        m_last[0] = p[0], m_last[1] = p[1];
    }
    bool end() {
        m_motion = Motion::None;
        return true;
    }
    void zoom(double factor) {
        viewer->renderer().renderer()->GetActiveCamera()->Dolly(factor);
        viewer->renderer().renderer()->ResetCameraClippingRange();
        Interactor->Render();
    }
};
vtkStandardNewMacro(ViewerStyle);

} // namespace

struct ViewerWindow::Vtk {
    vtkNew<vtkRenderWindowInteractor> interactor;
    vtkNew<ViewerStyle> style;
    vtkNew<vtkCallbackCommand> timer;
};

const char* ViewerWindow::help() {
    return "space play/pause   n one step   r reset   f fit camera   q quit\n"
           "shift-drag on the surface: pull a node   t select a tool, then ctrl-drag: move it";
}

ViewerWindow::ViewerWindow(Session& session, const RenderOptions& options)
    : m_session(session), m_renderer([&] {
          RenderOptions o = options;
          if (o.help.empty() && o.text) o.help = help();
          return o;
      }()) {
    // (VTK's interactor warns, when it is made, that it has no InteractionStyle module: we set our own style)
    vtkObject::GlobalWarningDisplayOff();
    m_vtk = std::make_unique<Vtk>();
    m_vtk->style->viewer = this;
    m_vtk->interactor->SetRenderWindow(m_renderer.window());
    m_vtk->interactor->SetInteractorStyle(m_vtk->style);
    m_vtk->interactor->Initialize();
    vtkObject::GlobalWarningDisplayOn();
    m_vtk->timer->SetClientData(this);
    m_vtk->timer->SetCallback([](vtkObject*, unsigned long, void* self, void*) { static_cast<ViewerWindow*>(self)->pump(); });
    m_vtk->interactor->AddObserver(vtkCommand::TimerEvent, m_vtk->timer);
    m_session.takeFrame(m_frame);
    m_renderer.show(m_frame);
    updateStatus();
}

ViewerWindow::~ViewerWindow() = default;

vtkRenderWindowInteractor* ViewerWindow::interactor() { return m_vtk->interactor; }

void ViewerWindow::selectTool(int k) { m_tool = k >= 0 && size_t(k) < m_session.toolCount() ? k : -1; }

bool ViewerWindow::pump() {
    const bool fresh = m_session.takeFrame(m_frame);
    if (fresh) m_renderer.show(m_frame);
    updateStatus();
    const auto t0 = std::chrono::steady_clock::now();
    m_renderer.render();
    const auto t1 = std::chrono::steady_clock::now();
    m_frameMs = 1e3 * std::chrono::duration<double>(t1 - t0).count();
    m_totalFrameMs += m_frameMs;
    ++m_frames;
    if (m_quitAfter > 0 && std::chrono::duration<double>(t1 - m_runStart).count() >= m_quitAfter) m_vtk->interactor->TerminateApp();
    return fresh;
}

void ViewerWindow::run(double quitAfter) {
    m_quitAfter = quitAfter;
    m_runStart = std::chrono::steady_clock::now();
    m_frames = 0;
    m_totalFrameMs = 0;
    m_session.start();
    m_vtk->interactor->CreateRepeatingTimer(16);  // about 60 frames a second at most
    m_renderer.render();
    m_vtk->interactor->Start();
    m_session.stop();
}

void ViewerWindow::updateStatus() {
    const SessionStats s = m_session.stats();
    char line[256];
    std::string text;
    std::snprintf(line, sizeof line, "t = %.4f s   step %ld   %s\n", m_frame.time, m_frame.step, s.playing ? "playing" : "paused (space plays)");
    text += line;
    std::snprintf(line, sizeof line, "%.3f ms/step   real-time factor %.3g   %.0f steps/frame   frame %.1f ms\n", s.msPerStep,
                  s.realTimeFactor, s.stepsPerFrame, m_frameMs);
    text += line;
    if (m_frame.field != Field::None) {
        std::snprintf(line, sizeof line, "%s: %.4g to %.4g %s\n", fieldName(m_frame.field), m_renderer.rangeMin(), m_renderer.rangeMax(),
                      fieldUnit(m_frame.field));
        text += line;
    }
    if (m_tool >= 0 && size_t(m_tool) < m_frame.tools.size()) {
        const Vec3& f = m_frame.tools[m_tool].force;
        std::snprintf(line, sizeof line, "tool %s (ctrl-drag moves it): force %.4g N\n", m_frame.tools[m_tool].name.c_str(), f.norm());
        text += line;
    }
    if (m_frame.grab.active) {
        std::snprintf(line, sizeof line, "grab force %.4g N\n", m_frame.grab.force.norm());
        text += line;
    }
    if (!s.error.empty()) text += s.error.substr(0, 300) + "\n";
    m_status = text;
    m_renderer.setStatus(text);
}

bool ViewerWindow::beginGrab(int x, int y) {
    int body, point;
    Vec3 hit;
    if (!m_renderer.pick(x, y, body, point, hit)) return false;
    m_depth = hit;
    m_drag = Drag::Grab;
    m_session.grab(body, point, hit);
    return true;
}

bool ViewerWindow::beginToolDrag(int x, int y) {
    if (m_tool < 0 || size_t(m_tool) >= m_frame.tools.size()) return false;
    m_toolStart = m_frame.tools[m_tool].pose;
    m_depth = m_toolStart.position;
    m_dragStart = m_renderer.displayToWorld(x, y, m_depth);
    m_drag = Drag::Tool;
    return true;
}

void ViewerWindow::drag(int x, int y) {
    if (m_drag == Drag::Grab) {
        m_session.moveGrab(m_renderer.displayToWorld(x, y, m_depth));
    } else if (m_drag == Drag::Tool) {
        core::Pose pose = m_toolStart;
        pose.position += m_renderer.displayToWorld(x, y, m_depth) - m_dragStart;
        m_session.moveTool(size_t(m_tool), pose);
    }
}

bool ViewerWindow::endDrag() {
    if (m_drag == Drag::None) return false;
    if (m_drag == Drag::Grab) m_session.release();
    m_drag = Drag::None;
    return true;
}

void ViewerWindow::key(const std::string& sym) {
    if (sym == "space" || sym == " ") m_session.play(!m_session.playing());
    else if (sym == "n") m_session.stepOnce();
    else if (sym == "r") m_session.reset();
    else if (sym == "f") m_renderer.fitCamera();
    else if (sym == "t") selectTool(m_tool + 1 < int(m_session.toolCount()) ? m_tool + 1 : -1);
    else if (sym == "q" || sym == "Escape") m_vtk->interactor->TerminateApp();
}

} // namespace fascia::view
