// Contact physics on a block: Coulomb friction sticks below its limit and slides above it, a body
// dropped on a sphere gains no energy, and tool and node forces are bitwise the same on 1 and 2
// threads.
#include "ContactTestSupport.h"

#include <omp.h>

#include <algorithm>
#include <cmath>

using namespace contacttest;

namespace {

/// The 0.5 kg block (0.1 x 0.1 x 0.05 m) on a floor with friction 0.5 (static) and 0.4 (kinetic),
/// under a gravity of 1 m/s^2 down and `pull` m/s^2 along x: a block on a plane inclined by
/// atan(pull), dragged by the same force per kilogram at every node (the static limit: pull = 0.5).
std::string dragScene(double pull, const std::string& integrator) {
    return blockScene(integrator, "", "  <PlaneTool name=\"floor\" body=\"@block/state\" staticFriction=\"0.5\" kineticFriction=\"0.4\"/>\n",
                      "dt=\"auto\" gravity=\"" + std::to_string(pull) + " 0 -1\"");
}

/// The x displacements of the bottom nodes (z = 0 at rest), and the mean x velocity of the nodes.
std::vector<double> bottomSlide(Simulation& sim) {
    auto& s = sim.state("state");
    std::vector<double> u;
    for (size_t i = 0; i < s.size(); ++i)
        if (s.x0()[i][2] == 0) u.push_back(s.x()[i][0] - s.x0()[i][0]);
    return u;
}
double meanVelocity(Simulation& sim) {
    auto& s = sim.state("state");
    double v = 0;
    for (const Vec3& vi : s.v()) v += vi[0];
    return v / double(s.size());
}

} // namespace

TEST_CASE("A block pulled below the Coulomb limit sticks to the floor", "[PlaneTool][RigidTool]") {
    // settling under its weight, the base bulges outward and its lightly loaded edge nodes slip a
    // little (partial slip, physical); once settled nothing moves: the base sticks
    auto sim = Simulation::fromString(dragScene(0.8 * 0.5, "<SemiImplicitEuler damping=\"30\"/>"), "scene.xml");
    sim->runUntil(1.0);
    const std::vector<double> settled = bottomSlide(*sim);
    sim->runUntil(3.0);
    const std::vector<double> later = bottomSlide(*sim);
    REQUIRE(settled.size() == 25);
    for (size_t k = 0; k < settled.size(); ++k) CHECK(std::abs(later[k] - settled[k]) < 1e-8);
    CHECK(std::abs(meanVelocity(*sim)) < 1e-8);
    RigidTool& floor = toolOf(*sim, "floor");
    CHECK(floor.force()[0] == Approx(0.8 * 0.5 * 0.5).epsilon(1e-3));  // the friction carries the pull, M g_x
    CHECK(floor.force()[2] == Approx(-0.5).epsilon(1e-3));
}

TEST_CASE("A block pulled above the Coulomb limit slides with the kinetic friction force", "[PlaneTool][RigidTool]") {
    // Rayleigh damping alpha on the sliding mass too: u'' = g_x - mu_k g_z - alpha u', from rest:
    // u'(t) = a0 / alpha (1 - exp(-alpha t)), a0 = g_x - mu_k g_z
    const double pull = 1.5 * 0.5, alpha = 30, a0 = pull - 0.4 * 1.0, T = 1.0;
    auto sim = Simulation::fromString(dragScene(pull, "<SemiImplicitEuler damping=\"30\"/>"), "scene.xml");
    sim->runUntil(T);
    const std::vector<double> u = bottomSlide(*sim);
    for (double uk : u) CHECK(uk > 0.5 * a0 / alpha * T);  // every base node slides
    CHECK(meanVelocity(*sim) == Approx(a0 / alpha * (1 - std::exp(-alpha * T))).epsilon(2e-3));
    RigidTool& floor = toolOf(*sim, "floor");
    CHECK(floor.force()[0] == Approx(0.4 * 0.5).epsilon(1e-3));  // kinetic friction mu_k M g_z
    CHECK(floor.force()[2] == Approx(-0.5).epsilon(1e-3));
}

TEST_CASE("A block dropped on a sphere without damping gains no energy over 10000 steps", "[SphereTool][RigidTool]") {
    // a quarter of a 0.1 x 0.1 x 0.05 m block on symmetry rollers (xmin, ymin), 5 mm above the top of
    // a sphere of radius 0.2 m centred on the symmetry axis: a frictionless block would slide off a
    // whole sphere, the quarter model stays on it
    const std::string integrator = GENERATE(std::string("<SemiImplicitEuler/>"), std::string("<CentralDifference/>"));
    CAPTURE(integrator);
    const double g = 9.81;
    auto sim = Simulation::fromString(
        blockScene(integrator,
                   "    <FixedConstraint name=\"symX\" group=\"xmin\" directions=\"1 0 0\"/>\n"
                   "    <FixedConstraint name=\"symY\" group=\"ymin\" directions=\"0 1 0\"/>\n",
                   "  <SphereTool name=\"ball\" body=\"@block/state\" radius=\"0.2\" position=\"0 0 -0.205\"/>\n",
                   "dt=\"auto\" gravity=\"0 0 -9.81\"", "2 2 2", "HEMLForceField", "tetrahedra6", 0.05, 0.05),
        "scene.xml");
    auto& s = sim->state("state");
    const auto& mass = sim->groups()[0].mass;
    auto* ff = dynamic_cast<fascia::core::BaseForceField*>(sim->find("ff"));
    REQUIRE(ff);
    auto energy = [&] {
        double e = ff->potentialEnergy(s);
        for (size_t i = 0; i < s.size(); ++i) e += mass[i] * (0.5 * s.v()[i].squaredNorm() + g * s.x()[i][2]);
        return e;
    };
    const double e0 = energy(), drop = 0.5 * 9.81 * 0.005;  // mass times the 5 mm fall, per kg
    double most = e0, kinetic = 0;
    for (int k = 0; k < 10000; ++k) {
        sim->step();
        most = std::max(most, energy());
        double ke = 0;
        for (size_t i = 0; i < s.size(); ++i) ke += 0.5 * mass[i] * s.v()[i].squaredNorm();
        kinetic = std::max(kinetic, ke);
    }
    CAPTURE(e0, most, kinetic);
    REQUIRE(kinetic > 0.5 * drop * 0.5);    // it fell onto the sphere
    REQUIRE(toolOf(*sim, "ball").force()[2] < 0);  // and rests on it
    CHECK(most <= e0 + 1e-3 * kinetic);      // never above its initial energy (round-off of the scheme)
}

TEST_CASE("Tool and node contact forces are bitwise the same with 1 and 2 threads", "[SphereTool][CapsuleTool][RigidTool]") {
    // 17 x 17 x 9 nodes: above the framework's parallel threshold, several element blocks
    const std::string ff = GENERATE(std::string("HEMLForceField"), std::string("TLEDForceField"));
    CAPTURE(ff);
    auto run = [&](int threads) {
        omp_set_num_threads(threads);
        auto sim = Simulation::fromString(
            blockScene("<SemiImplicitEuler damping=\"20\"/>", "    <FixedConstraint name=\"base\" group=\"zmin\"/>\n",
                       "  <SphereTool name=\"ball\" body=\"@block/state\" radius=\"0.02\" keyTimes=\"0 0.02\" "
                       "keyPositions=\"0.03 0.05 0.07  0.03 0.05 0.066\" staticFriction=\"0.3\"/>\n"
                       "  <CapsuleTool name=\"probe\" body=\"@block/state\" radius=\"0.005\" length=\"0.05\" axis=\"0.3 0 1\" "
                       "keyTimes=\"0 0.02\" keyPositions=\"0.07 0.05 0.056  0.07 0.05 0.052\"/>\n"
                       "  <PlaneTool name=\"wall\" body=\"@block/state\" normal=\"-1 0 0\" orientation=\"0.995 0 0.0998 0\" "
                       "keyTimes=\"0 0.02\" keyPositions=\"0.1 0.05 0.025  0.098 0.05 0.025\"/>\n",
                       "dt=\"auto\"", "16 16 8", ff),
            "scene.xml");
        sim->run(30);
        struct Out { Vec3 f1, t1, f2, f3, t3; Positions c1, c2, c3, x; size_t n3; };
        RigidTool &ball = toolOf(*sim, "ball"), &probe = toolOf(*sim, "probe"), &wall = toolOf(*sim, "wall");
        return Out{ball.force(), ball.torque(), probe.force(), wall.force(), wall.torque(), ball.contactForces(),
                   probe.contactForces(), wall.contactForces(), sim->state("state").x(), wall.contactCount()};
    };
    const int before = omp_get_max_threads();
    const auto one = run(1), two = run(2);
    omp_set_num_threads(before);
    CHECK(one.f1.norm() > 0);
    CHECK(one.f2.norm() > 0);
    CHECK(one.f1 == two.f1);
    CHECK(one.t1 == two.t1);
    CHECK(one.f2 == two.f2);
    CHECK(one.n3 > 50);  // the tilted wall touches many nodes: their sum's order shows in its last bits
    CHECK(one.f3 == two.f3);
    CHECK(one.t3 == two.t3);
    CHECK(one.c3 == two.c3);
    CHECK(one.c1 == two.c1);
    CHECK(one.c2 == two.c2);
    CHECK(one.x == two.x);
}
