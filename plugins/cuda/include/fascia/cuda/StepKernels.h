#pragma once
/// The bodies of the device step's two kernels, as host/device functions (FASCIA_HD) over the
/// layout of StepLayout.h: the GPU wraps each in a __global__ launch (CudaRunner.cu, one thread per
/// element or node), the CPU emulation calls them in loops (EmulatedRunner.h). The element math is
/// the element layer's and the laws' (Tensor3.h, BatchView.h, Relaxation.h, materials::evaluateLaw):
/// nothing of it is written again here (docs/design.md, principle 9).
///   element kernels (tetrahedra, hexahedra): gather u of its 4 or 8 nodes -> F from dN/dX (TLED
///     eq. (1)) -> invariants -> the law's response (evaluateLaw: HEML section 4.4 below J0) -> P
///     (Tensor3.h firstPiola) -> f_a = -V P dN_a/dX (TLED eq. (3)), for hexahedra with the
///     hourglass forces of fascia/elements/Hourglass.h, written to the element's own slots; with
///     Prony series (ElementParams::prony; the kernels' Relaxed, a compile-time choice), between the
///     response and P: the rest shift -> S split into its isochoric and volumetric parts (TLED eq.
///     (10), secondPiola) -> Y_i = A_i R + B_i Y_i (TLED eq. (30), the element's own states
///     advanced in place), S = Phi - sum_i Y_i (TLED eq. (24)) -> P = F S. The fibre directions
///     (I4, I6, P) are those of the element's material group (ElementParams a0, b0), or its own
///     from StepArrays fa, fb (the kernels' PerElementFibres, a compile-time choice, instantiated
///     for the laws that read a fibre only); a runner launches them once per material group, with
///     the group's law, over the group's element list (StepSetup::Group);
///   HEML's element kernel (HEMLForceField, StepSetup::Form::Edges; tetrahedra): its current edges
///     from the rest ones and u -> squared lengths, J, the invariants from G (HEML eq. (C.1)) -> the
///     law's response -> link coefficients and volume terms (eq. (29), (C.2)-(C.4)), relaxed by its
///     one Prony series as HEMLForceField relaxes them (eq. (18)-(20)) -> the nodal forces (eq.
///     (12)-(13)), all of it fascia/elements/EdgeForm.h, written to the element's own slots (the
///     same as TLED's tetrahedra); in mass-spring mode a spring per edge (eq. (38));
///   face kernel (a face under a SurfacePressure): its current edges from the rest ones and u ->
///     its follower load (fascia/elements/Pressure.h), written to its own slots;
///   node kernel: the sum of its (element, corner) slots in their fixed order, + external force
///     + m g, held axes zeroed, then SemiImplicitEuler (v += kick (f/m - alpha v), u += dt v, HEML
///     eq. (32)) or CentralDifference, the held axes at their constraint's position and velocity
///     (at rest, or a PrescribedDisplacement's at t + dt).
#include "fascia/cuda/StepLayout.h"
#include "fascia/elements/BatchView.h"
#include "fascia/elements/EdgeForm.h"
#include "fascia/elements/Hourglass.h"
#include "fascia/elements/Pressure.h"
#include "fascia/elements/Relaxation.h"
#include "fascia/materials/Material.h"

namespace fascia::cuda {

namespace detail {

/// Where corner k of an element kind's corners (k = corners per element x e + a) writes its force:
/// its own record of byElement, or in node order (StepArrays sf) its slot's.
template <class T>
FASCIA_HD FASCIA_INLINE T* cornerOut(T* byElement, const std::uint32_t* slotOf, T* sf, size_t k) {
    return slotOf ? sf + 3 * static_cast<size_t>(slotOf[k]) : byElement + 3 * k;
}

/// u of the NN corners of element e (corner a's node at nodes[a n + e]).
template <int NN, class T>
FASCIA_HD FASCIA_INLINE void gatherCorners(const int* nodes, int n, int e, const T* u, elements::NodalBatch<NN, 1, T>& out) {
    for (int a = 0; a < NN; ++a) {
        const int node = nodes[a * n + e];
        for (int i = 0; i < 3; ++i) out.v[a][i][0] = u[3 * node + i];
    }
}

/// The invariants the law uses (BaseMaterial::Uses bits, compile-time).
template <class Law>
struct Uses {
    static constexpr bool i2 = (Law::uses & materials::BaseMaterial::UsesI2) != 0, i4 = (Law::uses & materials::BaseMaterial::UsesI4) != 0,
                          i6 = (Law::uses & materials::BaseMaterial::UsesI6) != 0;
};

/// The fibre directions an element's stress reads (a0 of I4, b0 of I6): references to the group's,
/// ElementParams a0 and b0, or to the element's own (the elastic kernels of uniform fibres then read
/// the kernel's parameters as they did before fibres per element: the same registers).
template <class T>
struct Fibres {
    const elements::Vec33<T>& a0;
    const elements::Vec33<T>& b0;
};

/// The fibre directions of element e among the n of its kind: with PerElementFibres those of the
/// arrays a, b (StepArrays fa, fb or hfa, hfb; row i at i n + e) that the law reads, loaded into own,
/// else (and for a direction it does not read) the group's, p.a0 and p.b0.
template <bool PerElementFibres, class Law, class T>
FASCIA_HD FASCIA_INLINE Fibres<T> fibresOf(const ElementParams<Law, T>& p, const T* a, const T* b, int n, int e, elements::Vec33<T> (&own)[2]) {
    if constexpr (PerElementFibres) {
        if constexpr (Uses<Law>::i4) own[0] = elements::Vec33<T>{a[e], a[n + e], a[2 * n + e]};
        if constexpr (Uses<Law>::i6) own[1] = elements::Vec33<T>{b[e], b[n + e], b[2 * n + e]};
        return {Uses<Law>::i4 ? own[0] : p.a0, Uses<Law>::i6 ? own[1] : p.b0};
    } else {
        return {p.a0, p.b0};
    }
}

/// The invariants of F (in) and the law's response to them (materials::evaluateLaw: HEML section
/// 4.4 below J0) as the stress formulas read it, with the fibre directions fib.
template <class Law, class T>
FASCIA_HD FASCIA_INLINE elements::Coefficients<T> response(const ElementParams<Law, T>& p, const Fibres<T>& fib, const elements::Mat33<T>& F,
                                                           materials::InvariantsT<T>& in) {
    const elements::Invariants3<T> iv = elements::invariants<Uses<Law>::i2>(F);
    in.I1 = iv.I1;
    in.I2 = iv.I2;
    in.J = iv.J;
    if constexpr (Uses<Law>::i4) in.I4 = elements::fibreInvariant(F, fib.a0);
    if constexpr (Uses<Law>::i6) in.I6 = elements::fibreInvariant(F, fib.b0);
    materials::ResponseT<T> r;
    materials::evaluateLaw(p.law, in, static_cast<double>(p.J0), r);
    return {r.dI1, r.dI2, r.dI4, r.dI6, r.dJiso, r.dJvol};
}

/// V P.
template <class T>
FASCIA_HD FASCIA_INLINE elements::Mat33<T> scaled(const elements::Mat33<T>& P, T V) {
    return {V * P.xx, V * P.xy, V * P.xz, V * P.yx, V * P.yy, V * P.yz, V * P.zx, V * P.zy, V * P.zz};
}

/// V P of an element of rest volume V at the deformation gradient F: the law's response and P
/// (Tensor3.h firstPiola).
template <class Law, class T>
FASCIA_HD FASCIA_INLINE elements::Mat33<T> scaledStress(const ElementParams<Law, T>& p, const Fibres<T>& fib, const elements::Mat33<T>& F,
                                                        T V) {
    materials::InvariantsT<T> in;
    const elements::Coefficients<T> c = response(p, fib, F, in);
    return scaled(elements::firstPiola<Uses<Law>::i2, Uses<Law>::i4, Uses<Law>::i6>(F, in.I1, c, fib.a0, fib.b0), V);
}

/// V P relaxed by the Prony series of p.prony (TLED eq. (24), (30)), as TLEDForceField's viscous
/// path (plugins/tled/TLEDKernel.h viscousStress): the law's response, s ln J moved between its parts
/// (Relaxation.h restShift), S = Siso + Svol (Tensor3.h secondPiola), then for each series, term and
/// component Y = A R + B Y (Relaxation.h pronyState, R the part the series relaxes) and S -= Y, in
/// that order; P = F S (firstPiolaOf). Y: the states of the element kind (n elements), element e's
/// term k component c at Y[(6 k + c) n + e] (StepLayout.h), advanced in place.
template <class Law, class T>
FASCIA_HD FASCIA_INLINE elements::Mat33<T> scaledRelaxedStress(const ElementParams<Law, T>& p, const Fibres<T>& fib, const elements::Mat33<T>& F,
                                                               T V, T* Y, int n, int e) {
    materials::InvariantsT<T> in;
    elements::Coefficients<T> c = response(p, fib, F, in);
    const PronyParams<T>& q = p.prony;
    if (q.restShift != T(0)) elements::restShift(c.dJiso, c.dJvol, in.J, q.restShift, p.J0);
    elements::Sym33<T> Si, Sv;
    elements::secondPiola<Uses<Law>::i2, Uses<Law>::i4, Uses<Law>::i6>(F, in.I1, in.J, c, fib.a0, fib.b0, Si, Sv);
    const T si[6] = {Si.xx, Si.yy, Si.zz, Si.xy, Si.yz, Si.xz}, sv[6] = {Sv.xx, Sv.yy, Sv.zz, Sv.xy, Sv.yz, Sv.xz};
    T S[6];
    for (int i = 0; i < 6; ++i) S[i] = si[i] + sv[i];
    // (bounds known at compile time, exits uniform across the elements: the loops unroll)
    int k = 0;
    for (int s = 0; s < kMaxSeries && s < q.series; ++s)
        for (int t = 0; t < kMaxTerms && t < q.terms[s]; ++t, ++k)
            for (int i = 0; i < 6; ++i) {
                const T R = q.iso[s] && q.vol[s] ? si[i] + sv[i] : q.iso[s] ? si[i] : sv[i];
                T& y = Y[(6 * k + i) * n + e];
                y = elements::pronyState(q.A[s][t], R, q.B[s][t], y);
                S[i] -= y;
            }
    return scaled(elements::firstPiolaOf(F, elements::Sym33<T>{S[0], S[1], S[2], S[3], S[4], S[5]}), V);
}

/// V P of the element, relaxed by p.prony's series (Relaxed) or elastic (a compile-time choice: the
/// elastic kernels carry none of the viscous path's registers), with the fibre directions fib. Y,
/// n, e: element e's states among the n of its kind.
template <bool Relaxed, class Law, class T>
FASCIA_HD FASCIA_INLINE elements::Mat33<T> elementStress(const ElementParams<Law, T>& p, const Fibres<T>& fib, const elements::Mat33<T>& F,
                                                         T V, T* Y, int n, int e) {
    if constexpr (Relaxed) return scaledRelaxedStress(p, fib, F, V, Y, n, e);
    else return scaledStress(p, fib, F, V);
}

} // namespace detail

/// The forces of tetrahedron e on its 4 corners, written to ef (its own slots), with the law of p
/// (e's material group); Relaxed: with the Prony series of p (p.prony.series > 0), its states
/// advanced (a runner launches the relaxed kernels when the setup has series, the elastic ones
/// otherwise); PerElementFibres: the fibre directions of e from d.fa, d.fb (a runner launches these
/// kernels when the setup has fibre arrays and the law reads a fibre).
template <bool Relaxed = false, bool PerElementFibres = false, class Law, class T>
FASCIA_HD FASCIA_INLINE void tetForces(const StepArrays<T>& d, const ElementParams<Law, T>& p, int e) {
    const int n = d.nTets;
    elements::NodalBatch<4, 1, T> u;
    detail::gatherCorners(d.tet, n, e, d.u, u);
    T g[9];
    for (int r = 0; r < 9; ++r) g[r] = d.dN[r * n + e];
    const elements::NodeRows<1, T> dN{g};
    elements::Vec33<T> own[2];
    const detail::Fibres<T> fib = detail::fibresOf<PerElementFibres>(p, d.fa, d.fb, n, e, own);
    const elements::Mat33<T> P = detail::elementStress<Relaxed>(p, fib, elements::deformationGradientTet(u, dN, 0), d.vol[e], d.Y, n, e);
    T s0 = 0, s1 = 0, s2 = 0;
    const size_t c0 = 4 * static_cast<size_t>(e);
    for (int a = 1; a < 4; ++a) {
        const elements::Vec33<T> f = elements::nodalForce(P, dN.at(a - 1, 0, 0), dN.at(a - 1, 1, 0), dN.at(a - 1, 2, 0));
        T* out = detail::cornerOut(d.ef, d.tetSlot, d.sf, c0 + a);
        out[0] = f.x;
        out[1] = f.y;
        out[2] = f.z;
        s0 += f.x;
        s1 += f.y;
        s2 += f.z;
    }
    T* out = detail::cornerOut(d.ef, d.tetSlot, d.sf, c0);
    out[0] = -s0;
    out[1] = -s1;
    out[2] = -s2;
}

/// The forces of hexahedron e on its 8 corners (uniform strain with hourglass control,
/// fascia/elements/Hourglass.h), written to hef (its own slots); Relaxed, PerElementFibres (from
/// d.hfa, d.hfb): as tetForces.
template <bool Relaxed = false, bool PerElementFibres = false, class Law, class T>
FASCIA_HD FASCIA_INLINE void hexForces(const StepArrays<T>& d, const ElementParams<Law, T>& p, int e) {
    const int n = d.nHexes;
    elements::NodalBatch<8, 1, T> u;
    detail::gatherCorners(d.hex, n, e, d.u, u);
    // u_a - u_0, as TLED's float gather does (plugins/tled/TLEDKernel.h): F and the hourglass modes see
    // differences only (the dN_a and each h_q sum to zero), so a rigid translation costs no digits
    for (int a = 7; a >= 0; --a)
        for (int i = 0; i < 3; ++i) u.v[a][i][0] -= u.v[0][i][0];
    T g[24], c[12], h[12];
    for (int r = 0; r < 24; ++r) g[r] = d.hdN[r * n + e];
    for (int r = 0; r < 12; ++r) c[r] = d.hgC[r * n + e];
    const elements::NodeRows<1, T> dN{g}, cq{c};
    const elements::Mat33<T> F = elements::deformationGradient(u, dN, 0);
    elements::hourglassModes(u, cq, 0, F, h);
    elements::Vec33<T> own[2];
    const detail::Fibres<T> fib = detail::fibresOf<PerElementFibres>(p, d.hfa, d.hfb, n, e, own);
    const elements::Mat33<T> P = detail::elementStress<Relaxed>(p, fib, F, d.hvol[e], d.hY, n, e);
    elements::NodalBatch<8, 1, T> f;
    elements::hexNodalForces(P, d.hgK[e], elements::NodeRows<1, T>{h}, cq, dN, 0, f);
    for (int a = 0; a < 8; ++a) {
        T* out = detail::cornerOut(d.hef, d.hexSlot, d.sf, 8 * static_cast<size_t>(e) + a);
        for (int i = 0; i < 3; ++i) out[i] = f.v[a][i][0];
    }
}

namespace detail {

/// The six current edges of tetrahedron e (EdgeForm.h): v_a = V_a + (u_a - u_0) for a = 1..3 from
/// its rest edges eV, then v4 = v2 - v1, v5 = v3 - v2, v6 = v1 - v3 (HEML eq. (A.2)).
template <class T>
FASCIA_HD FASCIA_INLINE void currentEdges(const StepArrays<T>& d, int e, T ev[6][3]) {
    const int n = d.nTets;
    elements::NodalBatch<4, 1, T> u;
    gatherCorners(d.tet, n, e, d.u, u);
    for (int a = 1; a < 4; ++a)
        for (int i = 0; i < 3; ++i) ev[a - 1][i] = d.eV[(3 * (a - 1) + i) * n + e] + (u.v[a][i][0] - u.v[0][i][0]);
    for (int i = 0; i < 3; ++i) {
        ev[3][i] = ev[1][i] - ev[0][i];
        ev[4][i] = ev[2][i] - ev[1][i];
        ev[5][i] = ev[0][i] - ev[2][i];
    }
}

/// The element's nodal forces f (EdgeForm.h edgeNodalForces) written to its own slots of ef.
template <class T>
FASCIA_HD FASCIA_INLINE void storeCorners(const StepArrays<T>& d, int e, const T f[4][3]) {
    for (int a = 0; a < 4; ++a) {
        T* out = cornerOut(d.ef, d.tetSlot, d.sf, 4 * static_cast<size_t>(e) + a);
        for (int i = 0; i < 3; ++i) out[i] = f[a][i];
    }
}

/// HEML's relaxation of the link coefficients g by the one series of q (HEMLKernel.h relax, HEML
/// eq. (18)-(20)): the volume terms shifted (q.restShift), the relaxed part R_k, then for each term
/// Y = A R + B Y (element e's states, advanced in place) and g_k -= sum of the terms.
template <class T>
FASCIA_HD FASCIA_INLINE void relaxLinks(const PronyParams<T>& q, const elements::Sym33<T>& D, T J, T V, T J0, T invDetV, T* Y, int n,
                                        int e, T g[6], T& Qi, T& Qv) {
    if (q.restShift != T(0)) elements::shiftVolumeTerms(Qi, Qv, V, q.restShift, J0, J);
    const T wIso = q.iso[0] ? T(1) : T(0), wVol = q.vol[0] ? T(1) : T(0);
    T R[6], sum[6] = {0, 0, 0, 0, 0, 0};
    elements::relaxedLinks(D, J, wIso * Qi + wVol * Qv, invDetV, wIso, g, R);
    for (int t = 0; t < kMaxTerms && t < q.terms[0]; ++t)
        for (int c = 0; c < 6; ++c) {
            T& y = Y[(6 * t + c) * n + e];
            y = elements::pronyState(q.A[0][t], R[c], q.B[0][t], y);
            sum[c] += y;
        }
    for (int c = 0; c < 6; ++c) g[c] -= sum[c];
}

} // namespace detail

/// HEML (HEMLForceField) on tetrahedron e, with the law of p (e's material group), written to its
/// own slots of ef: its current edges, their squared lengths l_k, J, the invariants from G and the
/// fibres' w (eq. (C.1)), the law's response (materials::evaluateLaw, section 4.4 below J0), the link
/// coefficients g_k and the volume terms (eq. (29), (C.2)-(C.4)), relaxed by p.prony's one series
/// (Relaxed), and the nodal forces (eq. (12)-(13)): fascia/elements/EdgeForm.h throughout.
template <bool Relaxed = false, class Law, class T>
FASCIA_HD FASCIA_INLINE void edgeForces(const StepArrays<T>& d, const ElementParams<Law, T>& p, int e) {
    const int n = d.nTets;
    T ev[6][3], l[6];
    detail::currentEdges(d, e, ev);
    for (int k = 0; k < 6; ++k) l[k] = ev[k][0] * ev[k][0] + ev[k][1] * ev[k][1] + ev[k][2] * ev[k][2];
    const T invDetV = d.eInvDetV[e], V = d.vol[e];
    const elements::Sym33<T> D = elements::gramOfLengths(l);
    T G[6], H[6];
    for (int q = 0; q < 6; ++q) G[q] = d.eG[q * n + e];
    materials::InvariantsT<T> in;
    elements::edgeInvariants(D, G, in.I1, in.I2, H);
    in.J = elements::edgeDeterminant(ev) * invDetV;
    T w4[3] = {0, 0, 0}, w6[3] = {0, 0, 0};
    for (int i = 0; i < 3; ++i) {
        if constexpr (detail::Uses<Law>::i4) w4[i] = d.ew4[i * n + e];
        if constexpr (detail::Uses<Law>::i6) w6[i] = d.ew6[i * n + e];
    }
    if constexpr (detail::Uses<Law>::i4) in.I4 = elements::edgeFibreInvariant(D, w4[0], w4[1], w4[2]);
    if constexpr (detail::Uses<Law>::i6) in.I6 = elements::edgeFibreInvariant(D, w6[0], w6[1], w6[2]);
    materials::ResponseT<T> r;
    materials::evaluateLaw(p.law, in, static_cast<double>(p.J0), r);
    T Sg[6], g[6];
    elements::edgeStress(G, H, in.I1, r.dI1, r.dI2, Sg);
    if constexpr (detail::Uses<Law>::i4) elements::addFibreTerm(Sg, w4[0], w4[1], w4[2], r.dI4);
    if constexpr (detail::Uses<Law>::i6) elements::addFibreTerm(Sg, w6[0], w6[1], w6[2], r.dI6);
    elements::linkCoefficients(Sg, V, g);
    T Qi = V * r.dJiso, Qv = V * r.dJvol;
    if constexpr (Relaxed) detail::relaxLinks(p.prony, D, in.J, V, p.J0, invDetV, d.Y, n, e, g, Qi, Qv);
    T f[4][3];
    elements::edgeNodalForces(g, (Qi + Qv) * invDetV, ev, f);
    detail::storeCorners(d, e, f);
}

/// HEML's mass-spring mode (eq. (38)-(41)) on tetrahedron e: a spring per edge (its share ekk of the
/// stiffness, rest length elen0), written to its own slots of ef.
template <class T>
FASCIA_HD FASCIA_INLINE void springForces(const StepArrays<T>& d, int e) {
    const int n = d.nTets;
    T ev[6][3], g[6], W = 0;
    detail::currentEdges(d, e, ev);
    for (int k = 0; k < 6; ++k) {
        const T L2 = ev[k][0] * ev[k][0] + ev[k][1] * ev[k][1] + ev[k][2] * ev[k][2];
        g[k] = elements::springLink(L2, d.ekk[k * n + e], d.elen0[k * n + e], W);
    }
    T f[4][3];
    elements::edgeNodalForces(g, T(0), ev, f);
    detail::storeCorners(d, e, f);
}

/// The follower pressure on face k of the faces under pressure (the triangles, then the
/// quadrilaterals; fascia/elements/Pressure.h), from its rest differences and u, written to its own
/// slots (tf or qf).
template <class T>
FASCIA_HD FASCIA_INLINE void faceForces(const StepArrays<T>& d, const FaceParams<T>& q, int k) {
    const auto rel = [&](const int* nodes, const T* D, int n, int f, int a) {
        const int b = nodes[a * n + f], o = nodes[f];
        return elements::Vec33<T>{D[(3 * (a - 1) + 0) * n + f] + (d.u[3 * b + 0] - d.u[3 * o + 0]),
                                  D[(3 * (a - 1) + 1) * n + f] + (d.u[3 * b + 1] - d.u[3 * o + 1]),
                                  D[(3 * (a - 1) + 2) * n + f] + (d.u[3 * b + 2] - d.u[3 * o + 2])};
    };
    if (k < d.nTris) {
        const elements::Vec33<T> f = elements::trianglePressureForce(rel(d.tri, d.triD, d.nTris, k, 1), rel(d.tri, d.triD, d.nTris, k, 2),
                                                                     q.p[d.triLoad[k]]);
        for (int a = 0; a < (d.triSlot ? 3 : 1); ++a) {
            T* out = d.triSlot ? d.sf + 3 * static_cast<size_t>(d.triSlot[3 * k + a]) : d.tf + 3 * static_cast<size_t>(k);
            out[0] = f.x;
            out[1] = f.y;
            out[2] = f.z;
        }
        return;
    }
    const int f = k - d.nTris;
    const elements::Vec33<T> x[4] = {{0, 0, 0}, rel(d.quad, d.quadD, d.nQuads, f, 1), rel(d.quad, d.quadD, d.nQuads, f, 2),
                                     rel(d.quad, d.quadD, d.nQuads, f, 3)};
    elements::Vec33<T> out[4];
    elements::quadPressureForces(x, q.p[d.quadLoad[f]], out);
    for (int a = 0; a < 4; ++a) {
        T* o = detail::cornerOut(d.qf, d.quadSlot, d.sf, 4 * static_cast<size_t>(f) + a);
        o[0] = out[a].x;
        o[1] = out[a].y;
        o[2] = out[a].z;
    }
}

/// The internal force on node `node`: its slots summed in their fixed order.
template <class T>
FASCIA_HD FASCIA_INLINE elements::Vec33<T> gatherForce(const StepArrays<T>& d, int node) {
    T f0 = 0, f1 = 0, f2 = 0;
    if (d.sf) {  // (in node order: one contiguous run, the same order)
        for (int k = d.slotStart[node]; k < d.slotStart[node + 1]; ++k) {
            f0 += d.sf[3 * static_cast<size_t>(k) + 0];
            f1 += d.sf[3 * static_cast<size_t>(k) + 1];
            f2 += d.sf[3 * static_cast<size_t>(k) + 2];
        }
        return {f0, f1, f2};
    }
    for (int k = d.slotStart[node]; k < d.slotStart[node + 1]; ++k) {
        const std::uint32_t s = d.slots[k];
        const int e = static_cast<int>(s >> 3), a = static_cast<int>(s & 7u);
        const int h = e - d.nTets, t = h - d.nHexes, q = t - d.nTris;
        const T* ef = e < d.nTets     ? d.ef + 3 * (4 * static_cast<size_t>(e) + a)
                      : h < d.nHexes  ? d.hef + 3 * (8 * static_cast<size_t>(h) + a)
                      : t < d.nTris   ? d.tf + 3 * static_cast<size_t>(t)
                                      : d.qf + 3 * (4 * static_cast<size_t>(q) + a);
        f0 += ef[0];
        f1 += ef[1];
        f2 += ef[2];
    }
    return {f0, f1, f2};
}

/// The force on node `node`: its slots, the external force, the curved loads and m g; the held axes' components
/// removed (the constraints' projectForces) and kept, negated, as their reactions (StepArrays::react).
template <class T>
FASCIA_HD FASCIA_INLINE void nodeForce(const StepArrays<T>& d, const NodeParams<T>& p, int node, T f[3]) {
    const elements::Vec33<T> fi = gatherForce(d, node);
    const T m = d.mass[node];
    T g[3] = {fi.x + d.ext[3 * node + 0] + m * p.g[0], fi.y + d.ext[3 * node + 1] + m * p.g[1], fi.z + d.ext[3 * node + 2] + m * p.g[2]};
    for (int k = 0; k < kMaxLoads && k < d.nLoads; ++k)
        for (int i = 0; i < 3; ++i) g[i] += p.load[k] * d.loadF[3 * (static_cast<size_t>(k) * d.nNodes + node) + i];
    for (int i = 0; i < 3; ++i) {
        f[i] = g[i];
        if (d.hold[3 * node + i] == 0) continue;
        d.react[3 * node + i] = -g[i];
        f[i] = T(0);
    }
}

/// Axis i of node `node` at the end of the step: a held axis is put at its constraint's position
/// and velocity (the constraints' projectPositions, projectVelocities); false for a free axis.
template <class T>
FASCIA_HD FASCIA_INLINE bool project(const StepArrays<T>& d, int node, int i, T& u, T& v) {
    const std::uint32_t h = d.hold[3 * node + i];
    if (h == 0) return false;
    u = h == 1 ? T(0) : d.tu[h - 2];
    v = h == 1 ? T(0) : d.tv[h - 2];
    return true;
}

/// Keeps the step's number in d.bad when probe, a sum of (u - u) and (v - v) over the node's new
/// values, is not 0 (x - x is 0 for a finite x and NaN otherwise): the smallest such step stays
/// (atomicMin on the device, an integer: no effect on any result; a plain min in the emulation).
template <class T>
FASCIA_HD FASCIA_INLINE void flagNonFinite(const StepArrays<T>& d, const NodeParams<T>& p, T probe) {
    if (probe == T(0)) return;
#ifdef __CUDA_ARCH__
    atomicMin(d.bad, p.step);
#else
    if (p.step < *d.bad) *d.bad = p.step;
#endif
}

/// One SemiImplicitEuler step of node `node` (HEML eq. (32)): v += kick (f/m - alpha v), u += dt v.
template <class T>
FASCIA_HD FASCIA_INLINE void eulerStep(const StepArrays<T>& d, const NodeParams<T>& p, int node) {
    T f[3];
    nodeForce(d, p, node, f);
    const T im = d.invMass[node];
    T probe = 0;
    for (int i = 0; i < 3; ++i) {
        T v = d.v[3 * node + i];
        v += p.kick * (im * f[i] - p.alpha * v);
        T u = d.u[3 * node + i] + p.dt * v;
        project(d, node, i, u, v);
        d.u[3 * node + i] = u;
        d.v[3 * node + i] = v;
        probe += (u - u) + (v - v);
    }
    flagNonFinite(d, p, probe);
}

/// One CentralDifference step of node `node` (TLED section 2, damped, as plugins/mechanics/
/// CentralDifference.cpp): u(n+1) = c1 [2 u(n) - c2 u(n-1) + dt^2 f/m] with c2 = 1 - a and
/// c1 = 1 / (1 + a) = 1 - b (NodeParams), in the increments d(n) = u(n) - u(n-1):
///   u(n+1) = u(n) + d(n+1),  d(n+1) = y - b y,  y = d(n) - a d(n) + dt^2 f/m
/// (since c1 (1 + a) = 1), so that in float the increments, not u, carry the scheme (a float u(n-1)
/// would lose the velocity to its rounding); v = (3 d(n+1) - d(n)) / (2 dt), the second-order
/// backward difference, once a step was taken, else c1 (d(n+1)/dt + dt/2 f/m), the exact value for
/// constant acceleration; on a (re)start d(0) = dt v(0) - dt^2/2 (f/m - alpha v(0)).
template <class T>
FASCIA_HD FASCIA_INLINE void centralStep(const StepArrays<T>& d, const NodeParams<T>& p, int node) {
    T f[3];
    nodeForce(d, p, node, f);
    const T im = d.invMass[node], dt = p.dt, dt2 = dt * dt;
    T probe = 0;
    for (int i = 0; i < 3; ++i) {
        const T un = d.u[3 * node + i], vn = d.v[3 * node + i];
        const T dn = p.start ? dt * vn - T(0.5) * dt * dt * (im * f[i] - p.alpha * vn) : d.du[3 * node + i];
        const T y = dn - p.a * dn + dt2 * im * f[i];
        const T dnext = y - p.b * y;
        const T z = dnext / dt + T(0.5) * dt * im * f[i];
        T v = p.twoSteps ? (3 * dnext - dn) / (2 * dt) : z - p.b * z;
        T u = un + dnext;
        // a held axis: the increment to its constraint's position (x(n) of the next step)
        d.du[3 * node + i] = project(d, node, i, u, v) ? u - un : dnext;
        d.u[3 * node + i] = u;
        d.v[3 * node + i] = v;
        probe += (u - u) + (v - v);
    }
    flagNonFinite(d, p, probe);
}

} // namespace fascia::cuda
