#pragma once
/// Hourglass control of the 8-node uniform-strain hexahedron (Flanagan-Belytschko 1981), one element
/// at a time, written once for TLEDForceField's batch loop (plugins/tled/TLEDKernel.h, element k of
/// a batch of kBatch) and the device step's element kernel (plugins/cuda/include/fascia/cuda/StepKernels.h,
/// one element in registers, Batch = 1). With the base vectors h_q (kHourglass, Geometry.h) and
/// c_q = sum_b h_qb X_b (hexHourglassVectors), gamma_qa = h_qa - c_q . dN_a/dX and
///   h_q = sum_a gamma_qa u_a = sum_a h_qa u_a - (F - I) c_q,   energy K/2 sum_q |h_q|^2,
///   f_a = -V P dN_a/dX - K sum_q gamma_qa h_q = -(V P - M) dN_a/dX - K sum_q h_qa h_q,
/// M = K sum_q h_q (x) c_q. The sums over the nodes with the +-1 entries of kHourglass are written as
/// sums and differences of node pairs. The hourglass displacements h_q are rows of a batch,
/// h[(3 q + j) Batch + k] for component j of element k.
#include "fascia/elements/BatchView.h"

// the CPU loops need the small loops below unrolled (a loop left over the nodes turns the dN loads
// into emulated gathers); nvcc unrolls them itself
#if defined(__CUDACC__)
#define FASCIA_HG_UNROLL(n)
#else
#define FASCIA_HG_PRAGMA(x) _Pragma(#x)
#define FASCIA_HG_UNROLL(n) FASCIA_HG_PRAGMA(GCC unroll n)
#endif

namespace fascia::elements {

/// Component j of the four hourglass displacements h_q of element k, into h[(3 q + j) Batch + k];
/// g = row j of F - I.
template <int Batch, class T>
FASCIA_HD FASCIA_INLINE void hourglassModes(const NodalBatch<8, Batch, T>& uv, const NodeRows<Batch, T>& c, int k, int j, T g0, T g1,
                                            T g2, T* __restrict h) {
    const auto& u = uv.v;
    const T d01 = u[0][j][k] - u[1][j][k], d23 = u[2][j][k] - u[3][j][k], d45 = u[4][j][k] - u[5][j][k],
            d67 = u[6][j][k] - u[7][j][k];
    const T a01 = u[0][j][k] + u[1][j][k], a23 = u[2][j][k] + u[3][j][k], a45 = u[4][j][k] + u[5][j][k],
            a67 = u[6][j][k] + u[7][j][k];
    const T X = d01 + d23, Y = d45 + d67;
    h[j * Batch + k] = (X + Y) - (g0 * c.at(0, 0, k) + g1 * c.at(0, 1, k) + g2 * c.at(0, 2, k));                    // ( 1,-1, 1,-1, 1,-1, 1,-1)
    h[(3 + j) * Batch + k] = (a01 - a23) + (a67 - a45) - (g0 * c.at(1, 0, k) + g1 * c.at(1, 1, k) + g2 * c.at(1, 2, k));  // ( 1, 1,-1,-1,-1,-1, 1, 1)
    h[(6 + j) * Batch + k] = (d01 - d23) + (d67 - d45) - (g0 * c.at(2, 0, k) + g1 * c.at(2, 1, k) + g2 * c.at(2, 2, k));  // ( 1,-1,-1, 1,-1, 1, 1,-1)
    h[(9 + j) * Batch + k] = (Y - X) - (g0 * c.at(3, 0, k) + g1 * c.at(3, 1, k) + g2 * c.at(3, 2, k));              // (-1, 1,-1, 1, 1,-1, 1,-1)
}

/// All three components of the hourglass displacements of element k from F (after the gradient).
template <int Batch, class T>
FASCIA_HD FASCIA_INLINE void hourglassModes(const NodalBatch<8, Batch, T>& u, const NodeRows<Batch, T>& c, int k, const Mat33<T>& F,
                                            T* __restrict h) {
    hourglassModes(u, c, k, 0, F.xx - 1, F.xy, F.xz, h);
    hourglassModes(u, c, k, 1, F.yx, F.yy - 1, F.yz, h);
    hourglassModes(u, c, k, 2, F.zx, F.zy, F.zz - 1, h);
}

/// The nodal forces of hexahedron k: VP = V P (P the first Piola-Kirchhoff stress of its uniform
/// strain), K its hourglass stiffness, h its hourglass displacements (hourglassModes), c its c_q,
/// dN its dN_a/dX; f_a into f (see the file comment; TLED eq. (3) for the uniform part).
template <int Batch, class T>
FASCIA_HD FASCIA_INLINE void hexNodalForces(const Mat33<T>& VP, T K, const NodeRows<Batch, T>& h, const NodeRows<Batch, T>& c,
                                            const NodeRows<Batch, T>& dN, int k, NodalBatch<8, Batch, T>& f) {
    T P0 = VP.xx, P1 = VP.xy, P2 = VP.xz, P3 = VP.yx, P4 = VP.yy, P5 = VP.yz, P6 = VP.zx, P7 = VP.zy, P8 = VP.zz;
    T r[3][8];  // K sum_q h_qa h_q per component, the pair sums of hourglassModes reversed
    FASCIA_HG_UNROLL(3)
    for (int j = 0; j < 3; ++j) {
        const T g0 = K * h.at(0, j, k), g1 = K * h.at(1, j, k), g2 = K * h.at(2, j, k), g3 = K * h.at(3, j, k);
        const T p = g0 + g2, m = g0 - g2, sp = g1 + g3, sm = g1 - g3;
        r[j][0] = p + sm;
        r[j][1] = sp - p;
        r[j][2] = m - sp;
        r[j][3] = -m - sm;
        r[j][4] = m - sm;
        r[j][5] = -m - sp;
        r[j][6] = p + sp;
        r[j][7] = sm - p;
    }
    FASCIA_HG_UNROLL(4)
    for (int q = 0; q < 4; ++q) {
        const T c0 = c.at(q, 0, k), c1 = c.at(q, 1, k), c2 = c.at(q, 2, k);
        const T k0 = K * h.at(q, 0, k), k1 = K * h.at(q, 1, k), k2 = K * h.at(q, 2, k);
        P0 -= k0 * c0; P1 -= k0 * c1; P2 -= k0 * c2;
        P3 -= k1 * c0; P4 -= k1 * c1; P5 -= k1 * c2;
        P6 -= k2 * c0; P7 -= k2 * c1; P8 -= k2 * c2;
    }
    // (fully unrolled: a loop left over the nodes turns the dN loads into emulated gathers)
    FASCIA_HG_UNROLL(8)
    for (int a = 0; a < 8; ++a) {
        const T g0 = dN.at(a, 0, k), g1 = dN.at(a, 1, k), g2 = dN.at(a, 2, k);
        f.v[a][0][k] = -(P0 * g0 + P1 * g1 + P2 * g2) - r[0][a];
        f.v[a][1][k] = -(P3 * g0 + P4 * g1 + P5 * g2) - r[1][a];
        f.v[a][2][k] = -(P6 * g0 + P7 * g1 + P8 * g2) - r[2][a];
    }
}

} // namespace fascia::elements
