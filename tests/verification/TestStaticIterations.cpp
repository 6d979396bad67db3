// Iterations of DynamicRelaxation, with no damping given, against an explicit run (CentralDifference,
// dt="auto") whose damping is swept over a grid, on the static cases of TestStaticSolutions.cpp:
// DynamicRelaxation must come within 1.5 times the best hand-tuned damping and beat a damping ten
// times off the best (either way) by a wide margin. The table is in docs/performance.md ("static
// solver"); `test_verification_static_iterations -s` prints it.
#include "StaticSupport.h"

#include <vector>

using namespace statics;

namespace {

const double kTol = 1e-8;
/// The explicit runs: dt="auto" at the default safety factor.
const char* kExplicitRoot = "dt=\"auto\" dtSafety=\"0.5\"";

/// The stretch to 1.5 (TLED tetrahedra), the Mooney-Rivlin tetrahedron, and the cube under pressure,
/// with `solverXml` as the solver and the loads applied at once.
std::string scene(int which, const std::string& solverXml, const std::string& root) {
    if (which == 0) {
        std::string s = stretchScene("TLEDForceField", "tetrahedra6", 1.5, solverXml, root);
        const std::string ramp = "shape=\"rampHold\" rampTime=\"1\"";
        s.replace(s.find(ramp), ramp.size(), "shape=\"step\"");
        return s;
    }
    const std::string faces[] = {"xmax", "ymax", "zmax"};
    std::string loads;
    for (auto& f : faces)
        loads += "<SurfacePressure name=\"p" + f + "\" nodeGroup=\"" + f + "\" pressure=\"1500\"/>\n";
    const std::string body =
        which == 1 ? R"(<MechanicalObject name="state" position="0 0 0  1 0 0  0 1 0  0 0 1"/>
  <LumpedMass totalMass="4"/>
  <CompressibleMooneyRivlin name="mat" C1="300" C2="150" kappa="4000"/>
  <TLEDForceField name="ff" tetrahedra="0 1 2 3"/>
  <FixedConstraint name="n0" indices="0"/>
  <FixedConstraint name="n1" indices="1" directions="0 1 1"/>
  <FixedConstraint name="n2" indices="2" directions="0 0 1"/>
  <ConstantForce name="load" indices="3" force="60 -40 120"/>)"
                   : R"(<GridMesh name="grid" min="0 0 0" max="1 1 1" resolution="3 3 3" element="tetrahedra6"/>
  <MechanicalObject name="state"/>
  <LumpedMass density="1000"/>
  <NeoHookean name="mat" mu="1000" kappa="5000"/>
  <TLEDForceField name="ff"/>
  <FixedConstraint name="xmin" group="xmin" directions="1 0 0"/>
  <FixedConstraint name="ymin" group="ymin" directions="0 1 0"/>
  <FixedConstraint name="zmin" group="zmin" directions="0 0 1"/>
  )" + loads;
    return "<Node name=\"root\" " + root + ">\n  " + body + "\n  " + solverXml + "\n</Node>";
}

/// Steps of the explicit run with damping alpha after which the residual stays below kTol times the
/// static load norm `load` (the run stops once it has stayed there for as many steps as it took, or
/// at maxSteps; maxSteps + 1 when it never settles or diverges).
long explicitSteps(int which, double alpha, double load, long maxSteps) {
    auto sim = Simulation::fromString(
        scene(which, "<CentralDifference damping=\"" + std::to_string(alpha) + "\"/>", kExplicitRoot));
    const auto& f = sim->state("state").f();
    long lastAbove = 0;
    for (long k = 1; k <= maxSteps; ++k) {
        try {
            sim->step();
        } catch (const fascia::core::Error&) {
            return maxSteps + 1;  // unstable (a damping alpha dt > 2 makes the explicit update diverge)
        }
        double r = 0;
        for (auto& v : f) r += v.squaredNorm();
        if (std::sqrt(r) > kTol * load) lastAbove = k;
        if (k - lastAbove > std::max(300L, lastAbove)) break;
    }
    return lastAbove >= maxSteps ? maxSteps + 1 : lastAbove + 1;
}

} // namespace

TEST_CASE("DynamicRelaxation converges within 1.5 times the best hand-tuned explicit damping",
          "[DynamicRelaxation]") {
    const char* names[] = {"stretch 1.5, TLED tetrahedra", "Mooney-Rivlin tetrahedron, nodal force",
                           "cube under pressure 1500 Pa"};
    const int which = GENERATE(0, 1, 2);
    CAPTURE(names[which]);
    auto dr = Simulation::fromString(scene(which,
                                           "<DynamicRelaxation name=\"dr\" tolerance=\"1e-8\" displacementTolerance=\"1e-8\"/>",
                                           "dt=\"1\""));
    dr->step();
    const auto& rep = solver(*dr).reports().at(0);
    REQUIRE(rep.converged);
    const long nDR = rep.iterations;
    // the damping grid: 0.25 * 2^(j/2) /s, j = 0 .. 22 (0.25 to 512 /s)
    double bestAlpha = 0;
    long best = -1;
    for (int j = 0; j <= 22; ++j) {
        const double alpha = 0.25 * std::pow(2.0, 0.5 * j);
        const long n = explicitSteps(which, alpha, rep.load, best > 0 ? 3 * best : 40 * nDR);
        if (best < 0 || n < best) best = n, bestAlpha = alpha;
    }
    REQUIRE(bestAlpha > 0.25);  // the best damping lies inside the grid
    REQUIRE(bestAlpha < 512);
    const long above = explicitSteps(which, 10 * bestAlpha, rep.load, 200 * nDR);
    const long below = explicitSteps(which, 0.1 * bestAlpha, rep.load, 200 * nDR);
    UNSCOPED_INFO("| " << names[which] << " | " << nDR << " | " << best << " (damping " << bestAlpha << " /s) | "
                       << above << " | " << below << " |");
    CHECK(double(nDR) <= 1.5 * double(best));
    CHECK(double(nDR) <= 0.25 * double(above));
    CHECK(double(nDR) <= 0.25 * double(below));
}
