// meshio components in scenes: GridMesh, MeshLoader, BoxROI, VTKExporter, Monitor.
#include "fascia/sim/Simulation.h"

#include <catch2/catch.hpp>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

using fascia::Vec3;
using fascia::core::Error;
using fascia::core::Simulation;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

fs::path freshDir(const std::string& name) {
    fs::path d = fs::temp_directory_path() / ("fascia-meshio-" + name + "-" + std::to_string(getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

std::string cube(const std::string& element, const std::string& extra = "", const std::string& res = "3 3 3") {
    return "<Node name=\"root\" dt=\"0.001\" gravity=\"0 0 -9.81\">\n"
           "  <GridMesh name=\"grid\" min=\"0 0 0\" max=\"0.2 0.1 0.1\" resolution=\"" + res + "\" element=\"" + element + "\"/>\n"
           "  <MechanicalObject name=\"state\"/>\n"
           "  <LumpedMass name=\"mass\" density=\"1000\"/>\n"
           "  <SemiImplicitEuler/>\n" + extra +
           "</Node>\n";
}

std::string errorOf(const std::string& xml) {
    try {
        Simulation::fromString(xml, "scene.xml");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

std::string slurp(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

} // namespace

TEST_CASE("GridMesh fills the box with positive elements and names its faces", "[GridMesh]") {
    const std::string element = GENERATE(as<std::string>{}, "tetrahedra6", "tetrahedra5", "hexahedra");
    CAPTURE(element);
    auto sim = Simulation::fromString(cube(element));
    auto& st = sim->state("state");
    CHECK(st.size() == 4 * 4 * 4);
    // total mass = rho * box volume exactly, so the elements tile the box without gap or overlap
    double total = 0;
    for (double m : sim->groups().front().mass) total += m;
    CHECK(total == Approx(1000 * 0.2 * 0.1 * 0.1).epsilon(1e-12));
    auto* topo = dynamic_cast<fascia::core::BaseTopology*>(sim->find("grid"));
    REQUIRE(topo);
    const auto& mesh = topo->meshData();
    CHECK(mesh.tetrahedra.size() + mesh.hexahedra.size() ==
          size_t(27) * (element == "tetrahedra6" ? 6 : element == "tetrahedra5" ? 5 : 1));
    for (auto& t : mesh.tetrahedra) {
        const auto& p = mesh.points;
        REQUIRE((p[t[1]] - p[t[0]]).dot((p[t[2]] - p[t[0]]).cross(p[t[3]] - p[t[0]])) > 0);
    }
    for (const char* face : {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"}) {
        INFO(face);
        REQUIRE(mesh.nodeGroups.count(face));
        CHECK(mesh.nodeGroups.at(face).size() == 16);
    }
    for (int i : mesh.nodeGroups.at("xmax")) CHECK(mesh.points[i][0] == 0.2);
}

TEST_CASE("a grid fixed at its base reports the whole weight as reaction", "[FixedConstraint][Monitor]") {
    auto dir = freshDir("reaction");
    auto sim = Simulation::fromString(cube("tetrahedra6", "  <FixedConstraint name=\"base\" group=\"zmin\"/>\n"
                                                          "  <FixedConstraint name=\"rest\" group=\"zmax\"/>\n"
                                                          "  <Monitor name=\"mon\" indices=\"0 63\" reactionOf=\"@base\" velocities=\"true\"/>\n"),
                                      "scene.xml", ".", {dir.string(), 0});
    sim->run(1);
    sim->finish();
    auto text = slurp(dir / "mon.csv");
    std::istringstream in(text);
    std::string header, row0, row1;
    std::getline(in, header);
    std::getline(in, row0);
    std::getline(in, row1);
    CHECK(header == "time [s],u0_x [m],u0_y [m],u0_z [m],v0_x [m/s],v0_y [m/s],v0_z [m/s],u63_x [m],u63_y [m],u63_z [m],"
                    "v63_x [m/s],v63_y [m/s],v63_z [m/s],reaction_x [N],reaction_y [N],reaction_z [N]");
    // no internal forces: each fixed node carries its own weight, the zmin face carries the mass of its nodes
    double baseMass = 0;
    auto* topo = dynamic_cast<fascia::core::BaseTopology*>(sim->find("grid"));
    for (int i : topo->meshData().nodeGroups.at("zmin")) baseMass += sim->groups().front().mass[i];
    const double rz = std::stod(row1.substr(row1.rfind(',') + 1));
    CHECK(rz == Approx(9.81 * baseMass).epsilon(1e-12));
    CHECK(row1.substr(0, 5) == "0.001");
}

TEST_CASE("BoxROI selects the nodes and elements inside its box", "[BoxROI]") {
    auto sim = Simulation::fromString(cube("hexahedra", "  <BoxROI name=\"box\" box=\"-1 -1 -1 0.0667 1 1\"/>\n"
                                                        "  <FixedConstraint indices=\"@box.indices\"/>\n"));
    auto* box = sim->find("box");
    auto* idx = dynamic_cast<fascia::core::Param<fascia::IndexList>*>(box->findParam("indices"));
    auto* hex = dynamic_cast<fascia::core::Param<fascia::IndexList>*>(box->findParam("hexahedronIndices"));
    REQUIRE(idx);
    CHECK(idx->get().size() == 32);  // the two first layers of nodes along x
    CHECK(hex->get().size() == 9);   // the first layer of cells
    CHECK_THAT(errorOf(cube("hexahedra", "  <BoxROI box=\"1 0 0 0 1 1\"/>\n")),
               Contains("scene.xml:6:") && Contains("box min exceeds max"));
    CHECK_THAT(errorOf(cube("hexahedra", "  <BoxROI box=\"0 0 0 1 1\"/>\n")), Contains("scene.xml:6:") && Contains("expected 6"));
}

TEST_CASE("MeshLoader reads, scales and moves a mesh, and a bad file is located in the scene and the file",
          "[MeshLoader]") {
    const std::string meshPath = std::string(FASCIA_SOURCE_DIR) + "/scenes/meshes/organ_2428.msh";
    auto sim = Simulation::fromString("<Node name=\"root\" dt=\"0.001\">\n"
                                      "  <MeshLoader name=\"a\" filename=\"" + meshPath + "\"/>\n"
                                      "  <Node name=\"moved\">\n"
                                      "    <MeshLoader name=\"b\" filename=\"" + meshPath + "\" scale=\"2\" translation=\"1 0 0\" rotation=\"0 0 90\"/>\n"
                                      "  </Node>\n"
                                      "</Node>\n");
    auto& a = dynamic_cast<fascia::core::BaseTopology*>(sim->find("a"))->meshData();
    auto& b = dynamic_cast<fascia::core::BaseTopology*>(sim->find("b"))->meshData();
    REQUIRE(a.points.size() == 621);
    REQUIRE(a.tetrahedra.size() == 2421);
    for (size_t i = 0; i < a.points.size(); i += 50) {
        const Vec3 expected(1 - 2 * a.points[i][1], 2 * a.points[i][0], 2 * a.points[i][2]);
        CHECK((b.points[i] - expected).norm() < 1e-14);
    }
    auto e = errorOf("<Node name=\"root\">\n\n  <MeshLoader filename=\"no/such/file.msh\"/>\n</Node>\n");
    CHECK_THAT(e, Contains("no/such/file.msh") && Contains("scene.xml:3"));
    CHECK_THAT(errorOf("<Node name=\"root\">\n  <MeshLoader/>\n</Node>\n"),
               Contains("scene.xml:2:") && Contains("missing required parameter 'filename'"));
    CHECK_THAT(errorOf("<Node name=\"root\">\n  <MeshLoader filename=\"x.msh\" scale=\"0\"/>\n</Node>\n"),
               Contains("scene.xml:2:") && Contains("scale = 0 is outside > 0"));
}

TEST_CASE("VTKExporter files open in VTK's own reader and the values round-trip", "[VTKExporter]") {
    const std::string compression = GENERATE(as<std::string>{}, "lz4", "zlib", "none");
    CAPTURE(compression);
    auto dir = freshDir("vtk-" + compression);
    auto sim = Simulation::fromString(cube("tetrahedra6", "  <FixedConstraint group=\"zmin\"/>\n"
                                                          "  <VTKExporter name=\"out\" every=\"2\" compression=\"" +
                                                              compression + "\"/>\n"),
                                      "scene.xml", ".", {dir.string(), 0});
    sim->run(4);
    sim->finish();
    auto pvd = slurp(dir / "out.pvd");
    CHECK_THAT(pvd, Contains("file=\"out_000000.vtu\"") && Contains("file=\"out_000002.vtu\"") &&
                        Contains("file=\"out_000004.vtu\""));
    CHECK(!fs::exists(dir / "out_000001.vtu"));
    vtkNew<vtkXMLUnstructuredGridReader> reader;
    reader->SetFileName((dir / "out_000004.vtu").string().c_str());
    reader->Update();
    vtkUnstructuredGrid* g = reader->GetOutput();
    auto& st = sim->state("state");
    REQUIRE(g->GetNumberOfPoints() == vtkIdType(st.size()));
    REQUIRE(g->GetNumberOfCells() == 27 * 6);
    vtkDataArray* u = g->GetPointData()->GetArray("displacement");
    vtkDataArray* v = g->GetPointData()->GetArray("velocity");
    REQUIRE(u);
    REQUIRE(v);
    REQUIRE(g->GetPointData()->GetArray("force"));
    for (size_t i = 0; i < st.size(); ++i) {
        double p[3], uu[3], vv[3];
        g->GetPoint(vtkIdType(i), p);
        u->GetTuple(vtkIdType(i), uu);
        v->GetTuple(vtkIdType(i), vv);
        for (int a = 0; a < 3; ++a) {
            REQUIRE(p[a] == st.x()[i][a]);
            REQUIRE(uu[a] == st.x()[i][a] - st.x0()[i][a]);
            REQUIRE(vv[a] == st.v()[i][a]);
        }
    }
}

namespace {
double g_testClock = 0;  ///< seconds, the clock VTKExporter reads in the .pvd test
double testClock() { return g_testClock; }
struct InjectedClock {
    InjectedClock() { fascia::core::setTimerClock(&testClock); }
    ~InjectedClock() { fascia::core::setTimerClock(nullptr); }
};
} // namespace

TEST_CASE("VTKExporter rewrites the .pvd after each of the first 100 files, then once a second of its clock, and completes it "
          "at the end",
          "[VTKExporter]") {
    // the rule (VTKExporter.h): after each file while there are at most 100, past that only when a
    // second has passed since the last rewrite, and at cleanup. The clock is injected, so the
    // expected rewrites are exact: the clock stands still for the first 110 files, then moves 0.25 s
    // a file (exact in binary), so that the .pvd is rewritten at every 4th file after the 110th.
    InjectedClock injected;
    g_testClock = 1000.0;
    auto dir = freshDir("long");
    auto sim = Simulation::fromString(cube("tetrahedra6", "  <FixedConstraint group=\"zmin\"/>\n  <VTKExporter name=\"out\"/>\n",
                                           "2 2 2"),
                                      "scene.xml", ".", {dir.string(), 0});
    auto count = [&] {
        const std::string pvd = slurp(dir / "out.pvd");
        size_t n = 0;
        for (size_t p = pvd.find("<DataSet"); p != std::string::npos; p = pvd.find("<DataSet", p + 1)) ++n;
        return n;
    };
    CHECK(!fs::exists(dir / "out.pvd"));  // the initial state is written at the first step, with the first one
    size_t files = 1, listed = 1;
    for (int step = 1; step <= 130; ++step) {
        if (files >= 110) g_testClock += 0.25;
        sim->step();
        ++files;
        if (files <= 100) listed = files;  // rewritten after every file
        else if (files > 110 && (files - 110) % 4 == 0) listed = files;  // a second after the last rewrite
        INFO("file " << files << ", clock " << g_testClock);
        REQUIRE(count() == listed);
    }
    CHECK(listed == 130);  // rewrites at 114, 118 ... 130: file 131 waits
    // a jump of the clock: the next file rewrites it at once, the one after does not
    g_testClock += 100;
    sim->step();
    CHECK(count() == 132);
    sim->step();
    CHECK(count() == 132);
    sim->finish();
    CHECK(count() == 133);
    CHECK_THAT(slurp(dir / "out.pvd"), Contains("file=\"out_000132.vtu\""));
}

TEST_CASE("a run killed mid-way leaves only complete exporter files", "[VTKExporter]") {
    // The child runs 3 steps (4 complete files), then caps the size of any file it writes at half
    // the smallest of them (RLIMIT_FSIZE, which binds root too): the next .vtu write crosses the
    // cap, the kernel raises SIGXFSZ inside that write, and the handler turns it into SIGKILL.
    // So the kill lands in the middle of writing a file, at a known file, with no sleep involved.
    auto dir = freshDir("killed");
    const std::string xml = cube("tetrahedra6", "  <FixedConstraint group=\"zmin\"/>\n  <VTKExporter name=\"out\"/>\n",
                                 "4 4 4");
    pid_t child = fork();
    REQUIRE(child >= 0);
    if (child == 0) {
        try {
            auto sim = Simulation::fromString(xml, "scene.xml", ".", {dir.string(), 0});
            sim->run(3);
            uintmax_t smallest = fs::file_size(dir / "out_000000.vtu");
            for (int i = 1; i <= 3; ++i) {
                const uintmax_t size = fs::file_size(dir / ("out_00000" + std::to_string(i) + ".vtu"));
                if (size < smallest) smallest = size;
            }
            const rlim_t cap = rlim_t(smallest / 2);
            std::ofstream(dir / "cap.txt") << cap << "\n";
            const rlimit noCore{0, 0}, fsize{cap, cap};
            setrlimit(RLIMIT_CORE, &noCore);
            std::signal(SIGXFSZ, [](int) { kill(getpid(), SIGKILL); });
            setrlimit(RLIMIT_FSIZE, &fsize);
            for (int i = 0; i < 10; ++i) sim->step();
        } catch (...) {
        }
        _exit(0);  // not reached when the cap works
    }
    int status = 0;
    waitpid(child, &status, 0);
    REQUIRE(WIFSIGNALED(status));
    REQUIRE(WTERMSIG(status) == SIGKILL);
    uintmax_t cap = 0;
    std::ifstream(dir / "cap.txt") >> cap;
    REQUIRE(cap > 0);
    // the kill landed during the write of the fifth file: its temporary holds exactly cap bytes
    REQUIRE(fs::exists(dir / ".out_000004.vtu.tmp"));
    CHECK(fs::file_size(dir / ".out_000004.vtu.tmp") == cap);
    int complete = 0;
    for (auto& e : fs::directory_iterator(dir)) {
        const auto name = e.path().filename().string();
        if (name[0] == '.') continue;  // the temporary file being written when killed
        if (e.path().extension() == ".vtu") {
            vtkNew<vtkXMLUnstructuredGridReader> reader;
            reader->SetFileName(e.path().string().c_str());
            reader->Update();
            INFO(name);
            REQUIRE(reader->GetOutput()->GetNumberOfPoints() == 5 * 5 * 5);
            REQUIRE(reader->GetOutput()->GetPointData()->GetArray("displacement"));
            ++complete;
        }
    }
    CHECK(complete == 4);
    CHECK_FALSE(fs::exists(dir / "out_000004.vtu"));
    // the collection lists only files that exist: the four complete ones
    auto pvd = slurp(dir / "out.pvd");
    CHECK_THAT(pvd, Contains("</VTKFile>"));
    std::istringstream in(pvd);
    int listed = 0;
    for (std::string line; std::getline(in, line);) {
        auto p = line.find("file=\"");
        if (p == std::string::npos) continue;
        auto f = line.substr(p + 6, line.find('"', p + 6) - p - 6);
        INFO(f);
        CHECK(fs::exists(dir / f));
        ++listed;
    }
    CHECK(listed == 4);
}

TEST_CASE("Monitor and exporter parameters are checked", "[Monitor][VTKExporter]") {
    CHECK_THAT(errorOf(cube("hexahedra", "  <Monitor indices=\"64\"/>\n")),
               Contains("scene.xml:6:") && Contains("node index 64 is out of range"));
    CHECK_THAT(errorOf(cube("hexahedra", "  <Monitor indices=\"0\" reactionOf=\"@grid\"/>\n")),
               Contains("scene.xml:6:") && Contains("which is not a BaseConstraint"));
    CHECK_THAT(errorOf(cube("hexahedra", "  <Monitor indices=\"0\" elements=\"1\"/>\n")),
               Contains("scene.xml:6:") && Contains("no element force field"));
    CHECK_THAT(errorOf(cube("hexahedra", "  <VTKExporter every=\"0\"/>\n")),
               Contains("scene.xml:6:") && Contains("every = 0 is outside >= 1"));
}

TEST_CASE("two exporters writing the same files are a located error", "[VTKExporter][Monitor]") {
    auto dir = freshDir("clash");
    auto err = [&](const std::string& xml) {
        try {
            Simulation::fromString(xml, "scene.xml", ".", {dir.string(), 0});
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    const std::string twoNodes = "<Node name=\"root\" dt=\"0.001\">\n"
                                 "  <Node name=\"a\">\n    <GridMesh/>\n    <MechanicalObject/>\n    <VTKExporter/>\n  </Node>\n"
                                 "  <Node name=\"b\">\n    <GridMesh/>\n    <MechanicalObject/>\n    <VTKExporter/>\n  </Node>\n"
                                 "</Node>\n";
    CHECK_THAT(err(twoNodes), Contains("scene.xml:10: error: VTKExporter") && Contains("/root/a/VTKExporter"));
    std::string monitors = twoNodes;
    for (auto p = monitors.find("VTKExporter"); p != std::string::npos; p = monitors.find("VTKExporter"))
        monitors.replace(p, 11, "Monitor indices=\"0\"");
    CHECK_THAT(err(monitors), Contains("scene.xml:10: error: Monitor") && Contains("Monitor.csv"));
}

TEST_CASE("a Monitor refuses a constraint of another state", "[Monitor]") {
    CHECK_THAT(errorOf("<Node name=\"root\" dt=\"0.001\">\n"
                       "  <Node name=\"a\">\n    <GridMesh/>\n    <MechanicalObject/>\n    <FixedConstraint name=\"fix\" indices=\"0\"/>\n  </Node>\n"
                       "  <Node name=\"b\">\n    <GridMesh resolution=\"1 1 1\"/>\n    <MechanicalObject/>\n"
                       "    <Monitor indices=\"0\" reactionOf=\"@/root/a/fix\"/>\n  </Node>\n"
                       "</Node>\n"),
               Contains("scene.xml:10:") && Contains("acts on another state"));
}

TEST_CASE("GridMesh parameters are checked", "[GridMesh]") {
    auto grid = [](const std::string& attrs) { return "<Node name=\"root\">\n  <GridMesh " + attrs + "/>\n</Node>\n"; };
    CHECK_THAT(errorOf(grid("min=\"0 0 0\" max=\"1 -1 1\"")), Contains("scene.xml:2:") && Contains("max must exceed min"));
    CHECK_THAT(errorOf(grid("resolution=\"2 0 2\"")), Contains("scene.xml:2:") && Contains("resolution"));
    CHECK_THAT(errorOf(grid("resolution=\"2 2\"")), Contains("scene.xml:2:") && Contains("expected 3"));
    CHECK_THAT(errorOf(grid("element=\"prisms\"")), Contains("scene.xml:2:") && Contains("one of tetrahedra6|tetrahedra5|hexahedra"));
    CHECK_THAT(errorOf(grid("resolution=\"1000 1000 1000\"")), Contains("scene.xml:2:") && Contains("at most 5e7"));
}

TEST_CASE("InlineMesh takes its points, elements and node groups from the scene, checked as a file's", "[InlineMesh]") {
    auto scene = [](const std::string& mesh, const std::string& state = "") {
        return "<Node name=\"root\" dt=\"0.001\">\n" + mesh +
               "  <MechanicalObject name=\"state\"" + state + "/>\n"
               "  <LumpedMass density=\"1000\"/>\n"
               "  <FixedConstraint group=\"base\"/>\n"
               "  <SemiImplicitEuler/>\n</Node>\n";
    };
    const std::string points = "points=\"0 0 0  0.01 0 0  0 0.01 0  0 0 0.01  0.01 0.01 0.01\"";
    auto sim = Simulation::fromString(scene("  <InlineMesh name=\"m\" " + points +
                                            " tetrahedra=\"0 1 2 3  1 2 3 4\" nodeGroups=\"base: 2 0 1 1; top: 4\"/>\n",
                                            " position=\"@m.positions\""));
    const auto& mesh = dynamic_cast<fascia::core::Param<fascia::MeshData>*>(sim->find("m")->findParam("mesh"))->get();
    CHECK(sim->state("state").x()[4] == fascia::Vec3(0.01, 0.01, 0.01));
    CHECK(dynamic_cast<fascia::core::BaseTopology*>(sim->find("m"))->boundaryTriangles().size() == 6);
    CHECK(mesh.points.size() == 5);
    CHECK(mesh.tetrahedra.size() == 2);
    CHECK(mesh.nodeGroups.at("base") == fascia::IndexList{0, 1, 2});  // sorted, unique
    CHECK(mesh.nodeGroups.at("top") == fascia::IndexList{4});
    // an inverted element: refused, or flipped with fixOrientation
    CHECK_THAT(errorOf(scene("  <InlineMesh " + points + " tetrahedra=\"0 2 1 3\"/>\n")), Contains("scene.xml:2:"));
    auto fixed = Simulation::fromString(scene("  <InlineMesh name=\"m\" " + points +
                                              " tetrahedra=\"0 2 1 3\" nodeGroups=\"base: 0\" fixOrientation=\"true\"/>\n"));
    CHECK(dynamic_cast<fascia::core::BaseTopology*>(fixed->find("m"))->meshData().tetrahedra.size() == 1);
    // a hexahedral one, and the errors of its own parameters
    CHECK_NOTHROW(Simulation::fromString(scene(
        "  <InlineMesh points=\"0 0 0 1 0 0 1 1 0 0 1 0 0 0 1 1 0 1 1 1 1 0 1 1\" hexahedra=\"0 1 2 3 4 5 6 7\" nodeGroups=\"base: 0 1 2 3\"/>\n")));
    CHECK_THAT(errorOf(scene("  <InlineMesh " + points + "/>\n")), Contains("scene.xml:2:") && Contains("no element"));
    CHECK_THAT(errorOf(scene("  <InlineMesh " + points + " tetrahedra=\"0 1 2 3\" nodeGroups=\"base: 9\"/>\n")),
               Contains("scene.xml:2:") && Contains("'9' is no node index in [0, 5)"));
    CHECK_THAT(errorOf(scene("  <InlineMesh " + points + " tetrahedra=\"0 1 2 3\" nodeGroups=\": 1\"/>\n")),
               Contains("has no name"));
}
