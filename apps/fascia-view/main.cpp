// fascia-view: a scene running live in a VTK window, or one picture of it. See `fascia-view --help`
// and docs/viewer.md.
#include "Display.h"
#include "SceneRenderer.h"
#include "Session.h"
#include "ViewerWindow.h"

#include "fascia/base/CommandLine.h"
#include "fascia/base/Error.h"

#include <omp.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

using namespace fascia;
using namespace fascia::view;

namespace {

const char* kHelp = R"(fascia-view: run a Fascia scene live in a window, or write a picture of it
usage:
  fascia-view SCENE.xml [options]                          a window (needs a display)
  fascia-view SCENE.xml --screenshot FILE.png [--steps N | --time T] [options]
                                                           a picture, no window (offscreen;
                                                           starts its own Xvfb without a display)
options:
  --field NAME     colour by displacement (mm, default), vonMises (kPa, the average of the
                   elements around each node), J, or none
  --range MIN MAX  a fixed colour range (default: it follows the data)
  --surface NAME   show only this mechanical state's surface, or this visual surface
                   (default: every body with a boundary surface)
  --camera VIEW    iso (default), x, -x, y, -y, z, -z (looking along that axis), or
                   "PX PY PZ FX FY FZ": the camera's position and focal point (m)
  --size WxH       the window or picture size in pixels (default 1024x768)
  --play           start playing (the window starts paused)
  --steps N        (--screenshot) steps to run before the picture (default 0: the initial state)
  --time T         (--screenshot) simulated time to run before the picture
  --dt DT          time step, overriding the scene's
  --threads N      OpenMP threads of the simulation (default: all cores)
  --output DIR     folder the scene's exporters and monitors write into (default: .)
  --grab-stiffness K  the mouse spring's stiffness in N/m (default: a quarter of the node's
                   mass over dt^2)
  --no-text        no status and key help in the picture
  --quit-after S   close the window after S seconds of wall time (benchmarks, scripts)
keys and mouse (the window):
  space play/pause, n one step, r reset (reload the scene), f fit the camera, q or Escape quit;
  left drag turns, right drag or the wheel zooms, middle drag pans; shift-left on the surface
  grabs the nearest node with a spring and dragging pulls it; t selects the next tool, and
  ctrl-left drag moves it in the view plane
exit codes:
  0  success
  1  a bad command line, or a picture that cannot be written
  2  an invalid scene or input (the located error on stderr), a --field that does not exist,
     a scene with no surface to show
  3  the simulation failed: before the picture (--screenshot), or in the window (which shows the
     message, paused, until it is closed)
  4  no display: a window needs one (run under xvfb-run -a), and a picture needs a display or
     Xvfb on PATH (Debian's xvfb)
)";

struct Options {
    SessionOptions session;
    RenderOptions render;
    std::string screenshot, field = "displacement";
    long steps = -1;
    double time = 0;
    int threads = 0;
    bool play = false;
    double quitAfter = 0;
};

Options parseArgs(int argc, char** argv) {
    core::CommandLine cl("fascia-view", argc, argv);
    Options o;
    while (cl.next()) {
        if (cl.isHelp()) {
            std::cout << kHelp;
            std::exit(0);
        } else if (cl.is("--field")) o.field = cl.text("a field name");
        else if (cl.is("--range")) {
            o.render.rangeMin = cl.number(-HUGE_VAL);
            o.render.rangeMax = cl.number(-HUGE_VAL);
            if (!(o.render.rangeMin < o.render.rangeMax)) cl.fail("--range needs MIN < MAX");
        } else if (cl.is("--surface")) o.session.surface = cl.text("a state or visual surface name");
        else if (cl.is("--camera")) o.render.camera = cl.text("a view");
        else if (cl.is("--size")) {
            const std::string v = cl.text("WxH");
            int w = 0, h = 0;
            char x = 0, extra = 0;
            if (std::sscanf(v.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || x != 'x' || w < 64 || h < 64 || w > 8192 || h > 8192)
                cl.fail("--size needs WxH, each from 64 to 8192 pixels, not '" + v + "'");
            o.render.width = w, o.render.height = h;
        } else if (cl.is("--play")) o.play = true;
        else if (cl.is("--screenshot")) o.screenshot = cl.path("a .png file");
        else if (cl.is("--steps")) o.steps = cl.integer(0, 1000000000L);
        else if (cl.is("--time")) o.time = cl.positive();
        else if (cl.is("--dt")) o.session.load.dt = cl.positive();
        else if (cl.is("--threads")) o.threads = int(cl.integer(1, 4096));
        else if (cl.is("--output")) o.session.load.outputDir = cl.path("a folder");
        else if (cl.is("--grab-stiffness")) o.session.grabStiffness = cl.positive();
        else if (cl.is("--no-text")) o.render.text = false;
        else if (cl.is("--quit-after")) o.quitAfter = cl.positive();
        else if (cl.isOption()) cl.unknownOption();
        else if (o.session.scene.empty()) o.session.scene = cl.arg();
        else cl.fail("one scene at a time ('" + o.session.scene + "' and '" + cl.arg() + "')");
    }
    if (o.session.scene.empty()) cl.fail("no scene given");
    if (o.steps >= 0 && o.time > 0) cl.fail("give --steps or --time, not both");
    if (o.screenshot.empty() && (o.steps >= 0 || o.time > 0)) cl.fail("--steps and --time go with --screenshot (the window runs until closed)");
    return o;
}

/// --screenshot: runs the steps on this thread and writes the picture offscreen.
int screenshot(Options& o) {
    PrivateDisplay display(true);
    o.render.offscreen = true;
    SceneRenderer renderer(o.render);  // (a bad --camera fails here, before the run)
    Session session(o.session);
    core::Simulation& sim = session.simulation();
    const long steps = o.time > 0 ? sim.stepsUntil(o.time) : std::max(o.steps, 0L);
    session.advance(steps);
    if (const std::string error = session.stats().error; !error.empty()) {
        std::cerr << "fascia-view: " << error << "\n";
        return 3;
    }
    Frame frame;
    session.takeFrame(frame);
    renderer.show(frame);
    char text[160];
    int n = std::snprintf(text, sizeof text, "t = %.4f s   step %ld", frame.time, frame.step);
    if (frame.field != Field::None)
        std::snprintf(text + n, sizeof text - n, "   %s %.4g to %.4g %s", fieldName(frame.field), renderer.rangeMin(),
                      renderer.rangeMax(), fieldUnit(frame.field));
    renderer.setStatus(text);
    renderer.writePng(o.screenshot);
    session.simulation().finish();
    std::printf("fascia-view: wrote %s (t = %.6g s, %ld steps)\n", o.screenshot.c_str(), frame.time, frame.step);
    return 0;
}

int window(Options& o) {
    PrivateDisplay display(false);
    Session session(o.session);
    ViewerWindow viewer(session, o.render);
    session.play(o.play);
    viewer.run(o.quitAfter);
    const SessionStats s = session.stats();
    session.simulation().finish();
    std::printf("fascia-view: %ld steps, %.4f ms/step, %ld frames, %.2f ms a frame to render\n", s.steps,
                s.steps ? 1e3 * s.stepWall / double(s.steps) : 0.0, viewer.frames(), viewer.meanFrameMs());
    if (s.error.empty()) return 0;
    std::cerr << "fascia-view: " << s.error << "\n";  // (the window showed it, paused, until closed)
    return 3;
}

} // namespace

int main(int argc, char** argv) {
    Options o = parseArgs(argc, argv);
    try {
        o.session.field = parseField(o.field);
        if (o.threads > 0) omp_set_num_threads(o.threads);
        return o.screenshot.empty() ? window(o) : screenshot(o);
    } catch (const NoDisplayError& e) {
        std::cerr << "fascia-view: " << e.what() << "\n";
        return 4;
    } catch (const core::Error& e) {
        const std::string text = e.what();
        std::cerr << (text.rfind("error:", 0) == 0 ? "fascia-view: " : "") << text << "\n";
        return e.kind() == core::ErrorKind::Input ? 2 : e.kind() == core::ErrorKind::Simulation ? 3 : 1;
    } catch (const std::exception& e) {
        std::cerr << "fascia-view: internal error: " << e.what() << "\n";
        return 1;
    }
}
