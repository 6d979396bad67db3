/// Loading plugins: the good one registers its components; every broken one is a clear error that
/// leaves the registry as it was. PluginManager and Registry are process-wide: each test loads
/// what it needs and checks only what no other test changes.
#include "CoreTestSupport.h"

#include "fascia/plugin/Plugin.h"
#include "fascia/plugin/Registry.h"

#include <cstdlib>
#include <iostream>
#include <sstream>

using namespace fascia;
using namespace fascia::core;
using namespace fascia::testing;

namespace {

std::string canonical(const std::string& f) { return fs::weakly_canonical(f).string(); }

const LoadedPlugin* loaded(const std::string& id) {
    for (auto& p : PluginManager::instance().plugins())
        if (p.id == id) return &p;
    return nullptr;
}

/// The registry's names and the loaded plugins' ids, to check that a failed load changed nothing.
struct Snapshot {
    std::vector<std::string> names, ids;
    Snapshot() {
        names = Registry::instance().names();
        for (auto& p : PluginManager::instance().plugins()) ids.push_back(p.id);
    }
    bool operator==(const Snapshot& o) const { return names == o.names && ids == o.ids; }
};

} // namespace

TEST_CASE("The good test plugin loads and registers its components with its id and file", "[PluginManager][Registry]") {
    loadTestPlugin();
    const LoadedPlugin* p = loaded("fascia.test");
    REQUIRE(p != nullptr);
    CHECK(p->version == "0.0.1");
    CHECK(p->description == "components for the core tests");
    CHECK(p->file == canonical(goodPluginFile()));
    CHECK(p->handle != nullptr);

    for (const char* name : {"TestCounter", "TestNaN", "TestState", "TestMass", "TestEuler"}) {
        CAPTURE(name);
        const ComponentEntry* e = Registry::instance().find(name);
        REQUIRE(e != nullptr);
        CHECK(e->name == name);
        CHECK(e->plugin == "fascia.test");
        CHECK(e->pluginFile == canonical(goodPluginFile()));
        CHECK_FALSE(e->description.empty());
        auto c = Registry::instance().create(name);
        REQUIRE(c != nullptr);
        CHECK(c->className() == name);
    }
    CHECK(Registry::instance().find("TestCounter")->description ==
          "counts beginStep and observe calls; a parameter of every type");
    CHECK(Registry::instance().create("NoSuchComponent") == nullptr);
    CHECK(Registry::instance().find("NoSuchComponent") == nullptr);
}

TEST_CASE("A created component declares its parameters with specs", "[Registry]") {
    loadTestPlugin();
    auto c = Registry::instance().create("TestCounter");
    REQUIRE(c);
    BaseParam* scale = c->findParam("scale");
    REQUIRE(scale);
    CHECK(scale->spec().unitText == "m");
    CHECK(scale->spec().rangeText() == "[0, 10)");
    CHECK(scale->typeName() == "double");
    CHECK(scale->defaultText() == "1");
    CHECK(c->findParam("label")->spec().isRequired);
    CHECK(c->findParam("beginSteps")->spec().isOutput);
    CHECK(c->findParam("partner")->isComponentLink());
    CHECK(c->findParam("partner")->typeName() == "link to TestCounter");
    CHECK(c->findParam("mode")->spec().rangeText() == "one of fast|accurate|debug");
}

TEST_CASE("Loading the same plugin twice is a no-op, by file, by path spelling, by id or by name", "[PluginManager]") {
    loadTestPlugin();
    auto& pm = PluginManager::instance();
    const size_t count = pm.plugins().size();
    const size_t names = Registry::instance().names().size();
    const LoadedPlugin& first = pm.loadFile(goodPluginFile());
    CHECK(&pm.loadFile(goodPluginFile()) == &first);
    CHECK(&pm.loadFile(std::string(TEST_PLUGIN_DIR) + "/good/../good/./libfascia_testplugin.so") == &first);
    CHECK(&pm.load("fascia.test") == &first);
    CHECK(&pm.load(goodPluginFile()) == &first);
    CHECK(&pm.load("fascia_testplugin", {}, {std::string(TEST_PLUGIN_DIR) + "/good"}) == &first);
    CHECK(&pm.load("libfascia_testplugin.so", {}, {std::string(TEST_PLUGIN_DIR) + "/good"}) == &first);
    CHECK(pm.plugins().size() == count);
    CHECK(Registry::instance().names().size() == names);
}

TEST_CASE("A plugin built for another ABI is refused with what to do", "[PluginManager]") {
    loadTestPlugin();
    const Snapshot before;
    const std::string file = testPluginFile("abi", "libfascia_testplugin_abi.so");
    auto e = errorOf([&] { PluginManager::instance().loadFile(file, {"s.xml", 4}); });
    REQUIRE(e);
    CHECK(e->kind() == ErrorKind::Input);
    CHECK(std::string(e->what()) == "s.xml:4: error: plugin '" + file +
                                        "' was built for ABI 999, this is ABI 7: rebuild it against Fascia " FASCIA_VERSION_TEXT);
    CHECK(FASCIA_ABI_VERSION == 7);
    CHECK(Snapshot() == before);
    CHECK(loaded("fascia.test.abi") == nullptr);
    // refused again, not half-loaded
    CHECK(errorOf([&] { PluginManager::instance().loadFile(file); }));
}

TEST_CASE("A plugin built with another Eigen alignment is refused naming both values", "[PluginManager]") {
    loadTestPlugin();
    const Snapshot before;
    const std::string file = testPluginFile("align", "libfascia_testplugin_align.so");
    auto e = errorOf([&] { PluginManager::instance().loadFile(file, {"s.xml", 4}); });
    REQUIRE(e);
    CHECK(e->kind() == ErrorKind::Input);
    CHECK(e->message() == "plugin '" + file + "' was built with EIGEN_MAX_ALIGN_BYTES=32, Fascia with 16: Eigen types "
                                             "would have another layout in the plugin than in the core");
    REQUIRE(e->notes().size() == 1);
    CHECK_THAT(e->notes()[0], Contains("link Fascia::fascia_core"));
    CHECK(coreBuildAbi().eigenMaxAlignBytes == 16);
    CHECK(coreBuildAbi().eigenMaxStaticAlignBytes == 16);
    CHECK(Snapshot() == before);
    CHECK(loaded("fascia.test.align") == nullptr);
}

TEST_CASE("A plugin built without optimisation loads, and the loader says so", "[PluginManager]") {
    const std::string file = testPluginFile("unoptimised", "libfascia_testplugin_unoptimised.so");
    std::ostringstream captured;
    std::streambuf* old = std::cerr.rdbuf(captured.rdbuf());
    const auto e = errorOf([&] { PluginManager::instance().loadFile(file, {"s.xml", 7}); });
    std::cerr.rdbuf(old);
    CHECK_FALSE(e);
    CHECK(loaded("fascia.test.unoptimised") != nullptr);
    if (coreBuildAbi().optimised)
        CHECK(captured.str() == "s.xml:7: warning: plugin '" + file + "' was built without optimisation: its components may "
                                "run tens of times slower; rebuild it with -DCMAKE_BUILD_TYPE=Release (or -O2)\n");
    else
        CHECK(captured.str().empty());  // a core built without optimisation says nothing of its plugins
}

TEST_CASE("A shared library without the entry point is not a plugin", "[PluginManager]") {
    loadTestPlugin();
    const Snapshot before;
    const std::string file = testPluginFile("noentry", "libfascia_testplugin_noentry.so");
    auto e = errorOf([&] { PluginManager::instance().loadFile(file, {"s.xml", 2}); });
    REQUIRE(e);
    CHECK(e->message() == "'" + file + "' is not a Fascia plugin: it exports no fascia_plugin_info()");
    CHECK(e->loc().line == 2);
    REQUIRE(e->notes().size() == 1);
    CHECK_THAT(e->notes()[0], Contains("FASCIA_PLUGIN("));
    CHECK(Snapshot() == before);
}

TEST_CASE("A missing plugin file is named", "[PluginManager]") {
    const std::string file = std::string(TEST_PLUGIN_DIR) + "/good/libfascia_nothere.so";
    auto e = errorOf([&] { PluginManager::instance().loadFile(file); });
    REQUIRE(e);
    CHECK(e->message() == "plugin file '" + file + "' does not exist");
    REQUIRE(e->notes().size() == 1);
}

TEST_CASE("A plugin not found by name lists the folders searched", "[PluginManager]") {
    auto e = errorOf([&] { PluginManager::instance().load("fascia_nosuchplugin", {"s.xml", 9}, {"/extra/dir"}); });
    REQUIRE(e);
    CHECK(e->loc().line == 9);
    CHECK_THAT(e->message(), StartsWith("plugin 'fascia_nosuchplugin' not found (searched /extra/dir, "));
    CHECK_THAT(e->message(), Contains(PluginManager::builtinPluginDir()));
    REQUIRE(e->notes().size() == 1);
    CHECK_THAT(e->notes()[0], Contains("FASCIA_PLUGIN_PATH"));
}

TEST_CASE("A file that is not a shared library cannot be loaded", "[PluginManager]") {
    TempDir dir;
    const std::string file = dir.write("libbogus.so", "this is not an ELF file\n");
    const Snapshot before;
    auto e = errorOf([&] { PluginManager::instance().loadFile(file); });
    REQUIRE(e);
    CHECK_THAT(e->message(), StartsWith("cannot load plugin '" + file + "': "));
    CHECK(Snapshot() == before);
}

TEST_CASE("A second plugin with an id already loaded is refused naming both files", "[PluginManager]") {
    loadTestPlugin();
    const Snapshot before;
    const std::string file = testPluginFile("sameid", "libfascia_testplugin_sameid.so");
    auto e = errorOf([&] { PluginManager::instance().loadFile(file); });
    REQUIRE(e);
    CHECK(e->message() == "two plugins have the id 'fascia.test': " + canonical(goodPluginFile()) + " and " + canonical(file));
    CHECK(Snapshot() == before);
    CHECK(Registry::instance().find("TestSameIdOnly") == nullptr);
}

TEST_CASE("The built-in plugin folder is next to the core library", "[PluginManager]") {
    const std::string dir = PluginManager::builtinPluginDir();
    CHECK_THAT(dir, Catch::Matchers::EndsWith("/fascia/plugins"));
    CHECK(fs::path(dir).parent_path().parent_path() == fs::weakly_canonical(fs::path(FASCIA_BINARY_DIR) / "lib"));
}

TEST_CASE("FASCIA_PLUGIN_PATH is a colon-separated list of folders", "[PluginManager]") {
    const char* old = std::getenv("FASCIA_PLUGIN_PATH");
    const std::string saved = old ? old : "";
    setenv("FASCIA_PLUGIN_PATH", "/a/b::/c:", 1);
    auto dirs = PluginManager::envPluginDirs();
    if (old) setenv("FASCIA_PLUGIN_PATH", saved.c_str(), 1);
    else unsetenv("FASCIA_PLUGIN_PATH");
    CHECK(dirs == std::vector<std::string>{"/a/b", "/c"});
}

TEST_CASE("A plugin is found by name in FASCIA_PLUGIN_PATH", "[PluginManager]") {
    loadTestPlugin();
    const char* old = std::getenv("FASCIA_PLUGIN_PATH");
    const std::string saved = old ? old : "";
    setenv("FASCIA_PLUGIN_PATH", (std::string(TEST_PLUGIN_DIR) + "/good").c_str(), 1);
    auto e = errorOf([&] { CHECK(PluginManager::instance().load("fascia_testplugin").id == "fascia.test"); });
    if (old) setenv("FASCIA_PLUGIN_PATH", saved.c_str(), 1);
    else unsetenv("FASCIA_PLUGIN_PATH");
    CHECK_FALSE(e);
}

TEST_CASE("Registering one name twice in the core's registry is an error naming both origins", "[Registry]") {
    struct A : Component {};
    struct B : Component {};
    Registry& r = Registry::instance();
    r.add<A>("TestRegistryTwice", "first");
    auto e = errorOf([&] { r.add<B>("TestRegistryTwice", "second"); });
    REQUIRE(e);
    CHECK(e->message() == "component 'TestRegistryTwice' is registered twice: by the core and by the core");
    CHECK(r.find("TestRegistryTwice")->description == "first");
}
