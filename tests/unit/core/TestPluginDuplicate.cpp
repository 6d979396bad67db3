/// Two plugins registering one component name: an error naming both, and the second plugin's
/// registrations rolled back. In its own executable: it leaves the process with a refused plugin.
#include "CoreTestSupport.h"

#include "fascia/plugin/Registry.h"

using namespace fascia;
using namespace fascia::core;
using namespace fascia::testing;

TEST_CASE("A plugin registering a name another plugin registered is refused, naming both", "[PluginManager][Registry]") {
    loadTestPlugin();
    const std::string good = fs::weakly_canonical(goodPluginFile()).string();
    const std::string dup = fs::weakly_canonical(testPluginFile("dup", "libfascia_testplugin_dup.so")).string();
    const auto namesBefore = Registry::instance().names();
    const size_t pluginsBefore = PluginManager::instance().plugins().size();

    auto e = errorOf([&] { PluginManager::instance().loadFile(dup, {"scene.xml", 5}); });
    REQUIRE(e);
    CHECK(e->kind() == ErrorKind::Input);
    CHECK(e->loc().file == "scene.xml");
    CHECK(e->loc().line == 5);
    CHECK(e->message() == "component 'TestCounter' is registered twice: by plugin 'fascia.test' (" + good +
                              ") and by plugin 'fascia.testdup' (" + dup + ")");
    REQUIRE(e->notes().size() == 1);
    CHECK_THAT(e->notes()[0], Contains("load only one of these plugins"));

    // the registry is as it was: the name it registered first is gone, TestCounter is still the good one's
    CHECK(Registry::instance().names() == namesBefore);
    CHECK(Registry::instance().find("TestDupOnly") == nullptr);
    REQUIRE(Registry::instance().find("TestCounter"));
    CHECK(Registry::instance().find("TestCounter")->plugin == "fascia.test");
    CHECK(PluginManager::instance().plugins().size() == pluginsBefore);

    // and a scene using TestCounter still works
    auto sim = scene(R"(<Node name="root" dt="0.1">
  <TestCounter name="c" label="a"/>
</Node>)");
    sim->run(2);
    CHECK(paramOf<int>(*sim, "c", "beginSteps") == 2);

    // refused again the same way
    auto again = errorOf([&] { PluginManager::instance().loadFile(dup); });
    REQUIRE(again);
    CHECK_THAT(again->message(), Contains("is registered twice"));
}
