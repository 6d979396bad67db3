/// A scene reports every independent error it can find in one load, as a compiler does: each located,
/// in the order of the scene, up to kErrorsShown and then counted; an error that follows from another
/// is not reported again; an XML syntax error stops at once (docs/design.md, section 7).
#include "CoreTestSupport.h"

#include "fascia/base/ErrorList.h"

#include <sstream>

using namespace fascia;
using namespace fascia::core;
using namespace fascia::testing;

namespace {

/// The lines of what() that are errors (not notes), each cut after its location.
std::vector<std::string> errorLines(const Error& e) {
    std::vector<std::string> out;
    std::istringstream in(e.what());
    for (std::string line; std::getline(in, line);)
        if (line.find(": error: ") != std::string::npos) out.push_back(line);
    return out;
}

/// The line numbers of the errors e stands for, in order.
std::vector<int> linesOf(const Error& e) {
    std::vector<int> out{e.loc().line};
    for (const Error& m : e.more()) out.push_back(m.loc().line);
    return out;
}

} // namespace

TEST_CASE("A scene with three independent mistakes reports three located errors in order", "[SceneLoader][Error]") {
    loadTestPlugin();
    TempDir dir;
    const std::string file = dir.write("three.xml", R"(<Node name="root" dt="0.01">
  <TestCounter name="a" label="a"/>
  <Node name="left">
    <TestCounter name="b" label="b" scal="2"/>
  </Node>
  <Node name="right">
    <TestCounter name="c" label="c" rate="0"/>
  </Node>
  <TestCounter name="d" label="d"/>
  <TestCountr name="e" label="e"/>
</Node>
)");
    auto e = errorOf([&] { Simulation::fromFile(file); });
    REQUIRE(e);
    CHECK(e->kind() == ErrorKind::Input);
    CHECK(e->count() == 3);
    CHECK(e->unshown() == 0);
    CHECK(linesOf(*e) == std::vector<int>{4, 7, 10});
    // what() is every error with its notes, one after the other, the first one first
    CHECK(std::string(e->what()) == file + ":4: error: TestCounter 'b': unknown attribute 'scal'\n" +
                                        file + ":4: note: did you mean 'scale'?\n" +
                                        file + ":7: error: TestCounter 'c': rate = 0 is outside > 0\n" +
                                        file + ":10: error: unknown component 'TestCountr'\n" +
                                        file + ":10: note: did you mean 'TestCounter'?");
    CHECK(e->message() == "TestCounter 'b': unknown attribute 'scal'");
    REQUIRE(e->more().size() == 2);
    CHECK(e->more()[1].message() == "unknown component 'TestCountr'");
    CHECK(e->more()[1].notes() == std::vector<std::string>{"did you mean 'TestCounter'?"});
}

TEST_CASE("Errors found by the later checks of a load are reported in the order of the scene", "[SceneLoader][Error]") {
    // links are resolved and required parameters checked after every element is built: their errors
    // still come in the order of their elements
    auto e = sceneError(R"(<Node name="root">
  <TestCounter name="a" label="a" partner="@nobody"/>
  <TestCounter name="b"/>
  <TestCounter name="c" label="c" iterations="0"/>
</Node>)");
    REQUIRE(e);
    CHECK(linesOf(*e) == std::vector<int>{2, 3, 4});
    CHECK(errorLines(*e) == std::vector<std::string>{
                                "scene.xml:2: error: TestCounter 'a': partner = \"@nobody\" links to nothing: no component "
                                "'nobody' from node 'root'",
                                "scene.xml:3: error: TestCounter 'b': missing required parameter 'label' (a required label)",
                                "scene.xml:4: error: TestCounter 'c': iterations = 0 is outside [1, 100]"});
}

TEST_CASE("A scene with 30 mistakes shows the first 20 and counts the others", "[SceneLoader][Error]") {
    std::string xml = "<Node name=\"root\">\n";
    for (int i = 0; i < 30; ++i) xml += "  <TestCounter name=\"c" + std::to_string(i) + "\" label=\"x\" rate=\"0\"/>\n";
    auto e = sceneError(xml + "</Node>\n");
    REQUIRE(e);
    CHECK(e->count() == 30);
    CHECK(e->more().size() == kErrorsShown - 1);
    CHECK(e->unshown() == 30 - kErrorsShown);
    CHECK(linesOf(*e).back() == 1 + int(kErrorsShown));  // the first 20, lines 2 to 21
    const std::string what = e->what();
    CHECK(errorLines(*e).size() == kErrorsShown);
    CHECK(what.substr(what.rfind('\n') + 1) == "scene.xml: note: 10 more errors not shown");
}

TEST_CASE("An error that follows from another one is not reported again", "[SceneLoader][Error]") {
    SECTION("links to an element that made no component") {
        auto e = sceneError(R"(<Node name="root">
  <TestCountr name="p" label="p"/>
  <TestCounter name="c" label="c" partner="@p" values="@p.values"/>
  <Node name="n">
    <TestCounter name="d" label="d" partner="../p"/>
  </Node>
</Node>)");
        REQUIRE(e);
        CHECK(linesOf(*e) == std::vector<int>{2, 5});  // the unknown component, and d's own error
        CHECK(e->message() == "unknown component 'TestCountr'");
        CHECK(e->more()[0].message() == "TestCounter 'd': partner = \"../p\" is not a link: write \"@../p\"");
    }
    SECTION("a time setting of a child node whose value was refused") {
        auto e = sceneError(R"(<Node name="root">
  <Node name="child" dtSafety="2"/>
</Node>)");
        REQUIRE(e);
        CHECK(e->count() == 1);  // not also "dtSafety belongs on the root node"
        CHECK(e->message() == "Node 'child': dtSafety = 2 is outside (0, 1]");
    }
    SECTION("a node name that was refused") {
        auto e = sceneError(R"(<Node name="root">
  <Node name="@g.value"/>
</Node>)");
        REQUIRE(e);
        CHECK(e->count() == 1);  // not also "a <Node> needs a name"
        CHECK(e->message() == "Node: attribute 'name' cannot be a link");
    }
    SECTION("no component is initialised when the scene has errors") {
        // c's init would fail too ("asked to fail"): it does not run
        auto e = sceneError(R"(<Node name="root">
  <TestCounter name="c" label="c" mode="debug" comment="fail"/>
  <TestCounter name="d" label="d" scal="1"/>
</Node>)");
        REQUIRE(e);
        CHECK(e->count() == 1);
        CHECK(e->loc().line == 3);
    }
}

TEST_CASE("An XML syntax error is one error, whatever else the scene holds", "[SceneLoader][Error]") {
    auto e = sceneError(R"(<Node name="root">
  <TestCounter name="c" label="c" scal="1"/>
  <TestCounter name="d" label=d/>
  <TestCountr name="e"/>
</Node>)");
    REQUIRE(e);
    CHECK(e->count() == 1);
    CHECK(e->more().empty());
    CHECK(std::string(e->what()) == "scene.xml:3: error: XML syntax error: malformed attribute (missing quotes or '=')");
}

TEST_CASE("The init errors of components in independent nodes are reported together", "[Simulation][Error]") {
    // a and b fail in sibling nodes: both are found. d (below a's node) and e (linked to a) would fail
    // too, but they may read what a failed to set up: they are not initialised, and say nothing
    auto e = sceneError(R"(<Node name="root" dt="0.01">
  <TestCounter name="top" label="top"/>
  <Node name="left">
    <TestCounter name="a" label="a" mode="debug" comment="fail"/>
    <Node name="inner">
      <TestCounter name="d" label="d" mode="debug" comment="fail"/>
    </Node>
  </Node>
  <Node name="right">
    <TestCounter name="b" label="b" mode="debug" comment="fail"/>
  </Node>
  <Node name="other">
    <TestCounter name="e" label="e" partner="@/root/left/a" mode="debug" comment="fail"/>
  </Node>
</Node>)");
    REQUIRE(e);
    CHECK(linesOf(*e) == std::vector<int>{4, 10});
    CHECK(e->message() == "TestCounter 'a': asked to fail");
    CHECK(e->more()[0].message() == "TestCounter 'b': asked to fail");
}

TEST_CASE("A link cycle is one error at init", "[Simulation][Error]") {
    auto e = sceneError(R"(<Node name="root" dt="0.01">
  <TestCounter name="a" label="a" partner="@b"/>
  <TestCounter name="b" label="b" partner="@a"/>
</Node>)");
    REQUIRE(e);
    CHECK(e->count() == 1);
    CHECK_THAT(e->message(), Contains("link cycle: /root/a depends, through its links, on itself"));
}
