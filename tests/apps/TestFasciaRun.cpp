/// fascia-run end to end: exit codes (0 good, 1 bad command line, 2 bad scene, 3 failed run), the
/// summary line, and the options.
#include "FasciaRunWorkspace.h"

#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
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

const std::string kGoodPlugin = std::string(TEST_PLUGIN_DIR) + "/good/libfascia_testplugin.so";

using fasciaruntest::slurpFile;
using fasciaruntest::Workspace;

/// A one-body scene of the test plugin's components.
std::string scene(const std::string& rootAttrs, const std::string& nanAttrs = "", const std::string& extra = "") {
    return R"(<Node name="root" )" + rootAttrs + R"(>
  <RequiredPlugin name=")" + kGoodPlugin + R"("/>
  <TestCounter name="counter" label="a"/>
  <Node name="body">
    <TestEuler name="euler"/>
    <TestState name="state" position="0 0 0  1 0 0"/>
    <TestMass name="mass" mass="2"/>
    <TestNaN name="nan" )" + nanAttrs + R"(/>
  </Node>)" + extra + R"(
</Node>
)";
}

/// Parses the summary line; false when it does not have the documented shape.
struct Summary {
    long steps = -1;
    double simulated = -1, wall = -1, msPerStep = -1, factor = -1;
};
bool parseSummary(const std::string& line, Summary& s) {
    static const std::regex re(
        R"(fascia-run: (\d+) steps, ([-+0-9.eE]+) s simulated, ([0-9.eE+-]+) s wall, ([0-9.eE+-]+) ms/step, real-time factor ([0-9.eE+-]+|inf|nan))");
    std::smatch m;
    if (!std::regex_match(line, m, re)) return false;
    s.steps = std::stol(m[1]);
    s.simulated = std::stod(m[2]);
    s.wall = std::stod(m[3]);
    s.msPerStep = std::stod(m[4]);
    s.factor = m[5] == "inf" || m[5] == "nan" ? -1 : std::stod(m[5]);
    return true;
}

} // namespace

TEST_CASE("fascia-run runs a good scene and prints the summary line", "[fascia-run]") {
    Workspace w;
    w.write("good.xml", scene("dt=\"0.01\""));
    auto r = w.run("good.xml --steps 10");
    INFO(r.out << r.err);
    CHECK(r.code == 0);
    Summary s;
    REQUIRE(parseSummary(r.summary(), s));
    CHECK(s.steps == 10);
    CHECK(s.simulated == Approx(0.1));
    CHECK(s.wall >= 0);
    // the wall time is printed to 1 ms: ms/step agrees with it to that resolution over 10 steps
    CHECK(s.msPerStep == Approx(1e3 * s.wall / 10).margin(0.05 + 1e-3));
    CHECK(r.err.empty());  // not a terminal: no progress bar
}

TEST_CASE("fascia-run --time runs ceil(T/dt) steps and ends on T exactly, the last step shortened", "[fascia-run]") {
    Workspace w;
    w.write("good.xml", scene("dt=\"0.01\""));
    auto r = w.run("good.xml --time 0.05");
    INFO(r.out << r.err);
    CHECK(r.code == 0);
    Summary s;
    REQUIRE(parseSummary(r.summary(), s));
    CHECK(s.steps == 5);
    CHECK(s.simulated == Approx(0.05));
    auto r2 = w.run("good.xml --time 0.041");
    INFO(r2.out << r2.err);
    REQUIRE(parseSummary(r2.summary(), s));
    CHECK(s.steps == 5);
    CHECK(s.simulated == 0.041);  // printed to 6 digits: 0.05 before (ceil(T/dt) dt)
    // endTime the same way
    w.write("end.xml", scene("dt=\"0.01\" endTime=\"0.0234\""));
    auto r3 = w.run("end.xml");
    REQUIRE(parseSummary(r3.summary(), s));
    CHECK(s.steps == 3);
    CHECK(s.simulated == 0.0234);
}

TEST_CASE("fascia-run refuses a dt larger than the end time with a located error", "[fascia-run]") {
    Workspace w;
    w.write("end.xml", scene("dt=\"0.01\" endTime=\"0.004\""));
    auto r = w.run("end.xml");
    CHECK(r.code == 2);
    CHECK_THAT(r.firstErrLine(), Contains("end.xml:1: error: Node 'root': dt = 0.01 s is larger than the end time 0.004 s: "
                                          "not even one step fits"));
    auto r2 = w.run("end.xml --time 0.002 --dt 0.005");
    CHECK(r2.code == 2);
    CHECK_THAT(r2.firstErrLine(), Contains("dt = 0.005 s is larger than the end time 0.002 s"));
    CHECK(w.run("end.xml --time 0.01").code == 0);  // one whole step fits
}

TEST_CASE("fascia-run without --steps or --time runs to the root's endTime, else 100 steps", "[fascia-run]") {
    Workspace w;
    w.write("end.xml", scene("dt=\"0.01\" endTime=\"0.03\""));
    w.write("noend.xml", scene("dt=\"0.01\""));
    Summary s;
    auto r = w.run("end.xml");
    INFO(r.out << r.err);
    REQUIRE(parseSummary(r.summary(), s));
    CHECK(s.steps == 3);
    auto r2 = w.run("noend.xml");
    REQUIRE(parseSummary(r2.summary(), s));
    CHECK(s.steps == 100);
    CHECK(s.simulated == Approx(1.0));
}

TEST_CASE("fascia-run --dt overrides the scene's time step", "[fascia-run]") {
    Workspace w;
    w.write("good.xml", scene("dt=\"0.01\""));
    auto r = w.run("good.xml --dt 0.02 --steps 3");
    INFO(r.out << r.err);
    CHECK(r.code == 0);
    Summary s;
    REQUIRE(parseSummary(r.summary(), s));
    CHECK(s.simulated == Approx(0.06));
    // a scene without dt runs with --dt, and fails without it
    w.write("nodt.xml", scene(""));
    CHECK(w.run("nodt.xml --dt 0.5 --steps 2").code == 0);
    auto bad = w.run("nodt.xml --steps 2");
    CHECK(bad.code == 2);
    CHECK_THAT(bad.err, Contains("no time step"));
}

TEST_CASE("fascia-run --quiet still prints the summary", "[fascia-run]") {
    Workspace w;
    w.write("good.xml", scene("dt=\"0.01\""));
    auto r = w.run("good.xml --steps 4 --quiet");
    INFO(r.out << r.err);
    CHECK(r.code == 0);
    Summary s;
    REQUIRE(parseSummary(r.summary(), s));
    CHECK(s.steps == 4);
    CHECK(r.err.empty());
}

TEST_CASE("fascia-run --steps 0 initialises and stops", "[fascia-run]") {
    Workspace w;
    w.write("good.xml", scene("dt=\"0.01\""));
    auto r = w.run("good.xml --steps 0");
    CHECK(r.code == 0);
    Summary s;
    REQUIRE(parseSummary(r.summary(), s));
    CHECK(s.steps == 0);
    CHECK(s.simulated == 0);
}

TEST_CASE("fascia-run --output creates the folder and accepts --threads", "[fascia-run]") {
    Workspace w;
    w.write("good.xml", scene("dt=\"0.01\""));
    auto r = w.run("good.xml --steps 2 --threads 1 --output out/deep");
    INFO(r.out << r.err);
    CHECK(r.code == 0);
    CHECK(fs::is_directory(w.dir() / "out" / "deep"));
    r = w.run("good.xml --steps 2 --threads 2 --worker-cores 0 --output out");
    INFO(r.out << r.err);
    CHECK(r.code == 0);
    CHECK_THAT(r.err, !Contains("could not be pinned"));
}

TEST_CASE("fascia-run exits 2 on a bad scene with the located error on stderr", "[fascia-run]") {
    Workspace w;
    SECTION("a value out of range") {
        const std::string f = w.write("bad.xml", scene("dt=\"0.01\"", "", R"(
  <TestCounter name="c" label="b" scale="12"/>)"));
        auto r = w.run("bad.xml --steps 3");
        CHECK(r.code == 2);
        CHECK(r.firstErrLine() == "bad.xml:10: error: TestCounter 'c': scale = 12 is outside [0, 10)");
        CHECK(r.summary().empty());
    }
    SECTION("an unknown component, with a suggestion") {
        w.write("bad.xml", scene("dt=\"0.01\"", "", R"(
  <TestCountr name="c" label="b"/>)"));
        auto r = w.run("bad.xml --steps 3");
        CHECK(r.code == 2);
        CHECK(r.firstErrLine() == "bad.xml:10: error: unknown component 'TestCountr'");
        CHECK_THAT(r.err, Contains("bad.xml:10: note: did you mean 'TestCounter'?"));
    }
    SECTION("an XML syntax error") {
        w.write("bad.xml", "<Node name=\"root\">\n  <TestCounter label=x/>\n</Node>\n");
        auto r = w.run("bad.xml");
        CHECK(r.code == 2);
        CHECK(r.firstErrLine() == "bad.xml:2: error: XML syntax error: malformed attribute (missing quotes or '=')");
    }
    SECTION("a missing scene file") {
        auto r = w.run("missing.xml");
        CHECK(r.code == 2);
        CHECK_THAT(r.err, Contains("missing.xml"));
        CHECK_THAT(r.err, Contains("no such file"));
    }
    SECTION("a missing plugin") {
        w.write("bad.xml", "<Node name=\"root\" dt=\"0.1\">\n  <RequiredPlugin name=\"fascia_nosuchplugin\"/>\n</Node>\n");
        auto r = w.run("bad.xml");
        CHECK(r.code == 2);
        CHECK_THAT(r.firstErrLine(), StartsWith("bad.xml:2: error: plugin 'fascia_nosuchplugin' not found"));
    }
}

TEST_CASE("fascia-run exits 3 when the simulation fails, naming the step and the component", "[fascia-run]") {
    Workspace w;
    w.write("nan.xml", scene("dt=\"0.01\"", "nanAtStep=\"3\""));
    auto r = w.run("nan.xml --steps 10");
    INFO(r.out << r.err);
    CHECK(r.code == 3);
    CHECK_THAT(r.err, Contains("step 3"));
    CHECK_THAT(r.err, Contains("/root/body/nan"));
    CHECK(r.summary().empty());
}

TEST_CASE("fascia-run exits 1 on a bad command line", "[fascia-run]") {
    Workspace w;
    w.write("good.xml", scene("dt=\"0.01\""));
    for (const char* args : {"good.xml --steps 3 --time 1", "good.xml --bogus", "good.xml --steps", "good.xml --steps -2",
                             "good.xml --dt 0", "good.xml --dt abc", "", "good.xml other.xml", "good.xml --worker-cores",
                             "good.xml --worker-cores 1,,2", "good.xml --worker-cores x", "good.xml --worker-cores 99999"}) {
        CAPTURE(args);
        auto r = w.run(args);
        CHECK(r.code == 1);
        CHECK_THAT(r.err, StartsWith("fascia-run: "));
        CHECK(r.summary().empty());
    }
}

TEST_CASE("fascia-run --help prints the usage and the exit codes", "[fascia-run]") {
    Workspace w;
    auto r = w.run("--help");
    CHECK(r.code == 0);
    CHECK_THAT(r.out, Contains("usage:"));
    CHECK_THAT(r.out, Contains("--steps N"));
    CHECK_THAT(r.out, Contains("--describe"));
    CHECK_THAT(r.out, Contains("exit codes"));
}

TEST_CASE("fascia-run --list prints every component with its plugin", "[fascia-run]") {
    Workspace w;
    const std::string env = "FASCIA_PLUGIN_PATH='" + std::string(TEST_PLUGIN_DIR) + "/good'";
    auto r = w.run("--list", env);
    INFO(r.out << r.err);
    CHECK(r.code == 0);
    CHECK(std::regex_search(r.out, std::regex(R"((^|\n)TestCounter +fascia\.test +counts beginStep and observe calls)")));
    CHECK(std::regex_search(r.out, std::regex(R"((^|\n)TestNaN +fascia\.test +)")));
}

TEST_CASE("fascia-run --describe prints a component's parameters", "[fascia-run]") {
    Workspace w;
    const std::string env = "FASCIA_PLUGIN_PATH='" + std::string(TEST_PLUGIN_DIR) + "/good'";
    auto r = w.run("--describe TestCounter", env);
    INFO(r.out << r.err);
    CHECK(r.code == 0);
    CHECK_THAT(r.out, StartsWith("TestCounter (plugin fascia.test): counts beginStep and observe calls"));
    CHECK_THAT(r.out, Contains("scale  [double, m] default: 1  range: [0, 10)"));
    CHECK_THAT(r.out, Contains("a length in [0, 10)"));
    CHECK_THAT(r.out, Contains("mode  [string] default: fast  range: one of fast|accurate|debug"));
    CHECK_THAT(r.out, Contains("label  [string] required"));
    CHECK_THAT(r.out, Contains("beginSteps  [int] output"));
    CHECK_THAT(r.out, Contains("partner  [link to TestCounter]"));

    auto bad = w.run("--describe TestCountr", env);
    CHECK(bad.code == 2);
    CHECK_THAT(bad.err, Contains("did you mean 'TestCounter'?"));
}

TEST_CASE("fascia-run --describe of every law prints its energy in full and --list its one-line summary", "[fascia-run]") {
    Workspace w;
    auto list = w.run("--list");
    REQUIRE(list.code == 0);
    // the laws: the components of the materials plugin
    std::vector<std::string> laws;
    std::istringstream in(list.out);
    for (std::string line; std::getline(in, line);) {
        std::istringstream words(line);
        std::string name, plugin;
        words >> name >> plugin;
        if (plugin == "fascia.materials") laws.push_back(name);
    }
    CHECK(laws.size() >= 11);
    for (const std::string& law : laws) {
        CAPTURE(law);
        auto r = w.run("--describe " + law);
        CHECK(r.code == 0);
        // line 1: "<Law> (plugin fascia.materials): summary", line 2: the energy
        const size_t eol = r.out.find('\n');
        REQUIRE(eol != std::string::npos);
        CHECK_THAT(r.out.substr(eol + 1, 4), Contains("W = "));
        CHECK_THAT(list.out, !Contains("W = "));  // --list keeps to the first line
    }
    auto grid = w.run("--describe GridMesh");
    CHECK_THAT(grid.out, Contains("node numbering:") && Contains("has index i + (nx + 1) (j + (ny + 1) k)"));
}

TEST_CASE("fascia-run --timers prints the time of each component", "[fascia-run]") {
    Workspace w;
    w.write("good.xml", scene("dt=\"0.01\""));
    auto r = w.run("good.xml --steps 3 --timers");
    INFO(r.out << r.err);
    CHECK(r.code == 0);
    CHECK(std::regex_search(r.out, std::regex(R"(/root/body/euler +TestEuler +[0-9.]+ +3\b)")));
}

namespace {

const std::string kProbePlugin = std::string(TEST_PLUGIN_DIR) + "/probe/libfascia_testplugin_probe.so";

/// A small body of the built-in plugins with a VTKExporter (in a build with VTK) and a Monitor, and
/// the test probe.
std::string probeScene(const std::string& probeAttrs) {
    return R"(<Node name="root" dt="0.001" gravity="0 0 -9.81">
  <RequiredPlugin name=")" + kProbePlugin + R"("/>
  <TestProbe name="probe" )" + probeAttrs + R"(/>
  <Node name="body">
    <GridMesh name="grid" min="0 0 0" max="0.2 0.1 0.1" resolution="2 2 2" element="tetrahedra6"/>
    <MechanicalObject name="state"/>
    <LumpedMass density="1000"/>
    <SemiImplicitEuler/>
    <FixedConstraint group="zmin"/>
    )" + std::string(FASCIA_HAVE_VTK ? "<VTKExporter name=\"out\"/>" : "") + R"(
    <Monitor name="mon" indices="0 26" positions="true"/>
  </Node>
</Node>
)";
}

/// fascia-run started in dir with args, its output into dir/stdout.txt and dir/stderr.txt.
pid_t spawnRun(const fs::path& dir, const std::vector<std::string>& args) {
    const pid_t pid = fork();
    if (pid != 0) return pid;
    if (chdir(dir.c_str()) != 0) _exit(126);
    if (!freopen("stdout.txt", "w", stdout) || !freopen("stderr.txt", "w", stderr) || !freopen("/dev/null", "r", stdin))
        _exit(126);
    std::vector<char*> argv{const_cast<char*>(FASCIA_RUN)};
    for (auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(FASCIA_RUN, argv.data());
    _exit(127);
}

} // namespace

TEST_CASE("fascia-run stops after the current step on SIGINT or SIGTERM, exits 130 and leaves complete files",
          "[fascia-run]") {
    const int sig = GENERATE(SIGINT, SIGTERM);
    CAPTURE(sig);
    Workspace w;
    w.write("probe.xml", probeScene("pauseAtStep=\"120\" readyFile=\"ready\""));
    const pid_t pid = spawnRun(w.dir(), {"probe.xml", "--steps", "1000", "--output", "out"});
    REQUIRE(pid > 0);
    // the probe writes "ready" at the start of step 120 and waits for the signal there: no sleep
    // decides when the signal lands
    // (the deadline only ends a hung child; the poll interval decides nothing)
    int status = 0;
    bool exited = false;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (!fs::exists(w.dir() / "ready") && !exited && std::chrono::steady_clock::now() < deadline) {
        exited = waitpid(pid, &status, WNOHANG) == pid;
        usleep(1000);
    }
    if (!exited && !fs::exists(w.dir() / "ready")) kill(pid, SIGKILL);
    REQUIRE_FALSE(exited);
    REQUIRE(fs::exists(w.dir() / "ready"));
    REQUIRE(kill(pid, sig) == 0);
    REQUIRE(waitpid(pid, &status, 0) == pid);
    const std::string out = slurpFile(w.dir() / "stdout.txt"), err = slurpFile(w.dir() / "stderr.txt");
    INFO(out << err);
    REQUIRE(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 130);
    CHECK_THAT(out, StartsWith("fascia-run: 120 steps, "));
    CHECK_THAT(err, Contains("fascia-run: interrupted after 120 steps (files written so far are complete)"));
    // the Monitor: a header and one complete row for the initial state and each of the 120 steps
    std::istringstream csv(slurpFile(w.dir() / "out" / "mon.csv"));
    std::vector<std::string> rows;
    for (std::string line; std::getline(csv, line);) rows.push_back(line);
    REQUIRE(rows.size() == 122);
    const auto fields = [](const std::string& s) { return std::count(s.begin(), s.end(), ',') + 1; };
    for (auto& r : rows) CHECK(fields(r) == fields(rows[0]));
    CHECK_THAT(rows.back(), StartsWith("0.12,"));
    // the exporter: the collection is closed and lists the 121 files, each of them complete (past
    // 100 files the exporter rewrites the .pvd at most once a second: the run must finish it)
    if (!FASCIA_HAVE_VTK) return;
    const std::string pvd = slurpFile(w.dir() / "out" / "out.pvd");
    CHECK_THAT(pvd, Contains("</VTKFile>"));
    for (int i = 0; i <= 120; ++i) {
        char f[32];
        std::snprintf(f, sizeof f, "out_%06d.vtu", i);
        INFO(f);
        CHECK_THAT(pvd, Contains("file=\"" + std::string(f) + "\""));
        const std::string vtu = slurpFile(w.dir() / "out" / f);
        CHECK(vtu.find("</VTKFile>") != std::string::npos);
    }
    CHECK_FALSE(fs::exists(w.dir() / "out" / "out_000121.vtu"));
    for (auto& e : fs::directory_iterator(w.dir() / "out")) CHECK(e.path().filename().string()[0] != '.');
}

TEST_CASE("fascia-run --threads sets the OpenMP threads the run uses", "[fascia-run]") {
    Workspace w;
    w.write("probe.xml", probeScene("threadsFile=\"threads.txt\""));
    const auto threads = [&](const std::string& args) {
        fs::remove(w.dir() / "threads.txt");
        auto r = w.run("probe.xml --steps 1 " + args, "OMP_NUM_THREADS=5");
        INFO(r.out << r.err);
        CHECK(r.code == 0);
        return slurpFile(w.dir() / "threads.txt");
    };
    // without --threads the run takes OpenMP's default (here OMP_NUM_THREADS); --threads overrides it
    CHECK(threads("") == "maxThreads 5\nteamSize 5\n");
    CHECK(threads("--threads 3") == "maxThreads 3\nteamSize 3\n");
    CHECK(threads("--threads 1") == "maxThreads 1\nteamSize 1\n");
}
