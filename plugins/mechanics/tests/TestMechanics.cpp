// Mechanics: free fall, constraints, prescribed motion, damping, parameter checks.
#include "SurfacePressure.h"
#include "fascia/sim/Simulation.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>

using fascia::core::Error;
using fascia::core::Simulation;
using Catch::Matchers::Contains;

namespace {

/// Three free points of 1 kg each (a point cloud: totalMass shared equally).
std::string cloud(const std::string& integrator, const std::string& extra = "", const std::string& gravity = "0 0 -9.81") {
    return "<Node name=\"root\" dt=\"0.01\" gravity=\"" + gravity + "\">\n"
           "  <Node name=\"body\">\n"
           "    <" + integrator + "/>\n"
           "    <MechanicalObject name=\"mo\" position=\"0 0 0  1 0 0  0 1 0\"/>\n"
           "    <LumpedMass totalMass=\"3\"/>\n" +
           extra +
           "  </Node>\n"
           "</Node>\n";
}

std::string errorOf(const std::string& xml) {
    try {
        Simulation::fromString(xml, "scene.xml");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

} // namespace

TEST_CASE("a free body under gravity follows u = g t^2/2 to round-off", "[SemiImplicitEuler][CentralDifference]") {
    const std::string integrator = GENERATE(as<std::string>{}, "SemiImplicitEuler", "CentralDifference");
    CAPTURE(integrator);
    auto sim = Simulation::fromString(cloud(integrator));
    auto& mo = sim->state("mo");
    for (int n = 1; n <= 200; ++n) {
        sim->step();
        const double t = sim->time();
        const double expected = -0.5 * 9.81 * t * t;
        REQUIRE(mo.x()[1][2] == Approx(expected).epsilon(1e-12).margin(1e-14));
        REQUIRE(mo.x()[1][0] == 1.0);
    }
}

TEST_CASE("plain semi-implicit Euler from rest is first order, as HEML eq. (32) says", "[SemiImplicitEuler]") {
    auto sim = Simulation::fromString(cloud("SemiImplicitEuler halfStepStart=\"false\""));
    sim->run(10);
    const double t = sim->time(), dt = 0.01;
    // x_n = g dt^2 n (n+1)/2 = g t (t + dt)/2
    CHECK(sim->state("mo").x()[0][2] == Approx(-0.5 * 9.81 * t * (t + dt)).epsilon(1e-12));
}

TEST_CASE("explicit Euler follows HEML eq. (31)", "[ExplicitEuler]") {
    auto sim = Simulation::fromString(cloud("ExplicitEuler"));
    sim->run(10);
    const double t = sim->time(), dt = 0.01;
    // x_n = g dt^2 n (n-1)/2
    CHECK(sim->state("mo").x()[0][2] == Approx(-0.5 * 9.81 * t * (t - dt)).epsilon(1e-12));
}

TEST_CASE("explicit Euler with damping follows the closed form of its damped steps", "[ExplicitEuler]") {
    // HEML eq. (31) with mass-proportional damping: x(n+1) = x(n) + dt v(n), v(n+1) = r v(n) + dt g with
    // r = 1 - alpha dt. Summed: v(n) = r^n v0 + dt g (1 - r^n)/(1 - r) and
    // x(n) = x0 + dt [v0 (1 - r^n)/(1 - r) + dt g/(1 - r) (n - (1 - r^n)/(1 - r))].
    const double dt = 0.01, alpha = 5, g = -9.81, v0 = 2;
    auto sim = Simulation::fromString("<Node name=\"root\" dt=\"0.01\" gravity=\"0 0 -9.81\">\n"
                                      "  <ExplicitEuler damping=\"5\"/>\n"
                                      "  <MechanicalObject name=\"mo\" position=\"0 0 0\" initialVelocity=\"2 0 2\"/>\n"
                                      "  <LumpedMass totalMass=\"2\"/>\n"
                                      "</Node>\n");
    auto& mo = sim->state("mo");
    sim->step();
    // one step: the position moves with v(0), the velocity feels gravity and the damping -alpha v(0)
    CHECK(mo.x()[0][0] == Approx(dt * v0).epsilon(1e-14));
    CHECK(mo.v()[0][0] == Approx(v0 * (1 - alpha * dt)).epsilon(1e-14));
    CHECK(mo.v()[0][2] == Approx(v0 + dt * (g - alpha * v0)).epsilon(1e-14));
    sim->run(49);
    const double r = 1 - alpha * dt, n = 50, rn = std::pow(r, n), s = (1 - rn) / (1 - r);
    CHECK(mo.v()[0][0] == Approx(rn * v0).epsilon(1e-12));
    CHECK(mo.x()[0][0] == Approx(dt * v0 * s).epsilon(1e-12));
    CHECK(mo.v()[0][2] == Approx(rn * v0 + dt * g * s).epsilon(1e-12));
    CHECK(mo.x()[0][2] == Approx(dt * (v0 * s + dt * g / (1 - r) * (n - s))).epsilon(1e-12));
}

TEST_CASE("the integrators move every node of a large state, on the threads", "[SemiImplicitEuler][ExplicitEuler]") {
    // 3,375 nodes: above kParallelNodes, and not a multiple of the node chunk or of the vector width,
    // so the last chunk ends in the loops' remainders; every node falls freely under gravity
    const std::string integrator = GENERATE(as<std::string>{}, "SemiImplicitEuler", "ExplicitEuler");
    CAPTURE(integrator);
    auto sim = Simulation::fromString("<Node name=\"root\" dt=\"0.01\" gravity=\"0.5 -1 -9.81\">\n"
                                      "  <GridMesh min=\"0 0 0\" max=\"1 1 1\" resolution=\"14 14 14\"/>\n"
                                      "  <MechanicalObject name=\"mo\"/>\n  <LumpedMass density=\"1000\"/>\n"
                                      "  <" + integrator + "/>\n</Node>\n");
    auto& mo = sim->state("mo");
    REQUIRE(mo.size() == 3375);
    sim->run(20);
    const double t = sim->time(), dt = 0.01;
    // semi-implicit Euler with its half-step start: g t^2/2; explicit Euler: g t (t - dt)/2
    const double s = integrator == "SemiImplicitEuler" ? 0.5 * t * t : 0.5 * t * (t - dt);
    const fascia::Vec3 g(0.5, -1, -9.81);
    double worst = 0;
    for (size_t i = 0; i < mo.size(); ++i) worst = std::max(worst, (mo.x()[i] - mo.x0()[i] - s * g).norm());
    CHECK(worst < 1e-12);
}

TEST_CASE("a fixed node stays exactly fixed and reports its reaction", "[FixedConstraint]") {
    auto sim = Simulation::fromString(cloud("SemiImplicitEuler", "    <FixedConstraint indices=\"2\"/>\n"));
    auto& mo = sim->state("mo");
    sim->run(50);
    CHECK(mo.x()[2] == mo.x0()[2]);
    CHECK(mo.v()[2].norm() == 0.0);
    // the support holds the node's weight: reaction = -m g
    CHECK(mo.reaction()[2][2] == Approx(9.81));
    CHECK(mo.x()[0][2] < -0.01);
}

TEST_CASE("a roller moves only along its free axes", "[FixedConstraint]") {
    auto sim = Simulation::fromString(cloud("SemiImplicitEuler",
                                            "    <FixedConstraint indices=\"0 1 2\" directions=\"0 0 1\"/>\n"
                                            "    <ConstantForce indices=\"1\" force=\"2 3 4\"/>\n"));
    auto& mo = sim->state("mo");
    sim->run(20);
    CHECK(mo.x()[1][2] == mo.x0()[1][2]);
    CHECK(mo.x()[1][0] > mo.x0()[1][0]);
    CHECK(mo.x()[1][1] > mo.x0()[1][1]);
    CHECK(mo.reaction()[1][2] == Approx(-4 + 9.81));
}

TEST_CASE("prescribed displacement follows its load shape exactly", "[PrescribedDisplacement]") {
    const std::string shape = GENERATE(as<std::string>{}, "ramp", "rampHold", "smooth", "step");
    CAPTURE(shape);
    auto sim = Simulation::fromString(cloud("SemiImplicitEuler",
                                            "    <PrescribedDisplacement indices=\"1\" displacement=\"0.1 0 -0.2\" shape=\"" +
                                                shape + "\" rampTime=\"0.5\" startTime=\"0.1\"/>\n",
                                            "0 0 0"));
    auto& mo = sim->state("mo");
    for (int n = 1; n <= 100; ++n) {
        sim->step();
        const double t = sim->time();
        const double tau = t - 0.1, r = std::max(0.0, tau / 0.5), q = std::min(r, 1.0);
        double s = 0;
        if (tau > 0) {
            if (shape == "ramp") s = r;
            else if (shape == "rampHold") s = q;
            else if (shape == "smooth") s = 10 * q * q * q - 15 * q * q * q * q + 6 * q * q * q * q * q;
            else s = 1;
        }
        INFO("t = " << t);
        REQUIRE(mo.x()[1][0] == Approx(1.0 + 0.1 * s).epsilon(1e-14));
        REQUIRE(mo.x()[1][2] == Approx(-0.2 * s).margin(1e-15));
    }
}

TEST_CASE("mass-proportional damping decays velocity as (1 - alpha dt)^n", "[SemiImplicitEuler]") {
    auto sim = Simulation::fromString(
        "<Node name=\"root\" dt=\"0.001\">\n"
        "  <SemiImplicitEuler damping=\"5\"/>\n"
        "  <MechanicalObject name=\"mo\" position=\"0 0 0\" initialVelocity=\"1 0 0\"/>\n"
        "  <LumpedMass totalMass=\"2\"/>\n"
        "</Node>\n");
    auto& mo = sim->state("mo");
    sim->run(400);
    // half-step start: first factor (1 - alpha dt/2)
    const double expected = (1 - 5 * 0.0005) * std::pow(1 - 5 * 0.001, 399);
    CHECK(mo.v()[0][0] == Approx(expected).epsilon(1e-12));
    // the continuous decay exp(-alpha t), within the scheme's first-order error alpha^2 dt t/2 = 5e-3
    CHECK(mo.v()[0][0] == Approx(std::exp(-5 * 0.4)).epsilon(5e-3));
}

TEST_CASE("central difference with damping decays like the continuous solution", "[CentralDifference]") {
    auto sim = Simulation::fromString(
        "<Node name=\"root\" dt=\"0.001\">\n"
        "  <CentralDifference damping=\"5\"/>\n"
        "  <MechanicalObject name=\"mo\" position=\"0 0 0\" initialVelocity=\"1 0 0\"/>\n"
        "  <LumpedMass totalMass=\"2\"/>\n"
        "</Node>\n");
    sim->run(400);
    // x(t) = (1 - exp(-alpha t))/alpha for v0 = 1
    CHECK(sim->state("mo").x()[0][0] == Approx((1 - std::exp(-2.0)) / 5).epsilon(1e-4));
    CHECK(sim->state("mo").v()[0][0] == Approx(std::exp(-2.0)).epsilon(1e-3));
}

TEST_CASE("mechanics parameters are checked with located errors", "[MechanicalObject][LumpedMass][FixedConstraint]") {
    using Catch::Matchers::Contains;
    SECTION("negative density") {
        auto e = errorOf(cloud("SemiImplicitEuler").replace(cloud("SemiImplicitEuler").find("totalMass=\"3\""), 13, "density=\"-1\""));
        CHECK_THAT(e, Contains("scene.xml:5: error: LumpedMass") && Contains("density = -1 is outside > 0"));
    }
    SECTION("both density and total mass") {
        auto xml = cloud("SemiImplicitEuler");
        xml.replace(xml.find("totalMass"), 0, "density=\"1000\" ");
        CHECK_THAT(errorOf(xml), Contains("scene.xml:5: error: LumpedMass") && Contains("not both"));
    }
    SECTION("index out of range") {
        CHECK_THAT(errorOf(cloud("SemiImplicitEuler", "    <FixedConstraint indices=\"7\"/>\n")),
                   Contains("scene.xml:6: error: FixedConstraint") && Contains("node index 7 is out of range") &&
                       Contains("3 nodes"));
    }
    SECTION("no nodes given") {
        CHECK_THAT(errorOf(cloud("SemiImplicitEuler", "    <FixedConstraint/>\n")),
                   Contains("scene.xml:6:") && Contains("indices=") && Contains("group="));
    }
    SECTION("a bad axis mask") {
        CHECK_THAT(errorOf(cloud("SemiImplicitEuler", "    <FixedConstraint indices=\"0\" directions=\"1 2 0\"/>\n")),
                   Contains("scene.xml:6:") && Contains("directions"));
        CHECK_THAT(errorOf(cloud("SemiImplicitEuler", "    <FixedConstraint indices=\"0\" directions=\"1 1\"/>\n")),
                   Contains("scene.xml:6:") && Contains("expected 3"));
    }
    SECTION("a bad load shape") {
        CHECK_THAT(errorOf(cloud("SemiImplicitEuler",
                                 "    <PrescribedDisplacement indices=\"0\" displacement=\"0 0 1\" shape=\"sine\"/>\n")),
                   Contains("scene.xml:6:") && Contains("one of ramp|rampHold|smooth|step"));
    }
    SECTION("missing displacement") {
        CHECK_THAT(errorOf(cloud("SemiImplicitEuler", "    <PrescribedDisplacement indices=\"0\"/>\n")),
                   Contains("scene.xml:6:") && Contains("missing required parameter 'displacement'"));
    }
    SECTION("negative damping") {
        CHECK_THAT(errorOf(cloud("SemiImplicitEuler damping=\"-1\"")), Contains("scene.xml:3:") && Contains("damping"));
    }
    SECTION("velocity count mismatch") {
        auto xml = cloud("SemiImplicitEuler");
        xml.replace(xml.find("position="), 0, "velocity=\"0 0 0\" ");
        CHECK_THAT(errorOf(xml), Contains("scene.xml:4:") && Contains("1 entries for 3 nodes"));
    }
    SECTION("constant force given twice") {
        CHECK_THAT(errorOf(cloud("SemiImplicitEuler", "    <ConstantForce indices=\"0\" force=\"1 0 0\" totalForce=\"1 0 0\"/>\n")),
                   Contains("scene.xml:6:") && Contains("not both"));
    }
    SECTION("no state") {
        CHECK_THAT(errorOf("<Node name=\"root\" dt=\"0.1\">\n  <LumpedMass totalMass=\"1\"/>\n</Node>\n"),
                   Contains("scene.xml:2:") && Contains("no MechanicalObject"));
    }
}

TEST_CASE("surface pressure gives -p A n on a face and nothing net on a closed surface", "[SurfacePressure]") {
    auto scene = [](const std::string& pressure) {
        return "<Node name=\"root\" dt=\"0.001\">\n"
               "  <GridMesh name=\"grid\" min=\"0 0 0\" max=\"0.2 0.1 0.3\" resolution=\"3 2 4\"/>\n"
               "  <MechanicalObject name=\"state\"/>\n"
               "  <LumpedMass density=\"1000\"/>\n"
               "  <SemiImplicitEuler/>\n  " + pressure + "\n</Node>\n";
    };
    auto total = [](Simulation& sim, const char* name) {
        auto* ff = dynamic_cast<fascia::core::BaseForceField*>(sim.find(name));
        auto& st = sim.state("state");
        fascia::Positions f(st.size(), fascia::Vec3::Zero());
        ff->addForce(st, f, 0.0);
        fascia::Vec3 sum = fascia::Vec3::Zero();
        for (auto& v : f) sum += v;
        return sum;
    };
    auto top = Simulation::fromString(scene("<SurfacePressure name=\"p\" pressure=\"1000\" nodeGroup=\"zmax\"/>"));
    const fascia::Vec3 ft = total(*top, "p");
    CHECK(ft[2] == Approx(-1000 * 0.2 * 0.1).epsilon(1e-12));
    CHECK(std::abs(ft[0]) + std::abs(ft[1]) < 1e-12);
    auto side = Simulation::fromString(scene("<SurfacePressure name=\"p\" pressure=\"1000\" nodeGroup=\"xmin\"/>"));
    CHECK(total(*side, "p")[0] == Approx(1000 * 0.1 * 0.3).epsilon(1e-12));  // outward normal -x, pushes +x
    auto all = Simulation::fromString(scene("<SurfacePressure name=\"p\" pressure=\"1000\"/>"));
    CHECK(total(*all, "p").norm() < 1e-12);
    CHECK(dynamic_cast<fascia::mechanics::SurfacePressure*>(all->find("p"))->triangleCount() == 2 * 2 * (3 * 2 + 2 * 4 + 3 * 4));
    CHECK_THAT(errorOf(scene("<SurfacePressure pressure=\"1\" nodeGroup=\"top\"/>")),
               Contains("scene.xml:6:") && Contains("no node group 'top'"));
}

TEST_CASE("overlapping constraints report the whole support reaction once", "[FixedConstraint]") {
    // a 1 kg-per-node cloud fixed by two constraints sharing node 0: the reactions sum to the weight
    auto sim = Simulation::fromString(cloud("SemiImplicitEuler", "    <FixedConstraint name=\"a\" indices=\"0 1\"/>\n"
                                                                 "    <FixedConstraint name=\"b\" indices=\"0 2\"/>\n"));
    sim->run(3);
    fascia::Vec3 sum = fascia::Vec3::Zero();
    for (auto& r : sim->state("mo").reaction()) sum += r;
    CHECK(sum[2] == Approx(3 * 9.81));
    CHECK(sim->state("mo").reaction()[0][2] == Approx(9.81));
}

TEST_CASE("an embedding program drives a node with external forces between steps", "[MechanicalObject]") {
    auto sim = Simulation::fromString(cloud("SemiImplicitEuler", "", "0 0 0"));
    auto& mo = sim->state("mo");
    mo.externalForce()[1] = fascia::Vec3(2, 0, 0);  // 2 N on a 1 kg node
    sim->run(100);
    const double t = sim->time();
    CHECK(mo.x()[1][0] == Approx(1 + 0.5 * 2 * t * t).epsilon(1e-12));
    CHECK(mo.x()[0][0] == 0.0);
    mo.externalForce()[1].setZero();
    const double v = mo.v()[1][0];
    sim->run(10);
    CHECK(mo.v()[1][0] == v);  // no force, no acceleration
}

TEST_CASE("central difference's first velocity includes the damping", "[CentralDifference]") {
    auto sim = Simulation::fromString(
        "<Node name=\"root\" dt=\"0.01\">\n"
        "  <CentralDifference damping=\"2\"/>\n"
        "  <MechanicalObject name=\"mo\" position=\"0 0 0\" initialVelocity=\"1 0 0\"/>\n"
        "  <LumpedMass totalMass=\"1\"/>\n"
        "</Node>\n");
    sim->step();
    CHECK(sim->state("mo").v()[0][0] == Approx(std::exp(-2 * 0.01)).epsilon(1e-4));
}

TEST_CASE("gravity without a mass is an error, not a body that silently stays put", "[LumpedMass]") {
    CHECK_THAT(errorOf("<Node name=\"root\" dt=\"0.1\" gravity=\"0 0 -9.81\">\n  <SemiImplicitEuler/>\n"
                       "  <MechanicalObject name=\"mo\" position=\"0 0 0\"/>\n</Node>\n"),
               Contains("scene.xml:3:") && Contains("no mass in its context"));
}

TEST_CASE("changing dt mid-run keeps the clock continuous and the integrator exact under constant acceleration",
          "[Simulation][CentralDifference][SemiImplicitEuler]") {
    // both schemes integrate a constant acceleration exactly (u = g t^2/2, checked above); after a change
    // of dt they must still do so: CentralDifference restarts its history x(n-1) for the new step, the
    // leapfrog's first kick spans (dt_old + dt_new)/2. A history kept from the old step (or a kick of
    // dt_new) leaves an error of order g dt^2, far above the round-off tolerance.
    const std::string integrator = GENERATE(as<std::string>{}, "CentralDifference", "SemiImplicitEuler");
    CAPTURE(integrator);
    auto sim = Simulation::fromString(cloud(integrator));
    auto& mo = sim->state("mo");
    auto check = [&](double dt) {
        const double t = sim->time();
        INFO("t = " << t << ", dt = " << dt);
        CHECK(mo.x()[1][2] == Approx(-0.5 * 9.81 * t * t).epsilon(1e-11));
        CHECK(mo.x()[1][0] == 1.0);
        // the velocity the state holds: v(t) for central difference, the mid-step v(t - dt/2) for leapfrog
        const double tv = integrator == "CentralDifference" ? t : t - 0.5 * dt;
        CHECK(mo.v()[1][2] == Approx(-9.81 * tv).epsilon(1e-11));
    };
    sim->run(10);  // 0.1 s
    check(0.01);
    sim->setDt(0.001);
    sim->run(10);
    CHECK(sim->time() == Approx(0.11).epsilon(1e-12));
    check(0.001);
    sim->setDt(0.004);
    sim->run(5);
    CHECK(sim->time() == Approx(0.13).epsilon(1e-12));
    check(0.004);
}
