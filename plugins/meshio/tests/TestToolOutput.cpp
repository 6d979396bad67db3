// The rigid tools in VTKExporter's series (tools="true", ToolOutput.h): each tool touching the body
// as a .vtp at its pose, with its force and torque, listed as further parts of the .pvd's
// timesteps; none with tools="false"; a restart goes on listing them; the checkpoint records of a
// series (PvdSeries) with parts, and as a build without parts wrote them.
#include "MeshioTestSupport.h"
#include "PvdSeries.h"
#include "fascia/base/Component.h"
#include "fascia/base/Error.h"
#include "fascia/base/StateIO.h"
#include "fascia/sim/Simulation.h"
#include "fascia/sim/Tool.h"

#include <catch2/catch.hpp>

#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>

#include <cmath>
#include <map>
#include <sstream>

using fascia::Positions;
using fascia::Triangles;
using fascia::Vec3;
using fascia::core::Simulation;
using namespace meshiotest;
using Catch::Matchers::Contains;

namespace {

// the probe's keyframes: down 5 mm onto the block's top (z = 0.05) by t = 0.02 s, then tilted by
// kTilt about y by t = 0.04 s, its tip centre (the pose's position) held
constexpr double kTilt = 20 * M_PI / 180;

/// A block 0.1 x 0.1 x 0.05 m fixed at its base, a keyframed capsule pressing its top and a plane
/// under it (both touching "state"; the plane after `exporter`, which is initialised after it all
/// the same), a sphere touching another body, and `exporter`.
std::string scene(const std::string& exporter) {
    std::ostringstream q;  // the tilt's quaternion, w x y z, to the last digit
    q.precision(17);
    q << std::cos(kTilt / 2) << " 0 " << std::sin(kTilt / 2) << " 0";
    return "<Node name=\"root\" dt=\"0.0005\">\n"
           "  <CapsuleTool name=\"probe\" body=\"@block/state\" radius=\"0.02\" length=\"0.05\" keyTimes=\"0 0.02 0.04\"\n"
           "               keyPositions=\"0.05 0.05 0.071  0.05 0.05 0.066  0.05 0.05 0.066\"\n"
           "               keyOrientations=\"1 0 0 0  1 0 0 0  " + q.str() + "\"/>\n"
           "  <SphereTool name=\"ball\" body=\"@other/points\" radius=\"0.01\" position=\"1 0 0\"/>\n"
           "  <Node name=\"block\">\n"
           "    <GridMesh name=\"grid\" min=\"0 0 0\" max=\"0.1 0.1 0.05\" resolution=\"4 4 2\"/>\n"
           "    <MechanicalObject name=\"state\"/>\n    <LumpedMass density=\"1000\"/>\n"
           "    <NeoHookean mu=\"1000\" kappa=\"5000\"/>\n    <HEMLForceField/>\n    <SemiImplicitEuler damping=\"20\"/>\n"
           "    <FixedConstraint group=\"zmin\"/>\n"
           "    " + exporter + "\n"
           "    <PlaneTool name=\"floor\" position=\"0.05 0.05 -0.01\"/>\n"
           "  </Node>\n"
           "  <Node name=\"other\">\n"
           "    <GridMesh min=\"1 0 0\" max=\"1.1 0.1 0.1\" resolution=\"1 1 1\"/>\n"
           "    <MechanicalObject name=\"points\"/>\n    <LumpedMass density=\"1000\"/>\n    <SemiImplicitEuler/>\n"
           "  </Node>\n"
           "</Node>\n";
}

/// The probe's pose at time t from its keyframes, independently of the contact plugin: the position
/// linear between keys; the tilt about y growing linearly from 0.02 s (slerp between two rotations
/// about one axis turns at a constant rate about it).
fascia::core::Pose probePose(double t) {
    fascia::core::Pose p;
    const double down = std::min(t / 0.02, 1.0), tilt = std::clamp((t - 0.02) / 0.02, 0.0, 1.0);
    p.position = Vec3(0.05, 0.05, 0.071 - 0.005 * down);
    p.orientation = Eigen::AngleAxisd(tilt * kTilt, Vec3::UnitY());
    return p;
}

/// What a tool was at one step the exporter wrote.
struct ToolAtStep {
    double t;
    fascia::core::Pose pose;  ///< expected (from the keyframes)
    Vec3 force, torque;       ///< the tool's, read after the step
};

/// Checks a tool's .vtp: its triangles are the tool's display mesh, its points that mesh at the
/// expected pose (to 1e-9 m), its field data the tool's force and torque, bitwise.
void checkToolFile(const fs::path& file, const fascia::core::BaseTool& tool, double extent, const ToolAtStep& at) {
    INFO(file.string());
    Positions local;
    Triangles triangles;
    REQUIRE(tool.displayMesh(extent, local, triangles));
    auto poly = readVtp(file);
    REQUIRE(poly);
    REQUIRE(poly->GetNumberOfPoints() == vtkIdType(local.size()));
    REQUIRE(poly->GetNumberOfPolys() == vtkIdType(triangles.size()));
    double worst = 0;
    for (size_t i = 0; i < local.size(); ++i) {
        double p[3];
        poly->GetPoint(vtkIdType(i), p);
        worst = std::max(worst, (Vec3(p[0], p[1], p[2]) - (at.pose.position + at.pose.orientation.toRotationMatrix() * local[i])).norm());
    }
    CHECK(worst <= 1e-9);
    vtkIdType npts = 0;
    const vtkIdType* ids = nullptr;
    poly->GetPolys()->InitTraversal();
    for (const auto& tri : triangles) {
        REQUIRE(poly->GetPolys()->GetNextCell(npts, ids));
        REQUIRE((npts == 3 && ids[0] == tri[0] && ids[1] == tri[1] && ids[2] == tri[2]));
    }
    for (const auto& [name, value] : {std::pair{"force", at.force}, std::pair{"torque", at.torque}}) {
        vtkDataArray* a = poly->GetFieldData()->GetArray(name);
        REQUIRE(a);
        REQUIRE((a->GetNumberOfTuples() == 1 && a->GetNumberOfComponents() == 3));
        CHECK(Vec3(a->GetComponent(0, 0), a->GetComponent(0, 1), a->GetComponent(0, 2)) == value);
    }
}

/// Runs `steps` steps, recording the probe and the floor at every 10th (and at step 0).
std::map<long, std::map<std::string, ToolAtStep>> runRecording(Simulation& sim, long steps) {
    std::map<long, std::map<std::string, ToolAtStep>> at;
    auto record = [&] {
        for (const std::string name : {"probe", "floor"}) {
            const fascia::core::BaseTool& t = sim.tool(name);
            const fascia::core::Pose pose = name == "probe" ? probePose(sim.time()) : t.pose();
            at[sim.stepCount()][name] = {sim.time(), pose, t.force(), t.torque()};
        }
    };
    record();
    for (long k = 1; k <= steps; ++k) {
        sim.step();
        if (k % 10 == 0) record();
    }
    return at;
}

std::string stepName(const std::string& stem, long step, const char* ext) {
    char b[16];
    std::snprintf(b, sizeof b, "_%06ld", step);
    return stem + b + ext;
}

} // namespace

TEST_CASE("VTKExporter writes each tool touching its body at its pose, with its force and torque, as parts of the .pvd's timesteps",
          "[VTKExporter][CapsuleTool][PlaneTool]") {
    const fs::path dir = freshDir("tools");
    auto sim = Simulation::fromString(scene("<VTKExporter name=\"out\" every=\"10\"/>"), "scene.xml", ".", {dir.string(), 0});
    const auto at = runRecording(*sim, 80);
    sim->finish();
    // contact, and a tilted probe, by the end: the comparisons below see a force and a rotation
    CHECK(at.at(80).at("probe").force.z() > 0);
    CHECK(at.at(80).at("probe").torque.norm() > 0);
    CHECK(sim->tool("probe").pose().orientation.angularDistance(Eigen::Quaterniond::Identity()) == Approx(kTilt));
    // per timestep: the body's .vtu, then the tools of its body in scene order (not the ball)
    const auto entries = pvdEntries(dir / "out.pvd");
    REQUIRE(entries.size() == 3 * at.size());
    size_t e = 0;
    for (const auto& [step, tools] : at) {
        CAPTURE(step);
        const std::vector<std::string> files{stepName("out", step, ".vtu"), stepName("out_probe", step, ".vtp"),
                                             stepName("out_floor", step, ".vtp")};
        for (int part = 0; part < 3; ++part, ++e) {
            CHECK(entries[e].t == tools.at("probe").t);
            CHECK(entries[e].part == part);
            CHECK(entries[e].file == files[size_t(part)]);
        }
        // the plane as a square of 1.5 times the block's rest half-diagonal (0.15 m / 2)
        checkToolFile(dir / files[1], sim->tool("probe"), 0, tools.at("probe"));
        checkToolFile(dir / files[2], sim->tool("floor"), 0.75 * 0.15, tools.at("floor"));
    }
    for (auto& f : fs::directory_iterator(dir)) CHECK(f.path().filename().string().rfind("out_ball", 0) == std::string::npos);
}

TEST_CASE("VTKExporter with tools false writes no tool and lists only the body", "[VTKExporter]") {
    const fs::path dir = freshDir("notools");
    auto sim = Simulation::fromString(scene("<VTKExporter name=\"out\" every=\"10\" tools=\"false\"/>"), "scene.xml", ".", {dir.string(), 0});
    sim->run(20);
    sim->finish();
    const auto entries = pvdEntries(dir / "out.pvd");
    CHECK(entries.size() == 3);
    for (const auto& en : entries) CHECK(en.part == 0);
    CHECK(fileNames(dir) == std::vector<std::string>{"out.pvd", "out_000000.vtu", "out_000010.vtu", "out_000020.vtu"});
}

TEST_CASE("A tool whose files another tool or the surface series would write is a located error", "[VTKExporter]") {
    auto errorOf = [](const std::string& xml) -> std::string {
        try {
            Simulation::fromString(xml, "scene.xml");
        } catch (const fascia::core::Error& e) {
            return e.what();
        }
        return "";
    };
    std::string xml = scene("<VTKExporter name=\"out\" surface=\"true\"/>");
    xml.replace(xml.find("name=\"floor\""), 12, "name=\"surface\"");
    CHECK_THAT(errorOf(xml), Contains("scene.xml:14: error: VTKExporter 'out': tool '/root/block/surface' would write out_surface_<step>.vtp, "
                                      "the files of its own out_surface series"));
    xml = scene("<VTKExporter name=\"out\"/>");
    xml.replace(xml.find("  <Node name=\"other\">"), 0,
                "  <Node name=\"held\">\n    <SphereTool name=\"probe\" body=\"@../block/state\" radius=\"0.01\" position=\"2 0 0\"/>\n  </Node>\n");
    CHECK_THAT(errorOf(xml), Contains("scene.xml:14: error: VTKExporter 'out': tools '/root/probe' and '/root/held/probe' touch its body "
                                      "under one name: their files out_probe_<step>.vtp would be the same"));
}

TEST_CASE("A restored run goes on listing the tools' files of the run before its checkpoint", "[VTKExporter][Simulation]") {
    const fs::path a = freshDir("tools-straight"), b = freshDir("tools-restarted"), ck = freshDir("tools-ckpt") / "run.ckpt";
    const std::string xml = scene("<VTKExporter name=\"out\" every=\"10\"/>");
    {
        auto sim = Simulation::fromString(xml, "scene.xml", ".", {a.string(), 0});
        sim->run(80);
        sim->finish();
    }
    {
        auto first = Simulation::fromString(xml, "scene.xml", ".", {b.string(), 0});
        first->run(40);
        first->save(ck.string());
        first->finish();
    }
    auto second = Simulation::fromString(xml, "scene.xml", ".", {b.string(), 0});
    second->restore(ck.string());
    second->run(40);
    second->finish();
    CHECK(pvdEntries(b / "out.pvd").size() == 3 * 9);  // steps 0, 10 ... 80, three parts each
    CHECK(slurp(a / "out.pvd") == slurp(b / "out.pvd"));
    CHECK(fileNames(a) == fileNames(b));
    CHECK(slurp(a / "out_probe_000080.vtp") == slurp(b / "out_probe_000080.vtp"));
}

namespace {
/// The records a series' saveState wrote, read back into a fresh series of the same .pvd.
fascia::meshio::PvdSeries restored(const std::string& bytes, const fs::path& pvd) {
    fascia::core::Component owner;
    owner.setName("out");
    fascia::core::StateReader in(bytes, 0, bytes.size(), "test.ckpt");
    in.beginSection("/out", "Component");
    fascia::meshio::PvdSeries s;
    s.reset(pvd.string());
    s.restoreState(in, "", owner);
    in.endSection();
    return s;
}
} // namespace

TEST_CASE("A series' checkpoint keeps each timestep's parts, and one written before parts reads as one part per timestep",
          "[VTKExporter]") {
    const fs::path dir = freshDir("pvd-parts");
    for (const char* f : {"out_000000.vtu", "out_probe_000000.vtp", "out_000001.vtu", "out_probe_000001.vtp", "out_floor_000001.vtp"})
        std::ofstream(dir / f) << "";  // the files the series lists, so that a restore finds them
    fascia::meshio::PvdSeries s;
    s.reset((dir / "out.pvd").string());
    s.add(0.0, {"out_000000.vtu", "out_probe_000000.vtp"});
    s.add(0.5, {"out_000001.vtu", "out_probe_000001.vtp", "out_floor_000001.vtp"});
    fascia::core::StateWriter w;
    w.beginSection("/out", "Component");
    s.saveState(w, "");
    w.endSection();
    const auto back = restored(w.bytes(), dir / "out.pvd");
    REQUIRE(back.steps().size() == 2);
    CHECK(back.steps()[1].t == 0.5);
    CHECK(back.steps()[1].parts == std::vector<std::string>{"out_000001.vtu", "out_probe_000001.vtp", "out_floor_000001.vtp"});
    // the records as they were before parts: one file name a line
    fascia::core::StateWriter old;
    old.beginSection("/out", "Component");
    old.put("times", std::vector<double>{0.0, 0.5});
    old.put("files", std::string("out_000000.vtu\nout_000001.vtu\n"));
    old.endSection();
    auto before = restored(old.bytes(), dir / "out.pvd");
    REQUIRE(before.steps().size() == 2);
    CHECK(before.steps()[0].parts == std::vector<std::string>{"out_000000.vtu"});
    CHECK(before.steps()[1].parts == std::vector<std::string>{"out_000001.vtu"});
    // and it goes on with parts: the .pvd lists each timestep's parts
    before.add(1.0, {"out_000002.vtu", "out_probe_000002.vtp"});
    const auto entries = pvdEntries(dir / "out.pvd");
    REQUIRE(entries.size() == 4);
    CHECK((entries[3].t == 1.0 && entries[3].part == 1 && entries[3].file == "out_probe_000002.vtp"));
    CHECK((entries[1].t == 0.5 && entries[1].part == 0 && entries[1].file == "out_000001.vtu"));
}
