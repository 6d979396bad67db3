#pragma once
/// The built-in hyperelastic laws as plain, inlinable structs (see Material.h for the interface:
/// uses, stressFreeAtRest(), isochoric(), volumetric()). Force fields dispatch once per element
/// loop on Material<Law> and inline these; user laws follow the same shape.
///
/// Every law is templated on the scalar type T (Material.h): its parameters are double members,
/// converted to T once per call; its constants are written T(...), so that the double instance is
/// exactly the double code it replaced and the float instance computes in float throughout.
/// Every derivative is a partial derivative of W(I1, I2, J, I4, I6) w.r.t. the plain invariants
/// (Material.h, Response). No law calls pow: J^(-1/3) comes from invCbrt() (exponent bits plus a
/// division-free Newton refinement), 1/J from (J^(-1/3))^3. Only the laws with a logarithmic
/// volume term need a logarithm (HEML eq. (26)): fastLog(), likewise without libm. Both have a
/// double and a float version, each tuned to its precision; everything is FASCIA_HD.
#include "fascia/base/Hd.h"
#include "fascia/materials/Material.h"

#include <cmath>
#include <cstdint>
#include <cstring>

namespace fascia::materials {

/// x^(-1/3) for finite x > 0, to a few ulp, without libm or division (docs/performance.md, lesson 1):
/// an initial guess from the exponent bits (max relative error 3.4 %) refined by four Newton
/// steps y <- y (4 - x y^3) / 3, whose error squares each step (3.4e-2, 2.3e-3, 1e-5, 2e-10, ~ulp).
/// Vectorises (the bit guess uses int64 <-> double conversions).
FASCIA_HD inline double invCbrt(double x) {
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

/// x^(-1/3) in float for finite normal x > 0, without libm or division: the same bit guess in
/// 32 bits (max relative error 3.4 %, with its own tuned constant), then three Newton steps, one
/// fewer than in double: the error after each is -2 e^2 of the one before (3.4e-2, 2.3e-3, 1.1e-5,
/// 2.2e-10), so after the third only the rounding of the steps is left. The third is written as a
/// correction, y - y/3 (x y^3 - 1), which halves that rounding against the form of the first two.
/// Measured: relative error at most 9.8e-8 (1.7 times float's unit roundoff u = 2^-24) for every
/// float in [1, 8) and sampled from 1e-30 to 1e30 (plugins/materials/tests/TestFloatLaws.cpp).
FASCIA_HD inline float invCbrt(float x) {
    std::int32_t i;
    std::memcpy(&i, &x, sizeof i);
    // bits(x^(-1/3)) ~ 4/3 bits(1.0f) - bits(x)/3 less 0.0662 of 2^23, tuned for the least max
    // error of the guess; computed in float, whose rounding moves the guess by 1e-5 at most
    i = static_cast<std::int32_t>(1419915904.0f - static_cast<float>(i) * (1.0f / 3.0f));
    float y;
    std::memcpy(&y, &i, sizeof y);
    const float x3 = x * (1.0f / 3.0f);
    y = y * (4.0f / 3.0f - x3 * (y * y * y));
    y = y * (4.0f / 3.0f - x3 * (y * y * y));
    const float e = x * (y * y * y) - 1.0f;
    return y - y * (1.0f / 3.0f) * e;
}

/// ln x for finite normal x > 0, to about 1 ulp, without libm (so that element loops vectorise):
/// x = 2^e m with m in [sqrt(1/2), sqrt(2)), ln m = 2 atanh(s), s = (m - 1)/(m + 1), |s| < 0.172,
/// by its odd series to s^21 (truncation below 1e-18).
FASCIA_HD inline double fastLog(double x) {
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

/// ln x in float for finite normal x > 0, without libm: the same reduction in 32 bits
/// (x = 2^e m, m in [sqrt(1/2), sqrt(2))), and with f = m - 1 (exact) and s = f/(2 + f), |s| < 0.172,
/// ln m = 2 atanh(s) = f - s (f - R), R = 2 s^2/3 + 2 s^4/5 + 2 s^6/7 + 2 s^8/9: since 2 s = f - s f,
/// the exact f carries the result and the roundings touch only the smaller s (f - R), which keeps
/// the error near x = 1 relative to ln x itself. The series' first omitted term is below 2.1e-9 of
/// ln m (a thirtieth of float's unit roundoff 2^-24); ln 2 is split in two floats, the first with
/// 15 significant bits, so that e times it is exact. Measured: relative error at most 1.4 u
/// (u = 2^-24) for every float in [1/2, 2), and at most 1.3 u of max(1, |ln x|) sampled from 1e-30
/// to 1e30 (plugins/materials/tests/TestFloatLaws.cpp).
FASCIA_HD inline float fastLog(float x) {
    std::int32_t i;
    std::memcpy(&i, &x, sizeof i);
    std::int32_t e = ((i >> 23) & 0xff) - 127;
    const std::int32_t mi = (i & 0x007fffff) | 0x3f800000;
    float m;
    std::memcpy(&m, &mi, sizeof m);
    const bool big = m > 1.41421356f;
    m = big ? 0.5f * m : m;
    e = big ? e + 1 : e;
    const float f = m - 1.0f;
    const float s = f / (2.0f + f), s2 = s * s;
    const float R = s2 * (2.0f / 3 + s2 * (2.0f / 5 + s2 * (2.0f / 7 + s2 * (2.0f / 9))));
    const float de = static_cast<float>(e);
    return de * 0.693145751953125f + ((f - s * (f - R)) + de * 1.42860682e-06f);
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
    template <class T>
    FASCIA_HD void isochoric(const InvariantsT<T>& in, ResponseT<T>& r) const {
        const T lambda = T(this->lambda), mu = T(this->mu);
        const T a = in.I1 - T(3);
        r.W += T(0.125) * lambda * a * a + T(0.25) * mu * (in.I1 * in.I1 - T(2) * in.I2 - T(2) * in.I1 + T(3));
        r.dI1 += T(0.25) * lambda * a + T(0.5) * mu * (in.I1 - T(1));
        r.dI2 += -T(0.5) * mu;
    }
    template <class T>
    FASCIA_HD void volumetric(T, T& W, T& dW, T& d2W) const { W = dW = d2W = T(0); }
};

/// The HEML paper's "incompressible" neo-Hookean (Table 3): W = C1 (I1 - 3). It has no pressure
/// or volumetric term: nothing resists volume change except through I1, and the rest state is
/// NOT stress-free (S = 2 C1 I at C = I). "Incompressible" only in the paper's sense (the law one
/// would use with an incompressibility constraint, which HEML does not impose).
struct IncompressibleNeoHookeanLaw {
    static constexpr unsigned uses = 0;
    double C1 = 0;  ///< Pa
    bool stressFreeAtRest() const { return false; }
    template <class T>
    FASCIA_HD void isochoric(const InvariantsT<T>& in, ResponseT<T>& r) const {
        const T C1 = T(this->C1);
        r.W += C1 * (in.I1 - T(3));
        r.dI1 += C1;
    }
    template <class T>
    FASCIA_HD void volumetric(T, T& W, T& dW, T& d2W) const { W = dW = d2W = T(0); }
};

/// The HEML paper's "incompressible" Mooney-Rivlin (Table 3): W = C1 (I1 - 3) + C2 (I2 - 3).
/// No volumetric term; not stress-free at rest (S = 2 (C1 + 2 C2) I at C = I).
struct IncompressibleMooneyRivlinLaw {
    static constexpr unsigned uses = BaseMaterial::UsesI2;
    double C1 = 0, C2 = 0;  ///< Pa
    bool stressFreeAtRest() const { return false; }
    template <class T>
    FASCIA_HD void isochoric(const InvariantsT<T>& in, ResponseT<T>& r) const {
        const T C1 = T(this->C1), C2 = T(this->C2);
        r.W += C1 * (in.I1 - T(3)) + C2 * (in.I2 - T(3));
        r.dI1 += C1;
        r.dI2 += C2;
    }
    template <class T>
    FASCIA_HD void volumetric(T, T& W, T& dW, T& d2W) const { W = dW = d2W = T(0); }
};

/// Compressible neo-Hookean of HEML eq. (26): W = C1 (I1 - 3) - mu ln J + lambda/2 (ln J)^2,
/// derivatives eq. (27). Stress-free at rest only when C1 = mu/2 (then it is the classical
/// Simo-Pister / Bonet-Wood neo-Hookean with Lame coefficients lambda, mu).
struct CompressibleNeoHookeanLaw {
    static constexpr unsigned uses = 0;
    double C1 = 0, mu = 0, lambda = 0;  ///< Pa
    bool stressFreeAtRest() const { return C1 == 0.5 * mu; }
    template <class T>
    FASCIA_HD void isochoric(const InvariantsT<T>& in, ResponseT<T>& r) const {
        const T C1 = T(this->C1);
        r.W += C1 * (in.I1 - T(3));
        r.dI1 += C1;
    }
    template <class T>
    FASCIA_HD void volumetric(T J, T& W, T& dW, T& d2W) const {
        const T mu = T(this->mu), lambda = T(this->lambda);
        const T lnJ = fastLog(J), iJ = T(1) / J;
        W = -mu * lnJ + T(0.5) * lambda * lnJ * lnJ;
        dW = (lambda * lnJ - mu) * iJ;  // HEML eq. (27)
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
    template <class T>
    FASCIA_HD void isochoric(const InvariantsT<T>& in, ResponseT<T>& r) const {
        const T C1 = T(this->C1), C2 = T(this->C2);
        const T t = invCbrt(in.J), t2 = t * t, t4 = t2 * t2, iJ = t2 * t;
        const T I1b = in.I1 * t2, I2b = in.I2 * t4;
        r.W += C1 * (I1b - T(3)) + C2 * (I2b - T(3));
        r.dI1 += C1 * t2;
        r.dI2 += C2 * t4;
        r.dJiso += -T(2.0 / 3.0) * (C1 * I1b + T(2) * C2 * I2b) * iJ;
    }
    template <class T>
    FASCIA_HD void volumetric(T J, T& W, T& dW, T& d2W) const {
        const T kappa = T(this->kappa);
        W = T(0.5) * kappa * (J - T(1)) * (J - T(1));
        dW = kappa * (J - T(1));
        d2W = kappa;
    }
};

/// Neo-Hookean with the isochoric split, as in TLED eq. (9), (31)-(32) without the fibre term:
///   W = mu/2 (I1bar - 3) + kappa/2 (J - 1)^2.  Stress-free at rest; shear mu, bulk kappa.
struct NeoHookeanLaw {
    static constexpr unsigned uses = 0;
    double mu = 0, kappa = 0;  ///< Pa
    bool stressFreeAtRest() const { return true; }
    template <class T>
    FASCIA_HD void isochoric(const InvariantsT<T>& in, ResponseT<T>& r) const {
        const T mu = T(this->mu);
        const T t = invCbrt(in.J), t2 = t * t, iJ = t2 * t;
        const T I1b = in.I1 * t2;
        r.W += T(0.5) * mu * (I1b - T(3));
        r.dI1 += T(0.5) * mu * t2;
        r.dJiso += -T(1.0 / 3.0) * mu * I1b * iJ;
    }
    template <class T>
    FASCIA_HD void volumetric(T J, T& W, T& dW, T& d2W) const {
        const T kappa = T(this->kappa);
        W = T(0.5) * kappa * (J - T(1)) * (J - T(1));
        dW = kappa * (J - T(1));
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
    template <class T>
    FASCIA_HD void isochoric(const InvariantsT<T>& in, ResponseT<T>& r) const {
        const T mu = T(this->mu), eta = T(this->eta);
        const T t = invCbrt(in.J), t2 = t * t, iJ = t2 * t;
        const T I1b = in.I1 * t2, I4b = in.I4 * t2, e4 = I4b - T(1);
        r.W += T(0.5) * mu * (I1b - T(3)) + T(0.25) * eta * e4 * e4;
        r.dI1 += T(0.5) * mu * t2;
        r.dI4 += T(0.5) * eta * e4 * t2;
        r.dJiso += -T(1.0 / 3.0) * (mu * I1b + eta * e4 * I4b) * iJ;
    }
    template <class T>
    FASCIA_HD void volumetric(T J, T& W, T& dW, T& d2W) const {
        const T kappa = T(this->kappa);
        W = T(0.5) * kappa * (J - T(1)) * (J - T(1));
        dW = kappa * (J - T(1));
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
    template <class T>
    FASCIA_HD void isochoric(const InvariantsT<T>& in, ResponseT<T>& r) const {
        const T mu = T(this->mu), eta = T(this->eta), eta2 = T(this->eta2);
        const T t = invCbrt(in.J), t2 = t * t, iJ = t2 * t;
        const T I1b = in.I1 * t2, I4b = in.I4 * t2, I6b = in.I6 * t2;
        const T e4 = I4b - T(1), e6 = I6b - T(1);
        r.W += T(0.5) * mu * (I1b - T(3)) + T(0.25) * eta * e4 * e4 + T(0.25) * eta2 * e6 * e6;
        r.dI1 += T(0.5) * mu * t2;
        r.dI4 += T(0.5) * eta * e4 * t2;
        r.dI6 += T(0.5) * eta2 * e6 * t2;
        r.dJiso += -T(1.0 / 3.0) * (mu * I1b + eta * e4 * I4b + eta2 * e6 * I6b) * iJ;
    }
    template <class T>
    FASCIA_HD void volumetric(T J, T& W, T& dW, T& d2W) const {
        const T kappa = T(this->kappa);
        W = T(0.5) * kappa * (J - T(1)) * (J - T(1));
        dW = kappa * (J - T(1));
        d2W = kappa;
    }
};

/// Lame and bulk moduli from Young's modulus E (Pa) and Poisson's ratio nu.
FASCIA_HD inline double lameMu(double E, double nu) { return E / (2.0 * (1.0 + nu)); }
FASCIA_HD inline double lameLambda(double E, double nu) { return E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)); }
FASCIA_HD inline double bulkFromE(double E, double nu) { return E / (3.0 * (1.0 - 2.0 * nu)); }

} // namespace fascia::materials
