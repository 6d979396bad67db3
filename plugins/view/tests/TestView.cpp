// The viewer's pictures and its mouse, under a display the test starts itself (Xvfb, through
// PrivateDisplay) in a real window and offscreen: where the body is in a picture, what a deformation
// changes, a scripted drag on a node, a tool moved by the mouse.
#include "Display.h"
#include "SceneRenderer.h"
#include "Session.h"
#include "ViewerWindow.h"

#include "fascia/base/Error.h"

#include <catch2/catch.hpp>
#include <vtkCommand.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkRenderWindowInteractor.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

using namespace fascia;
using namespace fascia::view;
namespace fs = std::filesystem;

namespace {

/// A 0.1 m cube of TLED tetrahedra, its base fixed, no gravity; `extra` goes into the root node.
std::string cubeScene(const std::string& extra = "") {
    return "<Node name=\"root\" dt=\"auto\" gravity=\"0 0 0\">\n" + extra +
           "  <Node name=\"cube\">\n"
           "    <GridMesh name=\"grid\" min=\"0 0 0\" max=\"0.1 0.1 0.1\" resolution=\"4 4 4\" element=\"tetrahedra6\"/>\n"
           "    <MechanicalObject name=\"state\"/>\n"
           "    <LumpedMass density=\"1000\"/>\n"
           "    <NeoHookean mu=\"3000\" kappa=\"30000\"/>\n"
           "    <TLEDForceField name=\"ff\"/>\n"
           "    <SemiImplicitEuler damping=\"40\"/>\n"
           "    <BoxROI name=\"base\" box=\"-1 -1 -1 1 1 0.001\"/>\n"
           "    <FixedConstraint name=\"fixed\" indices=\"@base.indices\"/>\n"
           "  </Node>\n"
           "</Node>\n";
}

/// A scene file in a fresh folder of this process.
std::string writeScene(const std::string& name, const std::string& xml) {
    const fs::path dir = fs::temp_directory_path() / ("fascia-view-test-" + std::to_string(getpid()));
    fs::create_directories(dir);
    const fs::path file = dir / name;
    std::ofstream(file) << xml;
    return file.string();
}

SessionOptions sessionFor(const std::string& file, Field field) {
    SessionOptions s;
    s.scene = file;
    s.load.outputDir = fs::path(file).parent_path().string();
    s.field = field;
    return s;
}

/// The plain picture the geometry tests read: no text, bar, marks or gradient.
RenderOptions plainOptions(bool offscreen) {
    RenderOptions o;
    o.width = 400, o.height = 300;
    o.offscreen = offscreen;
    o.scalarBar = o.text = o.markConstrained = o.gradient = false;
    o.camera = "y";
    return o;
}

/// A picture as RGB bytes, row 0 at the bottom (VTK's display rows).
struct Picture {
    int w = 0, h = 0;
    std::vector<unsigned char> rgb;
    const unsigned char* at(int x, int y) const { return &rgb[3 * (size_t(y) * w + x)]; }
};

Picture readPng(const std::string& path) {
    vtkNew<vtkPNGReader> reader;
    reader->SetFileName(path.c_str());
    reader->Update();
    vtkImageData* im = reader->GetOutput();
    Picture p;
    p.w = im->GetDimensions()[0], p.h = im->GetDimensions()[1];
    const int comps = im->GetNumberOfScalarComponents();
    p.rgb.resize(3 * size_t(p.w) * p.h);
    for (int y = 0; y < p.h; ++y)
        for (int x = 0; x < p.w; ++x)
            for (int c = 0; c < 3; ++c) p.rgb[3 * (size_t(y) * p.w + x) + c] = *(static_cast<unsigned char*>(im->GetScalarPointer(x, y, 0)) + c * (comps > c));
    return p;
}

bool differs(const unsigned char* a, const unsigned char* b) {
    for (int c = 0; c < 3; ++c)
        if (std::abs(int(a[c]) - int(b[c])) > 8) return true;
    return false;
}

/// The pixels whose centres the body's projected triangles cover: their count and centroid.
struct Coverage {
    long count = 0;
    double cx = 0, cy = 0;
};

Coverage projectedCoverage(SceneRenderer& r, const BodyFrame& b, int w, int h) {
    std::vector<char> mask(size_t(w) * h, 0);
    for (auto& t : b.triangles) {
        Vec3 p[3];
        for (int k = 0; k < 3; ++k) p[k] = r.worldToDisplay(b.points[t[k]]);
        const double x0 = std::min({p[0].x(), p[1].x(), p[2].x()}), x1 = std::max({p[0].x(), p[1].x(), p[2].x()});
        const double y0 = std::min({p[0].y(), p[1].y(), p[2].y()}), y1 = std::max({p[0].y(), p[1].y(), p[2].y()});
        auto edge = [](const Vec3& a, const Vec3& b, double x, double y) { return (b.x() - a.x()) * (y - a.y()) - (b.y() - a.y()) * (x - a.x()); };
        for (int y = std::max(0, int(y0)); y <= std::min(h - 1, int(y1)); ++y)
            for (int x = std::max(0, int(x0)); x <= std::min(w - 1, int(x1)); ++x) {
                const double px = x + 0.5, py = y + 0.5;
                const double e0 = edge(p[0], p[1], px, py), e1 = edge(p[1], p[2], px, py), e2 = edge(p[2], p[0], px, py);
                if ((e0 >= 0 && e1 >= 0 && e2 >= 0) || (e0 <= 0 && e1 <= 0 && e2 <= 0)) mask[size_t(y) * w + x] = 1;
            }
    }
    Coverage c;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (mask[size_t(y) * w + x]) ++c.count, c.cx += x + 0.5, c.cy += y + 0.5;
    if (c.count) c.cx /= c.count, c.cy /= c.count;
    return c;
}

/// The pixels that differ from the plain background (the corner pixel): count and centroid.
Coverage pictureCoverage(const Picture& p, const Picture* other = nullptr) {
    Coverage c;
    const unsigned char* bg = p.at(0, 0);
    for (int y = 0; y < p.h; ++y)
        for (int x = 0; x < p.w; ++x)
            if (other ? differs(p.at(x, y), other->at(x, y)) : differs(p.at(x, y), bg)) ++c.count, c.cx += x + 0.5, c.cy += y + 0.5;
    if (c.count) c.cx /= c.count, c.cy /= c.count;
    return c;
}

/// A mouse event at display point p with the given modifiers, through the window's interactor.
void mouse(ViewerWindow& w, unsigned long event, const Vec3& p, bool ctrl = false, bool shift = false) {
    w.interactor()->SetEventInformation(int(std::lround(p.x())), int(std::lround(p.y())), ctrl, shift);
    w.interactor()->InvokeEvent(event);
}

} // namespace

TEST_CASE("A picture shows the body where its nodes project, in a window and offscreen", "[view][SceneRenderer]") {
    PrivateDisplay display(true);
    const bool offscreen = GENERATE(false, true);
    CAPTURE(offscreen);
    Session session(sessionFor(writeScene("cube.xml", cubeScene()), Field::None));
    SceneRenderer r(plainOptions(offscreen));
    Frame f;
    REQUIRE(session.takeFrame(f));
    r.show(f);
    const std::string png = writeScene("rest.png", "");
    r.writePng(png);
    const Picture pic = readPng(png);
    REQUIRE(pic.w == 400);
    REQUIRE(pic.h == 300);
    const Coverage seen = pictureCoverage(pic), expected = projectedCoverage(r, f.bodies[0], pic.w, pic.h);
    CHECK(seen.count > 0.2 * pic.w * pic.h);  // not blank: the cube fills a good part of the view
    CHECK(std::abs(double(seen.count) / double(expected.count) - 1) < 0.03);
    CHECK(std::abs(seen.cx - expected.cx) < 2);
    CHECK(std::abs(seen.cy - expected.cy) < 2);
}

TEST_CASE("A picture of a deformed state differs from the rest state where the deformation is", "[view][SceneRenderer]") {
    PrivateDisplay display(true);
    Session session(sessionFor(writeScene("cube.xml", cubeScene()), Field::Displacement));
    RenderOptions o = plainOptions(true);
    o.rangeMin = 0, o.rangeMax = 10;  // mm: the same colours in both pictures
    SceneRenderer r(o);
    Frame f;
    session.takeFrame(f);
    r.show(f);
    const std::string rest = writeScene("rest.png", ""), bent = writeScene("bent.png", "");
    r.writePng(rest);
    const double xSplit = r.worldToDisplay(Vec3(0.05, 0, 0.1)).x();
    // left of the nodes next to the bent half: their normals, and so their shading, change with it
    const double xQuiet = r.worldToDisplay(Vec3(0.025, 0, 0.1)).x();
    // the right half (x > 0.05) bent up, up to 10 mm at x = 0.1; the left half as it was
    core::BaseMechanicalState& s = session.simulation().state("state");
    for (size_t i = 0; i < s.size(); ++i)
        if (s.x0()[i].x() > 0.05) s.x()[i].z() += 0.2 * (s.x0()[i].x() - 0.05) * s.x0()[i].z() / 0.1 * 10;
    session.advance(0);
    REQUIRE(session.takeFrame(f));
    r.show(f);
    r.writePng(bent);
    const Picture a = readPng(rest), b = readPng(bent);
    const Coverage changed = pictureCoverage(b, &a), body = pictureCoverage(a);
    CHECK(changed.count > 0.1 * body.count);
    long left = 0;
    for (int y = 0; y < a.h; ++y)
        for (int x = 0; x < a.w && x + 0.5 < xQuiet - 2; ++x) left += differs(a.at(x, y), b.at(x, y));
    CHECK(left == 0);  // nothing changed away from the bent half
    CHECK(changed.cx > xSplit);
}

TEST_CASE("A scripted shift-drag on a node pulls it towards the cursor, and the body springs back on release", "[view][ViewerWindow]") {
    PrivateDisplay display(true);
    Session session(sessionFor(writeScene("cube.xml", cubeScene()), Field::Displacement));
    RenderOptions o = plainOptions(false);
    ViewerWindow w(session, o);
    w.pump();
    core::BaseMechanicalState& s = session.simulation().state("state");
    const Vec3 node(0.05, 0, 0.075);  // a node of the front face (y = 0), which the camera faces
    int index = -1;
    for (size_t i = 0; i < s.size(); ++i)
        if ((s.x0()[i] - node).norm() < 1e-9) index = int(i);
    REQUIRE(index >= 0);
    SceneRenderer& r = w.renderer();
    const Vec3 press = r.worldToDisplay(node), pull = r.worldToDisplay(node + Vec3(0, 0, 0.02));
    mouse(w, vtkCommand::LeftButtonPressEvent, press, false, true);
    mouse(w, vtkCommand::MouseMoveEvent, pull, false, true);
    session.advance(400);
    w.pump();
    const Vec3 moved = s.x()[index] - s.x0()[index];
    INFO("the node moved by " << moved.transpose() << " m");
    CHECK(moved.z() > 0.005);                        // towards the cursor, 20 mm up
    CHECK(std::abs(moved.x()) < 0.3 * moved.z());
    CHECK(session.grabForce().z() > 0);
    CHECK(w.status().find("grab force") != std::string::npos);
    mouse(w, vtkCommand::LeftButtonReleaseEvent, pull);
    session.advance(1500);
    CHECK(session.grabForce().norm() == 0);
    CHECK((s.x()[index] - s.x0()[index]).norm() < 0.2 * moved.norm());  // springs back
}

TEST_CASE("A tool moved by scripted ctrl-drag presses the body", "[view][ViewerWindow]") {
    PrivateDisplay display(true);
    const std::string ball = "  <SphereTool name=\"ball\" body=\"@cube/state\" radius=\"0.02\" position=\"0.05 0.05 0.125\"/>\n";
    Session session(sessionFor(writeScene("ball.xml", cubeScene(ball)), Field::Displacement));
    ViewerWindow w(session, plainOptions(false));
    w.pump();
    REQUIRE(session.toolCount() == 1);
    w.interactor()->SetKeyEventInformation(0, 0, 't', 0, "t");
    w.interactor()->InvokeEvent(vtkCommand::CharEvent);
    REQUIRE(w.selectedTool() == 0);
    SceneRenderer& r = w.renderer();
    const Vec3 centre(0.05, 0.05, 0.125);
    const Vec3 from = r.worldToDisplay(centre), to = r.worldToDisplay(centre - Vec3(0, 0, 0.015));
    mouse(w, vtkCommand::LeftButtonPressEvent, from, true);
    mouse(w, vtkCommand::MouseMoveEvent, to, true);
    mouse(w, vtkCommand::LeftButtonReleaseEvent, to, true);
    session.advance(300);
    w.pump();
    core::BaseTool& tool = session.simulation().tool("ball");
    INFO("tool at " << tool.pose().position.transpose());
    CHECK(std::abs(tool.pose().position.z() - 0.11) < 0.002);  // 15 mm down, within a pixel or so
    CHECK(std::abs(tool.pose().position.x() - 0.05) < 0.002);
    CHECK(tool.force().z() > 0);  // the body pushes the ball up: it presses 10 mm in
    CHECK(w.status().find("tool ball") != std::string::npos);
}

TEST_CASE("PngSnapshot writes pictures every N steps and of the final state, and refuses a bad camera where it is", "[view][PngSnapshot]") {
    const std::string snap = "  <PngSnapshot name=\"pics\" filename=\"snap.png\" every=\"50\" field=\"vonMises\" camera=\"x\" width=\"320\" "
                             "height=\"240\" rangeMin=\"0\" rangeMax=\"1\" surface=\"state\" text=\"false\"/>\n";
    const std::string file = writeScene("snap.xml", cubeScene(snap));
    const fs::path dir = fs::path(file).parent_path() / "snap-out";
    fs::remove_all(dir);
    {
        core::LoadOptions load;
        load.outputDir = dir.string();
        auto sim = core::Simulation::fromFile(file, load);
        sim->run(120);
        sim->finish();
    }
    for (const char* name : {"snap_000000.png", "snap_000050.png", "snap_000100.png", "snap.png"}) {
        CAPTURE(name);
        REQUIRE(fs::exists(dir / name));
        const Picture p = readPng((dir / name).string());
        CHECK(p.w == 320);
        CHECK(p.h == 240);
        CHECK(pictureCoverage(p).count > 0);
    }
    CHECK(!fs::exists(dir / "snap_000120.png"));  // the final state is snap.png
    const std::string bad = writeScene("bad.xml", cubeScene("  <PngSnapshot camera=\"sideways\"/>\n"));
    try {
        core::Simulation::fromFile(bad);
        FAIL("a bad camera was accepted");
    } catch (const core::Error& e) {
        CHECK(std::string(e.what()).find("bad.xml:2") != std::string::npos);
        CHECK(std::string(e.what()).find("camera 'sideways' is not a view") != std::string::npos);
    }
}
