// TLED and HEML are two discretisations of the same tetrahedral P1 finite-element energy: for the
// same law, mesh and positions their nodal forces must agree to round-off (docs/design.md, principle 3).
#include "TLEDTestSupport.h"

#include "fascia/heml/HEMLForceField.h"
#include "fascia/materials/RelaxationSplit.h"

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

TEST_CASE("TLEDForceField and HEMLForceField relax the same stress: their viscous forces agree along a changing large deformation",
          "[TLEDForceField][HEMLForceField][ViscoelasticProny]") {
    // TLED relaxes the second Piola-Kirchhoff stress S of the relaxed part (TLED eq. (24), (30)); HEML
    // the same S written as six link coefficients (HEMLKernel.h, relax): one model, so along any
    // deformation history, at large strain and with two terms, the forces agree to round-off. A held
    // deformation would not tell them apart (both relax to alpha_inf times the same force); a path
    // that changes does, as the history is carried from one deformation to the next.
    for (const std::string& type : allMaterialTypes())
        for (const std::string apply : {"isochoric", "volumetric", "both"}) {
            Positions p = gridPoints(3, 3, 3, 0.02);
            const Tetrahedra t = gridTets(3, 3, 3);
            Bench b(p);
            const materials::BaseMaterial& m = b.material(type, defaultParams(type));
            const bool iso = apply != "volumetric", vol = apply != "isochoric";
            if (!materials::relaxationRestError(materials::relaxationSplit(m, 0.4), iso, vol, type).empty()) continue;
            CAPTURE(type, apply);
            auto& prony = b.prony("0.3 0.25", "0.02 0.1", apply);
            const double dt = 0.005;
            prony.setTimeStep(dt);
            b.forceField(t, {}).init();
            b.ff->dtChanged(dt);
            auto& heml = b.root.add<fascia::heml::HEMLForceField>("heml");
            heml.setClassName("HEMLForceField");
            heml.m_tetrahedra.set(t);
            heml.init();
            std::mt19937 rng(5);
            std::uniform_real_distribution<double> u(-1, 1);
            std::vector<Vec3> noise(p.size());
            for (auto& v : noise) v = Vec3(u(rng), u(rng), u(rng));
            double worst = 0, scale = 0;
            for (int n = 1; n <= 12; ++n) {
                // a stretch with shear and a volume change that grows for 6 steps, then turns back
                const double s = n <= 6 ? n / 6.0 : (12 - n) / 6.0 + 0.3;
                Mat3 A;
                A << 1 + 0.4 * s, 0.2 * s, -0.1 * s, 0.05 * s, 1 - 0.15 * s, 0.15 * s, -0.1 * s, 0.1 * s, 1 + 0.2 * s;
                for (size_t i = 0; i < p.size(); ++i) b.state->x()[i] = A * p[i] + 0.002 * s * noise[i];
                const double time = n * dt;
                const Positions fT = b.forces(time);
                Positions fH(b.state->size(), Vec3::Zero());
                heml.addForce(*b.state, fH, time);
                const NodalDifference d = nodalDifference(fT, fH);
                worst = std::max(worst, d.diff / d.scale);
                scale = std::max(scale, d.scale);
            }
            CAPTURE(worst);
            CHECK(scale > 0);
            CHECK(worst < 1e-10);
        }
}
