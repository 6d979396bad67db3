/// Scenes from XML: every kind of input error is located (file and line) with a clear message.
#include "CoreTestSupport.h"

#include "fascia/plugin/Plugin.h"
#include "fascia/plugin/Registry.h"

using namespace fascia;
using namespace fascia::core;
using namespace fascia::testing;

namespace {

/// Checks that xml fails with message (the first line of what(), location included).
void expectSceneError(const std::string& xml, int line, const std::string& message) {
    auto e = sceneError(xml);
    REQUIRE(e);
    INFO(e->what());
    CHECK(e->kind() == ErrorKind::Input);
    CHECK(e->loc().file == "scene.xml");
    CHECK(e->loc().line == line);
    const std::string what = e->what();
    CHECK(what.substr(0, what.find('\n')) == "scene.xml:" + std::to_string(line) + ": error: " + message);
}

bool hasNote(const Error& e, const std::string& note) {
    for (auto& n : e.notes())
        if (n == note) return true;
    return false;
}

} // namespace

TEST_CASE("A scene with the test component loads and runs N steps", "[SceneLoader][TestCounter]") {
    auto sim = scene(R"(<Node name="root" dt="0.01">
  <TestCounter name="c" label="x"/>
</Node>)");
    const int n = GENERATE(0, 1, 7);
    sim->run(n);
    CHECK(paramOf<int>(*sim, "c", "beginSteps") == n);
    CHECK(paramOf<int>(*sim, "c", "observed") == n + 1);  // the initial state, then each step
    CHECK(sim->stepCount() == n);
    if (n > 0) CHECK(paramOf<double>(*sim, "c", "lastTime") == (n - 1) * 0.01);
}

TEST_CASE("Every attribute of the test component is read from the scene", "[SceneLoader][TestCounter]") {
    auto sim = scene(R"(<Node name="root" dt="0.01">
  <TestCounter name="c" label="x" scale="9.5" rate="3" ceiling="-4" iterations="100" enabled="false" mode="accurate"
               direction="0 -1 0.5" indices="1 2 3" box="0 0 0 1 2 3" values="1 2 3.5" file="mesh.vtk"/>
</Node>)");
    Component* c = sim->find("c");
    REQUIRE(c);
    CHECK(c->className() == "TestCounter");
    CHECK(c->loc().line == 2);
    CHECK(paramOf<double>(*c, "scale") == 9.5);
    CHECK(paramOf<double>(*c, "rate") == 3);
    CHECK(paramOf<double>(*c, "ceiling") == -4);
    CHECK(paramOf<int>(*c, "iterations") == 100);
    CHECK(paramOf<bool>(*c, "enabled") == false);
    CHECK(paramOf<std::string>(*c, "mode") == "accurate");
    CHECK(paramOf<Vec3>(*c, "direction") == Vec3(0, -1, 0.5));
    CHECK(paramOf<IndexList>(*c, "indices") == IndexList{1, 2, 3});
    CHECK(paramOf<NumberList>(*c, "box") == NumberList{0, 0, 0, 1, 2, 3});
    CHECK(paramOf<double>(*c, "valuesSum") == 6.5);  // computed in init
    CHECK(paramOf<FilePath>(*c, "file").written == "mesh.vtk");
    CHECK(c->findParam("scale")->loc().line == 2);
}

TEST_CASE("An XML syntax error is located at its line", "[SceneLoader]") {
    SECTION("unquoted attribute") {
        expectSceneError(R"(<Node name="root">
  <TestCounter label="a"/>
  <TestCounter label=b/>
</Node>)", 3, "XML syntax error: malformed attribute (missing quotes or '=')");
    }
    SECTION("mismatched closing tag") {
        expectSceneError(R"(<Node name="root">
  <Node name="a">
    <TestCounter label="a"/>
  </Nod>
</Node>)", 2, "XML syntax error: mismatched closing tag");  // TinyXML2 gives the opening tag's line
    }
    SECTION("an attribute given twice") {
        auto e = sceneError(R"(<Node name="root">

  <TestCounter label="a" label="b"/>
</Node>)");
        REQUIRE(e);
        CHECK(e->loc().line == 3);
        CHECK_THAT(e->what(), StartsWith("scene.xml:3: error: XML syntax error"));
    }
    SECTION("empty scene") {
        auto e = sceneError("");
        REQUIRE(e);
        CHECK_THAT(e->what(), StartsWith("scene.xml:"));
        CHECK_THAT(e->what(), Contains("the scene is empty"));
    }
}

TEST_CASE("The root element must be a Node", "[SceneLoader]") {
    expectSceneError(R"(<Scene name="root">
</Scene>)", 1, "the root element is <Scene>, expected <Node>");
}

TEST_CASE("An unknown component is located and the closest names are suggested", "[SceneLoader]") {
    auto xml = R"(<Node name="root">
  <TestCounter label="a"/>
  <TestCountr label="b"/>
</Node>)";
    expectSceneError(xml, 3, "unknown component 'TestCountr'");
    auto e = sceneError(xml);
    REQUIRE(e);
    CHECK(hasNote(*e, "did you mean 'TestCounter'?"));
    CHECK_THAT(e->what(), Contains("scene.xml:3: note: did you mean 'TestCounter'?"));
}

TEST_CASE("An unknown component with nothing close points to --list and RequiredPlugin", "[SceneLoader]") {
    auto e = sceneError(R"(<Node name="root">
  <Qwxzvbnmkjhg/>
</Node>)");
    REQUIRE(e);
    CHECK(e->loc().line == 2);
    REQUIRE(e->notes().size() == 1);
    CHECK_THAT(e->notes()[0], Contains("fascia-run --list"));
    CHECK_THAT(e->notes()[0], Contains("RequiredPlugin"));
}

TEST_CASE("An unknown component provided by a plugin not loaded gives the plugin hint", "[SceneLoader][Registry]") {
    loadTestPlugin();
    const std::string hint = "TestFromElsewhere is in plugin 'fascia.elsewhere', which is not built: enable it";
    Registry::instance().addKnownElsewhere("TestFromElsewhere", hint);
    REQUIRE(Registry::instance().knownElsewhere("TestFromElsewhere"));
    CHECK(*Registry::instance().knownElsewhere("TestFromElsewhere") == hint);
    CHECK(Registry::instance().knownElsewhere("TestNowhere") == nullptr);
    auto e = sceneError(R"(<Node name="root">

  <TestFromElsewhere/>
</Node>)");
    REQUIRE(e);
    CHECK(e->loc().line == 3);
    CHECK(e->message() == "unknown component 'TestFromElsewhere'");
    REQUIRE_FALSE(e->notes().empty());
    CHECK(e->notes()[0] == hint);
}

TEST_CASE("An unknown attribute is located with suggestions", "[SceneLoader]") {
    auto xml = R"(<Node name="root">
  <TestCounter name="c" label="a"
               scal="2"/>
</Node>)";
    expectSceneError(xml, 2, "TestCounter 'c': unknown attribute 'scal'");
    auto e = sceneError(xml);
    REQUIRE(e);
    CHECK(hasNote(*e, "did you mean 'scale'?"));
}

TEST_CASE("An unknown attribute with nothing close lists what the component takes", "[SceneLoader]") {
    auto e = sceneError(R"(<Node name="root">
  <TestCounter name="c" label="a" qqqqqqqqqq="2"/>
</Node>)");
    REQUIRE(e);
    CHECK(e->loc().line == 2);
    REQUIRE(e->notes().size() == 1);
    CHECK_THAT(e->notes()[0], StartsWith("TestCounter takes: name, scale, rate,"));
    CHECK_THAT(e->notes()[0], Contains("partner"));
}

TEST_CASE("An unknown attribute of a node is located with suggestions", "[SceneLoader][Node]") {
    auto xml = R"(<Node name="root" dt="0.01">
  <Node name="organ" gravty="0 0 -9.81">
  </Node>
</Node>)";
    expectSceneError(xml, 2, "Node 'organ': unknown attribute 'gravty'");
    auto e = sceneError(xml);
    REQUIRE(e);
    CHECK(hasNote(*e, "did you mean 'gravity'?"));
}

TEST_CASE("A value that does not parse is located at its element", "[SceneLoader]") {
    expectSceneError(R"(<Node name="root">
  <TestCounter name="a" label="a"/>
  <TestCounter name="b" label="b" iterations="ten"/>
</Node>)", 3, "TestCounter 'b': iterations = \"ten\" is not an integer");
    expectSceneError(R"(<Node name="root" dt="fast">
</Node>)", 1, "Node 'root': dt = \"fast\" is not a positive number of seconds or \"auto\"");
    expectSceneError(R"(<Node name="root">
  <TestCounter name="c" label="a"
     direction="1 0"/>
</Node>)", 2, "TestCounter 'c': direction = \"1 0\" is not three numbers \"x y z\"");
}

TEST_CASE("A value out of range is located at its element", "[SceneLoader]") {
    expectSceneError(R"(<Node name="root">
  <TestCounter name="c" label="a" scale="10"/>
</Node>)", 2, "TestCounter 'c': scale = 10 is outside [0, 10)");
    expectSceneError(R"(<Node name="root">
  <TestCounter name="c" label="a" rate="0"/>
</Node>)", 2, "TestCounter 'c': rate = 0 is outside > 0");
    expectSceneError(R"(<Node name="root">
  <Node name="n">
    <TestCounter name="c" label="a" mode="slow"/>
  </Node>
</Node>)", 3, "TestCounter 'c': mode = slow is not one of fast|accurate|debug");
    expectSceneError(R"(<Node name="root">
  <TestCounter name="c" label="a" box="0 0 0 1 1"/>
</Node>)", 2, "TestCounter 'c': box = 0 0 0 1 1 has 5 entries, expected 6");
    expectSceneError(R"(<Node name="root" dtSafety="1.5">
</Node>)", 1, "Node 'root': dtSafety = 1.5 is outside (0, 1]");
}

TEST_CASE("A missing required parameter is located at the component", "[SceneLoader]") {
    expectSceneError(R"(<Node name="root">
  <TestCounter name="ok" label="a"/>
  <Node name="n">
    <TestCounter name="c"/>
  </Node>
</Node>)", 4, "TestCounter 'c': missing required parameter 'label' (a required label)");
}

TEST_CASE("An output parameter set in the scene is located", "[SceneLoader]") {
    expectSceneError(R"(<Node name="root">
  <TestCounter name="c" label="a" beginSteps="3"/>
</Node>)", 2, "TestCounter 'c': 'beginSteps' is computed by the component and cannot be set; it can only be linked to");
}

TEST_CASE("A link to nothing is located, with close names suggested", "[SceneLoader][Link]") {
    auto xml = R"(<Node name="root">
  <TestCounter name="counter" label="a"/>
  <Node name="n">
    <TestCounter name="c" label="b" partner="@countr"/>
  </Node>
</Node>)";
    expectSceneError(xml, 4, "TestCounter 'c': partner = \"@countr\" links to nothing: no component 'countr' from node 'n'");
    auto e = sceneError(xml);
    REQUIRE(e);
    CHECK(hasNote(*e, "did you mean 'counter'?"));
}

TEST_CASE("A relative link that leaves the tree links to nothing", "[SceneLoader][Link]") {
    expectSceneError(R"(<Node name="root">
  <TestCounter name="a" label="a"/>
  <TestCounter name="c" label="b" partner="@../../a"/>
</Node>)", 3, "TestCounter 'c': partner = \"@../../a\" links to nothing: no component '../../a' from node 'root'");
}

TEST_CASE("A link to a component of the wrong type is located", "[SceneLoader][Link]") {
    expectSceneError(R"(<Node name="root">
  <TestNaN name="nan"/>
  <TestCounter name="c" label="b" partner="@nan"/>
</Node>)", 3, "TestCounter 'c': partner = \"@nan\" links to TestNaN 'nan', which is not a TestCounter");
}

TEST_CASE("A link to its own component is located", "[SceneLoader][Link]") {
    expectSceneError(R"(<Node name="root">
  <TestCounter name="c" label="b" partner="@c"/>
</Node>)", 2, "TestCounter 'c': partner links to its own component");
}

TEST_CASE("A data link needs a field that exists and has the same type", "[SceneLoader][Link]") {
    SECTION("no field") {
        expectSceneError(R"(<Node name="root">
  <TestCounter name="a" label="a" values="1 2"/>
  <TestCounter name="c" label="b" values="@a"/>
</Node>)", 3, "TestCounter 'c': values = \"@a\" must link to a field: \"@component.field\"");
    }
    SECTION("unknown field") {
        auto xml = R"(<Node name="root">
  <TestCounter name="a" label="a" values="1 2"/>
  <TestCounter name="c" label="b" values="@a.valuez"/>
</Node>)";
        expectSceneError(xml, 3, "TestCounter 'c': values = \"@a.valuez\" links to nothing: TestCounter 'a' has no field 'valuez'");
        auto e = sceneError(xml);
        REQUIRE(e);
        CHECK(hasNote(*e, "did you mean 'values'?"));
    }
    SECTION("wrong type") {
        expectSceneError(R"(<Node name="root">
  <TestCounter name="a" label="a"/>
  <TestCounter name="c" label="b" values="@a.iterations"/>
</Node>)", 3, "TestCounter 'c': values (number list) cannot take TestCounter.iterations (int)");
    }
    SECTION("unknown component") {
        expectSceneError(R"(<Node name="root">
  <TestCounter name="c" label="b" values="@../a.values"/>
</Node>)", 2, "TestCounter 'c': values = \"@../a.values\" links to nothing: no component '../a' from node 'root'");
    }
}

TEST_CASE("A data link reads the other component's value, relative paths included", "[SceneLoader][Link]") {
    auto sim = scene(R"(<Node name="root" dt="0.1">
  <TestCounter name="src" label="a" values="1 2 3"/>
  <Node name="child">
    <Node name="grandchild">
      <TestCounter name="up" label="b" values="@../../src.values"/>
      <TestCounter name="bare" label="c" values="@src.values" scale="@/root/src.valuesSum"/>
    </Node>
  </Node>
</Node>)");
    CHECK(paramOf<NumberList>(*sim, "up", "values") == NumberList{1, 2, 3});
    CHECK(paramOf<double>(*sim, "up", "valuesSum") == 6);
    CHECK(paramOf<double>(*sim, "bare", "valuesSum") == 6);
    CHECK(paramOf<double>(*sim, "bare", "scale") == 6);  // linked to an output, filled by src's init
}

TEST_CASE("A component link finds its target by relative, absolute and bare paths", "[SceneLoader][Link]") {
    auto sim = scene(R"(<Node name="root" dt="0.1">
  <TestCounter name="top" label="a"/>
  <Node name="a">
    <TestCounter name="x" label="b"/>
    <Node name="b">
      <TestCounter name="rel" label="c" partner="@../x"/>
      <TestCounter name="abs" label="d" partner="@/root/a/x"/>
      <TestCounter name="bare" label="e" partner="@top"/>
      <TestCounter name="down" label="f" partner="@/a/b/rel"/>
    </Node>
  </Node>
</Node>)");
    CHECK(sim->find("rel")->findParam("partner")->linkTarget() == sim->find("x"));
    CHECK(sim->find("abs")->findParam("partner")->linkTarget() == sim->find("x"));
    CHECK(sim->find("bare")->findParam("partner")->linkTarget() == sim->find("top"));
    CHECK(sim->find("down")->findParam("partner")->linkTarget() == sim->find("rel"));
}

TEST_CASE("Node attributes take parameter links as component attributes do, except the name", "[SceneLoader][Node]") {
    // gravity linked to a component's Vec3 and dtSafety to a double: the node sees the linked values
    auto sim = scene(R"(<Node name="root" dtSafety="@c.ceiling">
  <TestCounter name="c" label="a" ceiling="0.25" direction="0.5 0 -1"/>
  <Node name="n" gravity="@../c.direction"/>
</Node>)");
    const fascia::core::Node* n = nullptr;
    sim->root().visit([&](const fascia::core::Node& x) { if (x.name() == "n") n = &x; });
    REQUIRE(n);
    CHECK(n->contextGravity() == Vec3(0.5, 0, -1));
    CHECK(sim->root().dtSafety.get() == 0.25);
    // a link of another type, or to nothing, is located as on a component
    expectSceneError(R"(<Node name="root">
  <TestCounter name="c" label="a"/>
  <Node name="n" gravity="@../c.ceiling"/>
</Node>)", 3, "Node 'n': gravity (vec3) cannot take TestCounter.ceiling (double)");
    expectSceneError(R"(<Node name="root">
  <Node name="n" gravity="@g.value"/>
</Node>)", 2, "Node 'n': gravity = \"@g.value\" links to nothing: no component 'g' from node 'n'");
    expectSceneError(R"(<Node name="root">
  <Node name="@g.value"/>
</Node>)", 2, "Node: attribute 'name' cannot be a link");
}

TEST_CASE("Names are unique among siblings and unnamed components are numbered", "[SceneLoader][Node]") {
    SECTION("numbering") {
        auto sim = scene(R"(<Node name="root">
  <TestCounter label="a"/>
  <TestCounter label="b"/>
  <TestCounter name="TestCounter3" label="c"/>
  <TestCounter label="d"/>
</Node>)");
        auto& comps = sim->root().components();
        REQUIRE(comps.size() == 4);
        CHECK(comps[0]->name() == "TestCounter");
        CHECK(comps[1]->name() == "TestCounter2");
        CHECK(comps[2]->name() == "TestCounter3");
        CHECK(comps[3]->name() == "TestCounter4");
    }
    SECTION("two components with one name") {
        expectSceneError(R"(<Node name="root">
  <TestCounter name="c" label="a"/>
  <TestCounter name="c" label="b"/>
</Node>)", 3, "two components of node 'root' are named 'c'");
    }
    SECTION("two child nodes with one name") {
        expectSceneError(R"(<Node name="root">
  <Node name="n"/>
  <Node name="n"/>
</Node>)", 3, "two child nodes of 'root' are named 'n'");
    }
    SECTION("a child node without a name") {
        expectSceneError(R"(<Node name="root">
  <Node/>
</Node>)", 2, "a <Node> needs a name");
    }
    SECTION("the root node without a name is 'root'") {
        auto sim = scene(R"(<Node>
  <TestCounter name="c" label="a"/>
</Node>)");
        CHECK(sim->root().name() == "root");
        CHECK(sim->find("c")->path() == "/root/c");
    }
}

TEST_CASE("A component cannot hold elements", "[SceneLoader]") {
    expectSceneError(R"(<Node name="root">
  <TestCounter name="c" label="a">
    <TestCounter name="d" label="b"/>
  </TestCounter>
</Node>)", 3, "component <TestCounter> cannot hold elements; put <TestCounter> in a <Node>");
}

TEST_CASE("A located error from a component's init names the component", "[SceneLoader]") {
    expectSceneError(R"(<Node name="root">
  <TestCounter name="c" label="a"
               mode="debug" comment="fail"/>
</Node>)", 2, "TestCounter 'c': asked to fail");
}

TEST_CASE("parseSceneString keeps elements, attributes in file order and lines", "[SceneLoader]") {
    ElementSpec s = parseSceneString(R"(<Node name="root" dt="0.5">
  <!-- a comment -->
  <A x="1" b="2"/>
  <Node name="n">
    <B/>
  </Node>
</Node>)", "mem.xml", ".");
    CHECK(s.tag == "Node");
    CHECK(s.loc.file == "mem.xml");
    CHECK(s.loc.line == 1);
    REQUIRE(s.attributes.size() == 2);
    CHECK(s.attributes[1] == std::pair<std::string, std::string>{"dt", "0.5"});
    REQUIRE(s.children.size() == 2);
    CHECK(s.children[0].tag == "A");
    CHECK(s.children[0].loc.line == 3);
    CHECK(s.children[0].attributes[0].first == "x");
    CHECK(s.children[0].attributes[1].first == "b");
    REQUIRE(s.children[1].children.size() == 1);
    CHECK(s.children[1].children[0].loc.line == 5);
}

// ---- files: includes, relative paths, RequiredPlugin ----------------------------------------

TEST_CASE("An include inserts another file, paths relative to the including file", "[SceneLoader]") {
    loadTestPlugin();
    TempDir dir;
    const std::string main = dir.write("scenes/main.xml", R"(<Node name="root" dt="0.01">
  <TestCounter name="top" label="a" file="top.txt"/>
  <include href="parts/organ.xml"/>
  <TestCounter name="after" label="b" partner="@organ/inner"/>
</Node>)");
    dir.write("scenes/parts/organ.xml", R"(<Node name="organ">
  <TestCounter name="inner" label="c" file="../../data/inner.txt"/>
  <include href="more.xml"/>
</Node>)");
    dir.write("scenes/parts/more.xml", R"(<TestCounter name="more" label="d" file="more.txt"/>)");
    auto sim = Simulation::fromFile(main);
    const fs::path d = dir.path();
    CHECK(paramOf<FilePath>(*sim, "top", "file").resolved == (d / "scenes/top.txt").string());
    CHECK(paramOf<FilePath>(*sim, "inner", "file").resolved == (d / "data/inner.txt").string());
    CHECK(paramOf<FilePath>(*sim, "more", "file").resolved == (d / "scenes/parts/more.txt").string());
    CHECK(paramOf<FilePath>(*sim, "inner", "file").written == "../../data/inner.txt");
    CHECK(sim->find("/root/organ/more") != nullptr);
    CHECK(sim->find("after")->findParam("partner")->linkTarget() == sim->find("inner"));
    // located in the file each element came from
    CHECK(sim->find("inner")->loc().file == (d / "scenes/parts/organ.xml").string());
    CHECK(sim->find("inner")->loc().line == 2);
    CHECK(sim->root().context().sceneFile == main);
}

TEST_CASE("An error in an included file is located in that file", "[SceneLoader]") {
    loadTestPlugin();
    TempDir dir;
    const std::string main = dir.write("main.xml", R"(<Node name="root">
  <include href="part.xml"/>
</Node>)");
    const std::string part = dir.write("part.xml", R"(<Node name="part">

  <TestCounter name="c" label="a" rate="-1"/>
</Node>)");
    auto e = errorOf([&] { Simulation::fromFile(main); });
    REQUIRE(e);
    CHECK(std::string(e->what()) == part + ":3: error: TestCounter 'c': rate = -1 is outside > 0");
}

TEST_CASE("A missing included file is located at the include line", "[SceneLoader]") {
    TempDir dir;
    const std::string main = dir.write("main.xml", R"(<Node name="root">
  <TestCounter name="c" label="a"/>
  <include href="nope.xml"/>
</Node>)");
    auto e = errorOf([&] { parseSceneFile(main); });
    REQUIRE(e);
    CHECK(std::string(e->what()) == main + ":3: error: cannot open '" + (dir.path() / "nope.xml").string() + "': no such file");
}

TEST_CASE("An include cycle is located at the include that closes it", "[SceneLoader]") {
    TempDir dir;
    const std::string a = dir.write("a.xml", R"(<Node name="root">
  <include href="sub/b.xml"/>
</Node>)");
    const std::string b = dir.write("sub/b.xml", R"(<Node name="b">

  <include href="../a.xml"/>
</Node>)");
    auto e = errorOf([&] { parseSceneFile(a); });
    REQUIRE(e);
    CHECK(std::string(e->what()) == b + ":3: error: '" + a + "' includes itself (include cycle)");
}

TEST_CASE("A file including itself is an include cycle", "[SceneLoader]") {
    TempDir dir;
    const std::string a = dir.write("self.xml", R"(<Node name="root">
  <include href="self.xml"/>
</Node>)");
    auto e = errorOf([&] { parseSceneFile(a); });
    REQUIRE(e);
    CHECK(e->loc().line == 2);
    CHECK_THAT(e->what(), Contains("includes itself (include cycle)"));
}

TEST_CASE("An include needs href and nothing else", "[SceneLoader]") {
    auto e1 = errorOf([] { parseSceneString("<Node name=\"root\">\n  <include/>\n</Node>", "scene.xml", "."); });
    REQUIRE(e1);
    CHECK(std::string(e1->what()) == "scene.xml:2: error: <include> needs an href=\"file.xml\" attribute");
    auto e2 = errorOf([] { parseSceneString("<Node name=\"root\">\n\n  <include href=\"a.xml\" hef=\"b\"/>\n</Node>", "scene.xml", "."); });
    REQUIRE(e2);
    CHECK_THAT(e2->what(), StartsWith("scene.xml:3: error: unknown attribute 'hef' of <include>"));
}

TEST_CASE("A missing scene file or a folder is a clear error", "[SceneLoader]") {
    TempDir dir;
    const std::string missing = (dir.path() / "missing.xml").string();
    auto e = errorOf([&] { Simulation::fromFile(missing); });
    REQUIRE(e);
    CHECK(std::string(e->what()) == missing + ":1: error: cannot open '" + missing + "': no such file");
    auto f = errorOf([&] { Simulation::fromFile(dir.path().string()); });
    REQUIRE(f);
    CHECK_THAT(f->what(), Contains("is a folder, not a scene file"));
}

TEST_CASE("fromString resolves relative paths against baseDir", "[SceneLoader][Simulation]") {
    loadTestPlugin();
    TempDir dir;
    SECTION("with a file name") {
        auto sim = Simulation::fromString(R"(<Node name="root">
  <TestCounter name="c" label="a" file="mesh.vtk"/>
</Node>)", "virtual.xml", dir.path().string());
        CHECK(paramOf<FilePath>(*sim, "c", "file").resolved == (dir.path() / "mesh.vtk").string());
    }
    SECTION("with the default name") {
        auto sim = Simulation::fromString(R"(<Node name="root">
  <TestCounter name="c" label="a" file="mesh.vtk"/>
</Node>)", "<string>", dir.path().string());
        CHECK(paramOf<FilePath>(*sim, "c", "file").resolved == (dir.path() / "mesh.vtk").string());
    }
}

TEST_CASE("RequiredPlugin loads the test plugin by absolute path and by a path relative to the scene",
          "[SceneLoader][PluginManager]") {
    TempDir dir;
    SECTION("absolute") {
        const std::string scene = dir.write("s.xml", R"(<Node name="root" dt="0.1">
  <RequiredPlugin name=")" + goodPluginFile() + R"("/>
  <TestCounter name="c" label="a"/>
</Node>)");
        auto sim = Simulation::fromFile(scene);
        CHECK(sim->find("c") != nullptr);
    }
    SECTION("relative to the scene") {
        const std::string rel = fs::relative(goodPluginFile(), dir.path() / "sub").string();
        const std::string scene = dir.write("sub/s.xml", R"(<Node name="root" dt="0.1">
  <TestCounter name="c" label="a"/>
  <Node name="n">
    <RequiredPlugin name=")" + rel + R"("/>
  </Node>
</Node>)");
        auto sim = Simulation::fromFile(scene);
        CHECK(sim->find("c") != nullptr);
    }
    bool found = false;
    for (auto& p : PluginManager::instance().plugins())
        if (p.id == "fascia.test") found = p.file == fs::weakly_canonical(goodPluginFile()).string();
    CHECK(found);
}

TEST_CASE("RequiredPlugin errors are located", "[SceneLoader][PluginManager]") {
    SECTION("not found") {
        auto e = sceneError(R"(<Node name="root">
  <RequiredPlugin name="fascia_nosuchplugin"/>
</Node>)");
        REQUIRE(e);
        CHECK_THAT(e->what(), StartsWith("scene.xml:2: error: plugin 'fascia_nosuchplugin' not found (searched "));
        CHECK(e->notes().size() == 1);
    }
    SECTION("no name") {
        expectSceneError(R"(<Node name="root">

  <RequiredPlugin/>
</Node>)", 3, "RequiredPlugin needs name=\"...\" (a plugin name or a path to its .so)");
    }
    SECTION("unknown attribute") {
        expectSceneError(R"(<Node name="root">
  <RequiredPlugin name="x" path="y"/>
</Node>)", 2, "unknown attribute 'path' of RequiredPlugin");
    }
    SECTION("a plugin built for another ABI") {
        auto e = sceneError(R"(<Node name="root">
  <RequiredPlugin name=")" + testPluginFile("abi", "libfascia_testplugin_abi.so") + R"("/>
</Node>)");
        REQUIRE(e);
        CHECK(e->loc().line == 2);
        CHECK_THAT(e->what(), Contains("was built for ABI 999, this is ABI " + std::to_string(FASCIA_ABI_VERSION) + ": rebuild it against Fascia"));
    }
}

TEST_CASE("dt, dtSafety and endTime on a child node are located errors", "[SceneLoader]") {
    for (const char* attr : {"dt=\"0.1\"", "dtSafety=\"0.5\"", "endTime=\"1\""}) {
        CAPTURE(attr);
        try {
            fascia::core::Simulation::fromString(std::string("<Node name=\"root\">\n  <Node name=\"child\" ") + attr + "/>\n</Node>\n",
                                                 "scene.xml");
            FAIL("expected an error");
        } catch (const fascia::core::Error& e) {
            CHECK_THAT(std::string(e.what()), Catch::Matchers::Contains("scene.xml:2: error: Node 'child'") &&
                                                  Catch::Matchers::Contains("belongs on the root node"));
        }
    }
}
