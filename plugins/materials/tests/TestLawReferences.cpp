// Every built-in law against an independent reference (LawReference.h): the energy W written from
// F with its paper formula, and P = dW/dF by finite differences of that energy, at several
// non-trivial deformations (off-axis fibres, compression, large stretch, below J0, inverted).
// A law error that is consistent in W and its derivatives (e.g. eta/4 written eta/2 everywhere)
// passes the derivative and conformance checks by construction; it fails here.
#include "LawReference.h"

#include "fascia/materials/CompressibleMooneyRivlin.h"
#include "fascia/materials/CompressibleNeoHookean.h"
#include "fascia/materials/Conformance.h"
#include "fascia/materials/IncompressibleMooneyRivlin.h"
#include "fascia/materials/IncompressibleNeoHookean.h"
#include "fascia/materials/NeoHookean.h"
#include "fascia/materials/Orthotropic.h"
#include "fascia/materials/StVenantKirchhoff.h"
#include "fascia/materials/TransverselyIsotropic.h"

#include <catch2/catch.hpp>

#include <memory>

using namespace fascia;
using namespace fascia::materials;
namespace conf = fascia::materials::conformance;

namespace {

std::unique_ptr<BaseMaterial> makeLaw(const lawref::LawSpec& s) {
    std::unique_ptr<BaseMaterial> m;
    if (s.type == "StVenantKirchhoff") m = std::make_unique<StVenantKirchhoff>();
    else if (s.type == "IncompressibleNeoHookean") m = std::make_unique<IncompressibleNeoHookean>();
    else if (s.type == "IncompressibleMooneyRivlin") m = std::make_unique<IncompressibleMooneyRivlin>();
    else if (s.type == "CompressibleNeoHookean") m = std::make_unique<CompressibleNeoHookean>();
    else if (s.type == "CompressibleMooneyRivlin") m = std::make_unique<CompressibleMooneyRivlin>();
    else if (s.type == "NeoHookean") m = std::make_unique<NeoHookean>();
    else if (s.type == "TransverselyIsotropic") m = std::make_unique<TransverselyIsotropic>();
    else m = std::make_unique<Orthotropic>();
    for (const auto& [k, v] : s.params()) m->findParam(k)->read(v, {});
    m->init();
    return m;
}

// deformations: general, compressive (J ~ 0.46), large stretch with shear, nearly isochoric shear,
// crushed below J0 = 0.4 (J ~ 0.2), inverted (J < 0)
Mat3 deformation(int k) {
    switch (k) {
    case 0: return (Mat3() << 1.2, 0.1, 0.0, -0.05, 0.9, 0.2, 0.03, 0.0, 1.1).finished();
    case 1: return (Mat3() << 0.8, 0.3, 0.1, 0.0, 0.7, -0.1, 0.2, 0.05, 0.9).finished();
    case 2: return (Mat3() << 1.6, 0.0, 0.3, 0.4, 1.3, 0.0, 0.0, -0.2, 1.4).finished();
    case 3: return (Mat3() << 1.0, 0.45, 0.0, 0.0, 1.0, 0.0, 0.1, 0.0, 1.0).finished();
    case 4: return (Mat3() << 0.6, 0.1, 0.0, 0.0, 0.55, 0.05, 0.0, 0.0, 0.6).finished();
    default: return (Mat3() << 0.9, 0.1, 0.0, 0.0, 0.8, 0.1, 0.05, 0.0, -0.4).finished();
    }
}

/// The material's own S = 2 dW/dC from its invariant derivatives (Material.h, Response).
Mat3 materialS(const BaseMaterial& m, const Mat3& F, const Vec3& a, const Vec3& b, double J0, Response* out = nullptr) {
    const Mat3 C = F.transpose() * F;
    const Invariants in = conf::invariantsOf(F, a, b);
    const Response r = conf::evaluateOne(m, in, J0);
    if (out) *out = r;
    const Mat3 I = Mat3::Identity();
    return 2 * (r.dI1 * I + r.dI2 * (in.I1 * I - C) + r.dI4 * a * a.transpose() + r.dI6 * b * b.transpose()) +
           in.J * (r.dJiso + r.dJvol) * C.inverse();
}

} // namespace

TEST_CASE("every law's energy equals its paper formula written from F, off-axis fibres and J0 branch included",
          "[BaseMaterial]") {
    const auto laws = lawref::allLaws();
    const size_t li = GENERATE(range(size_t(0), size_t(8)));
    const int k = GENERATE(range(0, 6));
    const double J0 = GENERATE(0.4, 0.7);
    const lawref::LawSpec& spec = laws[li];
    auto m = makeLaw(spec);
    const Mat3 F = deformation(k);
    const Vec3 a = spec.a0.normalized(), b = spec.b0.normalized();
    const double W = conf::evaluateOne(*m, conf::invariantsOf(F, a, b), J0).W;
    const double ref = lawref::energy(spec, F, J0);
    CAPTURE(spec.type, k, J0, F.determinant(), W, ref);
    CHECK(std::abs(ref) > 1.0);  // a non-trivial energy
    CHECK(W == Approx(ref).epsilon(1e-12));
}

TEST_CASE("every law's stress P = F S equals the derivative of its paper energy", "[BaseMaterial]") {
    const auto laws = lawref::allLaws();
    const size_t li = GENERATE(range(size_t(0), size_t(8)));
    const int k = GENERATE(range(0, 6));
    const double J0 = GENERATE(0.4, 0.7);
    const lawref::LawSpec& spec = laws[li];
    const Mat3 F = deformation(k);
    // the finite differences need det F away from the kink at J0
    REQUIRE(std::abs(F.determinant() - J0) > 0.02);
    auto m = makeLaw(spec);
    const Vec3 a = spec.a0.normalized(), b = spec.b0.normalized();
    const Mat3 P = F * materialS(*m, F, a, b, J0);
    const Mat3 ref = lawref::stressP(spec, F, J0);
    CAPTURE(spec.type, k, J0, F.determinant());
    INFO("P =\n" << P << "\nreference =\n" << ref);
    CHECK(ref.norm() > 10.0);
    CHECK((P - ref).norm() < 1e-9 * ref.norm());
}

TEST_CASE("the isochoric and volumetric parts of every law match the reference split", "[BaseMaterial]") {
    // viscoelasticity relaxes one part or the other (ViscoelasticProny apply=): dJiso belongs to the
    // isochoric part and dJvol to the pure-J one. With the invariants fixed, a change of J alone
    // moves W by the two parts' J derivatives: compare each to the reference part's J derivative.
    const auto laws = lawref::allLaws();
    const size_t li = GENERATE(range(size_t(0), size_t(8)));
    const int k = GENERATE(0, 1, 2, 4);
    const lawref::LawSpec& spec = laws[li];
    auto m = makeLaw(spec);
    const Mat3 F = deformation(k);
    const double J0 = 0.4, J = F.determinant();
    const Vec3 a = spec.a0.normalized(), b = spec.b0.normalized();
    const Response r = conf::evaluateOne(*m, conf::invariantsOf(F, a, b), J0);
    // reference: W_part(J) with C held fixed; only the J dependence of each part differs
    auto partAt = [&](lawref::Part part, double Jt) {
        double W = 0;
        if (part == lawref::Part::Isochoric) return lawref::isochoricW(spec, F, std::max(Jt, J0), a, b);
        double Wv, dWv, d2Wv;
        if (Jt >= J0) {
            lawref::volumetricW(spec, Jt, Wv, dWv, d2Wv);
            W = Wv;
        } else {
            lawref::volumetricW(spec, J0, Wv, dWv, d2Wv);
            W = Wv + dWv * (Jt - J0) + 0.5 * d2Wv * (Jt - J0) * (Jt - J0);
        }
        return W;
    };
    const double h = 1e-6;
    const double dIso = (partAt(lawref::Part::Isochoric, J + h) - partAt(lawref::Part::Isochoric, J - h)) / (2 * h);
    const double dVol = (partAt(lawref::Part::Volumetric, J + h) - partAt(lawref::Part::Volumetric, J - h)) / (2 * h);
    const double scale = spec.mu + spec.kappa + spec.lambda + spec.C1 + spec.C2;
    CAPTURE(spec.type, k, J, r.dJiso, dIso, r.dJvol, dVol);
    CHECK(r.dJiso == Approx(dIso).margin(1e-7 * scale));
    CHECK(r.dJvol == Approx(dVol).margin(1e-7 * scale));
}

TEST_CASE("the reference itself: known values of the paper formulas", "[BaseMaterial]") {
    // hand-checkable cases of LawReference.h, so that a slip there cannot hide a slip in a law
    SECTION("uniaxial stretch of Saint Venant-Kirchhoff: W = (lambda/2 + mu) E11^2") {
        const auto s = lawref::lawNamed("StVenantKirchhoff");
        const Mat3 F = Vec3(1.2, 1, 1).asDiagonal();
        const double E11 = 0.5 * (1.44 - 1);
        CHECK(lawref::energy(s, F) == Approx((0.5 * s.lambda + s.mu) * E11 * E11).epsilon(1e-14));
    }
    SECTION("isochoric stretch along the fibre: only mu/2 (I1bar - 3) and eta/4 (lambda^2 - 1)^2") {
        auto s = lawref::lawNamed("TransverselyIsotropic");
        s.a0 = Vec3(0, 0, 1);
        const double l = 1.3;
        const Mat3 F = Vec3(1 / std::sqrt(l), 1 / std::sqrt(l), l).asDiagonal();
        const double ref = 0.5 * s.mu * (l * l + 2 / l - 3) + 0.25 * s.eta * (l * l - 1) * (l * l - 1);
        CHECK(lawref::energy(s, F) == Approx(ref).epsilon(1e-13));
    }
    SECTION("dilation of the neo-Hookean law: only kappa/2 (J - 1)^2") {
        const auto s = lawref::lawNamed("NeoHookean");
        const Mat3 F = 1.1 * Mat3::Identity();
        const double J = 1.331;
        CHECK(lawref::energy(s, F) == Approx(0.5 * s.kappa * (J - 1) * (J - 1)).epsilon(1e-12));
        // below J0 the pure-J term follows its tangent parabola, exact for a quadratic
        const Mat3 G = std::cbrt(0.2) * Mat3::Identity();
        CHECK(lawref::energy(s, G, 0.4, lawref::Part::Volumetric) == Approx(0.5 * s.kappa * 0.64).epsilon(1e-12));
        // and the isochoric part is taken at J0: Cbar = (0.2 / 0.4)^(2/3) I
        CHECK(lawref::energy(s, G, 0.4, lawref::Part::Isochoric) ==
              Approx(0.5 * s.mu * (3 * std::pow(0.5, 2.0 / 3.0) - 3)).epsilon(1e-12));
    }
    SECTION("the off-axis fibre directions are orthogonal") { CHECK(lawref::offAxisA().dot(lawref::offAxisB()) == 0.0); }
}
