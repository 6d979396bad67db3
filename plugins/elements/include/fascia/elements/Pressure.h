#pragma once
/// The follower pressure of a face, -p n dA on its corners (SurfacePressure), as host/device
/// functions on the scalar T: SurfacePressure (plugins/mechanics) and the device step
/// (plugins/cuda) call these, so that the face math is written once (docs/design.md, principle 9).
/// Both take the corners relative to the first one, d_a = x_a - x_0: the forces depend on
/// differences only, so that the device step forms them from its displacements (rest differences
/// plus u_a - u_0) without the digits a float position far from the origin would lose.
#include "fascia/elements/Tensor3.h"

namespace fascia::elements {

/// The force on each corner of a triangle under the pressure p (Pa), its edges e1 = x1 - x0 and
/// e2 = x2 - x0 turned outwards (counterclockwise seen from outside): -p A n / 3 = -(p / 6) e1 x e2.
template <class T>
FASCIA_HD FASCIA_INLINE Vec33<T> trianglePressureForce(const Vec33<T>& e1, const Vec33<T>& e2, T p) {
    const T s = -p / T(6);
    return {s * (e1.y * e2.z - e1.z * e2.y), s * (e1.z * e2.x - e1.x * e2.z), s * (e1.x * e2.y - e1.y * e2.x)};
}

/// The corner forces of a quadrilateral under the pressure p (Pa), its corners counterclockwise seen
/// from outside, d[a] = x_a - x_0 (d[0] = 0): the bilinear patch x(xi, eta) = sum_a N_a x_a on
/// [-1, 1]^2, f_a = -p int N_a (dx/dxi x dx/deta) dxi deta, which 2x2 Gauss points of weight 1
/// integrate exactly (the integrand is of degree 2 in xi and in eta). The derivatives' weights sum to
/// zero, so the patch's d_a give them as its x_a would.
template <class T>
FASCIA_HD FASCIA_INLINE void quadPressureForces(const Vec33<T> d[4], T p, Vec33<T> f[4]) {
    const T xi[4] = {-1, 1, 1, -1}, eta[4] = {-1, -1, 1, 1};
    const T g = T(0.57735026918962576451);  // 1 / sqrt(3)
    for (int a = 0; a < 4; ++a) f[a] = {0, 0, 0};
    for (int q = 0; q < 4; ++q) {
        const T s = xi[q] * g, t = eta[q] * g;
        Vec33<T> dxi{0, 0, 0}, deta{0, 0, 0};
        for (int a = 1; a < 4; ++a) {
            const T wx = T(0.25) * xi[a] * (1 + eta[a] * t), we = T(0.25) * eta[a] * (1 + xi[a] * s);
            dxi = {dxi.x + wx * d[a].x, dxi.y + wx * d[a].y, dxi.z + wx * d[a].z};
            deta = {deta.x + we * d[a].x, deta.y + we * d[a].y, deta.z + we * d[a].z};
        }
        const Vec33<T> n{dxi.y * deta.z - dxi.z * deta.y, dxi.z * deta.x - dxi.x * deta.z, dxi.x * deta.y - dxi.y * deta.x};
        for (int a = 0; a < 4; ++a) {
            const T w = -p * T(0.25) * (1 + xi[a] * s) * (1 + eta[a] * t);
            f[a] = {f[a].x + w * n.x, f[a].y + w * n.y, f[a].z + w * n.z};
        }
    }
}

} // namespace fascia::elements
