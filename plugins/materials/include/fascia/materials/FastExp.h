#pragma once
/// e^x and (e^x - 1)/x without libm, in the style of invCbrt() and fastLog() (Laws.h), so that
/// element loops with exponential laws (HolzapfelGasserOgdenLaw) still vectorise; in double and in
/// float, each with its series length chosen for its precision, and FASCIA_HD (fascia/base/Hd.h).
#include "fascia/base/Hd.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace fascia::materials {

/// e^x to about 1 ulp, without libm or branches. x = n ln 2 + r with n = round(x / ln 2) (by the
/// 1.5 * 2^52 shifter, whose low mantissa bits then hold n), r = x - n ln 2 in two parts
/// (Cody-Waite: n ln2hi is exact), |r| <= ln(2)/2, e^r by its Taylor series to r^13 (truncation
/// below 5e-18 relative), and 2^n put into the exponent bits. x is clamped to [-708, 708] so
/// that 2^n stays a normal number: above 708 the result is e^708 (~3e307) instead of overflowing.
FASCIA_HD inline double fastExp(double x) {
    x = std::min(std::max(x, -708.0), 708.0);
    const double shifter = 6755399441055744.0;  // 1.5 * 2^52
    const double t = x * 1.4426950408889634 + shifter;
    const double n = t - shifter;
    const double r = (x - n * 6.93147180369123816490e-01) - n * 1.90821492927058770002e-10;
    // Horner from the highest term: 1/k!, k = 13 .. 0
    double p = 1.0 / 6227020800.0;
    p = p * r + 1.0 / 479001600.0;
    p = p * r + 1.0 / 39916800.0;
    p = p * r + 1.0 / 3628800.0;
    p = p * r + 1.0 / 362880.0;
    p = p * r + 1.0 / 40320.0;
    p = p * r + 1.0 / 5040.0;
    p = p * r + 1.0 / 720.0;
    p = p * r + 1.0 / 120.0;
    p = p * r + 1.0 / 24.0;
    p = p * r + 1.0 / 6.0;
    p = p * r + 0.5;
    p = p * r + 1.0;
    p = p * r + 1.0;
    std::int64_t i, s0;
    std::memcpy(&i, &t, sizeof i);
    std::memcpy(&s0, &shifter, sizeof s0);
    const std::int64_t bits = (i - s0 + 1023) << 52;  // i - s0 = n
    double scale;
    std::memcpy(&scale, &bits, sizeof scale);
    return p * scale;
}

/// e^x in float without libm or branches, as the double version: n = round(x / ln 2) by the
/// 1.5 * 2^23 shifter, r = x - n ln 2 in two parts (the first, with 15 significant bits, times n
/// is exact), |r| <= ln(2)/2, e^r by its Taylor series to r^7 (the first omitted term r^8/8! is
/// below 7.4e-9 of e^r, an eighth of float's unit roundoff 2^-24), and 2^n put into the exponent
/// bits. x is clamped to [-87, 87] so that 2^n stays a normal float: above 87 the result is e^87
/// (~6e37) instead of overflowing. Measured: relative error at most 1.3 u (7.7e-8) sampled from
/// -87 to 87 (plugins/materials/tests/TestFloatLaws.cpp).
FASCIA_HD inline float fastExp(float x) {
    x = std::min(std::max(x, -87.0f), 87.0f);
    const float shifter = 12582912.0f;  // 1.5 * 2^23
    const float t = x * 1.44269504f + shifter;
    const float n = t - shifter;
    const float r = (x - n * 0.693145751953125f) - n * 1.42860682e-06f;
    // Horner from the highest term: 1/k!, k = 7 .. 0
    float p = 1.0f / 5040.0f;
    p = p * r + 1.0f / 720.0f;
    p = p * r + 1.0f / 120.0f;
    p = p * r + 1.0f / 24.0f;
    p = p * r + 1.0f / 6.0f;
    p = p * r + 0.5f;
    p = p * r + 1.0f;
    p = p * r + 1.0f;
    std::int32_t i, s0;
    std::memcpy(&i, &t, sizeof i);
    std::memcpy(&s0, &shifter, sizeof s0);
    const std::int32_t bits = (i - s0 + 127) << 23;  // i - s0 = n
    float scale;
    std::memcpy(&scale, &bits, sizeof scale);
    return p * scale;
}

/// (e^x - 1)/x (1 at x = 0) to a few ulp, without cancellation near 0: for |x| < 1/2 its series
/// sum_k x^k/(k+1)! to x^14 (truncation below 2e-18), else (fastExp(x) - 1)/x. Branch-free (both
/// are computed, one is selected), so it vectorises.
FASCIA_HD inline double fastExprel(double x) {
    // Horner from the highest term: 1/(k+1)!, k = 14 .. 0
    double s = 1.0 / 1307674368000.0;
    s = s * x + 1.0 / 87178291200.0;
    s = s * x + 1.0 / 6227020800.0;
    s = s * x + 1.0 / 479001600.0;
    s = s * x + 1.0 / 39916800.0;
    s = s * x + 1.0 / 3628800.0;
    s = s * x + 1.0 / 362880.0;
    s = s * x + 1.0 / 40320.0;
    s = s * x + 1.0 / 5040.0;
    s = s * x + 1.0 / 720.0;
    s = s * x + 1.0 / 120.0;
    s = s * x + 1.0 / 24.0;
    s = s * x + 1.0 / 6.0;
    s = s * x + 0.5;
    s = s * x + 1.0;
    const bool small = std::abs(x) < 0.5;
    const double big = (fastExp(x) - 1.0) / (small ? 1.0 : x);
    return small ? s : big;
}

/// (e^x - 1)/x in float (1 at x = 0), as the double version: for |x| < 1/2 its series
/// sum_k x^k/(k+1)! to x^7 (the first omitted term x^8/9! is below 1.4e-8 of the sum, a quarter of
/// float's unit roundoff), else (fastExp(x) - 1)/x, whose cancellation at |x| >= 1/2 costs a factor
/// 1.6 at most. Branch-free. Measured: relative error at most 2.7 u (1.6e-7) sampled from -20 to 20
/// and from 1e-30 to 1 on both sides of 0 (plugins/materials/tests/TestFloatLaws.cpp).
FASCIA_HD inline float fastExprel(float x) {
    // Horner from the highest term: 1/(k+1)!, k = 7 .. 0
    float s = 1.0f / 40320.0f;
    s = s * x + 1.0f / 5040.0f;
    s = s * x + 1.0f / 720.0f;
    s = s * x + 1.0f / 120.0f;
    s = s * x + 1.0f / 24.0f;
    s = s * x + 1.0f / 6.0f;
    s = s * x + 0.5f;
    s = s * x + 1.0f;
    const bool small = std::abs(x) < 0.5f;
    const float big = (fastExp(x) - 1.0f) / (small ? 1.0f : x);
    return small ? s : big;
}

} // namespace fascia::materials
