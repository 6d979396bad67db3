// Scene-level verification of HEMLForceField (with the mechanics and meshio plugins): laterally free
// uniaxial compression and stretch of a cube against the closed forms of Analytic.h (HEML section
// 5.1), and release of a cube crushed through J = 0 (HEML section 4.4).
#include "Analytic.h"
#include "fascia/heml/HEMLForceField.h"
#include "fascia/sim/Simulation.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <string>

using fascia::Vec3;
using fascia::core::Simulation;
using namespace hemltest::analytic;

namespace {

// A cube of side L on three symmetry planes (rollers on xmin, ymin, zmin): its top face pulled or
// pushed along z (free laterally) gives a homogeneous uniaxial state, exact for linear tetrahedra.
std::string uniaxialScene(const std::string& material, double L, double dz, double rampTime, double damping) {
    return "<Node name=\"root\" dt=\"auto\" dtSafety=\"0.5\">\n"
           "  <Node name=\"cube\">\n"
           "    <GridMesh name=\"grid\" min=\"0 0 0\" max=\"" + std::to_string(L) + " " + std::to_string(L) + " " + std::to_string(L) +
           "\" resolution=\"2 2 2\" element=\"tetrahedra6\"/>\n"
           "    <MechanicalObject name=\"mo\"/>\n"
           "    <LumpedMass density=\"1000\"/>\n"
           "    <SemiImplicitEuler damping=\"" + std::to_string(damping) + "\"/>\n"
           "    " + material + "\n"
           "    <HEMLForceField name=\"ff\"/>\n"
           "    <FixedConstraint group=\"xmin\" directions=\"1 0 0\"/>\n"
           "    <FixedConstraint group=\"ymin\" directions=\"0 1 0\"/>\n"
           "    <FixedConstraint group=\"zmin\" directions=\"0 0 1\"/>\n"
           "    <PrescribedDisplacement name=\"top\" group=\"zmax\" directions=\"0 0 1\" displacement=\"0 0 " + std::to_string(dz) +
           "\" shape=\"smooth\" rampTime=\"" + std::to_string(rampTime) + "\"/>\n"
           "  </Node>\n"
           "</Node>\n";
}

struct Measured {
    double Pzz;  // nominal stress from the top reaction: reaction = P_zz S0 (HEML eq. (33))
    double lt;   // lateral stretch of the far corner
};

Measured runToEquilibrium(Simulation& sim, double L, double endTime) {
    while (sim.time() < endTime) sim.step();
    auto& mo = sim.state("mo");
    double Fz = 0;
    int corner = -1;
    for (size_t i = 0; i < mo.size(); ++i) {
        if (std::abs(mo.x0()[i].z() - L) < 1e-12) Fz += mo.reaction()[i].z();
        if ((mo.x0()[i] - Vec3(L, L, L)).norm() < 1e-12) corner = int(i);
    }
    REQUIRE(corner >= 0);
    return {Fz / (L * L), mo.x()[corner].x() / L};
}

} // namespace

TEST_CASE("uniaxial compression of a Saint Venant-Kirchhoff cube matches HEML section 5.1", "[HEMLForceField]") {
    // E = 3000 Pa, nu = 0.3: lambda = 1730.77, mu = 1153.85; the curve for stretches from 1 down to 0.6
    const double l = GENERATE(0.95, 0.9, 0.8, 0.7, 0.6);
    const double L = 0.1, E = 3000, nu = 0.3;
    const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
    auto sim = Simulation::fromString(
        uniaxialScene("<StVenantKirchhoff youngModulus=\"3000\" poissonRatio=\"0.3\"/>", L, (l - 1) * L, 1.0, 30.0));
    REQUIRE(sim->dt() > 0);
    const Measured m = runToEquilibrium(*sim, L, 3.0);
    const auto ref = svkUniaxial(lambda, mu, l);
    INFO("P_zz " << m.Pzz << " vs " << ref.Pzz << ", lt " << m.lt << " vs " << ref.lt);
    CHECK(m.Pzz == Approx(ref.Pzz).epsilon(0.005));  // the paper's comparison, within 0.5 %
    CHECK(m.Pzz == Approx(ref.Pzz).epsilon(1e-5));   // homogeneous: P1 elements are exact
    CHECK(m.lt == Approx(ref.lt).epsilon(1e-5));
}

TEST_CASE("a homogeneous large stretch of a compressible neo-Hookean cube is exact", "[HEMLForceField]") {
    // HEML eq. (26) with C1 = mu/2, E = 3000 Pa, nu = 0.45: stretched to twice its length, and the
    // compression curve from 1 down to 0.6
    const double L = 0.1, E = 3000, nu = 0.45;
    const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
    const double l = GENERATE(2.0, 1.5, 0.9, 0.8, 0.7, 0.6);
    auto sim = Simulation::fromString(
        uniaxialScene("<CompressibleNeoHookean youngModulus=\"3000\" poissonRatio=\"0.45\"/>", L, (l - 1) * L, 1.0, 30.0));
    const Measured m = runToEquilibrium(*sim, L, 3.0);
    const auto ref = compressibleNeoHookeanUniaxial(mu / 2, mu, lambda, l);
    INFO("l = " << l << ": P_zz " << m.Pzz << " vs " << ref.Pzz << ", lt " << m.lt << " vs " << ref.lt);
    CHECK(m.Pzz == Approx(ref.Pzz).epsilon(1e-5));
    CHECK(m.lt == Approx(ref.lt).epsilon(1e-5));
}

TEST_CASE("a cube crushed flat and inverted springs back to its rest shape", "[HEMLForceField]") {
    const std::string law = GENERATE(as<std::string>{}, "CompressibleNeoHookean", "NeoHookean");
    const double L = 0.1;
    const std::string xml =
        "<Node name=\"root\" dt=\"auto\" dtSafety=\"0.5\">\n"
        "  <Node name=\"cube\">\n"
        "    <GridMesh min=\"0 0 0\" max=\"0.1 0.1 0.1\" resolution=\"2 2 2\"/>\n"
        "    <MechanicalObject name=\"mo\"/>\n"
        "    <LumpedMass density=\"1000\"/>\n"
        "    <SemiImplicitEuler damping=\"30\"/>\n"
        "    <" + law + " youngModulus=\"3000\" poissonRatio=\"0.45\"/>\n"
        "    <HEMLForceField name=\"ff\"/>\n"
        "    <FixedConstraint group=\"zmin\"/>\n"
        "  </Node>\n"
        "</Node>\n";
    auto sim = Simulation::fromString(xml);
    auto& mo = sim->state("mo");
    // crush: every node at 2 % of its height, the middle layer pushed through the bottom (inverted elements)
    for (size_t i = 0; i < mo.size(); ++i) {
        const double z = mo.x0()[i].z();
        mo.x()[i].z() = std::abs(z - 0.05) < 1e-12 ? -0.01 : 0.02 * z;
    }
    std::vector<fascia::core::CellField> cells;
    auto* ff = dynamic_cast<fascia::heml::HEMLForceField*>(sim->find("ff"));
    REQUIRE(ff);
    ff->cellData(mo, cells);
    double minJ = 1;
    for (double J : cells[0].values) minJ = std::min(minJ, J);
    CHECK(minJ < 0);  // some elements start inverted
    while (sim->time() < 3.0) sim->step();  // throws on NaN or blow-up
    double err = 0;
    for (size_t i = 0; i < mo.size(); ++i) err = std::max(err, (mo.x()[i] - mo.x0()[i]).norm());
    CAPTURE(law, err);
    CHECK(err < 1e-3 * L);
    cells.clear();
    ff->cellData(mo, cells);
    for (double J : cells[0].values) CHECK(J == Approx(1.0).margin(1e-3));
}

TEST_CASE("scene errors of HEMLForceField are located at its XML line", "[HEMLForceField]") {
    auto errorOf = [](const std::string& ffLine, const std::string& extra = "") {
        const std::string xml = "<Node name=\"root\" dt=\"0.001\">\n"
                                "  <Node name=\"body\">\n"
                                "    <GridMesh min=\"0 0 0\" max=\"0.1 0.1 0.1\" resolution=\"1 1 1\"/>\n"
                                "    <MechanicalObject name=\"mo\"/>\n"
                                "    <LumpedMass density=\"1000\"/>\n" + extra +
                                "    " + ffLine + "\n"
                                "  </Node>\n"
                                "</Node>\n";
        try {
            Simulation::fromString(xml, "scene.xml");
        } catch (const fascia::core::Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    CHECK_THAT(errorOf("<HEMLForceField name=\"ff\"/>"), Catch::Contains("scene.xml:6: error: HEMLForceField 'ff': no material"));
    CHECK_THAT(errorOf("<HEMLForceField name=\"ff\" J0=\"1.5\"/>", "    <NeoHookean mu=\"1000\" kappa=\"5000\"/>\n"),
               Catch::Contains("scene.xml:7"));
    CHECK_THAT(errorOf("<HEMLForceField name=\"ff\" groupMaterials=\"1 @nothing\"/>", "    <NeoHookean mu=\"1000\" kappa=\"5000\"/>\n"),
               Catch::Contains("no component 'nothing'"));
    CHECK_THAT(errorOf("<HEMLForceField name=\"ff\"/>", "    <NeoHookean mu=\"1000\" kappa=\"5000\" youngModulus=\"3000\"/>\n"),
               Catch::Contains("scene.xml:6: error: NeoHookean"));
}
