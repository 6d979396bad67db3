// Law-level tests of the materials plugin: fast J^(-1/3), derivatives against finite differences,
// energies against direct tensor formulas, stress at rest, moduli, parameter checks.
#include "fascia/materials/Conformance.h"
#include "fascia/materials/BuiltinMaterials.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <memory>
#include <utility>

using namespace fascia;
using namespace fascia::materials;
namespace conf = fascia::materials::conformance;

namespace {

// the parameters of these tests where they differ from the material's own example (kExample)
std::vector<std::pair<std::string, std::string>> testParams(const std::string& name) {
    if (name == "StVenantKirchhoff") return {{"youngModulus", "3000"}, {"poissonRatio", "0.3"}};
    if (name == "IncompressibleMooneyRivlin") return {{"C1", "400"}, {"C2", "150"}};
    if (name == "CompressibleNeoHookean") return {{"mu", "1000"}, {"lambda", "4000"}};
    if (name == "CompressibleMooneyRivlin") return {{"C1", "400"}, {"C2", "150"}, {"kappa", "20000"}};
    if (name == "TransverselyIsotropic") return {{"mu", "1000"}, {"kappa", "20000"}, {"eta", "2000"}, {"direction", "1 1 0"}};
    if (name == "Orthotropic")
        return {{"mu", "1000"}, {"kappa", "20000"}, {"eta", "2000"}, {"eta2", "700"}, {"direction", "1 1 0"}, {"direction2", "0 0 2"}};
    return exampleParameters(name);
}

// every built-in material (the one list, BuiltinMaterials.h) with typical soft-tissue parameters (Pa)
std::unique_ptr<BaseMaterial> makeMaterial(const std::string& name) {
    auto m = createBuiltinMaterial(name);
    if (!m) throw std::runtime_error("unknown material " + name);
    for (const auto& [k, v] : testParams(name)) m->findParam(k)->read(v, {});
    m->init();
    return m;
}

const std::vector<std::string> kAll = builtinMaterialNames();

Vec3 dirOf(const BaseMaterial& m, int k, const Vec3& fallback) {
    const Vec3* d = m.fibreDirection(k);
    return d ? *d : fallback;
}

double energyOfF(const BaseMaterial& m, const Mat3& F, double J0 = 0.4) {
    const auto in = conf::invariantsOf(F, dirOf(m, 0, Vec3(0, 0, 1)), dirOf(m, 1, Vec3(1, 0, 0)));
    return conf::evaluateOne(m, in, J0).W;
}

Mat3 testF(int k) {
    switch (k) {
    case 0: return (Mat3() << 1.2, 0.1, 0.0, -0.05, 0.9, 0.2, 0.03, 0.0, 1.1).finished();   // general, J ~ 1.2
    case 1: return (Mat3() << 0.8, 0.3, 0.1, 0.0, 0.7, -0.1, 0.2, 0.05, 0.9).finished();    // compressive, J ~ 0.5
    case 2: return (Mat3() << 1.6, 0.0, 0.0, 0.4, 1.3, 0.0, 0.0, -0.2, 1.4).finished();     // large stretch
    default: return (Mat3() << 0.6, 0.1, 0.0, 0.0, 0.55, 0.05, 0.0, 0.0, 0.6).finished();  // J ~ 0.2 < J0
    }
}

} // namespace

TEST_CASE("invCbrt matches the cube root to a few ulp over twelve decades", "[Laws]") {
    double worst = 0;
    for (double x = 1e-6; x < 1e6; x *= 1.0137) {
        const double ref = 1.0 / std::cbrt(x);
        worst = std::max(worst, std::abs(invCbrt(x) - ref) / ref);
    }
    CHECK(worst < 2e-15);
    CHECK(invCbrt(1.0) == Approx(1.0).epsilon(1e-16));
    CHECK(invCbrt(8.0) == Approx(0.5).epsilon(1e-16));
}

TEST_CASE("fastLog matches std::log to about an ulp", "[Laws]") {
    double worst = 0;
    for (double x = 1e-8; x < 1e8; x *= 1.0091) {
        const double ref = std::log(x);
        worst = std::max(worst, std::abs(fastLog(x) - ref) / std::max(1.0, std::abs(ref)));
    }
    CHECK(worst < 4e-16);
    CHECK(fastLog(1.0) == 0.0);
    const double nearOne = 1.0 + 1e-12;  // relative accuracy near ln 1 = 0
    CHECK(std::abs(fastLog(nearOne) - std::log(nearOne)) < 1e-27);
}

TEST_CASE("every derivative of every law matches central differences of its energy", "[BaseMaterial]") {
    const std::string name = GENERATE(from_range(kAll));
    const int k = GENERATE(0, 1, 2, 3);
    auto m = makeMaterial(name);
    const auto in = conf::invariantsOf(testF(k), dirOf(*m, 0, Vec3(0, 0, 1)), dirOf(*m, 1, Vec3(1, 0, 0)));
    const auto rep = conf::checkLawDerivatives(*m, in, 0.4);
    INFO(name << " F#" << k << " J = " << in.J << " worst " << rep.worst << ": " << rep.analytic << " vs " << rep.numeric);
    CHECK(rep.maxRelError < 1e-7);
}

TEST_CASE("the energy is continuous across J0 and finite through inversion", "[BaseMaterial]") {
    const std::string name = GENERATE(from_range(kAll));
    auto m = makeMaterial(name);
    const auto in = conf::invariantsOf(testF(1));
    INFO(name);
    CHECK(conf::energyJumpAtJ0(*m, in, 0.4) < 1e-9);
    for (double J : {0.3, 0.0, -0.2, -1.0}) {
        Invariants c = in;
        c.J = J;
        const Response r = conf::evaluateOne(*m, c, 0.4);
        CAPTURE(J);
        CHECK(std::isfinite(r.W));
        CHECK(std::isfinite(r.dJvol));
        CHECK(r.dJiso == 0.0);
    }
}

TEST_CASE("laws with a volumetric part push back ever harder as J goes through J0 to inversion", "[BaseMaterial]") {
    const std::string name = GENERATE("CompressibleNeoHookean", "CompressibleMooneyRivlin", "NeoHookean");
    auto m = makeMaterial(name);
    Invariants in;
    double prev = 0;
    bool first = true;
    for (double J : {0.6, 0.4, 0.2, 0.0, -0.3}) {
        in.J = J;
        const Response r = conf::evaluateOne(*m, in, 0.4);
        CAPTURE(name, J);
        CHECK(r.dJvol < 0);  // compression resisted
        if (!first) CHECK(r.dJvol < prev);
        prev = r.dJvol;
        first = false;
    }
}

TEST_CASE("the stress at rest vanishes exactly for the stress-free laws and not for HEML's incompressible ones",
          "[BaseMaterial]") {
    const std::string name = GENERATE(from_range(kAll));
    auto m = makeMaterial(name);
    const double res = conf::restStressResidual(*m);
    INFO(name << " residual " << res);
    if (name == "IncompressibleNeoHookean" || name == "IncompressibleMooneyRivlin") {
        CHECK_FALSE(m->stressFreeAtRest());
        CHECK(res > 0.1);
    } else {
        CHECK(m->stressFreeAtRest());
        CHECK(res < 1e-14);
    }
}

TEST_CASE("compressible neo-Hookean with C1 other than mu/2 is not stress-free at rest", "[CompressibleNeoHookean]") {
    CompressibleNeoHookean m;
    m.m_mu.set(1000);
    m.m_lambda.set(4000);
    m.m_C1.set(700);  // HEML eq. (26): stress-free needs C1 = mu/2 = 500 (a warning is printed)
    m.init();
    CHECK_FALSE(m.stressFreeAtRest());
    // residual (2 C1 - mu) / 2 = 200 relative to mu
    CHECK(conf::restStressResidual(m) == Approx(0.2).epsilon(1e-12));
}

TEST_CASE("law energies equal the direct tensor formulas", "[BaseMaterial]") {
    const int k = GENERATE(0, 1, 2);
    const Mat3 F = testF(k);
    const Mat3 C = F.transpose() * F;
    const Mat3 E = 0.5 * (C - Mat3::Identity());
    const double J = F.determinant();
    const double I1 = C.trace(), I2 = 0.5 * (I1 * I1 - (C * C).trace());
    const double Jm23 = std::pow(J, -2.0 / 3.0);
    CAPTURE(k);

    SECTION("Saint Venant-Kirchhoff: lambda/2 (tr E)^2 + mu tr(E^2), HEML Table 3") {
        auto m = makeMaterial("StVenantKirchhoff");
        const double lam = lameLambda(3000, 0.3), mu = lameMu(3000, 0.3);
        CHECK(energyOfF(*m, F) == Approx(0.5 * lam * E.trace() * E.trace() + mu * (E * E).trace()).epsilon(1e-12));
    }
    SECTION("compressible neo-Hookean, HEML eq. (26)") {
        auto m = makeMaterial("CompressibleNeoHookean");
        const double ref = 500 * (I1 - 3) - 1000 * std::log(J) + 2000 * std::log(J) * std::log(J);
        CHECK(energyOfF(*m, F) == Approx(ref).epsilon(1e-12));
    }
    SECTION("compressible Mooney-Rivlin with modified invariants") {
        auto m = makeMaterial("CompressibleMooneyRivlin");
        const double ref = 400 * (I1 * Jm23 - 3) + 150 * (I2 * Jm23 * Jm23 - 3) + 10000 * (J - 1) * (J - 1);
        CHECK(energyOfF(*m, F) == Approx(ref).epsilon(1e-12));
    }
    SECTION("orthotropic: the eq. (33) convention eta/4 (I4bar - 1)^2 for both families") {
        auto m = makeMaterial("Orthotropic");
        const Vec3 a = Vec3(1, 1, 0).normalized(), b(0, 0, 1);
        const double I4b = Jm23 * a.dot(C * a), I6b = Jm23 * b.dot(C * b);
        const double ref = 500 * (I1 * Jm23 - 3) + 0.25 * 2000 * (I4b - 1) * (I4b - 1) +
                           0.25 * 700 * (I6b - 1) * (I6b - 1) + 10000 * (J - 1) * (J - 1);
        CHECK(energyOfF(*m, F) == Approx(ref).epsilon(1e-12));
    }
}

TEST_CASE("P = F S built from the law's derivatives is the finite-difference derivative of W(F)", "[BaseMaterial]") {
    const std::string name = GENERATE(from_range(kAll));
    const int k = GENERATE(0, 1, 2);
    auto m = makeMaterial(name);
    const Vec3 a = dirOf(*m, 0, Vec3(0, 0, 1)), b = dirOf(*m, 1, Vec3(1, 0, 0));
    const Mat3 F = testF(k);
    const Mat3 C = F.transpose() * F;
    const auto in = conf::invariantsOf(F, a, b);
    const Response r = conf::evaluateOne(*m, in, 0.4);
    // S = 2 [dI1 I + dI2 (I1 I - C) + dI4 A0 + dI6 B0] + J dW/dJ C^-1   (Material.h, Response)
    const Mat3 S = 2 * (r.dI1 * Mat3::Identity() + r.dI2 * (in.I1 * Mat3::Identity() - C) + r.dI4 * a * a.transpose() +
                        r.dI6 * b * b.transpose()) +
                   in.J * (r.dJiso + r.dJvol) * C.inverse();
    const Mat3 P = F * S;
    Mat3 Pfd;
    const double h = 1e-6;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            Mat3 Fp = F, Fm = F;
            Fp(i, j) += h;
            Fm(i, j) -= h;
            Pfd(i, j) = (energyOfF(*m, Fp) - energyOfF(*m, Fm)) / (2 * h);
        }
    INFO(name << " F#" << k << "\nP =\n" << P << "\nfd =\n" << Pfd);
    CHECK((P - Pfd).norm() < 1e-7 * P.norm());
}

TEST_CASE("moduli from Young's modulus and Poisson's ratio", "[BaseMaterial]") {
    const double E = 3000, nu = 0.3, mu = E / (2 * (1 + nu)), K = E / (3 * (1 - 2 * nu));
    SECTION("Saint Venant-Kirchhoff") {
        auto m = makeMaterial("StVenantKirchhoff");
        CHECK(m->shearModulus() == Approx(mu));
        CHECK(m->bulkModulus() == Approx(K));
        // dilatational wave speed sqrt((lambda + 2 mu)/rho)
        CHECK(m->waveSpeed(1000) == Approx(std::sqrt((lameLambda(E, nu) + 2 * mu) / 1000)));
    }
    SECTION("neo-Hookean") {
        NeoHookean m;
        m.m_E.set(E);
        m.m_nu.set(nu);
        m.init();
        CHECK(m.law().mu == Approx(mu));
        CHECK(m.law().kappa == Approx(K));
    }
    SECTION("compressible neo-Hookean takes C1 = mu/2") {
        CompressibleNeoHookean m;
        m.m_E.set(E);
        m.m_nu.set(nu);
        m.init();
        CHECK(m.law().C1 == Approx(mu / 2));
        CHECK(m.law().lambda == Approx(E * nu / ((1 + nu) * (1 - 2 * nu))));
        CHECK(m.stressFreeAtRest());
    }
    SECTION("incompressible laws report a zero bulk modulus") {
        CHECK(makeMaterial("IncompressibleNeoHookean")->bulkModulus() == 0.0);
        CHECK(makeMaterial("IncompressibleNeoHookean")->shearModulus() == Approx(1000));
        CHECK(makeMaterial("IncompressibleMooneyRivlin")->shearModulus() == Approx(1100));
    }
    SECTION("fibres raise the wave speed") {
        auto ti = makeMaterial("TransverselyIsotropic");
        auto nh = makeMaterial("NeoHookean");
        CHECK(ti->waveSpeed(1000) > nh->waveSpeed(1000));
        REQUIRE(ti->fibreDirection(0));
        CHECK(ti->fibreDirection(0)->norm() == Approx(1.0));
        CHECK(ti->fibreDirection(1) == nullptr);
        CHECK(nh->fibreDirection(0) == nullptr);
    }
}

TEST_CASE("moduli given both ways, neither way or half way are located errors", "[BaseMaterial]") {
    SECTION("both") {
        NeoHookean m;
        m.m_mu.set(1000);
        m.m_kappa.set(5000);
        m.m_E.set(3000);
        m.m_nu.set(0.3);
        CHECK_THROWS_WITH(m.init(), Catch::Contains("not both"));
    }
    SECTION("neither") {
        NeoHookean m;
        CHECK_THROWS_WITH(m.init(), Catch::Contains("no elastic moduli given"));
    }
    SECTION("E without nu") {
        StVenantKirchhoff m;
        m.m_E.set(3000);
        CHECK_THROWS_WITH(m.init(), Catch::Contains("'youngModulus' is given without 'poissonRatio'"));
    }
    SECTION("mu without kappa") {
        TransverselyIsotropic m;
        m.m_mu.set(3000);
        CHECK_THROWS_WITH(m.init(), Catch::Contains("'mu' is given without 'kappa'"));
    }
    SECTION("parallel fibre directions") {
        Orthotropic m;
        m.m_mu.set(1000);
        m.m_kappa.set(5000);
        m.m_dir.set(Vec3(0, 0, 1));
        m.m_dir2.set(Vec3(0, 0, -3));
        CHECK_THROWS_WITH(m.init(), Catch::Contains("parallel"));
    }
    SECTION("zero fibre direction") {
        TransverselyIsotropic m;
        m.m_mu.set(1000);
        m.m_kappa.set(5000);
        m.m_dir.set(Vec3::Zero());
        CHECK_THROWS_WITH(m.init(), Catch::Contains("non-zero"));
    }
}

namespace {
/// S11 and S22 (= S33) of a law under F = diag(a, l, l), from its derivatives (Material.h, Response):
/// S = 2 [dI1 I + dI2 (I1 I - C)] + J dW/dJ C^-1.
std::pair<double, double> uniaxialS(const BaseMaterial& m, double a, double l) {
    const Mat3 F = Vec3(a, l, l).asDiagonal();
    const auto in = conf::invariantsOf(F);
    const auto r = conf::evaluateOne(m, in, 0.4);
    const double dJ = r.dJiso + r.dJvol;
    return {2 * (r.dI1 + r.dI2 * (in.I1 - a * a)) + in.J * dJ / (a * a),
            2 * (r.dI1 + r.dI2 * (in.I1 - l * l)) + in.J * dJ / (l * l)};
}
/// The root of f in [lo, hi] by bisection (f changes sign there).
template <class Fn>
double bisect(Fn f, double lo, double hi) {
    const bool up = f(hi) > 0;
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        ((f(mid) > 0) == up ? hi : lo) = mid;
    }
    return 0.5 * (lo + hi);
}
/// The lateral stretch of uniaxial stress (S22 = 0) at axial stretch a.
double lateral(const BaseMaterial& m, double a) {
    return bisect([&](double l) { return uniaxialS(m, a, l).second; }, 0.3, 1.0);
}
/// The axial stretch at nominal stress P11 = a S11 = P.
double stretchAt(const BaseMaterial& m, double P) {
    return bisect([&](double a) { return a * uniaxialS(m, a, lateral(m, a)).first - P; }, 1.0, 3.0);
}
} // namespace

TEST_CASE("docs/materials.md's neo-Hookean figures: NeoHookean and CompressibleNeoHookean part by 2 per cent in uniaxial stress",
          "[NeoHookean][CompressibleNeoHookean]") {
    // E = 1 Pa, nu = 0.3 for both (docs/materials.md, section 2); closed forms of the lateral stress:
    //   CompressibleNeoHookean: sigma22 J = mu (l^2 - 1) + lambda ln J
    //   NeoHookean:             sigma22 = mu J^(-5/3) (l^2 - I1/3) + kappa (J - 1),  J = a l^2, I1 = a^2 + 2 l^2
    auto make = [](const std::string& name) {
        auto m = createBuiltinMaterial(name);
        m->findParam("youngModulus")->read("1", {});
        m->findParam("poissonRatio")->read("0.3", {});
        m->init();
        return m;
    };
    const auto cnh = make("CompressibleNeoHookean"), nh = make("NeoHookean");
    const double E = 1, nu = 0.3, mu = E / (2 * (1 + nu)), lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), kappa = lambda + 2 * mu / 3;
    const double a = 2.0;
    const double lc = lateral(*cnh, a), ln = lateral(*nh, a);
    const double lcClosed = bisect([&](double l) { return mu * (l * l - 1) + lambda * std::log(a * l * l); }, 0.3, 1.0);
    const double lnClosed = bisect([&](double l) {
        const double J = a * l * l, I1 = a * a + 2 * l * l;
        return mu * std::pow(J, -5.0 / 3.0) * (l * l - I1 / 3) + kappa * (J - 1);
    }, 0.3, 1.0);
    CHECK(lc == Approx(lcClosed).epsilon(1e-12));
    CHECK(ln == Approx(lnClosed).epsilon(1e-12));
    // the figures as printed in the doc (5 digits)
    CHECK(std::abs(lc - 0.79808) < 5e-6);
    CHECK(std::abs(ln - 0.81314) < 5e-6);
    CHECK(std::abs((ln - lc) / lc - 0.019) < 5e-4);
    const double sc = stretchAt(*cnh, 0.25), sn = stretchAt(*nh, 0.25);
    CHECK(std::abs(sc - 1.30215) < 5e-6);
    CHECK(std::abs(sn - 1.33164) < 5e-6);
    CHECK(std::abs((sn - sc) / sc - 0.023) < 5e-4);
}
