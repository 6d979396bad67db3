#pragma once
/// The bodies of the device step's two kernels, as host/device functions (FASCIA_HD) over the
/// layout of StepLayout.h: the GPU wraps each in a __global__ launch (CudaRunner.cu, one thread per
/// element or node), the CPU emulation calls them in loops (EmulatedRunner.h). The element math is
/// the element layer's and the laws' (Tensor3.h, BatchView.h, materials::evaluateLaw): nothing of
/// it is written again here (docs/design.md, principle 9).
///   element kernel: gather u of its 4 nodes -> F from dN/dX (TLED eq. (1)) -> invariants -> the
///     law's response (evaluateLaw: HEML section 4.4 below J0) -> P (Tensor3.h firstPiola) ->
///     f_a = -V P dN_a/dX (TLED eq. (3)), written to the element's own 4 slots;
///   node kernel: the sum of its (element, corner) slots in their fixed order, + external force
///     + m g, held axes zeroed, then v += kick (f/m - alpha v), u += dt v (HEML eq. (32)), held
///     axes at rest (u = v = 0).
#include "fascia/cuda/StepLayout.h"
#include "fascia/elements/BatchView.h"
#include "fascia/materials/Material.h"

namespace fascia::cuda {

/// The forces of tetrahedron e on its 4 corners, written to ef (its own slots).
template <class Law, class T>
FASCIA_HD FASCIA_INLINE void elementForces(const StepArrays<T>& d, const ElementParams<Law, T>& p, int e) {
    using materials::BaseMaterial;
    constexpr bool i2 = (Law::uses & BaseMaterial::UsesI2) != 0, i4 = (Law::uses & BaseMaterial::UsesI4) != 0,
                   i6 = (Law::uses & BaseMaterial::UsesI6) != 0;
    const int n = d.nTets;
    elements::NodalBatch<4, 1, T> u;
    for (int a = 0; a < 4; ++a) {
        const int node = d.tet[a * n + e];
        for (int i = 0; i < 3; ++i) u.v[a][i][0] = d.u[3 * node + i];
    }
    T g[9];
    for (int r = 0; r < 9; ++r) g[r] = d.dN[r * n + e];
    const elements::NodeRows<1, T> dN{g};
    const elements::Mat33<T> F = elements::deformationGradientTet(u, dN, 0);
    const elements::Invariants3<T> iv = elements::invariants<i2>(F);
    materials::InvariantsT<T> in;
    in.I1 = iv.I1;
    in.I2 = iv.I2;
    in.J = iv.J;
    if constexpr (i4) in.I4 = elements::fibreInvariant(F, p.a0);
    if constexpr (i6) in.I6 = elements::fibreInvariant(F, p.b0);
    materials::ResponseT<T> r;
    materials::evaluateLaw(p.law, in, static_cast<double>(p.J0), r);
    const elements::Coefficients<T> c{r.dI1, r.dI2, r.dI4, r.dI6, r.dJiso, r.dJvol};
    const elements::Mat33<T> P0 = elements::firstPiola<i2, i4, i6>(F, in.I1, c, p.a0, p.b0);
    const T V = d.vol[e];
    const elements::Mat33<T> P{V * P0.xx, V * P0.xy, V * P0.xz, V * P0.yx, V * P0.yy, V * P0.yz, V * P0.zx, V * P0.zy, V * P0.zz};
    T s0 = 0, s1 = 0, s2 = 0;
    for (int a = 1; a < 4; ++a) {
        const elements::Vec33<T> f = elements::nodalForce(P, dN.at(a - 1, 0, 0), dN.at(a - 1, 1, 0), dN.at(a - 1, 2, 0));
        d.ef[(3 * a + 0) * n + e] = f.x;
        d.ef[(3 * a + 1) * n + e] = f.y;
        d.ef[(3 * a + 2) * n + e] = f.z;
        s0 += f.x;
        s1 += f.y;
        s2 += f.z;
    }
    d.ef[0 * n + e] = -s0;
    d.ef[1 * n + e] = -s1;
    d.ef[2 * n + e] = -s2;
}

/// The internal force on node `node`: its slots summed in their fixed order.
template <class T>
FASCIA_HD FASCIA_INLINE elements::Vec33<T> gatherForce(const StepArrays<T>& d, int node) {
    T f0 = 0, f1 = 0, f2 = 0;
    const int n = d.nTets;
    for (int k = d.slotStart[node]; k < d.slotStart[node + 1]; ++k) {
        const std::uint32_t s = d.slots[k];
        const int e = static_cast<int>(s >> 2), a = static_cast<int>(s & 3u);
        f0 += d.ef[(3 * a + 0) * n + e];
        f1 += d.ef[(3 * a + 1) * n + e];
        f2 += d.ef[(3 * a + 2) * n + e];
    }
    return {f0, f1, f2};
}

/// One step of node `node`: forces, constraints, SemiImplicitEuler's update (HEML eq. (32)).
template <class T>
FASCIA_HD FASCIA_INLINE void nodeStep(const StepArrays<T>& d, const NodeParams<T>& p, int node) {
    const elements::Vec33<T> fi = gatherForce(d, node);
    const T m = d.mass[node], im = d.invMass[node];
    const T f[3] = {fi.x + d.ext[3 * node + 0] + m * p.g[0], fi.y + d.ext[3 * node + 1] + m * p.g[1],
                    fi.z + d.ext[3 * node + 2] + m * p.g[2]};
    const unsigned held = d.fixed[node];
    for (int i = 0; i < 3; ++i) {
        const bool h = (held >> i) & 1u;
        const T fc = h ? T(0) : f[i];
        T v = d.v[3 * node + i];
        v += p.kick * (im * fc - p.alpha * v);
        T u = d.u[3 * node + i] + p.dt * v;
        d.v[3 * node + i] = h ? T(0) : v;
        d.u[3 * node + i] = h ? T(0) : u;
    }
}

} // namespace fascia::cuda
