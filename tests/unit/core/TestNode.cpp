/// The scene graph: paths, lookups in the context, link path resolution.
#include "CoreTestSupport.h"

#include "fascia/scene/Node.h"

using namespace fascia;
using namespace fascia::core;
using namespace fascia::testing;

namespace {

struct Shape : Component {};
struct Sphere : Shape {};
struct Cube : Shape {};
struct Other : Component {};

/// root{ s0:Sphere, o0:Other, a{ c1:Cube, b{ s2:Sphere, x:Other } }, d{ x:Other } }
struct Tree {
    Node root{"root"};
    Node* a;
    Node* b;
    Node* d;
    Sphere* s0;
    Other* o0;
    Cube* c1;
    Sphere* s2;
    Other* bx;
    Other* dx;
    Tree() {
        s0 = &root.add<Sphere>("s0");
        o0 = &root.add<Other>("o0");
        a = &root.addChild("a");
        c1 = &a->add<Cube>("c1");
        b = &a->addChild("b");
        s2 = &b->add<Sphere>("s2");
        bx = &b->add<Other>("x");
        d = &root.addChild("d");
        dx = &d->add<Other>("x");
    }
};

} // namespace

TEST_CASE("Nodes and components know their paths", "[Node]") {
    Tree t;
    CHECK(t.root.path() == "/root");
    CHECK(t.b->path() == "/root/a/b");
    CHECK(t.bx->path() == "/root/a/b/x");
    CHECK(t.s0->path() == "/root/s0");
    CHECK(t.b->parent() == t.a);
    CHECK(t.b->root() == &t.root);
    CHECK(t.s2->node() == t.b);
    CHECK(t.a->child("b") == t.b);
    CHECK(t.a->child("x") == nullptr);
    CHECK(t.b->component("x") == t.bx);
    CHECK(t.b->component("s0") == nullptr);
}

TEST_CASE("Components added in code get their class name", "[Node]") {
    Tree t;
    CHECK(t.s0->className() == "Sphere");
    CHECK(t.c1->className() == "Cube");
}

TEST_CASE("findInContext looks in the node, then in its ancestors", "[Node]") {
    Tree t;
    CHECK(t.b->findInContext<Sphere>() == t.s2);   // local first
    CHECK(t.b->findInContext<Cube>() == t.c1);     // parent
    CHECK(t.b->findInContext<Shape>() == t.s2);    // base class, local first
    CHECK(t.a->findInContext<Shape>() == t.c1);
    CHECK(t.a->findInContext<Sphere>() == t.s0);   // root, not the child b
    CHECK(t.d->findInContext<Cube>() == nullptr);  // a sibling's component is not in the context
    CHECK(t.d->findInContext<Other>() == t.dx);
    CHECK(t.root.findLocal<Other>() == t.o0);
    CHECK(t.a->findLocal<Sphere>() == nullptr);
}

TEST_CASE("findAllInSubtree lists depth first in declaration order", "[Node]") {
    Tree t;
    auto shapes = t.root.findAllInSubtree<Shape>();
    CHECK(shapes == std::vector<Shape*>{t.s0, t.c1, t.s2});
    auto others = t.root.findAllInSubtree<Other>();
    CHECK(others == std::vector<Other*>{t.o0, t.bx, t.dx});
    CHECK(t.d->findAllInSubtree<Shape>().empty());
    CHECK(t.b->findAllLocal<Component>().size() == 2);
}

TEST_CASE("findByName finds the first match depth first", "[Node]") {
    Tree t;
    CHECK(t.root.findByName("s2") == t.s2);
    CHECK(t.root.findByName("x") == t.bx);  // a/b/x comes before d/x
    CHECK(t.d->findByName("x") == t.dx);
    CHECK(t.root.findByName("nothing") == nullptr);
}

TEST_CASE("findUnique takes a path or a name found once, and rejects an ambiguous name", "[Node]") {
    Tree t;
    CHECK(t.root.findUnique("s2") == t.s2);
    CHECK(t.root.findUnique("d/x") == t.dx);
    CHECK(t.d->findUnique("x") == t.dx);  // unique below d
    CHECK(t.root.findUnique("nothing") == nullptr);
    CHECK_THROWS_WITH(t.root.findUnique("x"), Catch::Contains("ambiguous: 2 components") && Catch::Contains("/root/a/b/x"));
}

TEST_CASE("resolveComponent follows relative, absolute and bare paths", "[Node]") {
    Tree t;
    struct Case { const char* from; const char* path; const char* expected; };
    auto c = GENERATE(values<Case>({
        {"/root/a/b", "x", "/root/a/b/x"},
        {"/root/a/b", "./x", "/root/a/b/x"},
        {"/root/a/b", "c1", "/root/a/c1"},             // bare name found in the parent
        {"/root/a/b", "s0", "/root/s0"},               // ... and in the root
        {"/root/a/b", "../c1", "/root/a/c1"},
        {"/root/a/b", "../../d/x", "/root/d/x"},
        {"/root/a/b", "/root/d/x", "/root/d/x"},
        {"/root/a/b", "/d/x", "/root/d/x"},            // the root's name may be left out
        {"/root/a/b", "/root/s0", "/root/s0"},
        {"/root/a/b", "/s0", "/root/s0"},
        {"/root", "a/b/s2", "/root/a/b/s2"},
        {"/root/d", "x", "/root/d/x"},                 // local before ancestors
        {"/root/a/b", "../x", ""},                     // '..' then no x in a
        {"/root/a/b", "../../../s0", ""},              // above the root
        {"/root/a/b", "dx", ""},
        {"/root/a", "s2", ""},                         // bare names are not searched downwards
        {"/root", "/root/a/nothing", ""},
        {"/root", "a/zz/s2", ""},
    }));
    CAPTURE(c.from, c.path);
    Node* from = t.root.resolveNode(c.from);
    REQUIRE(from != nullptr);
    Component* found = from->resolveComponent(c.path);
    if (std::string(c.expected).empty()) {
        CHECK(found == nullptr);
    } else {
        REQUIRE(found != nullptr);
        CHECK(found->path() == c.expected);
    }
}

TEST_CASE("resolveNode follows node paths", "[Node]") {
    Tree t;
    CHECK(t.b->resolveNode("..") == t.a);
    CHECK(t.b->resolveNode("../..") == &t.root);
    CHECK(t.b->resolveNode("../../..") == nullptr);
    CHECK(t.b->resolveNode("/") == &t.root);
    CHECK(t.b->resolveNode("/root") == &t.root);
    CHECK(t.b->resolveNode("/d") == t.d);
    CHECK(t.root.resolveNode("a/b") == t.b);
    CHECK(t.root.resolveNode("") == &t.root);
    CHECK(t.root.resolveNode("a/c") == nullptr);
}

TEST_CASE("Gravity is inherited from the nearest node that sets it", "[Node]") {
    Tree t;
    CHECK(t.b->contextGravity() == Vec3::Zero());
    t.root.gravity.set(Vec3(0, 0, -9.81));
    CHECK(t.b->contextGravity() == Vec3(0, 0, -9.81));
    t.a->gravity.set(Vec3(1, 0, 0));
    CHECK(t.b->contextGravity() == Vec3(1, 0, 0));
    CHECK(t.d->contextGravity() == Vec3(0, 0, -9.81));
}

TEST_CASE("Every node shares the root's context", "[Node]") {
    Tree t;
    t.b->context().dt = 0.125;
    CHECK(t.root.context().dt == 0.125);
    CHECK(&t.d->context() == &t.root.context());
    CHECK(t.root.context().outputDir == ".");
}

TEST_CASE("Simulation::find takes a name or a path", "[Simulation][Node]") {
    auto sim = scene(R"(<Node name="root">
  <TestCounter name="c" label="a"/>
  <Node name="n">
    <TestCounter name="c" label="b"/>
    <TestCounter name="d" label="c"/>
  </Node>
</Node>)");
    // a bare name must be unique in the scene: two 'c' make it ambiguous, and the error says so
    try {
        sim->find("c");
        FAIL("an ambiguous name must be an error");
    } catch (const fascia::core::Error& e) {
        CHECK_THAT(std::string(e.what()), Catch::Matchers::Contains("'c' is ambiguous") &&
                                              Catch::Matchers::Contains("2 components"));
    }
    CHECK(sim->find("d")->path() == "/root/n/d");
    CHECK(sim->find("/root/n/c")->path() == "/root/n/c");
    CHECK(sim->find("n/c")->path() == "/root/n/c");
    CHECK(sim->find("zz") == nullptr);
    CHECK(sim->find("/root/zz/c") == nullptr);
}
