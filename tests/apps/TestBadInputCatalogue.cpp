/// The bad-input catalogue (tests/apps/badinput/catalogue.txt, described in its README.md): every
/// case runs the real fascia-run in a fresh workspace holding a copy of tests/apps/badinput, and must
/// exit with its code (2 for bad input, 1 for an output that cannot be written or a bad command line,
/// never a crash or the kill of a hung run), print its exact first error line (the workspace path
/// written $W), and leave no file behind: the workspace holds the same files after the run as
/// before it. One TEST_CASE per group of the catalogue.
#include "BadInputTable.h"
#include "fascia/plugin/Plugin.h"

#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

using namespace fasciaruntest;

const fs::path kCatalogueDir = fs::path(FASCIA_SOURCE_DIR) / "tests" / "apps" / "badinput";

/// One line of catalogue.txt: group | name | setup | arguments | exit code | first line of stderr.
struct Case {
    int line = 0;
    std::string group, name, args, message;
    std::vector<std::string> setup;
    int code = -1;
};

/// Every case of the catalogue, in file order (a malformed line fails the test that reads it).
std::vector<Case> readCatalogue() {
    std::vector<Case> cases;
    for (const TableRow& r : readTable(kCatalogueDir / "catalogue.txt", 6)) {
        const auto& f = r.fields;
        Case c;
        c.line = r.line;
        c.group = f[0];
        c.name = f[1];
        if (f[2] != "-") c.setup = split(f[2], ", ");
        c.args = f[3];
        c.code = std::stoi(f[4]);
        c.message = f[5];
        cases.push_back(c);
    }
    return cases;
}

/// The places a message may name that differ between machines, and their names in the catalogue.
std::vector<std::pair<std::string, std::string>> placeholders(const Workspace& w) {
    return {{"$W", w.dir().string()},
            {"$PLUGINS", TEST_PLUGIN_DIR},
            {"$BUILTIN", BUILTIN_PLUGIN_DIR},
            {"$ABI", "ABI " + std::to_string(FASCIA_ABI_VERSION)},
            {"$VERSION", "Fascia " FASCIA_VERSION_TEXT}};
}

std::string expand(std::string s, const Workspace& w) {
    for (const auto& [name, value] : placeholders(w)) s = replaceAll(s, name, value);
    return s;
}

std::string abbreviate(std::string s, const Workspace& w) {
    for (const auto& [name, value] : placeholders(w)) s = replaceAll(s, value, name);
    return s;
}

/// The scene of a mesh case: the mesh at `path` loaded, simulated and monitored (line 2: MeshLoader).
std::string meshScene(const std::string& path) {
    return "<Node name=\"root\" dt=\"0.01\" endTime=\"0.02\">\n"
           "  <MeshLoader name=\"mesh\" filename=\"" + path + "\"/>\n"
           "  <MechanicalObject name=\"state\"/>\n"
           "  <LumpedMass density=\"1000\"/>\n"
           "  <StVenantKirchhoff lambda=\"1500\" mu=\"1000\"/>\n"
           "  <HEMLForceField name=\"heml\"/>\n"
           "  <SemiImplicitEuler damping=\"20\"/>\n"
           "  <Monitor name=\"curve\" indices=\"0\"/>\n"
           "</Node>\n";
}

/// Includes that fan out: includes/fanout0.xml includes fanout1.xml twice, ... down to fanout<depth>.xml.
void writeFanOut(const Workspace& w, int depth) {
    for (int i = 0; i < depth; ++i)
        w.write("includes/fanout" + std::to_string(i) + ".xml", "<Node name=\"n" + std::to_string(i) + "\">\n  <include href=\"fanout" +
                                                           std::to_string(i + 1) + ".xml\"/>\n  <include href=\"fanout" +
                                                           std::to_string(i + 1) + ".xml\"/>\n</Node>\n");
    w.write("includes/fanout" + std::to_string(depth) + ".xml", "<Node name=\"leaf\"/>\n");
}

/// Carries out one setup action of a case in w; false when the case cannot run here (and says why).
bool setUp(const std::string& action, const Workspace& w, std::string& env) {
    const size_t eq = action.find('=');
    REQUIRE(eq != std::string::npos);
    const std::string verb = action.substr(0, eq), arg = expand(action.substr(eq + 1), w);
    const fs::path at = w.dir() / arg;
    if (verb == "mesh") {
        w.write("mesh.xml", meshScene(arg));
    } else if (verb == "fifo") {
        REQUIRE(::mkfifo(at.c_str(), 0600) == 0);
    } else if (verb == "link") {  // link=PATH->TARGET
        const size_t arrow = arg.find("->");
        REQUIRE(arrow != std::string::npos);
        fs::create_symlink(arg.substr(arrow + 2), w.dir() / arg.substr(0, arrow));
    } else if (verb == "mkdir") {
        fs::create_directories(at);
    } else if (verb == "file") {
        w.write(arg, "not a folder\n");
    } else if (verb == "readonly") {
        if (::geteuid() == 0) {
            WARN("running as root, who may write anywhere: an unwritable folder cannot be made, case skipped");
            return false;
        }
        fs::create_directories(at);
        fs::permissions(at, fs::perms::owner_read | fs::perms::owner_exec);
    } else if (verb == "sparse") {  // sparse=PATH:BYTES, a file of that size holding nothing
        const size_t colon = arg.rfind(':');
        REQUIRE(colon != std::string::npos);
        w.write(arg.substr(0, colon), "");
        fs::resize_file(w.dir() / arg.substr(0, colon), std::stoull(arg.substr(colon + 1)));
    } else if (verb == "fanout") {
        writeFanOut(w, std::stoi(arg));
    } else if (verb == "env") {
        env += " " + arg;
    } else if (verb == "needs") {
        const bool vtk = FASCIA_HAVE_VTK;
        if ((arg == "vtk" && !vtk) || (arg == "novtk" && vtk)) return false;
        REQUIRE((arg == "vtk" || arg == "novtk"));
    } else {
        FAIL("unknown setup action '" << action << "'");
    }
    return true;
}

/// Runs one case; returns false when it was skipped here.
bool runCase(const Case& c) {
    INFO("case '" << c.name << "' (tests/apps/badinput/catalogue.txt:" << c.line << ")");
    Workspace w;
    fs::copy(kCatalogueDir, w.dir(), fs::copy_options::recursive);
    std::string env;
    for (const auto& a : c.setup)
        if (!setUp(a, w, env)) return false;
    const std::set<std::string> before = snapshot(w);
    std::string args = expand(c.args, w);
    if (args.find("--output") == std::string::npos) args += " --output out";
    const auto r = w.run(args, env);
    INFO("stderr: " << abbreviate(r.err, w));
    CHECK(r.code < 124);  // 124 and above: killed after hanging, or died of a signal
    CHECK(r.code == c.code);
    if (c.message == "-") CHECK(r.err.empty());
    else CHECK(abbreviate(r.firstErrLine(), w) == c.message);
    if (c.code != 0) {
        CHECK(r.summary().empty());
        checkUntouched(w, before);
    }
    return true;
}

/// Runs every case of `group` and checks that there were some.
void runGroup(const std::string& group) {
    int ran = 0, skipped = 0;
    for (const Case& c : readCatalogue())
        if (c.group == group) (runCase(c) ? ran : skipped)++;
    INFO(ran << " cases of group '" << group << "' ran, " << skipped << " skipped");
    CHECK(ran > 0);
}

} // namespace

TEST_CASE("The bad-input catalogue holds at least 80 cases with unique names in known groups", "[fascia-run]") {
    const auto cases = readCatalogue();
    CHECK(cases.size() >= 80);
    std::set<std::string> names;
    const std::set<std::string> groups{"scene", "include", "mesh", "plugin", "output", "cli"};
    for (const auto& c : cases) {
        INFO("catalogue.txt:" << c.line);
        CHECK(names.insert(c.name).second);
        CHECK(groups.count(c.group) == 1);
        CHECK((c.code == 0 || c.code == 1 || c.code == 2));
        CHECK(!c.message.empty());
    }
}

TEST_CASE("Every bad scene of the catalogue fails at its line with exit code 2 and writes nothing", "[fascia-run]") {
    runGroup("scene");
}

TEST_CASE("Every bad include of the catalogue fails at its line with exit code 2 and writes nothing", "[fascia-run]") {
    runGroup("include");
}

TEST_CASE("Every bad mesh of the catalogue fails at its line or byte with exit code 2 and writes nothing", "[fascia-run]") {
    runGroup("mesh");
}

TEST_CASE("Every bad plugin of the catalogue fails at its RequiredPlugin with exit code 2", "[fascia-run]") {
    runGroup("plugin");
}

TEST_CASE("Every output of the catalogue that cannot be written fails with its exit code and writes nothing", "[fascia-run]") {
    runGroup("output");
}

TEST_CASE("Every bad command line of the catalogue fails with exit code 1 and a usage message", "[fascia-run]") {
    runGroup("cli");
}
