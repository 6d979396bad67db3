// The closed forms of Analytic.h against independent reference values, and the materials plugin's
// laws against the closed forms (homogeneous states: uniaxial free, confined through J0).
#include "Analytic.h"
#include "fascia/materials/CompressibleNeoHookean.h"
#include "fascia/materials/Conformance.h"
#include "fascia/materials/StVenantKirchhoff.h"

#include <catch2/catch.hpp>

using namespace hemltest::analytic;
using namespace fascia;
namespace conf = fascia::materials::conformance;

namespace {
// nominal stress P = F S of a material at F, from its invariant derivatives (Material.h)
Mat3 nominalStress(const materials::BaseMaterial& m, const Mat3& F, double J0 = 0.4) {
    const Mat3 C = F.transpose() * F;
    const auto in = conf::invariantsOf(F);
    const auto r = conf::evaluateOne(m, in, J0);
    const Mat3 S = 2 * (r.dI1 * Mat3::Identity() + r.dI2 * (in.I1 * Mat3::Identity() - C)) +
                   in.J * (r.dJiso + r.dJvol) * C.inverse();
    return F * S;
}
} // namespace

TEST_CASE("Saint Venant-Kirchhoff uniaxial closed form matches the reference table", "[Analytic]") {
    // rows copied from the independent reference table tests/reference/uniaxial.txt, section (a1): l, lt, P_zz / Y (mu = 1)
    struct Row { double lambda, l, lt, PzzOverY; };
    const Row rows[] = {
        {1.5, 1.5, 0.79056942, 0.93750000},   {1.5, 0.8, 1.05261579, -0.14400000},
        {1.5, 0.4, 1.11892806, -0.16800000},  {49.0, 0.7, 1.11798927, -0.17850000},
        {49.0, 0.2, 1.21260051, -0.09600000},
    };
    for (const Row& r : rows) {
        const double mu = 1.0, Y = mu * (3 * r.lambda + 2 * mu) / (r.lambda + mu);
        const auto a = svkUniaxial(r.lambda, mu, r.l);
        CAPTURE(r.lambda, r.l);
        CHECK(a.lt == Approx(r.lt).epsilon(1e-8));
        CHECK(a.Pzz / Y == Approx(r.PzzOverY).epsilon(1e-8));
    }
    // absolute example of the same table (TLED constants): l = 0.8 -> lt 1.08462000, P_zz -2818.033862 Pa
    const auto t = svkUniaxial(321832.0, 6567.0, 0.8);
    CHECK(t.lt == Approx(1.08462000).epsilon(1e-8));
    CHECK(t.Pzz == Approx(-2818.033862).epsilon(1e-9));
}

TEST_CASE("compressible neo-Hookean uniaxial closed form matches the reference table", "[Analytic]") {
    // rows copied from the independent reference table tests/reference/uniaxial.txt, section (a2), C1 = mu/2, mu = 1: l, lt, J, P_zz / mu
    struct Row { double lambda, l, lt, J, Pzz; };
    const Row rows[] = {
        {1.5, 1.5, 0.8801745918, 1.16206097, 0.9835284586},
        {1.5, 0.7, 1.1079347328, 0.85926356, -1.0535991032},
        {1.5, 0.2, 1.4895450899, 0.44374891, -10.8937228747},
        {9.0, 0.3, 1.6569963989, 0.82369112, -8.8521235531},
        {49.0, 0.5, 1.4004112186, 0.98057579, -3.4223031625},
    };
    for (const Row& r : rows) {
        const auto a = compressibleNeoHookeanUniaxial(0.5, 1.0, r.lambda, r.l);
        CAPTURE(r.lambda, r.l, a.iterations);
        CHECK(a.lt == Approx(r.lt).epsilon(1e-9));
        CHECK(a.J == Approx(r.J).epsilon(1e-7));
        CHECK(a.Pzz == Approx(r.Pzz).epsilon(1e-9));
        CHECK(a.iterations < 20);
    }
    // absolute example (TLED constants as compressible NH): l = 0.9 -> lt 1.0529247290, P_zz -2179.153039 Pa
    const auto t = compressibleNeoHookeanUniaxial(6567.0 / 2, 6567.0, 321832.0, 0.9);
    CHECK(t.lt == Approx(1.0529247290).epsilon(1e-9));
    CHECK(t.Pzz == Approx(-2179.153039).epsilon(1e-9));
}

TEST_CASE("compressible neo-Hookean confined compression through J0 matches the reference table", "[Analytic]") {
    // rows copied from the independent reference table tests/reference/uniaxial.txt, section (a3), J0 = 0.4, mu = 1: l = J, P_zz / mu, P_xx / mu
    struct Row { double lambda, l, Pzz, Pxx; };
    const Row rows[] = {
        {1.5, 0.6, -2.3437307261, -0.7662384356},   {1.5, 0.2, -10.5791353668, -1.1558270734},
        {1.5, 0.0, -15.6221804891, 1.0000000000},   {1.5, -0.2, -20.6652256113, 5.0930451223},
        {49.0, 0.05, -322.2855274773, -15.1167763739},
    };
    for (const Row& r : rows) {
        const auto a = compressibleNeoHookeanConfined(0.5, 1.0, r.lambda, r.l, 0.4);
        CAPTURE(r.lambda, r.l);
        CHECK(a.Pzz == Approx(r.Pzz).epsilon(1e-9));
        CHECK(a.Pxx == Approx(r.Pxx).epsilon(1e-9));
    }
}

TEST_CASE("the materials plugin reproduces the closed forms", "[Analytic]") {
    const double mu = 1000, lambda = 9000;
    SECTION("Saint Venant-Kirchhoff: laterally free, P_zz of HEML section 5.1") {
        materials::StVenantKirchhoff m;
        m.m_mu.set(mu);
        m.m_lambda.set(lambda);
        m.init();
        for (double l : {1.3, 0.9, 0.6, 0.3}) {
            const auto a = svkUniaxial(lambda, mu, l);
            const Mat3 P = nominalStress(m, Vec3(a.lt, a.lt, l).asDiagonal());
            CAPTURE(l);
            CHECK(std::abs(P(0, 0)) < 1e-9 * mu);
            CHECK(P(2, 2) == Approx(a.Pzz).epsilon(1e-11));
        }
    }
    SECTION("compressible neo-Hookean: laterally free and confined through J0 and inversion") {
        materials::CompressibleNeoHookean m;
        m.m_mu.set(mu);
        m.m_lambda.set(lambda);
        m.init();
        for (double l : {1.4, 0.8, 0.4, 0.2}) {
            const auto a = compressibleNeoHookeanUniaxial(mu / 2, mu, lambda, l);
            const Mat3 P = nominalStress(m, Vec3(a.lt, a.lt, l).asDiagonal());
            CAPTURE(l);
            CHECK(std::abs(P(0, 0)) < 1e-9 * mu);
            CHECK(P(2, 2) == Approx(a.Pzz).epsilon(1e-11));
        }
        for (double l : {0.8, 0.3, 0.05, -0.2}) {
            const auto a = compressibleNeoHookeanConfined(mu / 2, mu, lambda, l, 0.4);
            // P = F S needs C^-1, undefined at J = 0: use P_zz = 2 C1 l + dW/dJ directly from the law
            const auto in = conf::invariantsOf(Vec3(1, 1, l).asDiagonal());
            const auto r = conf::evaluateOne(m, in, 0.4);
            CAPTURE(l);
            CHECK(2 * r.dI1 * l + r.dJiso + r.dJvol == Approx(a.Pzz).epsilon(1e-12));
            CHECK(2 * r.dI1 + (r.dJiso + r.dJvol) * l == Approx(a.Pxx).epsilon(1e-12));
        }
    }
}
