/// The simulation loop: time step, step count and time, group assembly, NaN detection, timers,
/// init order along links.
#include "CoreTestSupport.h"

#include "fascia/plugin/Registry.h"

#include <algorithm>
#include <cmath>

using namespace fascia;
using namespace fascia::core;
using namespace fascia::testing;

namespace {

/// One body of one node: state, mass, integrator, a force field.
std::string body(const std::string& rootAttrs, const std::string& nanAttrs, const std::string& massAttrs = "mass=\"2\"") {
    return R"(<Node name="root" )" + rootAttrs + R"(>
  <TestCounter name="counter" label="a"/>
  <Node name="body">
    <TestEuler name="euler"/>
    <TestState name="state" position="0 0 0  1 0 0"/>
    <TestMass name="mass" )" + massAttrs + R"(/>
    <TestNaN name="nan" )" + nanAttrs + R"(/>
  </Node>
</Node>)";
}

} // namespace

TEST_CASE("The time step comes from the root node and time is steps times dt", "[Simulation]") {
    auto sim = scene(body("dt=\"0.01\"", ""));
    CHECK(sim->dt() == 0.01);
    CHECK(sim->root().context().dt == 0.01);
    CHECK(sim->stepCount() == 0);
    CHECK(sim->time() == 0.0);
    CHECK(paramOf<double>(*sim, "counter", "dtSeen") == 0.01);  // dtChanged at init
    sim->run(3);
    CHECK(sim->stepCount() == 3);
    CHECK(sim->time() == 3 * 0.01);
    sim->run(997);
    CHECK(sim->stepCount() == 1000);
    CHECK(sim->time() == 1000 * 0.01);  // no drift from summing dt
    CHECK(sim->root().context().step == 1000);
    CHECK(sim->root().context().time == sim->time());
}

TEST_CASE("dt=\"auto\" takes the smallest stable step of the force fields times dtSafety", "[Simulation]") {
    SECTION("default safety 0.5") {
        auto sim = scene(body("dt=\"auto\"", "criticalDt=\"0.004\""));
        CHECK(sim->criticalTimeStep() == 0.004);
        CHECK(sim->dt() == 0.004 * 0.5);
    }
    SECTION("dtSafety") {
        auto sim = scene(body("dt=\"auto\" dtSafety=\"0.25\"", "criticalDt=\"0.004\""));
        CHECK(sim->dt() == 0.004 * 0.25);
    }
    SECTION("no force field reports one: located error") {
        auto e = sceneError(body("dt=\"auto\"", ""));
        REQUIRE(e);
        CHECK(std::string(e->what()) ==
              "scene.xml:1: error: Node 'root': dt=\"auto\" but no force field reports a stable time step; give dt in seconds");
    }
}

TEST_CASE("Stepping without a time step is a located error", "[Simulation]") {
    auto sim = scene(body("", ""));
    CHECK(sim->dt() == 0.0);
    auto e = errorOf([&] { sim->step(); });
    REQUIRE(e);
    CHECK(e->kind() == ErrorKind::Input);
    CHECK(std::string(e->what()) == "scene.xml:1: error: no time step: set dt on the root node (seconds or \"auto\") or pass --dt");
    CHECK(sim->stepCount() == 0);
}

TEST_CASE("setDt tells every component and refuses non-positive steps", "[Simulation]") {
    auto sim = scene(body("", ""));
    sim->setDt(0.5);
    CHECK(sim->dt() == 0.5);
    CHECK(paramOf<double>(*sim, "counter", "dtSeen") == 0.5);
    sim->run(2);
    CHECK(sim->time() == 1.0);
    for (double bad : {0.0, -1.0, std::nan("")}) {
        CAPTURE(bad);
        auto e = errorOf([&] { sim->setDt(bad); });
        REQUIRE(e);
        CHECK_THAT(e->message(), Contains("is not a positive number"));
    }
    CHECK(sim->dt() == 0.5);
}

TEST_CASE("Each state gets one group with the integrator, masses and force fields of its context", "[Simulation][MechanicalGroup]") {
    auto sim = scene(body("dt=\"0.1\" gravity=\"0 0 -10\"", ""));
    REQUIRE(sim->groups().size() == 1);
    const MechanicalGroup& g = sim->groups()[0];
    CHECK(g.state == sim->find("state"));
    CHECK(g.integrator == sim->find("euler"));
    CHECK(g.forceFields.size() == 1);
    CHECK(g.masses.size() == 1);
    CHECK(g.constraints.empty());
    CHECK(g.gravity == Vec3(0, 0, -10));
    CHECK(g.mass == std::vector<double>{2, 2});
    CHECK(g.invMass == std::vector<double>{0.5, 0.5});
    CHECK(&sim->state("state") == sim->find("state"));
    CHECK(&sim->state("/root/body/state") == sim->find("state"));
}

TEST_CASE("The loop applies forces and gravity through the integrator", "[Simulation][MechanicalGroup]") {
    // mass 2, force (0, 4, 0), gravity (0, 0, -10): a = (0, 2, -10); semi-implicit Euler from rest
    // gives v_n = n dt a and x_n = x_0 + dt^2 a n(n+1)/2
    const double dt = 0.01;
    const int n = 25;
    auto sim = scene(body("dt=\"0.01\" gravity=\"0 0 -10\"", "force=\"0 4 0\""));
    sim->run(n);
    const Vec3 a(0, 2, -10);
    auto& s = sim->state("state");
    REQUIRE(s.size() == 2);
    const Vec3 expectedX1 = Vec3(1, 0, 0) + dt * dt * a * (n * (n + 1) / 2.0);
    CHECK((s.x()[1] - expectedX1).norm() < 1e-12);
    CHECK((s.v()[0] - n * dt * a).norm() < 1e-12);
    CHECK(s.x0()[1] == Vec3(1, 0, 0));
}

TEST_CASE("Positions written between steps are used by the next step", "[Simulation]") {
    auto sim = scene(body("dt=\"0.1\"", ""));
    auto& s = sim->state("state");
    s.x()[0] = Vec3(5, 6, 7);
    sim->step();
    CHECK(s.x()[0] == Vec3(5, 6, 7));  // no force, no velocity
    s.v()[0] = Vec3(1, 0, 0);
    sim->step();
    CHECK((s.x()[0] - Vec3(5.1, 6, 7)).norm() < 1e-12);
}

TEST_CASE("A NaN force is a simulation error naming the step and the force field", "[Simulation][MechanicalGroup]") {
    auto sim = scene(body("dt=\"0.01\"", "nanAtStep=\"3\" nanNode=\"1\""));
    sim->run(2);
    auto e = errorOf([&] { sim->run(5); });
    REQUIRE(e);
    INFO(e->what());
    CHECK(e->kind() == ErrorKind::Simulation);
    CHECK_THAT(e->message(), StartsWith("[/root/body/nan] step 3: "));
    CHECK_THAT(e->message(), Contains("node 1"));
    CHECK(sim->stepCount() == 2);  // the failed step does not count
}

TEST_CASE("A NaN on a large state is caught by the parallel finite check", "[Simulation][MechanicalGroup]") {
    // above kParallelNodes nodes the finite check runs on the OpenMP threads
    const int n = int(kParallelNodes) + 1000;
    std::string positions;
    for (int i = 0; i < n; ++i) positions += std::to_string(i) + " 0 0 ";
    const std::string xml = R"(<Node name="root" dt="0.01">
  <Node name="body">
    <TestEuler name="euler"/>
    <TestState name="state" position=")" + positions + R"("/>
    <TestMass name="mass" mass="2"/>
    <TestNaN name="nan" nanAtStep="2" nanNode=")" + std::to_string(n - 7) + R"("/>
  </Node>
</Node>)";
    auto sim = scene(xml);
    sim->run(1);
    auto e = errorOf([&] { sim->run(3); });
    REQUIRE(e);
    INFO(e->what());
    CHECK(e->kind() == ErrorKind::Simulation);
    CHECK_THAT(e->message(), StartsWith("[/root/body/nan] step 2: "));
    CHECK_THAT(e->message(), Contains("node " + std::to_string(n - 7)));
}

TEST_CASE("An infinite velocity in the last node of a large state is caught", "[Simulation][MechanicalGroup]") {
    // 3,049 nodes: the finite check reads the node arrays in chunks of kNodeChunk nodes, 8 values at
    // a time; the last node of the last chunk is in its remainder
    const int n = int(kParallelNodes) + 1001;
    std::string positions;
    for (int i = 0; i < n; ++i) positions += std::to_string(i) + " 0 0 ";
    auto sim = scene(R"(<Node name="root" dt="0.01"><Node name="body"><TestEuler name="euler"/>
    <TestState name="state" position=")" + positions + R"("/><TestMass name="mass" mass="2"/></Node></Node>)");
    sim->run(1);
    auto& s = sim->state("state");
    const size_t bad = GENERATE(size_t(0), size_t(1500), size_t(3048));
    CAPTURE(bad);
    s.v()[bad][2] = -INFINITY;
    SECTION("in the velocity alone: the check by itself") {
        // (the group's check, called directly: a step would carry the velocity into the position)
        auto& g = const_cast<MechanicalGroup&>(sim->groups()[0]);
        auto e = errorOf([&] { g.checkFinite(sim->time()); });
        REQUIRE(e);
        INFO(e->what());
        CHECK_THAT(e->message(), Contains("node " + std::to_string(bad) + " has a non-finite velocity"));
    }
    SECTION("after a step, in the position too") {
        auto e = errorOf([&] { sim->run(1); });
        REQUIRE(e);
        INFO(e->what());
        CHECK(e->kind() == ErrorKind::Simulation);
        CHECK_THAT(e->message(), Contains("node " + std::to_string(bad) + " has a non-finite position"));
    }
}

TEST_CASE("Components without a state or an integrator are warned about, not fatal", "[Simulation]") {
    auto sim = scene(R"(<Node name="root" dt="0.1">
  <TestNaN name="lonely"/>
  <Node name="noIntegrator">
    <TestState name="s"/>
    <TestMass name="m"/>
  </Node>
</Node>)");
    CHECK(sim->groups().empty());
    sim->run(2);
    CHECK(sim->stepCount() == 2);
}

TEST_CASE("A force field on a state without mass is a located error", "[Simulation]") {
    auto e = sceneError(R"(<Node name="root" dt="0.1">
  <TestEuler/>
  <Node name="b">
    <TestState name="s"/>
    <TestNaN name="f"/>
  </Node>
</Node>)");
    REQUIRE(e);
    CHECK(std::string(e->what()) == "scene.xml:4: error: TestState 's': no mass in its context: add a LumpedMass next to it");
}

TEST_CASE("state() of a name that is no state is an error", "[Simulation]") {
    auto sim = scene(body("dt=\"0.1\"", ""));
    auto e = errorOf([&] { sim->state("counter"); });
    REQUIRE(e);
    CHECK(e->message() == "no mechanical state 'counter' in the scene");
    CHECK(errorOf([&] { sim->state("nothing"); }));
}

namespace {
/// An injected timer clock: each read advances it by exactly 1 ms, so that the time a timer
/// accumulates counts the clock reads inside it, whatever the machine's speed.
double g_fakeNow = 0.0;
double fakeClock() { return g_fakeNow += 1e-3; }
} // namespace

TEST_CASE("Timers accumulate the calls and time of each component", "[Simulation]") {
    fascia::core::setTimersEnabled(true);
    fascia::core::setTimerClock(&fakeClock);
    auto sim = scene(body("dt=\"0.01\"", "force=\"1 0 0\""));
    sim->run(4);
    auto rows = sim->timers();
    auto row = [&](const std::string& path) {
        auto it = std::find_if(rows.begin(), rows.end(), [&](const TimerRow& r) { return r.path == path; });
        REQUIRE(it != rows.end());
        return *it;
    };
    CHECK(rows.size() == 5);
    CHECK(row("/root/body/euler").calls == 4);
    CHECK(row("/root/body/euler").type == "TestEuler");
    CHECK(row("/root/body/nan").calls == 4);
    CHECK(row("/root/counter").calls == 5);  // observed at init and after each step
    CHECK(row("/root/body/state").calls == 0);
    // inclusive: a step of the integrator reads the clock at its start, around the force field
    // (2 reads, 1 ms for the force field) and at its end: 3 ms per step; the observer 1 ms a call
    CHECK(row("/root/body/euler").seconds == Approx(4 * 3e-3).epsilon(1e-9));
    CHECK(row("/root/body/nan").seconds == Approx(4 * 1e-3).epsilon(1e-9));
    CHECK(row("/root/counter").seconds == Approx(5 * 1e-3).epsilon(1e-9));
    CHECK(row("/root/body/state").seconds == 0.0);
    sim->run(4);
    rows = sim->timers();
    CHECK(row("/root/body/euler").calls == 8);
    CHECK(row("/root/body/nan").calls == 8);
    CHECK(row("/root/body/euler").seconds == Approx(8 * 3e-3).epsilon(1e-9));
    // switched off: calls still counted, no time added, the clock not read
    fascia::core::setTimersEnabled(false);
    const double clockBefore = g_fakeNow;
    sim->run(2);
    rows = sim->timers();
    CHECK(row("/root/body/euler").calls == 10);
    CHECK(row("/root/body/euler").seconds == Approx(8 * 3e-3).epsilon(1e-9));
    CHECK(g_fakeNow == clockBefore);
    fascia::core::setTimerClock(nullptr);
}

TEST_CASE("Timers read steady_clock unless a clock is injected", "[Simulation]") {
    fascia::core::setTimerClock(&fakeClock);
    const double t = fascia::core::timerNow();
    CHECK(fascia::core::timerNow() == Approx(t + 1e-3).epsilon(1e-12));
    fascia::core::setTimerClock(nullptr);
    const double a = fascia::core::timerNow(), b = fascia::core::timerNow();
    CHECK(b >= a);  // monotonic
    CHECK(a != Approx(g_fakeNow));
}

TEST_CASE("Timer rows are sorted by path", "[Simulation]") {
    auto sim = scene(body("dt=\"0.01\"", ""));
    auto rows = sim->timers();
    CHECK(std::is_sorted(rows.begin(), rows.end(), [](auto& a, auto& b) { return a.path < b.path; }));
}

TEST_CASE("Init order follows links: the target is initialised first", "[Simulation][Link]") {
    SECTION("component link to a later component") {
        auto sim = scene(R"(<Node name="root">
  <TestCounter name="b" label="b" partner="@n/a"/>
  <Node name="n">
    <TestCounter name="a" label="a"/>
  </Node>
</Node>)");
        const int a = paramOf<int>(*sim, "a", "initIndex");
        const int b = paramOf<int>(*sim, "b", "initIndex");
        CHECK(a < b);
        CHECK(paramOf<int>(*sim, "b", "partnerInitIndex") == a);  // b saw a initialised
    }
    SECTION("data link to a later component") {
        auto sim = scene(R"(<Node name="root">
  <TestCounter name="c" label="c" values="@d.values" scale="@e.valuesSum"/>
  <TestCounter name="d" label="d" values="1 2"/>
  <TestCounter name="e" label="e" values="@d.values"/>
</Node>)");
        CHECK(paramOf<int>(*sim, "d", "initIndex") < paramOf<int>(*sim, "c", "initIndex"));
        CHECK(paramOf<int>(*sim, "e", "initIndex") < paramOf<int>(*sim, "c", "initIndex"));
        CHECK(paramOf<double>(*sim, "c", "valuesSum") == 3);
        CHECK(paramOf<double>(*sim, "c", "scale") == 3);
    }
    SECTION("dependencies() count too: the mass after its state") {
        auto sim = scene(R"(<Node name="root" dt="0.1">
  <TestEuler/>
  <TestMass name="m" mass="3"/>
  <TestState name="s" position="0 0 0 1 1 1 2 2 2"/>
</Node>)");
        CHECK(sim->groups().at(0).mass == std::vector<double>{3, 3, 3});
    }
}

TEST_CASE("A link cycle is a located error", "[Simulation][Link]") {
    auto e = sceneError(R"(<Node name="root">
  <TestCounter name="a" label="a" partner="@b"/>
  <TestCounter name="b" label="b" values="@c.values"/>
  <TestCounter name="c" label="c" partner="@a"/>
</Node>)");
    REQUIRE(e);
    CHECK(e->kind() == ErrorKind::Input);
    CHECK(std::string(e->what()) == "scene.xml:2: error: TestCounter 'a': link cycle: /root/a depends, through its links, on itself");
}

TEST_CASE("A scene built in code runs like one from XML", "[Simulation]") {
    loadTestPlugin();
    auto root = std::make_unique<Node>("root");
    auto& counter = root->addComponent(Registry::instance().create("TestCounter"));
    counter.setName("c");
    root->dt.set(TimeStep{false, 0.25});
    Simulation sim(std::move(root));
    sim.init();
    CHECK(sim.dt() == 0.25);
    sim.run(4);
    CHECK(sim.time() == 1.0);
    CHECK(paramOf<int>(sim, "c", "beginSteps") == 4);
}

TEST_CASE("Values set from code are checked at init like values read from XML", "[Simulation][Param]") {
    loadTestPlugin();
    const auto build = [](const std::string& param, const std::string& value) {
        auto root = std::make_unique<Node>("root");
        auto& counter = root->addComponent(Registry::instance().create("TestCounter"));
        counter.setName("c");
        auto* p = counter.findParam(param);
        REQUIRE(p != nullptr);
        if (param == "mode") dynamic_cast<Param<std::string>&>(*p).set(value);
        else dynamic_cast<Param<double>&>(*p).set(std::stod(value));
        return std::make_unique<Simulation>(std::move(root));
    };
    SECTION("a choice outside the list") {
        auto sim = build("mode", "slow");
        CHECK_THROWS_WITH(sim->init(), Catch::Contains("TestCounter 'c'") && Catch::Contains("mode = slow") &&
                                           Catch::Contains("fast|accurate|debug"));
    }
    SECTION("a number outside its range") {
        auto sim = build("rate", "-1");
        CHECK_THROWS_WITH(sim->init(), Catch::Contains("TestCounter 'c'") && Catch::Contains("rate = -1"));
    }
    SECTION("values inside pass") {
        auto sim = build("mode", "accurate");
        CHECK_NOTHROW(sim->init());
    }
}

TEST_CASE("By default a component is initialised after the state in its context", "[Simulation][Component]") {
    auto sim = scene(R"(<Node name="root" dt="0.1">
  <TestCounter name="before" label="a"/>
  <TestState name="s" position="0 0 0 1 1 1 2 2 2 3 3 3"/>
  <Node name="child">
    <TestCounter name="below" label="b"/>
  </Node>
  <Node name="stateless">
  </Node>
</Node>)");
    CHECK(paramOf<int>(*sim, "before", "stateSizeAtInit") == 4);
    CHECK(paramOf<int>(*sim, "below", "stateSizeAtInit") == 4);
}

TEST_CASE("Every component is marked initialised after init", "[Simulation][Component]") {
    auto sim = scene(body("dt=\"0.1\"", ""));
    for (const char* name : {"counter", "euler", "state", "mass", "nan"}) {
        CAPTURE(name);
        REQUIRE(sim->find(name));
        CHECK(sim->find(name)->initialised());
    }
}

TEST_CASE("LoadOptions override the scene's dt and set the output folder", "[Simulation]") {
    loadTestPlugin();
    TempDir dir;
    LoadOptions opts;
    opts.dt = 0.002;
    opts.outputDir = (dir.path() / "out" / "nested").string();
    auto sim = Simulation::fromString(body("dt=\"0.01\"", ""), "scene.xml", ".", opts);
    CHECK(sim->dt() == 0.002);
    CHECK(paramOf<double>(*sim, "counter", "dtSeen") == 0.002);
    CHECK(sim->outputDir() == opts.outputDir);
    CHECK(sim->root().context().outputDir == opts.outputDir);
    // checked at load, created when the run starts (a scene found invalid before leaves no folder)
    CHECK_FALSE(fs::exists(dir.path() / "out"));
    sim->run(5);
    CHECK(fs::is_directory(opts.outputDir));
    CHECK(sim->time() == 5 * 0.002);
}

TEST_CASE("A dt override beats dt=\"auto\" and needs no force field to report one", "[Simulation]") {
    loadTestPlugin();
    LoadOptions opts;
    opts.dt = 0.003;
    auto sim = Simulation::fromString(body("dt=\"auto\"", ""), "scene.xml", ".", opts);
    CHECK(sim->dt() == 0.003);
}
