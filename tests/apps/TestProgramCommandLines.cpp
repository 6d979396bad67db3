/// The command line of every program (tests/apps/badinput/programs.txt, described in
/// tests/apps/badinput/README.md): each case runs the real program in a fresh, empty workspace (its
/// temporary folder, TMPDIR, inside it) and must exit with its code (0 for --help and the controls,
/// 1 for a bad command line or output, 2 for a bad input file; never a crash or the kill of a hung
/// run), print its exact first line (of stderr, or of stdout for "stdout: ..."), and leave the
/// workspace as it found it. One TEST_CASE per program, as the catalogue test (TestBadInputCatalogue.cpp).
#include "BadInputTable.h"

#include <catch2/catch.hpp>

#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

using namespace fasciaruntest;

const fs::path kTable = fs::path(FASCIA_SOURCE_DIR) / "tests" / "apps" / "badinput" / "programs.txt";

/// Where each program of the table is (the build's targets).
const std::map<std::string, std::string> kPrograms = {{"fascia-run", FASCIA_RUN},
                                                      {"fascia-bench", FASCIA_BENCH},
                                                      {"fascia-dump", FASCIA_DUMP},
                                                      {"fascia-param-coverage", FASCIA_PARAM_COVERAGE},
                                                      {"fascia-haptics-demo", FASCIA_HAPTICS_DEMO}};

/// One line of programs.txt: program | name | setup | arguments | exit code | first line.
struct Case {
    int line = 0;
    std::string program, name, args, message;
    std::vector<std::string> setup;
    int code = -1;
};

/// Every case of the table, in file order (a malformed line fails the test that reads it).
std::vector<Case> readCases() {
    std::vector<Case> cases;
    for (const TableRow& r : readTable(kTable, 6)) {
        const auto& f = r.fields;
        Case c;
        c.line = r.line;
        c.program = f[0];
        c.name = f[1];
        if (f[2] != "-") c.setup = split(f[2], ", ");
        c.args = f[3] == "-" ? "" : f[3];
        c.code = std::stoi(f[4]);
        c.message = f[5];
        cases.push_back(c);
    }
    return cases;
}

/// The table's names for places that differ between machines: $W the workspace, $SOURCE the source tree.
std::string expand(const std::string& s, const Workspace& w) {
    return replaceAll(replaceAll(s, "$W", w.dir().string()), "$SOURCE", FASCIA_SOURCE_DIR);
}
std::string abbreviate(const std::string& s, const Workspace& w) {
    return replaceAll(replaceAll(s, w.dir().string(), "$W"), FASCIA_SOURCE_DIR, "$SOURCE");
}

/// A good scene for fascia-run: one cell of a cube, two steps, nothing written.
const char* kCubeScene = "<Node name=\"root\" dt=\"0.01\" endTime=\"0.02\">\n"
                         "  <GridMesh name=\"grid\" min=\"0 0 0\" max=\"0.1 0.1 0.1\" resolution=\"1 1 1\"/>\n"
                         "  <MechanicalObject name=\"state\"/>\n"
                         "  <LumpedMass density=\"1000\"/>\n"
                         "  <StVenantKirchhoff lambda=\"1500\" mu=\"1000\"/>\n"
                         "  <HEMLForceField name=\"heml\"/>\n"
                         "  <SemiImplicitEuler/>\n"
                         "</Node>\n";

/// Carries out one setup action of a case in w.
void setUp(const std::string& action, const Workspace& w) {
    const size_t eq = action.find('=');
    REQUIRE(eq != std::string::npos);
    const std::string verb = action.substr(0, eq), arg = expand(action.substr(eq + 1), w);
    if (verb == "mkdir") {
        fs::create_directories(w.dir() / arg);
    } else if (verb == "file") {
        w.write(arg, "not a folder\n");
    } else if (verb == "cube") {
        w.write(arg, kCubeScene);
    } else if (verb == "text") {  // text=PATH:LINE, a file of that one line
        const size_t colon = arg.find(':');
        REQUIRE(colon != std::string::npos);
        w.write(arg.substr(0, colon), arg.substr(colon + 1) + "\n");
    } else {
        FAIL("unknown setup action '" << action << "'");
    }
}

void runCase(const Case& c) {
    INFO(c.program << " case '" << c.name << "' (tests/apps/badinput/programs.txt:" << c.line << ")");
    const auto program = kPrograms.find(c.program);
    REQUIRE(program != kPrograms.end());
    Workspace w;
    for (const auto& a : c.setup) setUp(a, w);
    const std::set<std::string> before = snapshot(w);
    // (TMPDIR in the workspace: a temporary folder left behind is seen too)
    const auto r = w.run(expand(c.args, w), "TMPDIR='" + w.dir().string() + "'", program->second);
    INFO("stdout: " << abbreviate(r.out.substr(0, 2000), w));
    INFO("stderr: " << abbreviate(r.err, w));
    CHECK(r.code < 124);  // 124 and above: killed after hanging, or died of a signal
    CHECK(r.code == c.code);
    const std::string stdoutPrefix = "stdout: ";
    if (c.message.rfind(stdoutPrefix, 0) == 0) {
        CHECK(r.err.empty());
        CHECK(abbreviate(r.out.substr(0, r.out.find('\n')), w) == c.message.substr(stdoutPrefix.size()));
    } else if (c.message == "-") {
        CHECK(r.err.empty());
    } else {
        CHECK(abbreviate(r.firstErrLine(), w) == c.message);
    }
    // no case writes anything: the errors write nothing, --help and the controls have nothing to write
    checkUntouched(w, before);
}

/// Runs every case of `program` and checks that there were some.
void runProgram(const std::string& program) {
    int ran = 0;
    for (const Case& c : readCases())
        if (c.program == program) {
            runCase(c);
            ++ran;
        }
    INFO(ran << " cases of " << program);
    CHECK(ran > 0);
}

} // namespace

TEST_CASE("The table of program command lines covers each program's help, unknown option and missing value", "[programs]") {
    const auto cases = readCases();
    std::set<std::string> names;
    std::map<std::string, std::set<std::string>> kinds;  // program -> what its cases show
    for (const auto& c : cases) {
        INFO("programs.txt:" << c.line);
        CHECK(kPrograms.count(c.program) == 1);
        CHECK(names.insert(c.program + " " + c.name).second);
        CHECK((c.code == 0 || c.code == 1 || c.code == 2));
        if (c.code == 0 && c.message.rfind("stdout: ", 0) == 0 && c.args == "--help") kinds[c.program].insert("help");
        if (c.message.find(": unknown option '") != std::string::npos) kinds[c.program].insert("unknown");
        if (c.message.find(" needs a value") != std::string::npos) kinds[c.program].insert("value");
        if (c.code == 2) kinds[c.program].insert("input");
    }
    for (const auto& [program, path] : kPrograms) {
        INFO(program);
        CHECK(kinds[program] == std::set<std::string>{"help", "input", "unknown", "value"});
    }
}

TEST_CASE("fascia-run's command line: help, bad options, values and paths (programs.txt)", "[programs]") {
    runProgram("fascia-run");
}

TEST_CASE("fascia-bench's command line: help, bad options, values, counts and paths (programs.txt)", "[programs]") {
    runProgram("fascia-bench");
}

TEST_CASE("fascia-dump's command line: help, bad options, values, counts and paths (programs.txt)", "[programs]") {
    runProgram("fascia-dump");
}

TEST_CASE("fascia-param-coverage's command line: help, bad options and paths (programs.txt)", "[programs]") {
    runProgram("fascia-param-coverage");
}

TEST_CASE("fascia-haptics-demo's command line: help, bad options, values, counts and paths (programs.txt)", "[programs]") {
    runProgram("fascia-haptics-demo");
}
