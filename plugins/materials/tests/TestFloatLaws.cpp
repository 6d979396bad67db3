// The laws in float (the scalar template of Material.h): every built-in law evaluated in float
// against the same law in double, with an error bound from float's unit roundoff and the condition of
// each formula; the float invCbrt, fastLog, fastExp and fastExprel against the standard functions in
// double over their ranges; and a user law in both forms: the templated one (examples/plugin/Yeoh.h)
// and the double-only form written before the template, which must still compile and give the same
// double results bitwise.
//
// This file is compiled with -Werror=double-promotion (plugins/materials/CMakeLists.txt), so a float
// law that mixes in a double constant (in.I1 - 3.0 instead of in.I1 - T(3)) does not compile.
#include "Yeoh.h"
#include "fascia/materials/BuiltinMaterials.h"
#include "fascia/materials/Conformance.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <memory>
#include <string>

using namespace fascia;
using namespace fascia::materials;
namespace conf = fascia::materials::conformance;

namespace {

constexpr double kU = 5.9604644775390625e-08;  // float's unit roundoff 2^-24
constexpr double kJ0 = 0.25;                   // the J0 of these tests: exact in float and in double

// ---- the bound ------------------------------------------------------------------------------------
//
// First-order rounding-error analysis of a straight-line formula q(x) of the invariants x_i: the
// float result equals q evaluated exactly at inputs perturbed by relative amounts |d_i| <= c u, and
// then rounded by a relative c' u, so
//     |q_float - q| <= K u (|q| + sum_i |x_i dq/dx_i|),   K = max(c, c'),
// where sum_i |x_i dq/dx_i| carries the condition of the formula: it is large where q cancels (I1bar - 3
// near rest, J - 1, (ln J)^2 near J = 1), and there the bound grows with it. c counts the roundings
// an input goes through before its first subtraction: at most invCbrt (2 u, measured below), t^2, t^3
// or t^4 (up to 3 u), the product with the invariant (1 u), and fastExp / fastLog where used (3 u):
// below 10 u; c' counts the roundings after it, below 10 u as well for these formulas (Horner in
// ArrudaBoyce: 9). K = 16 covers both with a margin; the parameters, rounded to float once, are
// relative perturbations of u of terms the same size as the x_i dq/dx_i. The dq/dx_i are taken by
// central differences of the double law (relative step 1e-6, far inside its smooth pieces).
constexpr double kK = 16;

// deformations: rest, stretch, compression, shear, a general one, near inversion (above J0, below J0,
// inverted), and stretch and compression along the first fibre direction a0 (fibres in tension and in
// compression), each isochoric apart from the first seven
struct Deformation {
    const char* name;
    Mat3 F;
};

Mat3 alongFibre(const Vec3& a, double lambda) {
    const Mat3 A = a * a.transpose();
    return lambda * A + (1.0 / std::sqrt(lambda)) * (Mat3::Identity() - A);
}

std::vector<Deformation> deformations(const Vec3& a0) {
    const auto diag = [](double a, double b, double c) { return Vec3(a, b, c).asDiagonal().toDenseMatrix(); };
    Mat3 shear = Mat3::Identity();
    shear(0, 1) = 0.5;
    return {{"rest", Mat3::Identity()},
            {"stretch", diag(1.3, 0.9, 1.05)},
            {"compression", diag(0.7, 1.1, 1.05)},
            {"simple shear 0.5", shear},
            {"general", (Mat3() << 1.2, 0.1, 0.0, -0.05, 0.9, 0.2, 0.03, 0.0, 1.1).finished()},
            {"near inversion, J = 0.30 above J0", diag(0.7, 0.7, 0.62)},
            {"near inversion, J = 0.09 below J0", diag(0.5, 0.45, 0.4)},
            {"inverted, J = -0.05", diag(0.5, 0.5, -0.2)},
            {"fibres in tension", alongFibre(a0, 1.25)},
            {"fibres in compression", alongFibre(a0, 0.8)}};
}

InvariantsT<float> toFloat(const Invariants& in) {
    return {static_cast<float>(in.I1), static_cast<float>(in.I2), static_cast<float>(in.J),
            static_cast<float>(in.I4), static_cast<float>(in.I6)};
}
Invariants toDouble(const InvariantsT<float>& in) {
    return {static_cast<double>(in.I1), static_cast<double>(in.I2), static_cast<double>(in.J),
            static_cast<double>(in.I4), static_cast<double>(in.I6)};
}

struct Quantity {
    const char* name;
    float ResponseT<float>::*f;
    double Response::*d;
};
const Quantity kQuantities[] = {{"W", &ResponseT<float>::W, &Response::W},
                                {"dI1", &ResponseT<float>::dI1, &Response::dI1},
                                {"dI2", &ResponseT<float>::dI2, &Response::dI2},
                                {"dI4", &ResponseT<float>::dI4, &Response::dI4},
                                {"dI6", &ResponseT<float>::dI6, &Response::dI6},
                                {"dJiso", &ResponseT<float>::dJiso, &Response::dJiso},
                                {"dJvol", &ResponseT<float>::dJvol, &Response::dJvol}};
double Invariants::*const kInputs[] = {&Invariants::I1, &Invariants::I2, &Invariants::J, &Invariants::I4, &Invariants::I6};

/// The largest ratio |q_float - q_double| / bound over the deformations and quantities, and where.
struct FloatReport {
    double worst = 0;
    std::string where;
};

/// The law in float against the law in double at every deformation, both at the same (float)
/// invariants, so that only the evaluation's rounding is measured, not the rounding of the inputs.
template <class Law>
FloatReport compareFloat(const Law& law, const Vec3& a0, const Vec3& b0) {
    FloatReport rep;
    for (const Deformation& def : deformations(a0)) {
        const InvariantsT<float> inF = toFloat(conf::invariantsOf(def.F, a0, b0));
        const Invariants in = toDouble(inF);
        ResponseT<float> rf;
        Response rd;
        evaluateLaw(law, inF, kJ0, rf);
        evaluateLaw(law, in, kJ0, rd);
        // the condition terms sum_i |x_i dq/dx_i|, per quantity
        double cond[7] = {};
        for (double Invariants::*x : kInputs) {
            const double h = 1e-6 * std::abs(in.*x);
            Invariants p = in, m = in;
            p.*x += h;
            m.*x -= h;
            Response rp, rm;
            evaluateLaw(law, p, kJ0, rp);
            evaluateLaw(law, m, kJ0, rm);
            for (int q = 0; q < 7; ++q)
                cond[q] += std::abs(in.*x * (rp.*(kQuantities[q].d) - rm.*(kQuantities[q].d)) / (2 * h));
        }
        for (int q = 0; q < 7; ++q) {
            const double ref = rd.*(kQuantities[q].d);
            const double err = std::abs(static_cast<double>(rf.*(kQuantities[q].f)) - ref);
            const double bound = kK * kU * (std::abs(ref) + cond[q]);
            const double ratio = err == 0 ? 0 : err / bound;
            if (ratio > rep.worst || !std::isfinite(ratio)) {
                rep.worst = std::isfinite(ratio) ? ratio : 1e300;
                rep.where = std::string(kQuantities[q].name) + " at " + def.name;
            }
        }
    }
    return rep;
}

Vec3 dirOf(const BaseMaterial& m, int k, const Vec3& fallback) {
    const Vec3* d = m.fibreDirection(k);
    return d ? *d : fallback;
}

// ---- a user law written for double only, the form before the scalar template ----------------------
// (examples/plugin/Yeoh.h as it was: non-template isochoric and volumetric on Invariants, Response)
struct DoubleOnlyYeohLaw {
    static constexpr unsigned uses = 0;
    double C10 = 0, C20 = 0, C30 = 0, kappa = 0;
    bool stressFreeAtRest() const { return true; }
    void isochoric(const Invariants& in, Response& r) const {
        const double t = invCbrt(in.J), t2 = t * t;
        const double x = in.I1 * t2 - 3.0;
        const double dWdI1bar = C10 + x * (2 * C20 + 3 * C30 * x);
        r.W += x * (C10 + x * (C20 + C30 * x));
        r.dI1 += dWdI1bar * t2;
        r.dJiso += dWdI1bar * in.I1 * (-2.0 / 3.0) * t2 * t2 * t;
    }
    void volumetric(double J, double& W, double& dW, double& d2W) const {
        W = 0.5 * kappa * (J - 1) * (J - 1);
        dW = kappa * (J - 1);
        d2W = kappa;
    }
};

// the component of a user law, as a plugin writes it (Material<Law> with the moduli)
template <class Law>
struct UserMaterial : Material<Law> {
    explicit UserMaterial(const Law& law) { this->m_law = law; }
    double shearModulus() const override { return 2 * this->m_law.C10; }
    double bulkModulus() const override { return this->m_law.kappa; }
};

template <class Law>
Law yeohParameters() {
    Law law;
    law.C10 = 1000;
    law.C20 = 300;
    law.C30 = 50;
    law.kappa = 20000;
    return law;
}

// ---- the float functions against the standard ones in double ---------------------------------------

float nextUp(float x) { return std::nextafter(x, 2 * x + 1); }

} // namespace

TEST_CASE("every built-in law in float agrees with double within the bound of its condition", "[BaseMaterial]") {
    const std::string name = GENERATE(from_range(builtinMaterialNames()));
    CAPTURE(name);
    forEachBuiltinMaterial([&](auto* tag) {
        using M = std::decay_t<decltype(*tag)>;
        if (name != M::kName) return;
        M m;
        for (const auto& [k, v] : exampleParameters(name)) m.findParam(k)->read(v, {});
        m.init();
        const FloatReport rep = compareFloat(m.law(), dirOf(m, 0, Vec3(0, 0, 1)), dirOf(m, 1, Vec3(1, 0, 0)));
        INFO("worst error / bound " << rep.worst << " (" << rep.where << ")");
        CHECK(rep.worst <= 1.0);
    });
}

TEST_CASE("a user law in the templated form runs in float within the same bound", "[Material]") {
    const FloatReport rep = compareFloat(yeohParameters<example::YeohLaw>(), Vec3(0, 0, 1), Vec3(1, 0, 0));
    INFO("worst error / bound " << rep.worst << " (" << rep.where << ")");
    CHECK(rep.worst <= 1.0);
}

TEST_CASE("a user law written for double only still compiles and gives the templated law's results bitwise", "[Material]") {
    const UserMaterial<DoubleOnlyYeohLaw> before(yeohParameters<DoubleOnlyYeohLaw>());
    const UserMaterial<example::YeohLaw> after(yeohParameters<example::YeohLaw>());
    int compared = 0;
    for (const Deformation& def : deformations(Vec3(0, 0, 1))) {
        CAPTURE(def.name);
        const Invariants in = conf::invariantsOf(def.F);
        const Response a = conf::evaluateOne(before, in, kJ0), b = conf::evaluateOne(after, in, kJ0);
        CHECK(std::memcmp(&a, &b, sizeof a) == 0);
        compared += a.W != 0.0;
    }
    CHECK(compared >= 9);  // not trivially equal: W != 0 away from rest
}

TEST_CASE("invCbrt in float is within 2 float roundoffs of the cube root, exhaustively over one period", "[Laws]") {
    // the bit guess repeats every 3 binades up to the rounding of float(bits), so [1, 8) holds
    // every case of the refinement; then sampled over 1e-30 .. 1e30
    double worst = 0;
    for (float x = 1.0f; x < 8.0f; x = nextUp(x)) {
        const double ref = 1.0 / std::cbrt(static_cast<double>(x));
        worst = std::max(worst, std::abs(static_cast<double>(invCbrt(x)) - ref) / ref);
    }
    for (double x = 1e-30; x < 1e30; x *= 1.000731) {
        const float xf = static_cast<float>(x);
        const double ref = 1.0 / std::cbrt(static_cast<double>(xf));
        worst = std::max(worst, std::abs(static_cast<double>(invCbrt(xf)) - ref) / ref);
    }
    INFO("worst relative error " << worst << " = " << worst / kU << " u");
    CHECK(worst < 2 * kU);
    CHECK(invCbrt(8.0f) == 0.5f);
}

TEST_CASE("fastLog in float is within 2 float roundoffs of ln x, exhaustively from 1/2 to 2", "[Laws]") {
    // [1/2, 2) holds both reductions (m below and above sqrt 2) and x near 1, where ln x is small and
    // the error is relative to ln x itself; then sampled over 1e-30 .. 1e30 relative to max(1, |ln x|)
    double worstNear = 0, worst = 0;
    for (float x = 0.5f; x < 2.0f; x = nextUp(x)) {
        if (x == 1.0f) continue;
        const double ref = std::log(static_cast<double>(x));
        worstNear = std::max(worstNear, std::abs(static_cast<double>(fastLog(x)) - ref) / std::abs(ref));
    }
    for (double x = 1e-30; x < 1e30; x *= 1.000731) {
        const float xf = static_cast<float>(x);
        const double ref = std::log(static_cast<double>(xf));
        worst = std::max(worst, std::abs(static_cast<double>(fastLog(xf)) - ref) / std::max(1.0, std::abs(ref)));
    }
    INFO("worst relative error on [1/2, 2) " << worstNear / kU << " u, elsewhere " << worst / kU << " u");
    CHECK(worstNear < 2 * kU);
    CHECK(worst < 2 * kU);
    CHECK(fastLog(1.0f) == 0.0f);
}

TEST_CASE("fastExp in float is within 2 float roundoffs of e^x from -87 to 87 and clamps above", "[fastExp]") {
    double worst = 0;
    for (double x = -87; x <= 87; x += 1.37e-4) {
        const float xf = static_cast<float>(x);
        const double ref = std::exp(static_cast<double>(xf));
        worst = std::max(worst, std::abs(static_cast<double>(fastExp(xf)) - ref) / ref);
    }
    INFO("worst relative error " << worst / kU << " u");
    CHECK(worst < 2 * kU);
    CHECK(fastExp(0.0f) == 1.0f);
    CHECK(std::isfinite(fastExp(1000.0f)));
    CHECK(static_cast<double>(fastExp(1000.0f)) == Approx(std::exp(87.0)).epsilon(2 * kU));
    CHECK(static_cast<double>(fastExp(-1000.0f)) == Approx(std::exp(-87.0)).epsilon(2 * kU));
}

TEST_CASE("fastExprel in float is within 3 float roundoffs of (e^x - 1)/x, without cancellation near zero", "[fastExp]") {
    double worst = 0;
    for (double x = -20; x < 20; x += 1.37e-4) {
        const float xf = static_cast<float>(x);
        const double xd = static_cast<double>(xf);
        const double ref = xf == 0.0f ? 1.0 : std::expm1(xd) / xd;
        worst = std::max(worst, std::abs(static_cast<double>(fastExprel(xf)) - ref) / ref);
    }
    for (double x = 1e-30; x < 1; x *= 1.01) {
        for (const double s : {x, -x}) {
            const float xf = static_cast<float>(s);
            const double xd = static_cast<double>(xf);
            const double ref = std::expm1(xd) / xd;
            worst = std::max(worst, std::abs(static_cast<double>(fastExprel(xf)) - ref) / ref);
        }
    }
    INFO("worst relative error " << worst / kU << " u");
    CHECK(worst < 3 * kU);
    CHECK(fastExprel(0.0f) == 1.0f);
}
