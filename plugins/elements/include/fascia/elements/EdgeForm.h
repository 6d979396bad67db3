#pragma once
/// HEML's element math on one tetrahedron (Goulette and Chen 2015, Appendices A-C), written once,
/// templated on the scalar T and FASCIA_HD, for HEMLForceField's vectorised chunk loops
/// (plugins/heml/HEMLKernel.h, called per lane) and the device step's HEML kernel
/// (plugins/cuda/include/fascia/cuda/StepKernels.h). Its variables:
///   ev[k]   the current edge k (edgeA(k) -> edgeB(k)), l_k = |ev[k]|^2 its squared length;
///   D       D(l) = V^T C V of eq. (A.4), the Gram matrix of the edges v1 v2 v3 (Sym33, xx yy zz xy yz xz);
///   G       V^-1 V^-T, 6 numbers per element in the same order: tr C_k = tr(D_k G) and
///           tr(C_i C_j) = tr(D_i G D_j G) (Appendix C), so G replaces the 27 numbers of vtr and Mtr;
///   H       G D G: (Mtr l)_k = tr(D_k H);
///   w       V^-1 a0 for a fibre direction a0: a0.C_k a0 = w.D_k w;
///   g_k     the link coefficients Vol dW/dl_k (eq. (29)); the forces -2 g_k (x_a - x_b) on node a of
///           edge k and the opposite on b (eq. (12)-(13)), plus -Vol dW/dJ dJ/dx (eq. (C.4)).
#include "fascia/elements/Tensor3.h"

#include <algorithm>
#include <cmath>

namespace fascia::elements {

/// Edge k joins local nodes edgeA(k) -> edgeB(k): v1 = x1 - x0, v2 = x2 - x0, v3 = x3 - x0,
/// v4 = v2 - v1, v5 = v3 - v2, v6 = v1 - v3 (HEML eq. (A.2)).
FASCIA_HD constexpr int edgeA(int k) { return k < 3 ? 0 : k - 2; }
FASCIA_HD constexpr int edgeB(int k) { return k < 3 ? k + 1 : (k == 5 ? 1 : k - 1); }

/// The smallest squared length and |J| the edge form divides by: 1e-300 in double, 1e-30 in float
/// (1e-300 would round to 0 there).
template <class T>
FASCIA_HD constexpr T edgeTiny() {
    if constexpr (sizeof(T) == sizeof(float)) return T(1e-30f);
    else return T(1e-300);
}

/// tr(D_k M) for the six D_k of eq. (A.6) and a symmetric M = (M11 M22 M33 M12 M23 M13): the map
/// from a 3x3 tensor in the rest edge basis to the six link coefficients.
template <class T>
FASCIA_HD FASCIA_INLINE void traceDk(T M11, T M22, T M33, T M12, T M23, T M13, T out[6]) {
    out[0] = M11 + M12 + M13;
    out[1] = M22 + M12 + M23;
    out[2] = M33 + M13 + M23;
    out[3] = -M12;
    out[4] = -M23;
    out[5] = -M13;
}

/// det(v1, v2, v3) of the first three edges (times 1/det V: the signed volume ratio J).
template <class T>
FASCIA_HD FASCIA_INLINE T edgeDeterminant(const T ev[6][3]) {
    return ev[0][0] * (ev[1][1] * ev[2][2] - ev[1][2] * ev[2][1]) + ev[0][1] * (ev[1][2] * ev[2][0] - ev[1][0] * ev[2][2]) +
           ev[0][2] * (ev[1][0] * ev[2][1] - ev[1][1] * ev[2][0]);
}

/// D(l) of eq. (A.4) from the squared lengths: D11 = l1, D12 = (l1 + l2 - l4) / 2, ...
template <class T>
FASCIA_HD FASCIA_INLINE Sym33<T> gramOfLengths(const T l[6]) {
    return {l[0], l[1], l[2], T(0.5) * (l[0] + l[1] - l[3]), T(0.5) * (l[1] + l[2] - l[4]), T(0.5) * (l[0] + l[2] - l[5])};
}

/// I1 = tr(D G) and I2 = (I1^2 - tr(D H)) / 2 with H = G D G (eq. (C.1)), H returned (G and H in
/// the order of Sym33).
template <class T>
FASCIA_HD FASCIA_INLINE void edgeInvariants(const Sym33<T>& D, const T G[6], T& I1, T& I2, T H[6]) {
    const T D11 = D.xx, D22 = D.yy, D33 = D.zz, D12 = D.xy, D23 = D.yz, D13 = D.xz;
    const T g11 = G[0], g22 = G[1], g33 = G[2], g12 = G[3], g23 = G[4], g13 = G[5];
    I1 = D11 * g11 + D22 * g22 + D33 * g33 + T(2) * (D12 * g12 + D23 * g23 + D13 * g13);
    const T P11 = g11 * D11 + g12 * D12 + g13 * D13, P12 = g11 * D12 + g12 * D22 + g13 * D23, P13 = g11 * D13 + g12 * D23 + g13 * D33;
    const T P21 = g12 * D11 + g22 * D12 + g23 * D13, P22 = g12 * D12 + g22 * D22 + g23 * D23, P23 = g12 * D13 + g22 * D23 + g23 * D33;
    const T P31 = g13 * D11 + g23 * D12 + g33 * D13, P32 = g13 * D12 + g23 * D22 + g33 * D23, P33 = g13 * D13 + g23 * D23 + g33 * D33;
    H[0] = P11 * g11 + P12 * g12 + P13 * g13;
    H[1] = P21 * g12 + P22 * g22 + P23 * g23;
    H[2] = P31 * g13 + P32 * g23 + P33 * g33;
    H[3] = P11 * g12 + P12 * g22 + P13 * g23;
    H[4] = P21 * g13 + P22 * g23 + P23 * g33;
    H[5] = P11 * g13 + P12 * g23 + P13 * g33;
    const T trC2 = D11 * H[0] + D22 * H[1] + D33 * H[2] + T(2) * (D12 * H[3] + D23 * H[4] + D13 * H[5]);
    I2 = T(0.5) * (I1 * I1 - trC2);
}

/// a0.C a0 = w.D w with w = V^-1 a0 (I4, or I6 with b0).
template <class T>
FASCIA_HD FASCIA_INLINE T edgeFibreInvariant(const Sym33<T>& D, T w1, T w2, T w3) {
    return D.xx * w1 * w1 + D.yy * w2 * w2 + D.zz * w3 * w3 + T(2) * (D.xy * w1 * w2 + D.yz * w2 * w3 + D.xz * w1 * w3);
}

/// The stress in the edge basis Sg = (dI1 + dI2 I1) G - dI2 H, whose g_k = Vol tr(D_k Sg) are
/// Vol (dI1 vtr_k + dI2 (I1 vtr_k - (Mtr l)_k)) (eq. (C.2)-(C.3)); fibres add to it (addFibreTerm).
template <class T>
FASCIA_HD FASCIA_INLINE void edgeStress(const T G[6], const T H[6], T I1, T dI1, T dI2, T Sg[6]) {
    const T a = dI1 + dI2 * I1;
    for (int q = 0; q < 6; ++q) Sg[q] = a * G[q] - dI2 * H[q];
}

/// Sg += s w w^T: a fibre's term s a0.C_k a0 = s w.D_k w (s = dI4 or dI6).
template <class T>
FASCIA_HD FASCIA_INLINE void addFibreTerm(T Sg[6], T w1, T w2, T w3, T s) {
    Sg[0] += s * w1 * w1;
    Sg[1] += s * w2 * w2;
    Sg[2] += s * w3 * w3;
    Sg[3] += s * w1 * w2;
    Sg[4] += s * w2 * w3;
    Sg[5] += s * w1 * w3;
}

/// The link coefficients g_k = Vol tr(D_k Sg).
template <class T>
FASCIA_HD FASCIA_INLINE void linkCoefficients(const T Sg[6], T Vol, T g[6]) {
    traceDk(Sg[0], Sg[1], Sg[2], Sg[3], Sg[4], Sg[5], g);
    for (int k = 0; k < 6; ++k) g[k] *= Vol;
}

/// A spring of stiffness kk and rest length l0 on an edge of squared length L2 (HEML eq. (38); at
/// least edgeTiny: a collapsed edge stays finite): its energy k/2 (l - l0)^2 added to W, and its
/// link coefficient dW/d(l^2) = k/2 (1 - l0 / l).
template <class T>
FASCIA_HD FASCIA_INLINE T springLink(T L2, T kk, T l0, T& W) {
    const T len = std::sqrt(L2 > edgeTiny<T>() ? L2 : edgeTiny<T>());
    W += T(0.5) * kk * (len - l0) * (len - l0);
    return T(0.5) * kk * (T(1) - l0 / len);
}

/// s ln J moved from the isochoric to the volumetric part of the volume terms Qi = Vol dW/dJiso and
/// Qv = Vol dW/dJvol before one of them relaxes (materials/RelaxationSplit.h): Vol s / max(J0, J)
/// (max: finite for crushed elements and padding slots, whose Vol is 0).
template <class T>
FASCIA_HD FASCIA_INLINE void shiftVolumeTerms(T& Qi, T& Qv, T Vol, T shift, T J0, T J) {
    const T q = Vol * shift / std::max(J0, J);
    Qi -= q;
    Qv += q;
}

/// The relaxed part as link coefficients R_k (HEMLForceField.h, HEMLKernel.h relax): wIso g_k plus
/// the relaxed volume term Q through dJ/dl_k = J/2 tr(D^-1 D_k) = tr(D_k invDetV^2 cof(D) / (2 J))
/// (Jacobi's formula; det D = (J det V)^2; |J| at least edgeTiny).
template <class T>
FASCIA_HD FASCIA_INLINE void relaxedLinks(const Sym33<T>& D, T J, T Q, T invDetV, T wIso, const T g[6], T R[6]) {
    constexpr T tiny = edgeTiny<T>();
    const T D11 = D.xx, D22 = D.yy, D33 = D.zz, D12 = D.xy, D23 = D.yz, D13 = D.xz;
    const T iJ = T(1) / (std::abs(J) > tiny ? J : (J < T(0) ? -tiny : tiny));
    const T s = T(0.5) * Q * invDetV * invDetV * iJ;
    T out[6];
    traceDk(s * (D22 * D33 - D23 * D23), s * (D11 * D33 - D13 * D13), s * (D11 * D22 - D12 * D12), s * (D13 * D23 - D12 * D33),
            s * (D12 * D13 - D11 * D23), s * (D12 * D23 - D13 * D22), out);
    for (int k = 0; k < 6; ++k) R[k] = wIso * g[k] + out[k];
}

/// The nodal forces of the element: the links' -2 g_k ev_k on edgeA(k), the opposite on edgeB(k)
/// (eq. (12)-(13), (B.1)-(B.2)), and the volume term -cJ d det(v)/dx_a (eq. (C.4)) with
/// cJ = Vol dW/dJ / det V.
template <class T>
FASCIA_HD FASCIA_INLINE void edgeNodalForces(const T g[6], T cJ, const T ev[6][3], T f[4][3]) {
    for (int a = 0; a < 4; ++a)
        for (int q = 0; q < 3; ++q) f[a][q] = T(0);
    for (int k = 0; k < 6; ++k)
        for (int q = 0; q < 3; ++q) {
            const T t = T(2) * g[k] * ev[k][q];
            f[edgeA(k)][q] += t;
            f[edgeB(k)][q] -= t;
        }
    const T* v1 = ev[0];
    const T* v2 = ev[1];
    const T* v3 = ev[2];
    const T g1[3] = {v2[1] * v3[2] - v2[2] * v3[1], v2[2] * v3[0] - v2[0] * v3[2], v2[0] * v3[1] - v2[1] * v3[0]};
    const T g2[3] = {v3[1] * v1[2] - v3[2] * v1[1], v3[2] * v1[0] - v3[0] * v1[2], v3[0] * v1[1] - v3[1] * v1[0]};
    const T g3[3] = {v1[1] * v2[2] - v1[2] * v2[1], v1[2] * v2[0] - v1[0] * v2[2], v1[0] * v2[1] - v1[1] * v2[0]};
    for (int q = 0; q < 3; ++q) {
        f[1][q] -= cJ * g1[q];
        f[2][q] -= cJ * g2[q];
        f[3][q] -= cJ * g3[q];
        f[0][q] += cJ * (g1[q] + g2[q] + g3[q]);
    }
}

} // namespace fascia::elements
