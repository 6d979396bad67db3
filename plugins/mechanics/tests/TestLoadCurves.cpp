// Load curves: each shape against its formula, the LoadCurve component and inline curves, and
// every load they scale (ConstantForce, gravity, SurfacePressure, PrescribedDisplacement): the
// load at a time t is c(t) times the full load. Expected values are the formulas of
// fascia/sim/LoadCurve.h written out here.
#include "PrescribedDisplacement.h"
#include "SurfacePressure.h"
#include "fascia/sim/LoadCurve.h"
#include "fascia/sim/Simulation.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

using fascia::Positions;
using fascia::Vec3;
using fascia::core::Curve;
using fascia::core::Error;
using fascia::core::Simulation;
using Catch::Matchers::Contains;

namespace {

Curve inlineCurve(const std::string& text) {
    Curve c;
    const std::string problem = Curve::parse(text, c);
    INFO(text << ": " << problem);
    REQUIRE(problem.empty());
    return c;
}

std::string parseProblem(const std::string& text) {
    Curve c;
    return Curve::parse(text, c);
}

/// Times from -0.5 to 3.5 s in steps of 1/64 s plus the points themselves and values close to them.
std::vector<double> sampleTimes() {
    std::vector<double> t;
    for (int k = -32; k <= 224; ++k) t.push_back(k / 64.0);
    for (double p : {0.0, 0.3, 0.5, 1.0, 1.3, 2.0, 2.5}) t.insert(t.end(), {p, std::nextafter(p, -1.0), std::nextafter(p, 9.0)});
    return t;
}

double smooth(double r) { return 10 * r * r * r - 15 * r * r * r * r + 6 * r * r * r * r * r; }

/// The tabulated curve of the tests below, written out by hand: linear or smooth between the points
/// (0, 0), (0.5, 2), (1.3, 2), (2, -1), (2.5, 0.5), the first value before and the last after them.
double table(double t, bool smoothly) {
    const double T[5] = {0, 0.5, 1.3, 2, 2.5}, C[5] = {0, 2, 2, -1, 0.5};
    if (t <= T[0]) return C[0];
    if (t > T[4]) return C[4];
    int k = 1;
    while (t > T[k]) ++k;
    const double r = (t - T[k - 1]) / (T[k] - T[k - 1]);
    return C[k - 1] + (C[k] - C[k - 1]) * (smoothly ? smooth(r) : r);
}

std::string scene(const std::string& body, const std::string& rootExtra = "") {
    return "<Node name=\"root\" dt=\"0.01\"" + rootExtra + ">\n"
           "  <LoadCurve name=\"table\" points=\"0 0  0.5 2  1.3 2  2 -1  2.5 0.5\"/>\n"
           "  <LoadCurve name=\"smoothTable\" points=\"0 0  0.5 2  1.3 2  2 -1  2.5 0.5\" interpolation=\"smooth\"/>\n"
           "  <LoadCurve name=\"ramp\" points=\"0 0  2 1\" after=\"extend\"/>\n"
           "  <GridMesh name=\"grid\" min=\"0 0 0\" max=\"0.2 0.1 0.3\" resolution=\"2 1 2\" element=\"hexahedra\"/>\n"
           "  <MechanicalObject name=\"state\"/>\n"
           "  <LumpedMass density=\"1000\"/>\n"
           "  <SemiImplicitEuler/>\n" +
           body + "</Node>\n";
}

std::string errorOf(const std::string& xml) {
    try {
        Simulation::fromString(xml, "scene.xml");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

Positions forcesOf(Simulation& sim, const std::string& name, double t) {
    auto* ff = dynamic_cast<fascia::core::BaseForceField*>(sim.find(name));
    REQUIRE(ff);
    auto& st = sim.state("state");
    Positions f(st.size(), Vec3::Zero());
    ff->addForce(st, f, t);
    return f;
}

/// The curves the loads are given in the scenes below, and their values by the formulas.
struct CurveCase {
    std::string attribute;                       ///< the load's curve="..."
    double (*expected)(double);
};
const CurveCase kCases[] = {
    {"@table", [](double t) { return table(t, false); }},
    {"@smoothTable", [](double t) { return table(t, true); }},
    {"@ramp", [](double t) { return std::max(0.0, t / 2); }},
    {"smoothStep 1.3", [](double t) { return smooth(std::clamp(t / 1.3, 0.0, 1.0)); }},
    {"step 0.5", [](double t) { return t > 0.5 ? 1.0 : 0.0; }},
};

} // namespace

TEST_CASE("each load curve shape follows its formula at every time", "[LoadCurve]") {
    for (double t : sampleTimes()) {
        CAPTURE(t);
        // a ramp is t/T clamped to [0, 1], exactly (one division and one multiplication by 1)
        CHECK(inlineCurve("ramp 0.5").value(t) == std::clamp(t / 0.5, 0.0, 1.0));
        CHECK(inlineCurve("ramp 0.5 extend").value(t) == std::max(0.0, t / 0.5));
        CHECK(inlineCurve("smoothStep 0.5").value(t) == Approx(smooth(std::clamp(t / 0.5, 0.0, 1.0))).margin(1e-15));
        CHECK(inlineCurve("step 1.3").value(t) == (t > 1.3 ? 1.0 : 0.0));
        CHECK(inlineCurve("linear 0 0 0.5 2 1.3 2 2 -1 2.5 0.5").value(t) == Approx(table(t, false)).margin(1e-15));
        CHECK(inlineCurve("smooth 0 0 0.5 2 1.3 2 2 -1 2.5 0.5").value(t) == Approx(table(t, true)).margin(1e-15));
        // hold and extend after the last point, the first value before the first
        CHECK(inlineCurve("linear 0.5 3 1 4").value(t) == Approx(t <= 0.5 ? 3 : t >= 1 ? 4 : 3 + 2 * (t - 0.5)).margin(1e-15));
        CHECK(inlineCurve("linear 0.5 3 1 4 extend").value(t) == Approx(t <= 0.5 ? 3 : 3 + 2 * (t - 0.5)).margin(1e-14));
        // one point: a constant
        CHECK(inlineCurve("linear 1 0.25").value(t) == 0.25);
        // a jump: two points at one time, the first value up to it, the second after it
        CHECK(inlineCurve("linear 0 1 1 1 1 3 2 3").value(t) == (t > 1 ? 3.0 : 1.0));
    }
    // the points themselves, exactly
    const Curve c = inlineCurve("smooth 0 0 0.5 2 1.3 2 2 -1 2.5 0.5");
    for (size_t k = 0; k < c.times().size(); ++k) CHECK(c.value(c.times()[k]) == c.values()[k]);
    // no curve: 1 at every time
    CHECK(Curve().value(-1) == 1.0);
    CHECK(Curve().value(1e9) == 1.0);
}

TEST_CASE("a load curve's rate is the derivative of its value from the right", "[LoadCurve]") {
    const char* forms[] = {"ramp 0.5", "ramp 0.5 extend", "smoothStep 0.5", "linear 0 0 0.5 2 1.3 2 2 -1 2.5 0.5",
                           "smooth 0 0 0.5 2 1.3 2 2 -1 2.5 0.5", "linear 0.5 3 1 4 extend"};
    const double h = 1e-7;
    for (const char* form : forms) {
        const Curve c = inlineCurve(form);
        for (int k = -8; k <= 56; ++k) {
            const double t = k / 16.0 + 0.01;  // off the points, where the curve is smooth
            INFO(form << " at t = " << t);
            CHECK(c.rate(t) == Approx((c.value(t + h) - c.value(t - h)) / (2 * h)).margin(1e-6));
        }
        // a load starts at rest: no rate at or before the first point
        CHECK(c.rate(c.times()[0]) == 0.0);
        CHECK(c.rate(c.times()[0] - 1) == 0.0);
    }
    CHECK(inlineCurve("ramp 0.5").rate(0.5) == 0.0);        // held from the last point on
    CHECK(inlineCurve("ramp 0.5 extend").rate(7) == 2.0);  // the last segment continued
}

TEST_CASE("a load curve that cannot be is refused with what is wrong", "[LoadCurve]") {
    CHECK_THAT(parseProblem("linear 0 0 1"), Contains("has 3 numbers, an odd count"));
    CHECK_THAT(parseProblem("linear"), Contains("has no points"));
    CHECK_THAT(parseProblem("linear 0 0 1 1 0.5 2"), Contains("times must not decrease: point 3 is at t = 0.5 s, after t = 1 s"));
    CHECK_THAT(parseProblem("smooth 0 0 1 1 extend"), Contains("extend continues a linear segment"));
    CHECK_THAT(parseProblem("linear 0 0 1 1 1 2 extend"), Contains("extend continues the last segment, which is a jump"));
    CHECK_THAT(parseProblem("ramp"), Contains("\"ramp\" takes one number, the duration T"));
    CHECK_THAT(parseProblem("ramp 0"), Contains("\"ramp\" needs a duration T > 0"));
    CHECK_THAT(parseProblem("smoothStep 1 2"), Contains("\"smoothStep\" takes one number"));
    CHECK_THAT(parseProblem("step"), Contains("\"step\" takes one number, the time t0"));
    CHECK_THAT(parseProblem("sine 1"), Contains("'sine' is no curve form"));
    CHECK_THAT(parseProblem("linear 0 x"), Contains("'x' is not a number"));
    CHECK_THAT(parseProblem(""), Contains("is empty"));
}

TEST_CASE("load curve input errors are located at the element or the attribute", "[LoadCurve]") {
    const std::string force = "  <ConstantForce name=\"f\" indices=\"0\" force=\"1 0 0\" curve=\"";
    SECTION("a link to a missing curve") {
        CHECK_THAT(errorOf(scene(force + "@nothere\"/>\n")),
                   Contains("scene.xml:9: error: ConstantForce 'f': curve = \"@nothere\" links to nothing: no component 'nothere'"));
    }
    SECTION("a link to a component that is no curve") {
        CHECK_THAT(errorOf(scene(force + "@state\"/>\n")),
                   Contains("scene.xml:9: error: ConstantForce 'f': curve = \"@state\" links to MechanicalObject 'state', which is not a LoadCurve"));
    }
    SECTION("an inline curve that does not parse") {
        CHECK_THAT(errorOf(scene(force + "linear 0 0 1\"/>\n")),
                   Contains("scene.xml:9: error: ConstantForce 'f': curve = \"linear 0 0 1\" has 3 numbers, an odd count"));
    }
    SECTION("a LoadCurve with times that decrease") {
        CHECK_THAT(errorOf(scene("  <LoadCurve name=\"bad\" points=\"0 0  2 1  1 0\"/>\n")),
                   Contains("scene.xml:9: error: LoadCurve 'bad': points: times must not decrease: point 3 is at t = 1 s, after t = 2 s"));
    }
    SECTION("a LoadCurve with an odd count of numbers") {
        CHECK_THAT(errorOf(scene("  <LoadCurve name=\"bad\" points=\"0 0  2\"/>\n")),
                   Contains("scene.xml:9: error: LoadCurve 'bad': points: has 3 numbers, an odd count"));
    }
    SECTION("a LoadCurve with no points") {
        CHECK_THAT(errorOf(scene("  <LoadCurve name=\"bad\" points=\"\"/>\n")),
                   Contains("scene.xml:9: error: LoadCurve 'bad': points: has no points"));
    }
    SECTION("a LoadCurve that extends a smooth segment") {
        CHECK_THAT(errorOf(scene("  <LoadCurve name=\"bad\" points=\"0 0 1 1\" interpolation=\"smooth\" after=\"extend\"/>\n")),
                   Contains("scene.xml:9: error: LoadCurve 'bad': points: extend continues a linear segment"));
    }
    SECTION("a gravity curve that links to nothing") {
        CHECK_THAT(errorOf(scene("", " gravity=\"0 0 -9.81\" gravityCurve=\"@nothere\"")),
                   Contains("scene.xml:1: error: Node 'root': gravityCurve = \"@nothere\" links to nothing"));
    }
    SECTION("a prescribed displacement with a curve and a shape") {
        CHECK_THAT(errorOf(scene("  <PrescribedDisplacement indices=\"0\" displacement=\"0 0 1\" curve=\"@ramp\" rampTime=\"2\"/>\n")),
                   Contains("scene.xml:9: error: PrescribedDisplacement 'PrescribedDisplacement': give curve or shape, rampTime and startTime, not both"));
    }
}

TEST_CASE("a constant force scaled by a curve is the curve times the full force at every time", "[ConstantForce][LoadCurve]") {
    for (const auto& cc : kCases) {
        CAPTURE(cc.attribute);
        auto sim = Simulation::fromString(scene("  <ConstantForce name=\"full\" indices=\"0 4\" force=\"1 -2 3\"/>\n"
                                                "  <ConstantForce name=\"scaled\" indices=\"0 4\" force=\"1 -2 3\" curve=\"" +
                                                cc.attribute + "\"/>\n"));
        for (double t : sampleTimes()) {
            const Positions full = forcesOf(*sim, "full", t), scaled = forcesOf(*sim, "scaled", t);
            INFO("t = " << t);
            for (size_t i = 0; i < full.size(); ++i) REQUIRE((scaled[i] - cc.expected(t) * full[i]).norm() <= 1e-13);
        }
        CHECK(forcesOf(*sim, "full", 0)[4] == Vec3(1, -2, 3));
    }
}

TEST_CASE("gravity scaled by the root node's curve is the curve times m g at every time", "[LoadCurve][LumpedMass]") {
    for (const auto& cc : kCases) {
        CAPTURE(cc.attribute);
        auto sim = Simulation::fromString(scene("", " gravity=\"0 -3 -9.81\" gravityCurve=\"" + cc.attribute + "\""));
        auto& group = const_cast<fascia::core::MechanicalGroup&>(sim->groups().at(0));
        auto& st = sim->state("state");
        for (double t : sampleTimes()) {
            group.computeForces(t);
            INFO("t = " << t);
            for (size_t i = 0; i < st.size(); ++i)
                REQUIRE((st.f()[i] - cc.expected(t) * group.mass[i] * Vec3(0, -3, -9.81)).norm() <= 1e-13);
        }
        CHECK(group.mass[0] > 0);
    }
    // a child node's own gravity takes its own curve (or none)
    auto sim = Simulation::fromString(
        "<Node name=\"root\" dt=\"0.01\" gravity=\"0 0 -10\" gravityCurve=\"ramp 2\">\n"
        "  <Node name=\"a\"><MechanicalObject name=\"ma\" position=\"0 0 0\"/><LumpedMass totalMass=\"1\"/><SemiImplicitEuler/></Node>\n"
        "  <Node name=\"b\" gravity=\"0 0 -1\"><MechanicalObject name=\"mb\" position=\"0 0 0\"/><LumpedMass totalMass=\"1\"/><SemiImplicitEuler/></Node>\n"
        "</Node>\n");
    for (auto& g : sim->groups()) {
        auto& group = const_cast<fascia::core::MechanicalGroup&>(g);
        group.computeForces(0.5);
        CHECK(group.state->f()[0][2] == (group.state->name() == "ma" ? -10 * 0.25 : -1.0));
    }
}

TEST_CASE("a surface pressure scaled by a curve is the curve times the full pressure at every time", "[SurfacePressure][LoadCurve]") {
    for (const auto& cc : kCases) {
        CAPTURE(cc.attribute);
        auto sim = Simulation::fromString(scene("  <SurfacePressure name=\"full\" pressure=\"100\"/>\n"
                                                "  <SurfacePressure name=\"scaled\" pressure=\"100\" curve=\"" + cc.attribute + "\"/>\n"));
        for (double t : sampleTimes()) {
            const Positions full = forcesOf(*sim, "full", t), scaled = forcesOf(*sim, "scaled", t);
            INFO("t = " << t);
            for (size_t i = 0; i < full.size(); ++i) REQUIRE((scaled[i] - cc.expected(t) * full[i]).norm() <= 1e-13);
        }
    }
    // rampTime is the ramp curve underneath
    auto sim = Simulation::fromString(scene("  <SurfacePressure name=\"old\" pressure=\"100\" rampTime=\"1.3\"/>\n"
                                            "  <SurfacePressure name=\"new\" pressure=\"100\" curve=\"ramp 1.3\"/>\n"));
    for (double t : sampleTimes()) {
        const Positions a = forcesOf(*sim, "old", t), b = forcesOf(*sim, "new", t);
        for (size_t i = 0; i < a.size(); ++i) REQUIRE(a[i] == b[i]);
    }
}

TEST_CASE("a prescribed displacement with a curve moves its nodes by the curve times the displacement", "[PrescribedDisplacement][LoadCurve]") {
    for (const auto& cc : kCases) {
        CAPTURE(cc.attribute);
        auto sim = Simulation::fromString(scene("  <PrescribedDisplacement name=\"pd\" indices=\"0 3\" displacement=\"0.01 0 -0.02\" curve=\"" +
                                                cc.attribute + "\"/>\n"));
        auto* pd = dynamic_cast<fascia::mechanics::PrescribedDisplacement*>(sim->find("pd"));
        REQUIRE(pd);
        auto& st = sim->state("state");
        const Curve& c = pd->m_curve.get();
        for (double t : sampleTimes()) {
            INFO("t = " << t);
            REQUIRE(pd->shape(t) == Approx(cc.expected(t)).margin(1e-15));
            REQUIRE(pd->shapeRate(t) == c.rate(t));
            pd->projectPositions(st, t);
            pd->projectVelocities(st, t);
            REQUIRE((st.x()[3] - st.x0()[3] - cc.expected(t) * Vec3(0.01, 0, -0.02)).norm() <= 1e-15);
            REQUIRE((st.v()[3] - c.rate(t) * Vec3(0.01, 0, -0.02)).norm() <= 1e-15);
        }
    }
}
