// TLED and HEML are two discretisations of the same tetrahedral P1 finite-element energy: for the
// same law, mesh and positions their nodal forces must agree to round-off (docs/design.md, principle 3).
#include "TledTestUtil.h"

#include "fascia/heml/HEMLForceField.h"

#include <catch2/catch.hpp>

#include <random>

using namespace tledtest;

TEST_CASE("TLEDForceField and HEMLForceField give the same nodal forces on the same tetrahedra",
          "[TLEDForceField][HEMLForceField]") {
    const std::string type = GENERATE(as<std::string>{}, "CompressibleNeoHookean", "NeoHookean", "TransverselyIsotropic",
                                      "StVenantKirchhoff", "CompressibleMooneyRivlin");
    CAPTURE(type);
    Positions p = gridPoints(3, 3, 3, 0.02);
    const Tetrahedra t = gridTets(3, 3, 3);
    Bench b(p);
    b.material(type, defaultParams(type));
    b.forceField(t, {}).init();
    auto& heml = b.root.add<fascia::heml::HEMLForceField>("heml");
    heml.setClassName("HEMLForceField");
    heml.m_tetrahedra.set(t);
    heml.init();

    // a large deformation, with some elements compressed below J0 = 0.4 (the HEML section 4.4 branch)
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1, 1);
    Mat3 A;
    A << 1.3, 0.2, -0.1, 0.05, 0.8, 0.15, -0.1, 0.1, 1.1;
    for (size_t i = 0; i < b.state->size(); ++i) b.state->x()[i] = A * p[i] + 0.004 * Vec3(u(rng), u(rng), u(rng));
    const bool crush = GENERATE(false, true);
    if (crush) b.state->x()[gridIndex(1, 1, 1, 3, 3)] = b.state->x()[gridIndex(2, 2, 2, 3, 3)] + Vec3(0.001, 0.0005, 0.0002);
    CAPTURE(crush);

    const Positions fT = b.forces();
    Positions fH(b.state->size(), Vec3::Zero());
    heml.addForce(*b.state, fH, 0);
    const NodalDifference d = nodalDifference(fT, fH);
    CAPTURE(d.scale, d.diff);
    CHECK(d.scale > 0);
    CHECK(d.diff < 1e-10 * d.scale);
    CHECK(b.ff->potentialEnergy(*b.state) == Approx(heml.potentialEnergy(*b.state)).epsilon(1e-10));
}
