// TLEDForceField in a whole scene (XML, mesh source, mass, integrator, constraints): the TLED paper's
// section 6.2 compression-relaxation of a 0.1 m cube with the transversely isotropic viscoelastic
// liver model, laterally free (rollers), against the homogeneous quasi-static reference.
#include "fascia/base/Error.h"
#include "fascia/sim/Simulation.h"

#include <catch2/catch.hpp>

#include <cmath>

namespace core = fascia::core;

namespace {

const char* kScene = R"(<Node name="root" dt="auto" dtSafety="0.5">
  <Node name="cube">
    <GridMesh name="grid" min="0 0 0" max="0.1 0.1 0.1" resolution="3 3 3" element="hexahedra"/>
    <MechanicalObject name="state"/>
    <LumpedMass density="1000"/>
    <TransverselyIsotropic name="liver" mu="6567" kappa="326210" eta="13134" direction="0 0 1"/>
    <ViscoelasticProny name="visco" alpha="0.5" tau="0.58" apply="isochoric"/>
    <TLEDForceField name="tled" mesh="@grid.mesh" hourglassStiffness="0.075"/>
    <CentralDifference damping="40"/>
    <FixedConstraint name="bottom" group="zmin" directions="0 0 1"/>
    <PrescribedDisplacement name="top" group="zmax" displacement="0 0 -0.03" shape="rampHold" rampTime="0.5" directions="0 0 1"/>
  </Node>
</Node>)";

double reactionZ(core::Simulation& sim, const std::string& constraint) {
    auto* c = dynamic_cast<core::BaseConstraint*>(sim.find(constraint));
    REQUIRE(c);
    const auto& r = sim.state("state").reaction();
    double fz = 0;
    for (int i : c->constrainedNodes()) fz += r[static_cast<size_t>(i)].z();
    return fz;
}

} // namespace

TEST_CASE("TLEDForceField relaxes a compressed cube like the homogeneous reference (TLED section 6.2)",
          "[TLEDForceField][scene]") {
    auto sim = core::Simulation::fromString(kScene, "relaxation.xml");
    auto* ff = dynamic_cast<core::BaseForceField*>(sim->find("tled"));
    REQUIRE(ff);
    CHECK(ff->elementCount() == 27);
    REQUIRE(ff->hexahedra());
    CHECK(ff->hexahedra()->size() == 27);
    // dt = 0.5 * L / c, L = V / A_max = 0.1/3 m, c = sqrt((kappa + 4/3 mu + eta) / rho)
    const double c = std::sqrt((326210 + 4.0 / 3.0 * 6567 + 13134) / 1000.0);
    CHECK(sim->dt() == Approx(0.5 * (0.1 / 3) / c).epsilon(1e-9));

    // reference (shared/reference/relaxation.txt, case TI-V-z): reaction on the loaded face
    // Fz = P_zz * A0 at t = 1 s and 5 s (exact hereditary integral, quasi-static)
    const double Fz1 = -86.252190, Fz5 = -67.309324;
    const long n1 = std::lround(1.0 / sim->dt()), n5 = std::lround(5.0 / sim->dt());
    sim->run(n1);
    const double r1 = reactionZ(*sim, "top");
    sim->run(n5 - n1);
    const double r5 = reactionZ(*sim, "top");
    CAPTURE(sim->time(), r1, r5);
    // the rollers carry the same force the other way
    CHECK(reactionZ(*sim, "bottom") == Approx(-r5).epsilon(1e-3));
    CHECK(r1 == Approx(Fz1).epsilon(2e-3));  // dynamics (inertia, damping) and time sampling
    CHECK(r5 == Approx(Fz5).epsilon(2e-4));
    // the cube stays homogeneous: every element has the same J (the reference's 0.99516 at 5 s)
    std::vector<core::CellField> cells;
    ff->cellData(sim->state("state"), cells);
    const core::CellField* J = nullptr;
    for (auto& f : cells)
        if (f.name == "J") J = &f;
    REQUIRE(J);
    for (double v : J->values) CHECK(v == Approx(0.99516225).epsilon(1e-6));
}

TEST_CASE("TLEDForceField scene errors are located at the element's line", "[TLEDForceField][scene]") {
    const char* bad = R"(<Node name="root" dt="0.001">
  <GridMesh name="grid" resolution="1 1 1"/>
  <MechanicalObject name="state"/>
  <LumpedMass density="1000"/>
  <TLEDForceField name="tled" fibreArray="fibres"/>
  <CentralDifference/>
</Node>)";
    try {
        core::Simulation::fromString(bad, "bad.xml");
        FAIL("no error");
    } catch (const core::Error& e) {
        const std::string msg = e.what();
        CAPTURE(msg);
        CHECK(msg.find("bad.xml:5: error: TLEDForceField 'tled':") != std::string::npos);
    }
}
