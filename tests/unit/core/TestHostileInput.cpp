/// Scenes made to hang, flood or fool the loader: FIFOs and devices, includes that fan out, a second
/// root or integrator, outputs that leave the output folder, many unnamed components. Each gets a
/// located error (or loads in linear time) instead of blocking, growing without bound or being
/// silently dropped.
#include "CoreTestSupport.h"

#include "fascia/base/InputFile.h"

#include <sys/stat.h>
#include <unistd.h>

#include <functional>
#include <set>

using namespace fascia;
using namespace fascia::testing;
using core::SourceLoc;

namespace {

/// The message of the error f throws ("" when it throws none).
template <class F> std::string messageOf(F&& f) {
    auto e = errorOf(std::forward<F>(f));
    return e ? std::string(e->what()) : std::string();
}

std::string fifoIn(const TempDir& dir, const std::string& name) {
    const std::string p = (dir.path() / name).string();
    REQUIRE(::mkfifo(p.c_str(), 0600) == 0);
    return p;
}

} // namespace

TEST_CASE("A scene file that is a FIFO is refused from its type without being opened", "[SceneLoader]") {
    // opening a FIFO for reading blocks until a writer comes: the loader must not open it at all
    TempDir dir;
    const std::string fifo = fifoIn(dir, "scene.xml");
    auto e = errorOf([&] { core::parseSceneFile(fifo); });
    REQUIRE(e);
    CHECK(e->kind() == core::ErrorKind::Input);
    CHECK_THAT(std::string(e->what()), StartsWith(fifo + ":1: error: '" + fifo + "' is a FIFO (named pipe), not a scene file"));
}

TEST_CASE("An include that is a FIFO or a device is refused at the include line", "[SceneLoader]") {
    TempDir dir;
    const std::string fifo = fifoIn(dir, "part.xml");
    const std::string top = dir.write("top.xml", "<Node name=\"root\">\n\n  <include href=\"part.xml\"/>\n</Node>\n");
    CHECK_THAT(messageOf([&] { core::parseSceneFile(top); }),
               StartsWith(top + ":3: error: '" + fifo + "' is a FIFO (named pipe), not a scene file"));
    // /dev/zero never ends: refused from its type, not read until memory runs out
    const std::string zero = dir.write("zero.xml", "<Node name=\"root\">\n  <include href=\"/dev/zero\"/>\n</Node>\n");
    CHECK_THAT(messageOf([&] { core::parseSceneFile(zero); }),
               StartsWith(zero + ":2: error: '/dev/zero' is a character device, not a scene file"));
}

TEST_CASE("A scene that is a device or a folder or missing or empty is an error at its line 1", "[SceneLoader]") {
    TempDir dir;
    CHECK_THAT(messageOf([&] { core::parseSceneFile("/dev/zero"); }),
               StartsWith("/dev/zero:1: error: '/dev/zero' is a character device, not a scene file"));
    const std::string missing = (dir.path() / "missing.xml").string();
    CHECK_THAT(messageOf([&] { core::parseSceneFile(missing); }),
               StartsWith(missing + ":1: error: cannot open '" + missing + "': no such file"));
    const std::string folder = (dir.path() / "folder.xml").string();
    fs::create_directories(folder);
    CHECK_THAT(messageOf([&] { core::parseSceneFile(folder); }),
               StartsWith(folder + ":1: error: '" + folder + "' is a folder, not a scene file"));
    const std::string empty = dir.write("empty.xml", "");
    CHECK_THAT(messageOf([&] { core::parseSceneFile(empty); }), StartsWith(empty + ":1: error: the scene is empty"));
    const std::string blank = dir.write("blank.xml", "\n\n   \n");
    CHECK_THAT(messageOf([&] { core::parseSceneFile(blank); }), StartsWith(blank + ":1: error: the scene is empty"));
}

TEST_CASE("Includes that fan out stop at the include limit with a located error", "[SceneLoader]") {
    // level k includes level k+1 twice: 20 levels would expand to 2^20 copies of the last file
    TempDir dir;
    const int levels = 20;
    for (int k = 0; k < levels; ++k)
        dir.write("l" + std::to_string(k) + ".xml", "<Node name=\"n\">\n  <include href=\"l" + std::to_string(k + 1) +
                                                        ".xml\"/>\n  <include href=\"l" + std::to_string(k + 1) +
                                                        ".xml\"/>\n</Node>\n");
    dir.write("l" + std::to_string(levels) + ".xml", "<Node name=\"leaf\"/>\n");
    const std::string top = (dir.path() / "l0.xml").string();
    auto e = errorOf([&] { core::parseSceneFile(top); });
    REQUIRE(e);
    CHECK_THAT(e->message(), StartsWith("more than 1000 includes in the scene"));
    // located at an <include> line (2 or 3) of one of the files
    CHECK_THAT(std::string(e->what()), Contains(".xml:2: error: ") || Contains(".xml:3: error: "));
    // the same tree 9 levels deep (1022 includes) is refused, 8 levels deep (510) loads
    dir.write("l8.xml", "<Node name=\"leaf\"/>\n");
    auto spec = core::parseSceneFile(top);
    size_t leaves = 0;
    std::function<void(const core::ElementSpec&)> count = [&](const core::ElementSpec& s) {
        leaves += s.children.empty() ? 1 : 0;
        for (auto& c : s.children) count(c);
    };
    count(spec);
    CHECK(leaves == 256);
    dir.write("l8.xml", "<Node name=\"n\">\n  <include href=\"l9.xml\"/>\n  <include href=\"l9.xml\"/>\n</Node>\n");
    dir.write("l9.xml", "<Node name=\"leaf\"/>\n");
    CHECK_THAT(messageOf([&] { core::parseSceneFile(top); }), Contains("more than 1000 includes in the scene"));
}

TEST_CASE("Scene files past the size limits are refused before they are read", "[SceneLoader]") {
    TempDir dir;
    // a sparse file: its size is known from stat without writing 65 MB
    const std::string big = dir.write("big.xml", "");
    fs::resize_file(big, core::kMaxSceneFileBytes + 1);
    CHECK_THAT(messageOf([&] { core::parseSceneFile(big); }),
               StartsWith(big + ":1: error: '" + big + "' is " + std::to_string(core::kMaxSceneFileBytes + 1) +
                          " bytes, more than the " + std::to_string(core::kMaxSceneFileBytes) +
                          " bytes a scene file may have"));
    const std::string top = dir.write("top.xml", "<Node name=\"root\">\n  <include href=\"big.xml\"/>\n</Node>\n");
    CHECK_THAT(messageOf([&] { core::parseSceneFile(top); }), StartsWith(top + ":2: error: '" + big + "' is "));
    // five includes of a 60 MiB file (under the per-file limit) pass the 256 MiB of a whole scene
    const std::string part = dir.write("part.xml", "<Node name=\"p\"/>\n" + std::string(60u << 20, ' ') + "\n");
    std::string many = "<Node name=\"root\">\n";
    for (int i = 0; i < 5; ++i) many += "  <include href=\"part.xml\"/>\n";
    const std::string manyFile = dir.write("many.xml", many + "</Node>\n");
    CHECK_THAT(messageOf([&] { core::parseSceneFile(manyFile); }),
               StartsWith(manyFile + ":6: error: the scene, includes expanded, is more than 268435456 bytes"));
    fs::remove(part);
    // a mesh file that is a FIFO is refused by the same check, which the mesh readers call
    const std::string fifo = fifoIn(dir, "mesh.msh");
    CHECK_THAT(messageOf([&] { core::requireRegularFile(fifo, "mesh file", core::kMaxMeshFileBytes, {fifo, 0}); }),
               StartsWith(fifo + ": error: '" + fifo + "' is a FIFO (named pipe), not a mesh file"));
    CHECK(core::requireRegularFile(top, "scene file", 1000, {}) == fs::file_size(top));
}

TEST_CASE("A second root element is an error at its line and not dropped", "[SceneLoader]") {
    auto e = errorOf([] { core::parseSceneString("<Node name=\"a\"/>\n\n<Node name=\"b\"/>\n", "scene.xml", "."); });
    REQUIRE(e);
    CHECK_THAT(std::string(e->what()), StartsWith("scene.xml:3: error: a second root element <Node> after <Node> (line 1)"));
    // in an included file too
    TempDir dir;
    dir.write("part.xml", "<Node name=\"p\"/>\n<TestMass/>\n");
    const std::string top = dir.write("top.xml", "<Node name=\"root\">\n  <include href=\"part.xml\"/>\n</Node>\n");
    CHECK_THAT(messageOf([&] { core::parseSceneFile(top); }),
               StartsWith((dir.path() / "part.xml").string() + ":2: error: a second root element <TestMass>"));
    // comments and the XML declaration around one root are fine
    CHECK_NOTHROW(core::parseSceneString("<?xml version=\"1.0\"?>\n<!-- a -->\n<Node name=\"a\"/>\n<!-- b -->\n",
                                         "scene.xml", "."));
}

TEST_CASE("A second integrator in the same node is an error at its line", "[Simulation]") {
    auto e = sceneError(R"(<Node name="root" dt="0.01">
  <TestEuler name="first"/>
  <TestState name="state" position="0 0 0"/>
  <TestMass mass="1"/>
  <TestEuler name="second"/>
</Node>)");
    REQUIRE(e);
    CHECK_THAT(std::string(e->what()),
               StartsWith("scene.xml:5: error: TestEuler 'second': a second integrator in node 'root', which has "
                          "TestEuler 'first' (scene.xml:2): only the first would be called"));
    // one integrator per node, a child node with its own, is fine
    CHECK_FALSE(sceneError(R"(<Node name="root" dt="0.01">
  <TestEuler name="first"/>
  <Node name="child">
    <TestEuler name="second"/>
    <TestState name="state" position="0 0 0"/>
    <TestMass mass="1"/>
  </Node>
</Node>)"));
}

TEST_CASE("Automatic names are the same as before and load in linear time", "[SceneLoader]") {
    loadTestPlugin();
    // the first free of Class, Class2, Class3, ... in declaration order, around names given by hand
    auto root = core::buildScene(core::parseSceneString(R"(<Node name="root">
  <TestMass/>
  <TestMass name="TestMass3"/>
  <TestMass/>
  <TestEuler/>
  <TestMass/>
  <TestMass name="TestEuler2"/>
  <TestEuler/>
  <TestEuler/>
  <TestMass/>
</Node>)",
                                                        "scene.xml", "."));
    std::vector<std::string> names;
    for (auto& c : root->components()) names.push_back(c->name());
    CHECK(names == std::vector<std::string>{"TestMass", "TestMass3", "TestMass2", "TestEuler", "TestMass4", "TestEuler2",
                                            "TestEuler3", "TestEuler4", "TestMass5"});
    // 200,000 unnamed siblings: the quadratic search took about n^2/2 = 2e10 set lookups (hours);
    // the linear one takes one each, well inside the test's time limit
    const int n = 200000;
    std::string xml = "<Node name=\"root\">\n";
    for (int i = 0; i < n; ++i) xml += "<TestMass/>\n";
    xml += "</Node>\n";
    auto big = core::buildScene(core::parseSceneString(xml, "scene.xml", "."));
    REQUIRE(big->components().size() == size_t(n));
    CHECK(big->components()[0]->name() == "TestMass");
    CHECK(big->components()[1]->name() == "TestMass2");
    CHECK(big->components()[n - 1]->name() == "TestMass" + std::to_string(n));
    std::set<std::string> unique;
    for (auto& c : big->components()) unique.insert(c->name());
    CHECK(unique.size() == size_t(n));
}

TEST_CASE("Outputs that leave the output folder are located errors", "[SceneContext]") {
    TempDir dir;
    core::Node root("root");
    auto& who = root.add<core::Component>("writer");
    who.setClassName("Writer");
    who.setLoc({"scene.xml", 7});
    auto& ctx = root.context();
    ctx.outputDir = (dir.path() / "out").string();
    const std::string out = ctx.outputDir;
    CHECK_NOTHROW(ctx.claimOutput(out + "/a.pvd", who));
    CHECK_NOTHROW(ctx.claimOutput(out + "/sub/b.csv", who));
    CHECK_NOTHROW(ctx.claimOutput(out + "/sub/../c.csv", who));
    for (const std::string& bad : {out + "/../x.pvd", out + "/sub/../../x.csv", std::string("/tmp/abs.csv"), out}) {
        CAPTURE(bad);
        CHECK_THAT(messageOf([&] { ctx.claimOutput(bad, who); }),
                   StartsWith("scene.xml:7: error: Writer 'writer': writes '" + bad +
                              "', which is outside the output folder '" + out + "'"));
    }
    // the default folder, "."
    ctx.outputDir = ".";
    CHECK_NOTHROW(ctx.claimOutput("./d.csv", who));
    CHECK_THAT(messageOf([&] { ctx.claimOutput("./../d.csv", who); }), Contains("outside the output folder '.'"));
}

TEST_CASE("An output folder that is a file or cannot be made is an output error naming it", "[Simulation]") {
    TempDir dir;
    const std::string file = dir.write("file", "x");
    auto sim = scene("<Node name=\"root\" dt=\"0.01\"/>");
    auto e = errorOf([&] { sim->setOutputDir(file); });
    REQUIRE(e);
    CHECK(e->kind() != core::ErrorKind::Input);  // exit 1 in fascia-run, as an unwritable output
    CHECK(e->kind() != core::ErrorKind::Simulation);
    CHECK_THAT(e->message(), StartsWith("output folder '" + file + "' is a file, not a folder"));
    auto e2 = errorOf([&] { sim->setOutputDir(file + "/sub"); });
    REQUIRE(e2);
    CHECK(e2->kind() != core::ErrorKind::Input);
    CHECK_THAT(e2->message(), StartsWith("cannot create output folder '" + file + "/sub': "));
    if (::geteuid() != 0) {  // root may write anywhere
        const fs::path ro = dir.path() / "readonly";
        fs::create_directories(ro);
        fs::permissions(ro, fs::perms::owner_read | fs::perms::owner_exec);
        auto e3 = errorOf([&] { sim->setOutputDir(ro.string()); });
        fs::permissions(ro, fs::perms::owner_all);
        REQUIRE(e3);
        CHECK(e3->kind() != core::ErrorKind::Input);
        CHECK_THAT(e3->message(), StartsWith("cannot write into output folder '" + ro.string() + "'"));
    }
}

TEST_CASE("Init writes nothing: observers see the initial state when the run starts", "[Simulation]") {
    auto sim = scene(R"(<Node name="root">
  <TestCounter name="c" label="x"/>
</Node>)");
    // no dt: a run would fail, and nothing has been observed (an exporter would have written nothing)
    CHECK(paramOf<int>(*sim, "c", "observed") == 0);
    CHECK_THAT(messageOf([&] { sim->step(); }), Contains("no time step"));
    CHECK(paramOf<int>(*sim, "c", "observed") == 0);
    sim->setDt(0.01);
    sim->start();
    CHECK(paramOf<int>(*sim, "c", "observed") == 1);
    sim->start();  // once
    CHECK(paramOf<int>(*sim, "c", "observed") == 1);
    sim->step();
    CHECK(paramOf<int>(*sim, "c", "observed") == 2);
}

TEST_CASE("run without a time step fails before the observers see anything", "[Simulation]") {
    auto sim = scene(R"(<Node name="root">
  <TestCounter name="c" label="x"/>
</Node>)");
    CHECK_THAT(messageOf([&] { sim->run(3); }), StartsWith("scene.xml:1: error: no time step"));
    CHECK(paramOf<int>(*sim, "c", "observed") == 0);
    sim->run(0);  // no step: no time step needed, the initial state is observed
    CHECK(paramOf<int>(*sim, "c", "observed") == 1);
}
