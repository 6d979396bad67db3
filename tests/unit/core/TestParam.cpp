/// Parameters: parsing of every type, ranges, choices, defaults, required, counts, outputs, paths.
#include "CoreTestSupport.h"

#include "fascia/base/Component.h"

using namespace fascia;
using namespace fascia::core;
using namespace fascia::testing;

namespace {

/// A component with one parameter of each type, built in code.
class Holder : public Component {
public:
    Holder() {
        setClassName("Holder");
        setName("h");
    }
    Param<bool> b{this, ParamSpec("b")};
    Param<int> i{this, ParamSpec("i"), 7};
    Param<double> d{this, ParamSpec("d").unit("Pa"), 2.5};
    Param<std::string> s{this, ParamSpec("s")};
    Param<std::string> e{this, ParamSpec("e").choices({"linear", "quadratic"}), "linear"};
    Param<Vec3> v{this, ParamSpec("v"), Vec3(1, 2, 3)};
    Param<IndexList> il{this, ParamSpec("il")};
    Param<NumberList> nl{this, ParamSpec("nl")};
    Param<FilePath> fp{this, ParamSpec("fp")};
    Param<TimeStep> ts{this, ParamSpec("ts")};
    Param<Positions> pos{this, ParamSpec("pos")};
    Param<Tetrahedra> tet{this, ParamSpec("tet")};
    Param<Hexahedra> hex{this, ParamSpec("hex")};
    Param<Triangles> tri{this, ParamSpec("tri")};
    Param<MeshData> mesh{this, ParamSpec("mesh")};
    // ranges
    Param<double> closed{this, ParamSpec("closed").min(0).max(0.5), 0.25};
    Param<double> halfOpen{this, ParamSpec("halfOpen").min(0).max(0.5, true), 0.25};
    Param<double> positive{this, ParamSpec("positive").above(0), 1.0};
    Param<double> belowOne{this, ParamSpec("belowOne").below(1), 0.0};
    Param<int> count{this, ParamSpec("count").min(1), 1};
    Param<NumberList> box{this, ParamSpec("box").count(6)};
    Param<IndexList> nodes{this, ParamSpec("nodes").max(9)};
    Param<Vec3> unit{this, ParamSpec("unit").min(-1).max(1), Vec3::Zero()};
    Param<std::string> req{this, ParamSpec("req").required()};
    Param<double> out{this, ParamSpec("out").output(), 0.0};
};

const SourceLoc here{"dir/scene.xml", 7};

/// The message of reading text into h's parameter name (empty when it is accepted).
std::string readError(Holder& h, const std::string& name, const std::string& text) {
    BaseParam* p = h.findParam(name);
    REQUIRE(p != nullptr);
    auto e = errorOf([&] { p->read(text, here); });
    if (!e) return {};
    CHECK(e->kind() == ErrorKind::Input);
    CHECK(e->loc().file == here.file);
    CHECK(e->loc().line == here.line);
    return e->what();
}

std::string valueAfterRead(const std::string& name, const std::string& text) {
    Holder h;
    auto msg = readError(h, name, text);
    INFO(msg);
    REQUIRE(msg.empty());
    return h.findParam(name)->valueText();
}

} // namespace

TEST_CASE("Every parameter type reads its good values", "[Param]") {
    struct Case { const char *param, *text, *shown; };
    auto c = GENERATE(values<Case>({
        {"b", "true", "true"}, {"b", "false", "false"}, {"b", "1", "true"}, {"b", "0", "false"},
        {"i", "-12", "-12"}, {"i", " 42 ", "42"},
        {"d", "2.5e3", "2500"}, {"d", "-0.125", "-0.125"}, {"d", "7", "7"},
        {"s", "any text, with commas", "any text, with commas"},
        {"e", "quadratic", "quadratic"},
        {"v", "1 -2.5 3e-1", "1 -2.5 0.3"}, {"v", "1,2,3", "1 2 3"}, {"v", "  4\n5\t6 ", "4 5 6"},
        {"il", "0 3, 5 7", "0 3 5 7"}, {"il", "", ""},
        {"nl", "1.5 -2 1e2", "1.5 -2 100"},
        {"fp", "mesh.vtk", "mesh.vtk"},
        {"ts", "0.001", "0.001"}, {"ts", "auto", "auto"},
        {"pos", "0 0 0 1 0 0", "0 0 0 1 0 0"},
        {"tet", "0 1 2 3 1 2 3 4", "0 1 2 3 1 2 3 4"},
        {"hex", "0 1 2 3 4 5 6 7", "0 1 2 3 4 5 6 7"},
        {"tri", "0 1 2", "0 1 2"},
    }));
    CAPTURE(c.param, c.text);
    CHECK(valueAfterRead(c.param, c.text) == c.shown);
}

TEST_CASE("Typed values are what the text says", "[Param]") {
    Holder h;
    h.v.read("1 -2.5 3e-1", here);
    CHECK(h.v.get() == Vec3(1, -2.5, 0.3));
    h.pos.read("0 0 0, 1 2 3", here);
    REQUIRE(h.pos.get().size() == 2);
    CHECK(h.pos.get()[1] == Vec3(1, 2, 3));
    h.tet.read("0 1 2 3 4 5 6 7", here);
    REQUIRE(h.tet.get().size() == 2);
    CHECK(h.tet.get()[1] == std::array<int, 4>{4, 5, 6, 7});
    h.ts.read("2e-4", here);
    CHECK_FALSE(h.ts.get().automatic);
    CHECK(h.ts.get().value == 2e-4);
    h.ts.read("auto", here);
    CHECK(h.ts.get().automatic);
    h.il.read("4 5", here);
    CHECK(h.il.get() == IndexList{4, 5});
    h.b.read("true", here);
    CHECK(h.b.get());
}

TEST_CASE("A value that does not parse is a located error saying what was expected", "[Param]") {
    struct Case { const char *param, *text, *message; };
    auto c = GENERATE(values<Case>({
        {"b", "yes", "Holder 'h': b = \"yes\" is not true or false"},
        {"b", "True", "Holder 'h': b = \"True\" is not true or false"},
        {"i", "3.5", "Holder 'h': i = \"3.5\" is not an integer"},
        {"i", "ten", "Holder 'h': i = \"ten\" is not an integer"},
        {"i", "1 2", "Holder 'h': i = \"1 2\" is not an integer"},
        {"i", "99999999999", "Holder 'h': i = \"99999999999\" is not an integer"},
        {"i", "", "Holder 'h': i = \"\" is not an integer"},
        {"d", "1.5.2", "Holder 'h': d = \"1.5.2\" is not a number"},
        {"d", "abc", "Holder 'h': d = \"abc\" is not a number"},
        {"d", "nan", "Holder 'h': d = \"nan\" is not a number"},
        {"d", "inf", "Holder 'h': d = \"inf\" is not a number"},
        {"d", "1e999", "Holder 'h': d = \"1e999\" is not a number"},
        {"d", "", "Holder 'h': d = \"\" is not a number"},
        {"d", "1 2", "Holder 'h': d = \"1 2\" is not a number"},
        {"v", "1 2", "Holder 'h': v = \"1 2\" is not three numbers \"x y z\""},
        {"v", "1 2 3 4", "Holder 'h': v = \"1 2 3 4\" is not three numbers \"x y z\""},
        {"v", "1 2 x", "Holder 'h': v = \"1 2 x\" is not three numbers \"x y z\""},
        {"il", "0 -1", "Holder 'h': il = \"0 -1\" is not a list of non-negative integers"},
        {"il", "0 1.5", "Holder 'h': il = \"0 1.5\" is not a list of non-negative integers"},
        {"nl", "1 two", "Holder 'h': nl = \"1 two\" is not a list of numbers"},
        {"fp", "", "Holder 'h': fp = \"\" is not a file path"},
        {"ts", "0", "Holder 'h': ts = \"0\" is not a positive number of seconds or \"auto\""},
        {"ts", "-1e-3", "Holder 'h': ts = \"-1e-3\" is not a positive number of seconds or \"auto\""},
        {"ts", "Auto", "Holder 'h': ts = \"Auto\" is not a positive number of seconds or \"auto\""},
        {"pos", "0 0 0 1", "Holder 'h': pos = \"0 0 0 1\" is not a list of coordinates, 3 per point"},
        {"tet", "0 1 2", "Holder 'h': tet = \"0 1 2\" is not a list of node indices, 4 per element"},
        {"tet", "0 1 2 -3", "Holder 'h': tet = \"0 1 2 -3\" is not a list of node indices, 4 per element"},
        {"hex", "0 1 2 3", "Holder 'h': hex = \"0 1 2 3\" is not a list of node indices, 8 per element"},
        {"tri", "0 1 2 3", "Holder 'h': tri = \"0 1 2 3\" is not a list of node indices, 3 per element"},
        {"mesh", "0 0 0", "Holder 'h': mesh = \"0 0 0\" is not a link to a mesh (\"@loader.mesh\"): a mesh cannot be written inline"},
    }));
    CAPTURE(c.param, c.text);
    Holder h;
    CHECK(readError(h, c.param, c.text) == std::string("dir/scene.xml:7: error: ") + c.message);
}

TEST_CASE("A long bad value is shortened in the message", "[Param]") {
    Holder h;
    const std::string text(100, 'x');
    CHECK(readError(h, "d", text) == "dir/scene.xml:7: error: Holder 'h': d = \"" + std::string(57, 'x') + "...\" is not a number");
}

TEST_CASE("Range limits are inclusive or exclusive as declared", "[Param]") {
    struct Case { const char *param, *text; bool ok; const char* problem; };
    auto c = GENERATE(values<Case>({
        {"closed", "0", true, ""}, {"closed", "0.5", true, ""},
        {"closed", "-1e-9", false, "closed = -1e-09 is outside [0, 0.5]"},
        {"closed", "0.50001", false, "closed = 0.50001 is outside [0, 0.5]"},
        {"halfOpen", "0", true, ""}, {"halfOpen", "0.4999", true, ""},
        {"halfOpen", "0.5", false, "halfOpen = 0.5 is outside [0, 0.5)"},
        {"positive", "1e-300", true, ""},
        {"positive", "0", false, "positive = 0 is outside > 0"},
        {"positive", "-2", false, "positive = -2 is outside > 0"},
        {"belowOne", "0.999", true, ""},
        {"belowOne", "1", false, "belowOne = 1 is outside < 1"},
        {"count", "1", true, ""},
        {"count", "0", false, "count = 0 is outside >= 1"},
        {"nodes", "0 9 3", true, ""},
        {"nodes", "0 10 3", false, "nodes = 0 10 3 entry 1 (10) is outside <= 9"},
        {"unit", "1 -1 0.5", true, ""},
        {"unit", "0 0 1.5", false, "unit = 0 0 1.5 entry 2 (1.5) is outside [-1, 1]"},
    }));
    CAPTURE(c.param, c.text);
    Holder h;
    const std::string msg = readError(h, c.param, c.text);
    if (c.ok) {
        CHECK(msg.empty());
    } else {
        CHECK(msg == std::string("dir/scene.xml:7: error: Holder 'h': ") + c.problem);
    }
}

TEST_CASE("The range text of a spec reads like the math", "[ParamSpec]") {
    CHECK(ParamSpec("a").min(0).max(0.5, true).rangeText() == "[0, 0.5)");
    CHECK(ParamSpec("a").above(0).below(1).rangeText() == "(0, 1)");
    CHECK(ParamSpec("a").min(-1).max(1).rangeText() == "[-1, 1]");
    CHECK(ParamSpec("a").above(0).rangeText() == "> 0");
    CHECK(ParamSpec("a").min(1).rangeText() == ">= 1");
    CHECK(ParamSpec("a").below(2.5).rangeText() == "< 2.5");
    CHECK(ParamSpec("a").max(3).rangeText() == "<= 3");
    CHECK(ParamSpec("a").choices({"x", "y", "z"}).rangeText() == "one of x|y|z");
    CHECK(ParamSpec("a").rangeText().empty());
}

TEST_CASE("An enum parameter takes only its choices, case included", "[Param]") {
    Holder h;
    CHECK(readError(h, "e", "quadratic").empty());
    CHECK(h.e.get() == "quadratic");
    CHECK(readError(h, "e", "cubic") == "dir/scene.xml:7: error: Holder 'h': e = cubic is not one of linear|quadratic");
    CHECK(readError(h, "e", "Linear") == "dir/scene.xml:7: error: Holder 'h': e = Linear is not one of linear|quadratic");
}

TEST_CASE("Defaults hold until the scene sets a value, and isSet says which", "[Param]") {
    Holder h;
    CHECK(h.i.get() == 7);
    CHECK(h.d.get() == 2.5);
    CHECK(h.e.get() == "linear");
    CHECK(h.v.get() == Vec3(1, 2, 3));
    CHECK(h.il.get().empty());
    CHECK_FALSE(h.ts.get().automatic);
    CHECK_FALSE(h.i.isSet());
    CHECK_FALSE(h.d.isSet());
    CHECK(h.d.defaultText() == "2.5");
    CHECK(h.v.defaultText() == "1 2 3");
    CHECK(h.e.defaultText() == "linear");
    CHECK(h.d.typeName() == "double");
    CHECK(h.il.typeName() == "index list");
    CHECK(h.d.spec().unitText == "Pa");

    h.d.read("4", here);
    CHECK(h.d.isSet());
    CHECK(h.d.get() == 4.0);
    CHECK(h.d.defaultText() == "2.5");
    CHECK(h.d.valueText() == "4");
    CHECK(h.d.loc().line == 7);
    h.i.set(3);
    CHECK(h.i.isSet());
    CHECK(h.i.get() == 3);
}

TEST_CASE("A list with a fixed count must have exactly that many entries", "[Param]") {
    Holder h;
    CHECK(readError(h, "box", "0 0 0 1 1 1").empty());
    CHECK(h.box.get().size() == 6);
    CHECK(readError(h, "box", "0 0 0 1 1") == "dir/scene.xml:7: error: Holder 'h': box = 0 0 0 1 1 has 5 entries, expected 6");
    CHECK(readError(h, "box", "0 0 0 1 1 1 1") ==
          "dir/scene.xml:7: error: Holder 'h': box = 0 0 0 1 1 1 1 has 7 entries, expected 6");
}

TEST_CASE("An output parameter cannot be set from the scene", "[Param]") {
    Holder h;
    CHECK(readError(h, "out", "3") ==
          "dir/scene.xml:7: error: Holder 'h': 'out' is computed by the component and cannot be set; it can only be linked to");
    CHECK_FALSE(h.out.isSet());
    // code may set it
    h.out.set(2.0);
    CHECK(h.out.get() == 2.0);
}

TEST_CASE("An output parameter cannot be made a link either", "[Param]") {
    Holder h;
    CHECK(readError(h, "out", "@other.d") ==
          "dir/scene.xml:7: error: Holder 'h': 'out' is computed by the component and cannot be set; it can only be linked to");
}

TEST_CASE("A value starting with @ is kept as a link for the scene builder", "[Param]") {
    Holder h;
    CHECK(readError(h, "d", "@other.d").empty());
    CHECK(h.d.linkText() == "@other.d");
    CHECK(h.d.isSet());
    CHECK(h.d.get() == 2.5);  // unresolved: still the default
}

TEST_CASE("A data link reads the source's current value", "[Param]") {
    Holder src, dst;
    src.nl.set({1, 2, 3});
    REQUIRE(dst.nl.canBindTo(src.nl));
    CHECK_FALSE(dst.nl.canBindTo(src.il));
    CHECK_FALSE(dst.d.canBindTo(src.i));
    dst.nl.bindTo(&src.nl);
    CHECK(dst.nl.get() == NumberList{1, 2, 3});
    src.nl.edit().push_back(4);
    CHECK(dst.nl.get().size() == 4);
    // setting it in code cuts the link
    dst.nl.set({9});
    CHECK(dst.nl.get() == NumberList{9});
    CHECK(src.nl.get().size() == 4);
}

TEST_CASE("A view reads a value kept elsewhere, and a link through it too, until the next set", "[Param]") {
    Holder src, dst;
    NumberList kept{1, 2, 3};
    src.nl.view(&kept);
    CHECK(src.nl.isSet());
    CHECK(&src.nl.get() == &kept);
    dst.nl.bindTo(&src.nl);
    kept.push_back(4);
    CHECK(dst.nl.get() == NumberList{1, 2, 3, 4});
    src.nl.set({9});
    CHECK(dst.nl.get() == NumberList{9});
    CHECK(kept.size() == 4);
    src.nl.view(&kept);
    src.nl.edit() = {7};  // edit() ends the view too, on the parameter's own value
    CHECK(src.nl.get() == NumberList{7});
    CHECK(kept.size() == 4);
}

TEST_CASE("File paths are resolved relative to the scene file's folder", "[Param]") {
    struct Case { const char *file, *written, *resolved; };
    auto c = GENERATE(values<Case>({
        {"/data/scenes/liver.xml", "mesh.vtk", "/data/scenes/mesh.vtk"},
        {"/data/scenes/liver.xml", "../meshes/liver.msh", "/data/meshes/liver.msh"},
        {"/data/scenes/liver.xml", "./a/./b.vtk", "/data/scenes/a/b.vtk"},
        {"/data/scenes/liver.xml", "/abs/mesh.vtk", "/abs/mesh.vtk"},
        {"scenes/liver.xml", "mesh.vtk", "scenes/mesh.vtk"},
        {"liver.xml", "mesh.vtk", "mesh.vtk"},
        {"<string>", "mesh.vtk", "mesh.vtk"},
        {"", "sub/../mesh.vtk", "mesh.vtk"},
    }));
    CAPTURE(c.file, c.written);
    Holder h;
    h.fp.read(c.written, {c.file, 3});
    CHECK(h.fp.get().written == c.written);
    CHECK(h.fp.get().resolved == c.resolved);
    CHECK(h.fp.valueText() == c.written);
}

TEST_CASE("A component link must be written with @", "[Link]") {
    struct Target : Component {};
    struct Linker : Component {
        Linker() { setClassName("Linker"); setName("l"); }
        Link<Target> target{this, ParamSpec("target")};
    } l;
    auto e = errorOf([&] { l.target.read("mo", here); });
    REQUIRE(e);
    CHECK_THAT(e->what(), StartsWith("dir/scene.xml:7: error: Linker 'l': target = \"mo\""));
    CHECK_THAT(e->what(), Contains("@mo"));
    l.target.read("@mo", here);
    CHECK(l.target.linkText() == "@mo");
    CHECK(l.target.isSet());
    CHECK(l.target.get() == nullptr);  // resolved by the scene builder
}

TEST_CASE("Component parameters register in declaration order with their names", "[Param]") {
    Holder h;
    auto names = h.paramNames();
    REQUIRE(names.size() >= 3);
    CHECK(names[0] == "name");
    CHECK(names[1] == "b");
    CHECK(names[2] == "i");
    CHECK(h.findParam("halfOpen") == &h.halfOpen);
    CHECK(h.findParam("nope") == nullptr);
}
