#pragma once
/// The libm-free x^(-1/3) and ln x of element loops (docs/performance.md, lesson 1), each with a
/// double and a float version tuned to its precision, FASCIA_HD for the device step: numerics, no
/// physics, so in the core beside Simd.h, where the laws (materials/Laws.h, which re-exports them
/// as materials::invCbrt and materials::fastLog) and the benchmark's reference kernel both take them.
#include "fascia/base/Hd.h"

#include <cstdint>
#include <cstring>

namespace fascia::core {

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

} // namespace fascia::core
