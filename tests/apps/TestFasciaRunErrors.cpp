/// fascia-run on scenes that must fail: located messages, the documented exit codes (2 for a bad
/// scene, 1 for an output that cannot be written), and no file written when the run fails before it
/// starts. Every child run is bounded by `timeout`, so a regression that blocks (on a FIFO) fails
/// its test instead of hanging the suite.
#include "FasciaRunWorkspace.h"

#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

using fasciaruntest::Workspace;

/// The exporter of these scenes: a VTKExporter, or in a build without VTK a second Monitor (both
/// write at the first observation and check their output path the same way).
const std::string kExporter = FASCIA_HAVE_VTK ? "VTKExporter" : "Monitor";

/// A one-cube HEML scene with a Monitor and an exporter (kExporter).
/// Line 1 is the root node; the force field is on line 6, the exporter on line 9.
std::string cube(const std::string& rootAttrs, const std::string& mu = "1000", const std::string& exporterAttrs = "",
                 const std::string& monitorAttrs = "", const std::string& extra = "") {
    return "<Node name=\"root\" " + rootAttrs + ">\n"
           "  <GridMesh name=\"grid\" min=\"0 0 0\" max=\"0.1 0.1 0.1\" resolution=\"1 1 1\" element=\"tetrahedra6\"/>\n"
           "  <MechanicalObject name=\"state\"/>\n"
           "  <LumpedMass density=\"1000\"/>\n"
           "  <StVenantKirchhoff lambda=\"1500\" mu=\"" + mu + "\"/>\n"
           "  <HEMLForceField name=\"heml\"/>\n"
           "  <SemiImplicitEuler damping=\"20\"/>\n"
           "  <Monitor name=\"curve\" indices=\"7\" " + monitorAttrs + "/>\n"
           "  <" + kExporter + " name=\"cube\" " + (FASCIA_HAVE_VTK ? "" : "indices=\"0\" ") + exporterAttrs + "/>\n" + extra +
           "</Node>\n";
}

} // namespace

TEST_CASE("The cube scene of these tests runs and writes its files", "[fascia-run]") {
    // the control for the "nothing written" tests below: the same scene with dt writes all four files
    Workspace w;
    w.write("cube.xml", cube("dt=\"1e-4\""));
    auto r = w.run("cube.xml --steps 2 --output out");
    INFO(r.err);
    CHECK(r.code == 0);
    const std::vector<std::string> files = FASCIA_HAVE_VTK
        ? std::vector<std::string>{"cube.pvd", "cube_000000.vtu", "cube_000001.vtu", "cube_000002.vtu", "curve.csv"}
        : std::vector<std::string>{"cube.csv", "curve.csv"};
    CHECK(w.filesIn("out") == files);
}

TEST_CASE("A scene that fails before the run starts leaves no file behind", "[fascia-run]") {
    Workspace w;
    SECTION("no dt") {
        w.write("s.xml", cube(""));
        auto r = w.run("s.xml --output out");
        CHECK(r.code == 2);
        CHECK_THAT(r.err, StartsWith("s.xml:1: error: no time step"));
    }
    SECTION("endTime of 1e300 s") {
        w.write("s.xml", cube("dt=\"0.01\" endTime=\"1e300\""));
        auto r = w.run("s.xml --output out");
        CHECK(r.code == 2);
        CHECK_THAT(r.err, StartsWith("s.xml:1: error: time ") && Contains("is more than 1e12 steps"));
    }
    SECTION("mu of 1e308 with dt auto") {
        w.write("s.xml", cube("dt=\"auto\"", "1e308"));
        auto r = w.run("s.xml --output out");
        INFO(r.err);
        CHECK(r.code == 2);
        // says why: the stable step the force field computes, not "set dt"
        CHECK_THAT(r.err, StartsWith("s.xml:6: error: HEMLForceField 'heml': dt=\"auto\" but the stable time step it "
                                     "computes is ") &&
                              Contains("not a positive number"));
        CHECK_THAT(r.err, !Contains("no time step"));
    }
    SECTION("an output outside the output folder") {
        w.write("s.xml", cube("dt=\"0.01\"", "1000", "filename=\"../x\""));
        auto r = w.run("s.xml --steps 1 --output out");
        CHECK(r.code == 2);
        CHECK_THAT(r.err, StartsWith("s.xml:9: error: " + kExporter + " 'cube': writes '") &&
                              Contains("', which is outside the output folder 'out'"));
        CHECK_FALSE(fs::exists(w.dir() / "x.pvd"));
        CHECK_FALSE(fs::exists(w.dir() / "x_000000.vtu"));
        CHECK_FALSE(fs::exists(w.dir() / "x"));
    }
    SECTION("an absolute Monitor path") {
        const std::string abs = (w.dir() / "abs.csv").string();
        w.write("s.xml", cube("dt=\"0.01\"", "1000", "", "filename=\"" + abs + "\""));
        auto r = w.run("s.xml --steps 1 --output out");
        CHECK(r.code == 2);
        CHECK_THAT(r.err, StartsWith("s.xml:8: error: Monitor 'curve': writes '" + abs +
                                     "', which is outside the output folder 'out'"));
        CHECK_FALSE(fs::exists(abs));
    }
    SECTION("a second integrator in the node") {
        w.write("s.xml", cube("dt=\"0.01\"", "1000", "", "", "  <SemiImplicitEuler name=\"again\"/>\n"));
        auto r = w.run("s.xml --steps 1 --output out");
        CHECK(r.code == 2);
        CHECK_THAT(r.err, StartsWith("s.xml:10: error: SemiImplicitEuler 'again': a second integrator in node 'root'"));
    }
    SECTION("a second root element") {
        w.write("s.xml", cube("dt=\"0.01\"") + "<Node name=\"other\"/>\n");
        auto r = w.run("s.xml --steps 1 --output out");
        CHECK(r.code == 2);
        CHECK_THAT(r.err, StartsWith("s.xml:11: error: a second root element <Node> after <Node> (line 1)"));
    }
    CHECK(w.filesIn("out").empty());
}

namespace {

/// The lines of a run's stderr.
std::vector<std::string> linesOf(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
}

/// s with the first `from` replaced by `to` (the test fails when there is none).
std::string edited(std::string s, const std::string& from, const std::string& to) {
    const size_t at = s.find(from);
    REQUIRE(at != std::string::npos);
    return s.replace(at, from.size(), to);
}

/// The lines of a run's stderr that are errors, not notes.
std::vector<std::string> errorLinesOf(const std::string& text) {
    std::vector<std::string> out;
    for (auto& line : linesOf(text))
        if (line.find(": error: ") != std::string::npos) out.push_back(line);
    return out;
}

} // namespace

TEST_CASE("A scene with three independent mistakes prints the three errors in order and their count, and exits 2",
          "[fascia-run]") {
    // an unknown attribute on line 4, a value out of range on line 7, an unknown component on line 10
    Workspace w;
    std::string s = cube("dt=\"0.01\"", "1000", "", "", "  <ConstantForse group=\"zmax\" totalForce=\"0 0 1\"/>\n");
    s = edited(s, "density=", "densty=");
    s = edited(s, "damping=\"20\"", "damping=\"-20\"");
    w.write("s.xml", s);
    auto r = w.run("s.xml --steps 1 --output out");
    INFO(r.err);
    CHECK(r.code == 2);
    CHECK(errorLinesOf(r.err) == std::vector<std::string>{
                                     "s.xml:4: error: LumpedMass: unknown attribute 'densty'",
                                     "s.xml:7: error: SemiImplicitEuler: damping = -20 is outside >= 0",
                                     "s.xml:10: error: unknown component 'ConstantForse'"});
    CHECK(r.firstErrLine() == "s.xml:4: error: LumpedMass: unknown attribute 'densty'");
    CHECK_THAT(r.err, Contains("s.xml:4: note: did you mean 'density'?\n"));
    CHECK_THAT(r.err, Contains("s.xml:10: note: did you mean 'ConstantForce'?\n"));
    CHECK(linesOf(r.err).back() == "s.xml: 3 errors");
    CHECK(w.filesIn("out").empty());
}

TEST_CASE("A scene with 30 mistakes prints the first 20, says how many more, and exits 2", "[fascia-run]") {
    Workspace w;
    std::string extra;
    for (int i = 0; i < 30; ++i) extra += "  <FixedConstraint name=\"fix" + std::to_string(i) + "\" group=\"zmin\" axes=\"1\"/>\n";
    w.write("s.xml", cube("dt=\"0.01\"", "1000", "", "", extra));
    auto r = w.run("s.xml --steps 1 --output out");
    INFO(r.err);
    CHECK(r.code == 2);
    const auto errors = errorLinesOf(r.err);
    REQUIRE(errors.size() == 20);
    CHECK(errors.front() == "s.xml:10: error: FixedConstraint 'fix0': unknown attribute 'axes'");
    CHECK(errors.back() == "s.xml:29: error: FixedConstraint 'fix19': unknown attribute 'axes'");
    const auto lines = linesOf(r.err);
    REQUIRE(lines.size() >= 2);
    CHECK(lines[lines.size() - 2] == "s.xml: note: 10 more errors not shown");
    CHECK(lines.back() == "s.xml: 30 errors");
}

TEST_CASE("An error that follows from another one is printed once", "[fascia-run]") {
    Workspace w;
    SECTION("a required parameter whose value was refused is not missing too") {
        std::string s = cube("dt=\"0.01\"");
        s = edited(s, "<StVenantKirchhoff lambda=\"1500\" mu=\"1000\"/>", "<IncompressibleNeoHookean C1=\"soft\"/>");
        w.write("s.xml", s);
        auto r = w.run("s.xml --steps 1 --output out");
        INFO(r.err);
        CHECK(r.code == 2);
        CHECK(errorLinesOf(r.err) == std::vector<std::string>{"s.xml:5: error: IncompressibleNeoHookean: C1 = \"soft\" is not a number"});
        CHECK_THAT(r.err, !Contains("errors"));  // one error: no count line
    }
    SECTION("a link to a component that could not be created is not a link to nothing") {
        std::string s = cube("dt=\"0.01\"");
        s = edited(s, "<StVenantKirchhoff", "<StVenantKirchof name=\"mat\"");
        s = edited(s, "<HEMLForceField name=\"heml\"/>", "<HEMLForceField name=\"heml\" material=\"@mat\"/>");
        w.write("s.xml", s);
        auto r = w.run("s.xml --steps 1 --output out");
        INFO(r.err);
        CHECK(r.code == 2);
        CHECK(errorLinesOf(r.err) == std::vector<std::string>{"s.xml:5: error: unknown component 'StVenantKirchof'"});
    }
}

TEST_CASE("An XML syntax error is printed alone, whatever else the scene holds", "[fascia-run]") {
    Workspace w;
    std::string s = cube("dt=\"0.01\"");
    s = edited(s, "density=", "densty=");                                // an error the build would find
    s = edited(s, "<Monitor name=\"curve\"", "<Monitor name=curve");    // line 8: stops the parse
    w.write("s.xml", s);
    auto r = w.run("s.xml --steps 1 --output out");
    INFO(r.err);
    CHECK(r.code == 2);
    CHECK(errorLinesOf(r.err) == std::vector<std::string>{
                                     "s.xml:8: error: XML syntax error: malformed attribute (missing quotes or '=')"});
    CHECK(linesOf(r.err).size() == 1);
}

TEST_CASE("A missing or folder or empty or FIFO scene is an error at its line 1 with exit code 2", "[fascia-run]") {
    Workspace w;
    auto r = w.run("missing.xml");
    CHECK(r.code == 2);
    CHECK_THAT(r.err, StartsWith("missing.xml:1: error: cannot open 'missing.xml': no such file"));
    fs::create_directories(w.dir() / "folder.xml");
    r = w.run("folder.xml");
    CHECK(r.code == 2);
    CHECK_THAT(r.err, StartsWith("folder.xml:1: error: 'folder.xml' is a folder, not a scene file"));
    w.write("empty.xml", "");
    r = w.run("empty.xml");
    CHECK(r.code == 2);
    CHECK_THAT(r.err, StartsWith("empty.xml:1: error: the scene is empty"));
    // a FIFO nobody writes to: opening it would block; it is refused from its type
    REQUIRE(::mkfifo((w.dir() / "fifo.xml").c_str(), 0600) == 0);
    r = w.run("fifo.xml");
    CHECK(r.code == 2);
    CHECK_THAT(r.err, StartsWith("fifo.xml:1: error: 'fifo.xml' is a FIFO (named pipe), not a scene file"));
    r = w.run("/dev/zero");
    CHECK(r.code == 2);
    CHECK_THAT(r.err, StartsWith("/dev/zero:1: error: '/dev/zero' is a character device, not a scene file"));
}

TEST_CASE("A mesh file that is a FIFO or a device is refused without blocking", "[fascia-run]") {
    Workspace w;
    REQUIRE(::mkfifo((w.dir() / "mesh.msh").c_str(), 0600) == 0);
    const std::string body = "  <MeshLoader name=\"mesh\" filename=\"FILE\"/>\n  <MechanicalObject/>\n</Node>\n";
    w.write("fifo.xml", "<Node name=\"root\" dt=\"0.01\">\n" + std::regex_replace(body, std::regex("FILE"), "mesh.msh"));
    auto r = w.run("fifo.xml --steps 1");
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Contains("is a FIFO (named pipe), not a mesh file"));
    // /dev/zero under a mesh name (a link): it never ends, and is refused from its type
    fs::create_symlink("/dev/zero", w.dir() / "zero.vtk");
    w.write("zero.xml", "<Node name=\"root\" dt=\"0.01\">\n" + std::regex_replace(body, std::regex("FILE"), "zero.vtk"));
    r = w.run("zero.xml --steps 1");
    CHECK(r.code == 2);
    CHECK_THAT(r.err, Contains("zero.vtk' is a character device, not a mesh file"));
}

TEST_CASE("An output folder that is a file or cannot be written gives exit code 1 naming it", "[fascia-run]") {
    Workspace w;
    w.write("s.xml", cube("dt=\"0.01\""));
    w.write("taken", "a file");
    auto r = w.run("s.xml --steps 1 --output taken");
    CHECK(r.code == 1);
    CHECK_THAT(r.err, StartsWith("taken: error: output folder 'taken' is a file, not a folder"));
    r = w.run("s.xml --steps 1 --output taken/sub");
    CHECK(r.code == 1);
    CHECK_THAT(r.err, StartsWith("taken/sub: error: cannot create output folder 'taken/sub': "));
    if (::geteuid() != 0) {  // root may write anywhere
        fs::create_directories(w.dir() / "ro");
        fs::permissions(w.dir() / "ro", fs::perms::owner_read | fs::perms::owner_exec);
        r = w.run("s.xml --steps 1 --output ro");
        fs::permissions(w.dir() / "ro", fs::perms::owner_all);
        CHECK(r.code == 1);
        CHECK_THAT(r.err, StartsWith("ro: error: cannot write into output folder 'ro': "));
    }
}

namespace {

/// The cube scene solved statically by DynamicRelaxation (line 7) with its attributes, held at the
/// bottom and pulled at the top.
std::string staticCube(const std::string& solverAttrs) {
    std::string s = cube("dt=\"1\"", "1000", "", "",
                         "  <FixedConstraint group=\"zmin\"/>\n  <ConstantForce group=\"zmax\" totalForce=\"0 0 5\"/>\n");
    const std::string explicitLine = "<SemiImplicitEuler damping=\"20\"/>";
    s.replace(s.find(explicitLine), explicitLine.size(), "<DynamicRelaxation name=\"dr\" " + solverAttrs + "/>");
    return s;
}

} // namespace

TEST_CASE("A static solve prints one line per load step with printSteps and a summary line", "[fascia-run][DynamicRelaxation]") {
    Workspace w;
    w.write("s.xml", staticCube("printSteps=\"true\""));
    auto r = w.run("s.xml --steps 2 --output out");
    INFO(r.out + r.err);
    CHECK(r.code == 0);
    CHECK_THAT(r.out, Contains("DynamicRelaxation 'dr': load step 1 (t = 1 s): "));
    CHECK_THAT(r.out, Contains("DynamicRelaxation 'dr': load step 2 (t = 2 s): 0 iterations"));
    CHECK_THAT(r.out, Contains("DynamicRelaxation 'dr': 2 load steps, "));
    CHECK_THAT(r.out, Contains("all converged"));
    // without printSteps: the summary only
    w.write("q.xml", staticCube(""));
    auto q = w.run("q.xml --steps 2 --output out2");
    CHECK(q.code == 0);
    CHECK(q.out.find("load step 1") == std::string::npos);
    CHECK_THAT(q.out, Contains("DynamicRelaxation 'dr': 2 load steps, "));
}

TEST_CASE("A static solve that does not converge within maxIterations warns at its line and exits 3 with its files",
          "[fascia-run][DynamicRelaxation]") {
    Workspace w;
    w.write("s.xml", staticCube("maxIterations=\"3\""));
    auto r = w.run("s.xml --steps 2 --output out");
    INFO(r.out + r.err);
    CHECK(r.code == 3);
    CHECK_THAT(r.err, Contains("s.xml:7: warning: DynamicRelaxation 'dr': load step 1 (t = 1 s) did not converge in 3 "
                               "iterations: residual "));
    CHECK_THAT(r.err, Contains(", rate "));
    CHECK_THAT(r.err, Contains("raise maxIterations"));
    CHECK_THAT(r.err, Contains("fascia-run: the static solution did not converge"));
    CHECK_THAT(r.out, Contains("2 load step(s) did not converge"));
    // the run went on to its end and wrote its files
    CHECK(w.filesIn("out") ==
          std::vector<std::string>{"cube.pvd", "cube_000000.vtu", "cube_000001.vtu", "cube_000002.vtu", "curve.csv"});
}
