#pragma once
/// The built-in hyperelastic laws as plain, inlinable structs (see Material.h for the interface:
/// uses, stressFreeAtRest(), isochoric(), volumetric()). Force fields dispatch once per element
/// loop on Material<Law> and inline these; user laws follow the same shape.
///
/// Every derivative is a partial derivative of W(I1, I2, J, I4, I6) w.r.t. the plain invariants
/// (Material.h, Response). No law calls pow: J^(-1/3) comes from invCbrt() (exponent bits plus a
/// division-free Newton refinement), 1/J from (J^(-1/3))^3. Only CompressibleNeoHookeanLaw needs
/// a logarithm (HEML eq. (26)): fastLog(), likewise without libm.
#include "fascia/materials/Material.h"

#include <cmath>
#include <cstdint>
#include <cstring>

namespace fascia::materials {

/// x^(-1/3) for finite x > 0, to a few ulp, without libm or division (docs/performance.md, lessons: no libm, no division):
/// an initial guess from the exponent bits (max relative error 3.4 %) refined by four Newton
/// steps y <- y (4 - x y^3) / 3, whose error squares each step (3.4e-2, 2.3e-3, 1e-5, 2e-10, ~ulp).
/// Vectorises (the bit guess uses int64 <-> double conversions).
inline double invCbrt(double x) {
    std::int64_t i;
    std::memcpy(&i, &x, sizeof i);
    // bits(x^p) ~ p bits(x) + (1 - p) bits(1.0) with p = -1/3, constant tuned for the least max error
    i = static_cast<std::int64_t>(6142608150558322754.0 - static_cast<double>(i) * (1.0 / 3.0));
    double y;
    std::memcpy(&y, &i, sizeof y);
    const double x3 = x * (1.0 / 3.0);
    // four steps, written out (a loop here would stop the element loops from vectorising)
    y = y * (4.0 / 3.0 - x3 * (y * y * y));
    y = y * (4.0 / 3.0 - x3 * (y * y * y));
    y = y * (4.0 / 3.0 - x3 * (y * y * y));
    y = y * (4.0 / 3.0 - x3 * (y * y * y));
    return y;
}

/// ln x for finite normal x > 0, to about 1 ulp, without libm (so that element loops vectorise):
/// x = 2^e m with m in [sqrt(1/2), sqrt(2)), ln m = 2 atanh(s), s = (m - 1)/(m + 1), |s| < 0.172,
/// by its odd series to s^21 (truncation below 1e-18).
inline double fastLog(double x) {
    std::int64_t i;
    std::memcpy(&i, &x, sizeof i);
    std::int64_t e = ((i >> 52) & 0x7ff) - 1023;
    const std::int64_t mi = (i & 0x000fffffffffffffLL) | 0x3ff0000000000000LL;
    double m;
    std::memcpy(&m, &mi, sizeof m);
    const bool big = m > 1.4142135623730951;
    m = big ? 0.5 * m : m;
    e = big ? e + 1 : e;
    const double s = (m - 1.0) / (m + 1.0), s2 = s * s;
    const double p =
        1.0 + s2 * (1.0 / 3 + s2 * (1.0 / 5 + s2 * (1.0 / 7 + s2 * (1.0 / 9 + s2 * (1.0 / 11 + s2 * (1.0 / 13 + s2 * (1.0 / 15 + s2 * (1.0 / 17 + s2 * (1.0 / 19 + s2 * (1.0 / 21))))))))));
    const double de = static_cast<double>(e);
    // ln 2 split so that de * ln2hi is exact
    return de * 6.93147180369123816490e-01 + (2.0 * s * p + de * 1.90821492927058770002e-10);
}

/// Saint Venant-Kirchhoff (HEML Table 3): W = lambda/2 (tr E)^2 + mu tr(E^2), E = (C - I)/2,
/// written with the invariants: tr E = (I1 - 3)/2, tr(E^2) = (I1^2 - 2 I2 - 2 I1 + 3)/4, so
///   W = lambda/8 (I1 - 3)^2 + mu/4 (I1^2 - 2 I2 - 2 I1 + 3).
/// No volumetric part: the HEML J0 treatment does nothing for it, and (HEML section 4.2) it
/// softens under strong compression; stress-free at rest.
struct StVenantKirchhoffLaw {
    static constexpr unsigned uses = BaseMaterial::UsesI2;
    double lambda = 0, mu = 0;  ///< Lame coefficients (Pa)
    bool stressFreeAtRest() const { return true; }
    void isochoric(const Invariants& in, Response& r) const {
        const double a = in.I1 - 3.0;
        r.W += 0.125 * lambda * a * a + 0.25 * mu * (in.I1 * in.I1 - 2.0 * in.I2 - 2.0 * in.I1 + 3.0);
        r.dI1 += 0.25 * lambda * a + 0.5 * mu * (in.I1 - 1.0);
        r.dI2 += -0.5 * mu;
    }
    void volumetric(double, double& W, double& dW, double& d2W) const { W = dW = d2W = 0.0; }
};

/// The HEML paper's "incompressible" neo-Hookean (Table 3): W = C1 (I1 - 3). It has no pressure
/// or volumetric term: nothing resists volume change except through I1, and the rest state is
/// NOT stress-free (S = 2 C1 I at C = I). "Incompressible" only in the paper's sense (the law one
/// would use with an incompressibility constraint, which HEML does not impose).
struct IncompressibleNeoHookeanLaw {
    static constexpr unsigned uses = 0;
    double C1 = 0;  ///< Pa
    bool stressFreeAtRest() const { return false; }
    void isochoric(const Invariants& in, Response& r) const {
        r.W += C1 * (in.I1 - 3.0);
        r.dI1 += C1;
    }
    void volumetric(double, double& W, double& dW, double& d2W) const { W = dW = d2W = 0.0; }
};

/// The HEML paper's "incompressible" Mooney-Rivlin (Table 3): W = C1 (I1 - 3) + C2 (I2 - 3).
/// No volumetric term; not stress-free at rest (S = 2 (C1 + 2 C2) I at C = I).
struct IncompressibleMooneyRivlinLaw {
    static constexpr unsigned uses = BaseMaterial::UsesI2;
    double C1 = 0, C2 = 0;  ///< Pa
    bool stressFreeAtRest() const { return false; }
    void isochoric(const Invariants& in, Response& r) const {
        r.W += C1 * (in.I1 - 3.0) + C2 * (in.I2 - 3.0);
        r.dI1 += C1;
        r.dI2 += C2;
    }
    void volumetric(double, double& W, double& dW, double& d2W) const { W = dW = d2W = 0.0; }
};

/// Compressible neo-Hookean of HEML eq. (26): W = C1 (I1 - 3) - mu ln J + lambda/2 (ln J)^2,
/// derivatives eq. (27). Stress-free at rest only when C1 = mu/2 (then it is the classical
/// Simo-Pister / Bonet-Wood neo-Hookean with Lame coefficients lambda, mu).
struct CompressibleNeoHookeanLaw {
    static constexpr unsigned uses = 0;
    double C1 = 0, mu = 0, lambda = 0;  ///< Pa
    bool stressFreeAtRest() const { return C1 == 0.5 * mu; }
    void isochoric(const Invariants& in, Response& r) const {
        r.W += C1 * (in.I1 - 3.0);
        r.dI1 += C1;
    }
    void volumetric(double J, double& W, double& dW, double& d2W) const {
        const double lnJ = fastLog(J), iJ = 1.0 / J;
        W = -mu * lnJ + 0.5 * lambda * lnJ * lnJ;
        dW = (lambda * lnJ - mu) * iJ;               // HEML eq. (27)
        d2W = (lambda - lambda * lnJ + mu) * iJ * iJ;
    }
};

/// Compressible Mooney-Rivlin with the isochoric split of HEML eq. (21)-(25):
///   W = C1 (I1bar - 3) + C2 (I2bar - 3) + kappa/2 (J - 1)^2,  I1bar = J^(-2/3) I1, I2bar = J^(-4/3) I2.
/// Stress-free at rest; small-strain shear modulus 2 (C1 + C2), bulk modulus kappa.
struct CompressibleMooneyRivlinLaw {
    static constexpr unsigned uses = BaseMaterial::UsesI2;
    double C1 = 0, C2 = 0, kappa = 0;  ///< Pa
    bool stressFreeAtRest() const { return true; }
    void isochoric(const Invariants& in, Response& r) const {
        const double t = invCbrt(in.J), t2 = t * t, t4 = t2 * t2, iJ = t2 * t;
        const double I1b = in.I1 * t2, I2b = in.I2 * t4;
        r.W += C1 * (I1b - 3.0) + C2 * (I2b - 3.0);
        r.dI1 += C1 * t2;
        r.dI2 += C2 * t4;
        r.dJiso += -(2.0 / 3.0) * (C1 * I1b + 2.0 * C2 * I2b) * iJ;
    }
    void volumetric(double J, double& W, double& dW, double& d2W) const {
        W = 0.5 * kappa * (J - 1.0) * (J - 1.0);
        dW = kappa * (J - 1.0);
        d2W = kappa;
    }
};

/// Neo-Hookean with the isochoric split, as in TLED eq. (9), (31)-(32) without the fibre term:
///   W = mu/2 (I1bar - 3) + kappa/2 (J - 1)^2.  Stress-free at rest; shear mu, bulk kappa.
struct NeoHookeanLaw {
    static constexpr unsigned uses = 0;
    double mu = 0, kappa = 0;  ///< Pa
    bool stressFreeAtRest() const { return true; }
    void isochoric(const Invariants& in, Response& r) const {
        const double t = invCbrt(in.J), t2 = t * t, iJ = t2 * t;
        const double I1b = in.I1 * t2;
        r.W += 0.5 * mu * (I1b - 3.0);
        r.dI1 += 0.5 * mu * t2;
        r.dJiso += -(1.0 / 3.0) * mu * I1b * iJ;
    }
    void volumetric(double J, double& W, double& dW, double& d2W) const {
        W = 0.5 * kappa * (J - 1.0) * (J - 1.0);
        dW = kappa * (J - 1.0);
        d2W = kappa;
    }
};

/// Transversely isotropic neo-Hookean of the TLED paper (section 3.2.2, eq. (31)-(33)):
///   W = mu/2 (I1bar - 3) + eta/4 (I4bar - 1)^2 + kappa/2 (J - 1)^2,  I4bar = J^(-2/3) a0.C a0.
/// The fibre term is eta/4, not the eta/2 printed in TLED eq. (31): eq. (33) and Appendix A (and
/// the published implementations) use the stress eta J^(-2/3) (I4bar - 1)(A0 - I4/3 C^-1), which is
/// the derivative 2 dW/dC of eta/4 (I4bar - 1)^2. Stress-free at rest.
struct TransverselyIsotropicLaw {
    static constexpr unsigned uses = BaseMaterial::UsesI4;
    double mu = 0, kappa = 0, eta = 0;  ///< Pa
    bool stressFreeAtRest() const { return true; }
    void isochoric(const Invariants& in, Response& r) const {
        const double t = invCbrt(in.J), t2 = t * t, iJ = t2 * t;
        const double I1b = in.I1 * t2, I4b = in.I4 * t2, e4 = I4b - 1.0;
        r.W += 0.5 * mu * (I1b - 3.0) + 0.25 * eta * e4 * e4;
        r.dI1 += 0.5 * mu * t2;
        r.dI4 += 0.5 * eta * e4 * t2;
        r.dJiso += -(1.0 / 3.0) * (mu * I1b + eta * e4 * I4b) * iJ;
    }
    void volumetric(double J, double& W, double& dW, double& d2W) const {
        W = 0.5 * kappa * (J - 1.0) * (J - 1.0);
        dW = kappa * (J - 1.0);
        d2W = kappa;
    }
};

/// Orthotropic extension (TLED section 3.2.3): the transversely isotropic law plus a second
/// fibre family b0 in the same eq. (33) convention:
///   W = mu/2 (I1bar - 3) + eta/4 (I4bar - 1)^2 + eta2/4 (I6bar - 1)^2 + kappa/2 (J - 1)^2.
struct OrthotropicLaw {
    static constexpr unsigned uses = BaseMaterial::UsesI4 | BaseMaterial::UsesI6;
    double mu = 0, kappa = 0, eta = 0, eta2 = 0;  ///< Pa
    bool stressFreeAtRest() const { return true; }
    void isochoric(const Invariants& in, Response& r) const {
        const double t = invCbrt(in.J), t2 = t * t, iJ = t2 * t;
        const double I1b = in.I1 * t2, I4b = in.I4 * t2, I6b = in.I6 * t2;
        const double e4 = I4b - 1.0, e6 = I6b - 1.0;
        r.W += 0.5 * mu * (I1b - 3.0) + 0.25 * eta * e4 * e4 + 0.25 * eta2 * e6 * e6;
        r.dI1 += 0.5 * mu * t2;
        r.dI4 += 0.5 * eta * e4 * t2;
        r.dI6 += 0.5 * eta2 * e6 * t2;
        r.dJiso += -(1.0 / 3.0) * (mu * I1b + eta * e4 * I4b + eta2 * e6 * I6b) * iJ;
    }
    void volumetric(double J, double& W, double& dW, double& d2W) const {
        W = 0.5 * kappa * (J - 1.0) * (J - 1.0);
        dW = kappa * (J - 1.0);
        d2W = kappa;
    }
};

/// Lame and bulk moduli from Young's modulus E (Pa) and Poisson's ratio nu.
inline double lameMu(double E, double nu) { return E / (2.0 * (1.0 + nu)); }
inline double lameLambda(double E, double nu) { return E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)); }
inline double bulkFromE(double E, double nu) { return E / (3.0 * (1.0 - 2.0 * nu)); }

} // namespace fascia::materials
