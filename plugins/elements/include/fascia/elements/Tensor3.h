#pragma once
/// The small 3x3 vocabulary of the element loops, templated on the scalar type T (double on the
/// CPU; float or double in device code later) and written with named scalars, not arrays, so that
/// the batch loops keep everything in registers (docs/performance.md, lessons 1 and 3).
///   Mat33<T>  a general 3x3 matrix, row-major (deformation gradient F, cofactor, P);
///   Sym33<T>  a symmetric one in Voigt order xx yy zz xy yz xz (C, B, S, Cauchy stress).
/// With the law's Response (fascia/materials/Material.h) the second Piola-Kirchhoff stress is
///   S = 2 [dI1 I + dI2 (I1 I - C) + dI4 A0 + dI6 B0] + J (dJiso + dJvol) C^-1     (TLED eq. (10))
/// and, without viscosity, P = F S directly as
///   P = 2 dI1 F + 2 dI2 (I1 F - F C) + 2 dI4 (F a0)(x)a0 + 2 dI6 (F b0)(x)b0 + (dJiso + dJvol) cof F
/// (F J C^-1 = cof F: no inverse, no division).
#include "fascia/elements/Hd.h"

#include <cmath>

namespace fascia::elements {

template <class T>
struct Vec33 {
    T x, y, z;
};

template <class T>
struct Mat33 {
    T xx, xy, xz, yx, yy, yz, zx, zy, zz;
    FASCIA_HD static Mat33 identity() { return {1, 0, 0, 0, 1, 0, 0, 0, 1}; }
};

template <class T>
struct Sym33 {
    T xx, yy, zz, xy, yz, xz;
};

template <class T>
FASCIA_HD FASCIA_INLINE Sym33<T> operator+(const Sym33<T>& a, const Sym33<T>& b) {
    return {a.xx + b.xx, a.yy + b.yy, a.zz + b.zz, a.xy + b.xy, a.yz + b.yz, a.xz + b.xz};
}

/// det F, expanded along the first row.
template <class T>
FASCIA_HD FASCIA_INLINE T det(const Mat33<T>& F) {
    return F.xx * (F.yy * F.zz - F.yz * F.zy) - F.xy * (F.yx * F.zz - F.yz * F.zx) + F.xz * (F.yx * F.zy - F.yy * F.zx);
}

/// The cofactor matrix cof F = det(F) F^-T.
template <class T>
FASCIA_HD FASCIA_INLINE Mat33<T> cofactor(const Mat33<T>& F) {
    return {F.yy * F.zz - F.yz * F.zy, F.yz * F.zx - F.yx * F.zz, F.yx * F.zy - F.yy * F.zx,
            F.xz * F.zy - F.xy * F.zz, F.xx * F.zz - F.xz * F.zx, F.xy * F.zx - F.xx * F.zy,
            F.xy * F.yz - F.xz * F.yy, F.xz * F.yx - F.xx * F.yz, F.xx * F.yy - F.xy * F.yx};
}

/// Right Cauchy-Green tensor C = F^T F.
template <class T>
FASCIA_HD FASCIA_INLINE Sym33<T> rightCauchyGreen(const Mat33<T>& F) {
    return {F.xx * F.xx + F.yx * F.yx + F.zx * F.zx, F.xy * F.xy + F.yy * F.yy + F.zy * F.zy,
            F.xz * F.xz + F.yz * F.yz + F.zz * F.zz, F.xx * F.xy + F.yx * F.yy + F.zx * F.zy,
            F.xy * F.xz + F.yy * F.yz + F.zy * F.zz, F.xx * F.xz + F.yx * F.yz + F.zx * F.zz};
}

/// Left Cauchy-Green tensor B = F F^T.
template <class T>
FASCIA_HD FASCIA_INLINE Sym33<T> leftCauchyGreen(const Mat33<T>& F) {
    return {F.xx * F.xx + F.xy * F.xy + F.xz * F.xz, F.yx * F.yx + F.yy * F.yy + F.yz * F.yz,
            F.zx * F.zx + F.zy * F.zy + F.zz * F.zz, F.xx * F.yx + F.xy * F.yy + F.xz * F.yz,
            F.yx * F.zx + F.yy * F.zy + F.yz * F.zz, F.xx * F.zx + F.xy * F.zy + F.xz * F.zz};
}

/// F a.
template <class T>
FASCIA_HD FASCIA_INLINE Vec33<T> apply(const Mat33<T>& F, Vec33<T> a) {
    return {F.xx * a.x + F.xy * a.y + F.xz * a.z, F.yx * a.x + F.yy * a.y + F.yz * a.z, F.zx * a.x + F.zy * a.y + F.zz * a.z};
}

/// The invariants of C = F^T F that a law reads (I2 only when asked, see BaseMaterial::Uses).
template <class T>
struct Invariants3 {
    T I1, I2, J;
};

/// I1 = tr C, I2 = (I1^2 - tr C^2) / 2 (3 when not wanted), J = det F.
template <bool WithI2, class T>
FASCIA_HD FASCIA_INLINE Invariants3<T> invariants(const Mat33<T>& F) {
    const T C00 = F.xx * F.xx + F.yx * F.yx + F.zx * F.zx;
    const T C11 = F.xy * F.xy + F.yy * F.yy + F.zy * F.zy;
    const T C22 = F.xz * F.xz + F.yz * F.yz + F.zz * F.zz;
    const T I1 = C00 + C11 + C22;
    T I2 = 3;
    if constexpr (WithI2) {
        const T C01 = F.xx * F.xy + F.yx * F.yy + F.zx * F.zy;
        const T C02 = F.xx * F.xz + F.yx * F.yz + F.zx * F.zz;
        const T C12 = F.xy * F.xz + F.yy * F.yz + F.zy * F.zz;
        I2 = T(0.5) * (I1 * I1 - (C00 * C00 + C11 * C11 + C22 * C22 + 2 * (C01 * C01 + C02 * C02 + C12 * C12)));
    }
    return {I1, I2, det(F)};
}

/// a0 . C a0 = |F a0|^2 (I4, or I6 for b0).
template <class T>
FASCIA_HD FASCIA_INLINE T fibreInvariant(const Mat33<T>& F, Vec33<T> a) {
    const Vec33<T> f = apply(F, a);
    return f.x * f.x + f.y * f.y + f.z * f.z;
}

/// The law's response coefficients of one element, as the stress formulas read them.
template <class T>
struct Coefficients {
    T dI1, dI2, dI4, dI6, dJiso, dJvol;
};

/// The floor of |J| in secondPiola: 1e-300 in double; 0 in float, where 1e-300 rounds to 0 (the
/// value the float path has always had: a J of exactly 0 gives an infinite J^-1 there), written
/// apart so that no constant is out of range for T (nvcc's error 221 in device code).
template <class T>
FASCIA_HD FASCIA_INLINE constexpr T jFloor() {
    if constexpr (sizeof(T) >= sizeof(double)) return T(1e-300);
    else return T(0);
}

/// S = Siso + Svol of TLED eq. (10): Siso = 2 [dI1 I + dI2 (I1 I - C) + dI4 A0 + dI6 B0] + J dJiso C^-1
/// and Svol = J dJvol C^-1, with J C^-1 = cof(F)^T cof(F) / J (J floored at jFloor in magnitude).
template <bool UseI2, bool UseI4, bool UseI6, class T>
FASCIA_HD FASCIA_INLINE void secondPiola(const Mat33<T>& F, T I1, T J, const Coefficients<T>& r, Vec33<T> a,
                                         Vec33<T> b, Sym33<T>& Siso, Sym33<T>& Svol) {
    const Mat33<T> cf = cofactor(F);
    const T c1 = 2 * r.dI1;
    constexpr T tiny = jFloor<T>();
    const T iJ = T(1) / (std::abs(J) > tiny ? J : (J < 0 ? -tiny : tiny));
    const Sym33<T> JCi{(cf.xx * cf.xx + cf.yx * cf.yx + cf.zx * cf.zx) * iJ, (cf.xy * cf.xy + cf.yy * cf.yy + cf.zy * cf.zy) * iJ,
                       (cf.xz * cf.xz + cf.yz * cf.yz + cf.zz * cf.zz) * iJ, (cf.xx * cf.xy + cf.yx * cf.yy + cf.zx * cf.zy) * iJ,
                       (cf.xy * cf.xz + cf.yy * cf.yz + cf.zy * cf.zz) * iJ, (cf.xx * cf.xz + cf.yx * cf.yz + cf.zx * cf.zz) * iJ};
    Sym33<T> S{c1, c1, c1, 0, 0, 0};
    if constexpr (UseI2) {
        const T c2 = 2 * r.dI2;
        S.xx += c2 * (I1 - (F.xx * F.xx + F.yx * F.yx + F.zx * F.zx));
        S.yy += c2 * (I1 - (F.xy * F.xy + F.yy * F.yy + F.zy * F.zy));
        S.zz += c2 * (I1 - (F.xz * F.xz + F.yz * F.yz + F.zz * F.zz));
        S.xy -= c2 * (F.xx * F.xy + F.yx * F.yy + F.zx * F.zy);
        S.yz -= c2 * (F.xy * F.xz + F.yy * F.yz + F.zy * F.zz);
        S.xz -= c2 * (F.xx * F.xz + F.yx * F.yz + F.zx * F.zz);
    }
    if constexpr (UseI4) {
        const T c4 = 2 * r.dI4;
        S.xx += c4 * a.x * a.x; S.yy += c4 * a.y * a.y; S.zz += c4 * a.z * a.z;
        S.xy += c4 * a.x * a.y; S.yz += c4 * a.y * a.z; S.xz += c4 * a.x * a.z;
    }
    if constexpr (UseI6) {
        const T c6 = 2 * r.dI6;
        S.xx += c6 * b.x * b.x; S.yy += c6 * b.y * b.y; S.zz += c6 * b.z * b.z;
        S.xy += c6 * b.x * b.y; S.yz += c6 * b.y * b.z; S.xz += c6 * b.x * b.z;
    }
    const T dJi = r.dJiso, dJv = r.dJvol;
    S.xx += dJi * JCi.xx; S.yy += dJi * JCi.yy; S.zz += dJi * JCi.zz;
    S.xy += dJi * JCi.xy; S.yz += dJi * JCi.yz; S.xz += dJi * JCi.xz;
    Siso = S;
    Svol = {dJv * JCi.xx, dJv * JCi.yy, dJv * JCi.zz, dJv * JCi.xy, dJv * JCi.yz, dJv * JCi.xz};
}

/// P = F S for a symmetric S.
template <class T>
FASCIA_HD FASCIA_INLINE Mat33<T> firstPiolaOf(const Mat33<T>& F, const Sym33<T>& S) {
    return {F.xx * S.xx + F.xy * S.xy + F.xz * S.xz, F.xx * S.xy + F.xy * S.yy + F.xz * S.yz, F.xx * S.xz + F.xy * S.yz + F.xz * S.zz,
            F.yx * S.xx + F.yy * S.xy + F.yz * S.xz, F.yx * S.xy + F.yy * S.yy + F.yz * S.yz, F.yx * S.xz + F.yy * S.yz + F.yz * S.zz,
            F.zx * S.xx + F.zy * S.xy + F.zz * S.xz, F.zx * S.xy + F.zy * S.yy + F.zz * S.yz, F.zx * S.xz + F.zy * S.yz + F.zz * S.zz};
}

/// P = dW/dF of the law's response without forming S (see the file comment).
template <bool UseI2, bool UseI4, bool UseI6, class T>
FASCIA_HD FASCIA_INLINE Mat33<T> firstPiola(const Mat33<T>& F, T I1, const Coefficients<T>& r, Vec33<T> a,
                                           Vec33<T> b) {
    const T c1 = 2 * r.dI1, cj = r.dJiso + r.dJvol;
    Mat33<T> P{c1 * F.xx + cj * (F.yy * F.zz - F.yz * F.zy), c1 * F.xy + cj * (F.yz * F.zx - F.yx * F.zz),
               c1 * F.xz + cj * (F.yx * F.zy - F.yy * F.zx), c1 * F.yx + cj * (F.xz * F.zy - F.xy * F.zz),
               c1 * F.yy + cj * (F.xx * F.zz - F.xz * F.zx), c1 * F.yz + cj * (F.xy * F.zx - F.xx * F.zy),
               c1 * F.zx + cj * (F.xy * F.yz - F.xz * F.yy), c1 * F.zy + cj * (F.xz * F.yx - F.xx * F.yz),
               c1 * F.zz + cj * (F.xx * F.yy - F.xy * F.yx)};
    if constexpr (UseI2) {
        // I1 F - F C with F C = (F F^T) F
        const T c2 = 2 * r.dI2;
        const Sym33<T> B = leftCauchyGreen(F);
        P.xx += c2 * (I1 * F.xx - (B.xx * F.xx + B.xy * F.yx + B.xz * F.zx));
        P.xy += c2 * (I1 * F.xy - (B.xx * F.xy + B.xy * F.yy + B.xz * F.zy));
        P.xz += c2 * (I1 * F.xz - (B.xx * F.xz + B.xy * F.yz + B.xz * F.zz));
        P.yx += c2 * (I1 * F.yx - (B.xy * F.xx + B.yy * F.yx + B.yz * F.zx));
        P.yy += c2 * (I1 * F.yy - (B.xy * F.xy + B.yy * F.yy + B.yz * F.zy));
        P.yz += c2 * (I1 * F.yz - (B.xy * F.xz + B.yy * F.yz + B.yz * F.zz));
        P.zx += c2 * (I1 * F.zx - (B.xz * F.xx + B.yz * F.yx + B.zz * F.zx));
        P.zy += c2 * (I1 * F.zy - (B.xz * F.xy + B.yz * F.yy + B.zz * F.zy));
        P.zz += c2 * (I1 * F.zz - (B.xz * F.xz + B.yz * F.yz + B.zz * F.zz));
    }
    const auto fibre = [&](T c, Vec33<T> d) {
        const T f0 = c * (F.xx * d.x + F.xy * d.y + F.xz * d.z), f1 = c * (F.yx * d.x + F.yy * d.y + F.yz * d.z),
                f2 = c * (F.zx * d.x + F.zy * d.y + F.zz * d.z);
        P.xx += f0 * d.x; P.xy += f0 * d.y; P.xz += f0 * d.z;
        P.yx += f1 * d.x; P.yy += f1 * d.y; P.yz += f1 * d.z;
        P.zx += f2 * d.x; P.zy += f2 * d.y; P.zz += f2 * d.z;
    };
    if constexpr (UseI4) fibre(2 * r.dI4, a);
    if constexpr (UseI6) fibre(2 * r.dI6, b);
    return P;
}

/// Cauchy stress F S F^T / J.
template <class T>
FASCIA_HD FASCIA_INLINE Sym33<T> cauchyStress(const Mat33<T>& F, const Sym33<T>& S, T J) {
    const Mat33<T> P = firstPiolaOf(F, S);
    return {(P.xx * F.xx + P.xy * F.xy + P.xz * F.xz) / J, (P.yx * F.yx + P.yy * F.yy + P.yz * F.yz) / J,
            (P.zx * F.zx + P.zy * F.zy + P.zz * F.zz) / J, (P.xx * F.yx + P.xy * F.yy + P.xz * F.yz) / J,
            (P.yx * F.zx + P.yy * F.zy + P.yz * F.zz) / J, (P.xx * F.zx + P.xy * F.zy + P.xz * F.zz) / J};
}

/// von Mises stress of a (Cauchy) stress sqrt(((s11 - s22)^2 + (s22 - s33)^2 + (s33 - s11)^2) / 2 + 3 (s12^2 + s23^2 + s13^2)).
template <class T>
FASCIA_HD FASCIA_INLINE T vonMises(const Sym33<T>& s) {
    const T a = s.xx - s.yy, b = s.yy - s.zz, c = s.zz - s.xx;
    return std::sqrt(T(0.5) * (a * a + b * b + c * c) + 3 * (s.xy * s.xy + s.yz * s.yz + s.xz * s.xz));
}

} // namespace fascia::elements
