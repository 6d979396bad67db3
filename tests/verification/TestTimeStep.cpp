// dt="auto" and the critical-time-step warning: force fields report a stable step from the element
// size and the dilatational wave speed c_d = sqrt((lambda + 2 mu)/rho).
#include "fascia/sim/Simulation.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <iostream>
#include <sstream>

using fascia::core::Simulation;
using Catch::Matchers::Contains;

namespace {
std::string cube(const std::string& dt, const std::string& ff) {
    return "<Node name=\"root\" dt=\"" + dt + "\" dtSafety=\"0.5\">\n"
           "  <GridMesh min=\"0 0 0\" max=\"0.1 0.1 0.1\" resolution=\"4 4 4\"/>\n"
           "  <MechanicalObject name=\"state\"/>\n  <LumpedMass density=\"1000\"/>\n"
           "  <CompressibleNeoHookean youngModulus=\"3000\" poissonRatio=\"0.45\"/>\n"
           "  <" + ff + " name=\"ff\"/>\n  <SemiImplicitEuler/>\n</Node>\n";
}
struct CaptureCerr {
    std::ostringstream out;
    std::streambuf* old = std::cerr.rdbuf(out.rdbuf());
    ~CaptureCerr() { std::cerr.rdbuf(old); }
};
} // namespace

TEST_CASE("dt=auto is the smallest stable step times the safety factor, and is stable", "[Simulation][verification]") {
    const std::string ff = GENERATE(as<std::string>{}, "HEMLForceField", "TLEDForceField");
    CAPTURE(ff);
    auto sim = Simulation::fromString(cube("auto", ff));
    const double crit = sim->criticalTimeStep();
    CHECK(sim->dt() == Approx(0.5 * crit).epsilon(1e-14));
    // the stable step is of the order of the element size over the wave speed: h = 0.025 m,
    // c_d = 3.373 m/s (tests/reference/waves_and_time_step.txt), shortest altitude of the 6-tet split h/sqrt(3)..h
    const double cd = 3.3733;
    CHECK(crit > 0.2 * 0.025 / cd);
    CHECK(crit < 0.025 / cd);
    sim->run(200);  // explicit and stable: finite
}

TEST_CASE("a dt above the critical step is a warning naming both and the force field", "[Simulation]") {
    CaptureCerr cap;
    auto sim = Simulation::fromString(cube("0.05", "HEMLForceField"), "scene.xml");
    CHECK_THAT(cap.out.str(), Contains("scene.xml:1: warning:") && Contains("dt = 0.05") &&
                                  Contains("above the critical time step") && Contains("HEMLForceField '/root/ff'"));
    CHECK(sim->dt() == 0.05);
}

TEST_CASE("an unstable run fails with a simulation error naming the step", "[Simulation]") {
    CaptureCerr cap;
    auto sim = Simulation::fromString(cube("0.05", "HEMLForceField"), "scene.xml");
    auto& st = sim->state("state");
    for (size_t i = 0; i < st.size(); ++i) st.x()[i] *= 1.01;  // a small stretch to start it moving
    try {
        sim->run(100000);
        FAIL("the run should have blown up");
    } catch (const fascia::core::Error& e) {
        CHECK(e.kind() == fascia::core::ErrorKind::Simulation);
        CHECK_THAT(std::string(e.what()), Contains("step ") && Contains("non-finite"));
    }
}
