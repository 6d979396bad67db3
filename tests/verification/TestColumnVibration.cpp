// Free vibration of a confined column (fixed base, free top, lateral displacements fixed):
// a 1-D P-wave problem with the closed-form frequencies f_n = (2n-1) c_d / (4H),
// c_d = sqrt((lambda + 2 mu)/rho). With N equal layers of linear elements and lumped masses the
// spatially discrete problem has the exact frequencies f_n,h = c_d/(pi h) sin((2n-1) pi h/(4H)),
// h = H/N, and central-difference/leapfrog time stepping maps omega -> (2/dt) asin(omega dt/2)
// (the same formulas as the independent table tests/reference/waves_and_time_step.txt, which lists 8.4246 Hz for
// N = 10, E = 3 kPa, nu = 0.45, rho = 1000 kg/m3).
#include "fascia/sim/Simulation.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

using fascia::core::Simulation;

namespace {

const double H = 0.1, rho = 1000, E = 3000, nu = 0.45;
const int N = 10;

double lambda() { return E * nu / ((1 + nu) * (1 - 2 * nu)); }
double mu() { return E / (2 * (1 + nu)); }
double cd() { return std::sqrt((lambda() + 2 * mu()) / rho); }

/// Measured frequency (Hz) of the top node from the mean spacing of its zero crossings.
double measureFrequency(Simulation& sim, int topNode, int steps) {
    auto& st = sim.state("state");
    std::vector<double> crossings;
    double prevU = st.x()[topNode][2] - st.x0()[topNode][2], prevT = sim.time();
    for (int i = 0; i < steps; ++i) {
        sim.step();
        const double u = st.x()[topNode][2] - st.x0()[topNode][2], t = sim.time();
        if ((u < 0) != (prevU < 0)) crossings.push_back(prevT + (t - prevT) * prevU / (prevU - u));
        prevU = u;
        prevT = t;
    }
    REQUIRE(crossings.size() >= 4);
    const double halfPeriod = (crossings.back() - crossings.front()) / double(crossings.size() - 1);
    return 1.0 / (2 * halfPeriod);
}

std::string columnScene(const std::string& element, const std::string& forceField, const std::string& material,
                        const std::string& integrator, double dt) {
    return "<Node name=\"root\" dt=\"" + std::to_string(dt) + "\">\n"
           "  <GridMesh name=\"grid\" min=\"0 0 0\" max=\"0.01 0.01 " + std::to_string(H) + "\" resolution=\"1 1 " +
           std::to_string(N) + "\" element=\"" + element + "\"/>\n"
           "  <MechanicalObject name=\"state\"/>\n"
           "  <LumpedMass density=\"" + std::to_string(rho) + "\"/>\n"
           "  " + material + "\n"
           "  <" + forceField + " name=\"ff\"/>\n"
           "  <" + integrator + "/>\n"
           "  <FixedConstraint name=\"rollers\" group=\"xmin\" directions=\"1 1 0\"/>\n"
           "  <FixedConstraint name=\"rollers2\" group=\"xmax\" directions=\"1 1 0\"/>\n"
           "  <FixedConstraint name=\"base\" group=\"zmin\"/>\n"
           "</Node>\n";
}

/// Displaces every node along z by the first discrete mode shape sin(k theta), theta = pi h/(2H).
void setFirstMode(Simulation& sim, double amplitude) {
    auto& st = sim.state("state");
    const double h = H / N, theta = M_PI * h / (2 * H);
    for (size_t i = 0; i < st.size(); ++i) {
        const double k = st.x0()[i][2] / h;
        st.x()[i][2] = st.x0()[i][2] + amplitude * std::sin(k * theta);
    }
}

} // namespace

TEST_CASE("a confined hexahedral column vibrates at the exact discrete P-wave frequency", "[TLEDForceField][verification]") {
    const std::string integrator = GENERATE(as<std::string>{}, "CentralDifference", "SemiImplicitEuler");
    CAPTURE(integrator);
    const double dt = 2e-4;
    auto sim = Simulation::fromString(columnScene("hexahedra", "TLEDForceField",
                                                  "<NeoHookean youngModulus=\"3000\" poissonRatio=\"0.45\"/>", integrator, dt));
    setFirstMode(*sim, 1e-7);
    const double h = H / N;
    const double fSpace = cd() / (M_PI * h) * std::sin(M_PI * h / (4 * H));
    CHECK(fSpace == Approx(8.4246).epsilon(1e-4));  // the reference table's value
    const double w = 2 * M_PI * fSpace;
    const double fExpected = 2.0 / dt * std::asin(w * dt / 2) / (2 * M_PI);
    const double f = measureFrequency(*sim, int(sim->state("state").size()) - 1, 3000);
    CHECK(f == Approx(fExpected).epsilon(2e-5));
}

TEST_CASE("a confined tetrahedral column vibrates at the continuum P-wave frequency within the mesh error",
          "[HEMLForceField][TLEDForceField][verification]") {
    const std::string ff = GENERATE(as<std::string>{}, "HEMLForceField", "TLEDForceField");
    CAPTURE(ff);
    auto sim = Simulation::fromString(columnScene("tetrahedra6", ff,
                                                  "<CompressibleNeoHookean youngModulus=\"3000\" poissonRatio=\"0.45\"/>",
                                                  "SemiImplicitEuler", 2e-4));
    setFirstMode(*sim, 1e-7);
    const double fExact = cd() / (4 * H);  // 8.4333 Hz in the table
    const double f = measureFrequency(*sim, int(sim->state("state").size()) - 1, 3000);
    // ten layers: the discrete (lumped, linear) value is 0.1 % below the continuum one
    CHECK(f == Approx(fExact).epsilon(3e-3));
}
