#pragma once
/// Typed views of element data stored as structure of arrays in batches: row r of a batch of
/// `Batch` elements holds one number per element, at r * Batch + k for element k. The views name
/// the rows (node a, component i) so that the loops read dN.at(a, i, k) instead of computing
/// strides by hand; they compile to the same constant offsets.
#include "fascia/elements/Hd.h"
#include "fascia/elements/Tensor3.h"

namespace fascia::elements {

/// Rows of 3 numbers per node (shape-function derivatives dN_a/dX, hourglass vectors, fibres).
template <int Batch, class T = double>
struct NodeRows {
    const T* __restrict p;
    /// component i (0..2) of node a, element k
    FASCIA_HD FASCIA_INLINE T at(int a, int i, int k) const { return p[(3 * a + i) * Batch + k]; }
    /// node a of element k as a vector
    FASCIA_HD FASCIA_INLINE Vec33<T> vec(int a, int k) const { return {at(a, 0, k), at(a, 1, k), at(a, 2, k)}; }
    /// the rows from node a on
    FASCIA_HD FASCIA_INLINE NodeRows from(int a) const { return {p + 3 * a * Batch}; }
};

/// Nodal vectors of the elements of a batch, u[a][i][k] (displacements, forces).
template <int NN, int Batch, class T = double>
struct NodalBatch {
    alignas(64) T v[NN][3][Batch];
    FASCIA_HD FASCIA_INLINE Vec33<T> vec(int a, int k) const { return {v[a][0][k], v[a][1][k], v[a][2][k]}; }
    FASCIA_HD FASCIA_INLINE void set(int a, int k, Vec33<T> f) {
        v[a][0][k] = f.x;
        v[a][1][k] = f.y;
        v[a][2][k] = f.z;
    }
};

/// A 3x3 matrix per element of a batch, row-major rows m[0..8][k].
template <int Batch, class T = double>
struct MatBatch {
    alignas(64) T m[9][Batch];
    FASCIA_HD FASCIA_INLINE Mat33<T> get(int k) const {
        return {m[0][k], m[1][k], m[2][k], m[3][k], m[4][k], m[5][k], m[6][k], m[7][k], m[8][k]};
    }
    FASCIA_HD FASCIA_INLINE void set(int k, const Mat33<T>& F) {
        m[0][k] = F.xx; m[1][k] = F.xy; m[2][k] = F.xz;
        m[3][k] = F.yx; m[4][k] = F.yy; m[5][k] = F.yz;
        m[6][k] = F.zx; m[7][k] = F.zy; m[8][k] = F.zz;
    }
};

/// A symmetric matrix per element of a batch, Voigt rows s[0..5][k] (xx yy zz xy yz xz).
template <int Batch, class T = double>
struct SymBatch {
    alignas(64) T s[6][Batch];
    FASCIA_HD FASCIA_INLINE Sym33<T> get(int k) const { return {s[0][k], s[1][k], s[2][k], s[3][k], s[4][k], s[5][k]}; }
    FASCIA_HD FASCIA_INLINE void set(int k, const Sym33<T>& S) {
        s[0][k] = S.xx; s[1][k] = S.yy; s[2][k] = S.zz;
        s[3][k] = S.xy; s[4][k] = S.yz; s[5][k] = S.xz;
    }
};

/// The law's response for a batch (what materials::Response holds, as rows).
template <int Batch, class T = double>
struct ResponseBatch {
    alignas(64) T W[Batch], d1[Batch], d2[Batch], d4[Batch], d6[Batch], dJi[Batch], dJv[Batch];
    FASCIA_HD FASCIA_INLINE Coefficients<T> coefficients(int k) const { return {d1[k], d2[k], d4[k], d6[k], dJi[k], dJv[k]}; }
};

/// Deformation gradient F = I + sum_a u_a (x) dN_a/dX of element k (NN nodes).
template <int NN, int Batch, class T>
FASCIA_HD FASCIA_INLINE Mat33<T> deformationGradient(const NodalBatch<NN, Batch, T>& u, const NodeRows<Batch, T>& dN, int k) {
    Mat33<T> F = Mat33<T>::identity();
    for (int a = 0; a < NN; ++a) {
        const T g0 = dN.at(a, 0, k), g1 = dN.at(a, 1, k), g2 = dN.at(a, 2, k);
        const T v0 = u.v[a][0][k], v1 = u.v[a][1][k], v2 = u.v[a][2][k];
        F.xx += v0 * g0; F.xy += v0 * g1; F.xz += v0 * g2;
        F.yx += v1 * g0; F.yy += v1 * g1; F.yz += v1 * g2;
        F.zx += v2 * g0; F.zy += v2 * g1; F.zz += v2 * g2;
    }
    return F;
}

/// The same for a linear tetrahedron whose rows hold dN_1..dN_3 only (dN_0 = -(dN_1 + dN_2 + dN_3)):
/// sum_a u_a dN_a = sum_{a>0} (u_a - u_0) dN_a.
template <int Batch, class T>
FASCIA_HD FASCIA_INLINE Mat33<T> deformationGradientTet(const NodalBatch<4, Batch, T>& u, const NodeRows<Batch, T>& dN123, int k) {
    Mat33<T> F = Mat33<T>::identity();
    for (int a = 1; a < 4; ++a) {
        const T g0 = dN123.at(a - 1, 0, k), g1 = dN123.at(a - 1, 1, k), g2 = dN123.at(a - 1, 2, k);
        const T v0 = u.v[a][0][k] - u.v[0][0][k], v1 = u.v[a][1][k] - u.v[0][1][k], v2 = u.v[a][2][k] - u.v[0][2][k];
        F.xx += v0 * g0; F.xy += v0 * g1; F.xz += v0 * g2;
        F.yx += v1 * g0; F.yy += v1 * g1; F.yz += v1 * g2;
        F.zx += v2 * g0; F.zy += v2 * g1; F.zz += v2 * g2;
    }
    return F;
}

/// -P g: the force on a node with shape-function gradient g (P already scaled by the volume).
template <class T>
FASCIA_HD FASCIA_INLINE Vec33<T> nodalForce(const Mat33<T>& P, T g0, T g1, T g2) {
    return {-(P.xx * g0 + P.xy * g1 + P.xz * g2), -(P.yx * g0 + P.yy * g1 + P.yz * g2), -(P.zx * g0 + P.zy * g1 + P.zz * g2)};
}

} // namespace fascia::elements
