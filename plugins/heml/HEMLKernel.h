#pragma once
/// Internal to HEMLForceField: the element loop (HEML Algorithm 2, its per-element math in
/// fascia/elements/EdgeForm.h, shared with the device step) over the data of HEMLData.h, templated on
/// how the law is evaluated (HEMLKernelLaws.h: an inlined built-in law, a batched virtual call for any
/// other material, or the mass-spring energy of eq. (38)) and on the scalar type T of the element data
/// and math: double, or float for precision="mixed" (docs/design.md, section 3). The element math is
/// written once for both; node positions, the block's node rows and the energy sum are double in both.
#include "HEMLData.h"

#include "fascia/elements/EdgeForm.h"
#include "fascia/elements/Hd.h"
#include "fascia/materials/Laws.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <type_traits>

namespace fascia::heml {

using elements::edgeA;
using elements::edgeB;
using elements::traceDk;

/// Scratch of one chunk (on the stack of the thread running a block), in the element scalar type T
/// but for the gathered positions (double: the edge differences are taken in double).
template <class T>
struct alignas(64) Chunk {
    double px[4][3][kLanes];
    T ev[6][3][kLanes];
    T l[6][kLanes];
    T H[6][kLanes];  ///< G D(l) G (symmetric)
    T I1[kLanes], I2[kLanes], J[kLanes], I4[kLanes], I6[kLanes];
    T We[kLanes];  ///< element energies Vol W
    T gk[6][kLanes], Qi[kLanes], Qv[kLanes];  ///< generalised forces Vol dW/dl_k, Vol dW/dJ (iso, vol)
    T W[kLanes], dI1[kLanes], dI2[kLanes], dI4[kLanes], dI6[kLanes], dJiso[kLanes], dJvol[kLanes];
    T f[4][3][kLanes];
    // the batched virtual call (GenericEval) is double only: BaseMaterial::evaluate
    materials::Invariants inv[kLanes];
    materials::Response resp[kLanes];

    /// Lane j's law response (in T, or the double of BaseMaterial::evaluate) into the
    /// structure-of-arrays fields.
    template <class R>
    void store(int j, const materials::ResponseT<R>& r) {
        W[j] = T(r.W);
        dI1[j] = T(r.dI1);
        dI2[j] = T(r.dI2);
        dI4[j] = T(r.dI4);
        dI6[j] = T(r.dI6);
        dJiso[j] = T(r.dJiso);
        dJvol[j] = T(r.dJvol);
    }
};

/// Edges, squared lengths l_k, invariants (eq. (C.1)) and J of the chunk at e0. The edges are
/// differences of the double positions, rounded to T once formed (in float: accurate edges of a
/// small element far from the origin); all after that is in T.
template <class T, class Eval>
FASCIA_INLINE void edgesAndInvariants(const Impl& d, Chunk<T>& c, size_t e0, bool useI4, bool useI6) {
    const ElementArrays<T>& el = d.arrays<T>();
    const T* invDetV = el.invDetV.data() + e0;
    // (GCC ivdep, not omp simd: omp simd would privatise the small local arrays into memory)
#pragma GCC ivdep
    for (int j = 0; j < kLanes; ++j) {
        T ev[6][3], l[6];
        for (int k = 0; k < 6; ++k) {
            for (int q = 0; q < 3; ++q) ev[k][q] = T(c.px[edgeB(k)][q][j] - c.px[edgeA(k)][q][j]);
            l[k] = ev[k][0] * ev[k][0] + ev[k][1] * ev[k][1] + ev[k][2] * ev[k][2];
            c.l[k][j] = l[k];
            for (int q = 0; q < 3; ++q) c.ev[k][q][j] = ev[k][q];
        }
        // signed volume ratio: det(v1, v2, v3) / det(V1, V2, V3)
        c.J[j] = elements::edgeDeterminant(ev) * invDetV[j];
        if constexpr (!Eval::spring) {
            // D(l) of eq. (A.4), I1 = tr(D G), I2 and H = G D G (eq. (C.1))
            const elements::Sym33<T> D = elements::gramOfLengths(l);
            const T G[6] = {el.G[0][e0 + j], el.G[1][e0 + j], el.G[2][e0 + j], el.G[3][e0 + j], el.G[4][e0 + j], el.G[5][e0 + j]};
            T I1, I2, H[6];
            elements::edgeInvariants(D, G, I1, I2, H);
            for (int q = 0; q < 6; ++q) c.H[q][j] = H[q];
            c.I1[j] = I1;
            c.I2[j] = I2;
            // I4 = a0.C a0 = w.D w, w = V^-1 a0 (I6 likewise with b0)
            c.I4[j] = useI4 ? elements::edgeFibreInvariant(D, el.w4[0][e0 + j], el.w4[1][e0 + j], el.w4[2][e0 + j]) : T(1);
            c.I6[j] = useI6 ? elements::edgeFibreInvariant(D, el.w6[0][e0 + j], el.w6[1][e0 + j], el.w6[2][e0 + j]) : T(1);
        }
    }
}

/// Generalised forces g_k = Vol dW/dl_k (eq. (29), (C.2)-(C.3)) and Vol dW/dJ of the chunk at e0.
template <class T, class Eval>
FASCIA_INLINE void generalisedForces(const Impl& d, Chunk<T>& c, size_t e0, bool useI4, bool useI6) {
    const ElementArrays<T>& el = d.arrays<T>();
    const T* vol = el.vol.data() + e0;
#pragma GCC ivdep
    for (int j = 0; j < kLanes; ++j) {
        T g[6], Qiso, Qvol, W;
        const T V = vol[j];
        if constexpr (Eval::spring) {
            // W = k/2 (l - l0)^2 per edge (eq. (38)); dW/d(l^2) = k/2 (1 - l0 / l)
            W = T(0);
            for (int k = 0; k < 6; ++k)
                g[k] = elements::springLink(c.l[k][j], el.kk[k][e0 + j], el.len0[k][e0 + j], W);
            Qiso = Qvol = T(0);
        } else {
            W = V * c.W[j];
            // g_k = Vol (dI1 vtr_k + dI2 (I1 vtr_k - (Mtr l)_k) + dI4 a0.C_k a0 + dI6 b0.C_k b0)   (eq. (C.2)-(C.3))
            //     = Vol tr(D_k Sg),  Sg = dI1 G + dI2 (I1 G - H) + dI4 w w^T + dI6 u u^T
            const T G[6] = {el.G[0][e0 + j], el.G[1][e0 + j], el.G[2][e0 + j], el.G[3][e0 + j], el.G[4][e0 + j], el.G[5][e0 + j]};
            const T H[6] = {c.H[0][j], c.H[1][j], c.H[2][j], c.H[3][j], c.H[4][j], c.H[5][j]};
            T Sg[6];
            elements::edgeStress(G, H, c.I1[j], c.dI1[j], c.dI2[j], Sg);
            if (useI4) elements::addFibreTerm(Sg, el.w4[0][e0 + j], el.w4[1][e0 + j], el.w4[2][e0 + j], c.dI4[j]);
            if (useI6) elements::addFibreTerm(Sg, el.w6[0][e0 + j], el.w6[1][e0 + j], el.w6[2][e0 + j], c.dI6[j]);
            elements::linkCoefficients(Sg, V, g);
            Qiso = V * c.dJiso[j];
            Qvol = V * c.dJvol[j];
        }
        c.We[j] = W;
        for (int k = 0; k < 6; ++k) c.gk[k][j] = g[k];
        c.Qi[j] = Qiso;
        c.Qv[j] = Qvol;
    }
}

/// The relaxed part R_k of the chunk's generalised forces as link coefficients (see relax), in T.
template <class T>
FASCIA_INLINE void relaxedPart(Impl& d, Chunk<T>& c, size_t e0, double shift, T rel[6][kLanes]) {
    const ElementArrays<T>& el = d.arrays<T>();
    // the parts that relax, each stress-free at rest: Vol s / J moved from Qi to Qv (their sum, the
    // elastic response, unchanged; max(J0, J) also keeps padding slots, where Vol = 0, finite)
    if (shift != 0.0) {
        const T* vol = el.vol.data() + e0;
        for (int j = 0; j < kLanes; ++j) elements::shiftVolumeTerms(c.Qi[j], c.Qv[j], vol[j], T(shift), T(d.J0), c.J[j]);
    }
    // the relaxed part as link coefficients R_k: g_k when the isochoric part relaxes, plus the
    // relaxed J coefficient (Qi, Qv or both, per `apply`) through dJ/dl_k
    const T* invDetV = el.invDetV.data() + e0;
    const T wIso = d.relaxIso ? T(1) : T(0), wVol = d.relaxVol ? T(1) : T(0);  // (no branch in the loop)
#pragma GCC ivdep
    for (int j = 0; j < kLanes; ++j) {
        const T l[6] = {c.l[0][j], c.l[1][j], c.l[2][j], c.l[3][j], c.l[4][j], c.l[5][j]};
        const T g[6] = {c.gk[0][j], c.gk[1][j], c.gk[2][j], c.gk[3][j], c.gk[4][j], c.gk[5][j]};
        T R[6];
        elements::relaxedLinks(elements::gramOfLengths(l), c.J[j], wIso * c.Qi[j] + wVol * c.Qv[j], invDetV[j], wIso, g, R);
        for (int k = 0; k < 6; ++k) rel[k][j] = R[k];
    }
}

/// Viscoelastic relaxation of the chunk's generalised forces (see HEMLForceField.h); shift: the
/// block material's Impl::restShift.
///
/// What relaxes is the relaxed part's second Piola-Kirchhoff stress as a whole, written as six link
/// coefficients R_k = Vol/2 S : C_k (the map of S onto them is linear and fixed by the rest shape,
/// so the recurrence on R_k is TLED eq. (30) on S, term by term). The link coefficients g_k carry
/// only the I1, I2, I4, I6 terms of S; the J terms act through Vol dW/dJ dJ/dx (eq. (C.4)). Each of
/// the two is not zero at rest where the law is written with the plain invariants or the modified
/// ones (NeoHookean: 2 dI1 = mu and dJiso = -mu at rest, which cancel only in their sum), so the
/// J part relaxed with it is turned into link coefficients too,
///   Q dJ/dl_k = Q J/2 tr(D^-1 D_k) = tr(D_k Q invDetV^2 cof(D) / (2 J))   (Jacobi's formula;
///   D = V^T C V = v^T v, the Gram matrix of the current edges, det D = (J det V)^2).
/// Relaxing g_k and Vol dW/dJ each by itself instead would multiply each one's history by a
/// different current geometry (the edges for g_k, cof F for the J part): under a changing
/// deformation their rest values no longer cancel (a creep test crept 4.6 % more at t = tau,
/// tests/verification/TestQuasiStaticCreep.cpp).
/// The history gamma is double in both precisions: R_k is converted to double for the recurrence
/// (so the states do not accumulate float rounding over the steps) and the sum of the terms is
/// rounded to T once, where it is subtracted.
template <class T>
FASCIA_INLINE void relax(Impl& d, Chunk<T>& c, size_t e0, double shift) {
    T rel[6][kLanes];
    relaxedPart(d, c, e0, shift, rel);
    // eq. (20) / TLED eq. (30): gamma_i^n = A_i R^n + B_i gamma_i^(n-1); eq. (18): g_k - sum_i gamma_i
    // (the J coefficients keep their elastic values: the relaxed J part's history is in gamma)
    double sum[6][kLanes] = {};
    for (int t = 0; t < d.nTerms; ++t) {
        const double A = d.A[t], Bt = d.B[t];
        for (int q = 0; q < 6; ++q) {
            const double* yp = d.Yprev[size_t(t * 6 + q)].data() + e0;
            double* yc = d.Ycur[size_t(t * 6 + q)].data() + e0;
#pragma GCC ivdep
            for (int j = 0; j < kLanes; ++j) {
                const double y = A * double(rel[q][j]) + Bt * yp[j];
                yc[j] = y;
                sum[q][j] += y;
            }
        }
    }
    for (int k = 0; k < 6; ++k)
        for (int j = 0; j < kLanes; ++j) c.gk[k][j] -= T(sum[k][j]);
}

/// Nodal forces of the chunk at e0 from its generalised forces.
template <class T>
FASCIA_INLINE void nodalForces(const Impl& d, Chunk<T>& c, size_t e0) {
    const T* invDetV = d.arrays<T>().invDetV.data() + e0;
#pragma GCC ivdep
    for (int j = 0; j < kLanes; ++j) {
        T g[6];
        for (int k = 0; k < 6; ++k) g[k] = c.gk[k][j];
        const T Qiso = c.Qi[j], Qvol = c.Qv[j];
        T ev[6][3];
        for (int k = 0; k < 6; ++k)
            for (int q = 0; q < 3; ++q) ev[k][q] = c.ev[k][q][j];
        // links: -2 g_k (x_a - x_b) on a, the opposite on b; volume: -Vol dW/dJ dJ/dx_i (EdgeForm.h)
        T f[4][3];
        elements::edgeNodalForces(g, (Qiso + Qvol) * invDetV[j], ev, f);
        for (int a = 0; a < 4; ++a)
            for (int q = 0; q < 3; ++q) c.f[a][q][j] = f[a][q];
    }
}

/// The chunk's nodal forces in double, for the block's double node rows: a double chunk's own, a
/// float chunk's converted into tmp (only the element forces are float; their sums are double).
using NodalRows = double[4][3][kLanes];
FASCIA_INLINE const NodalRows& forcesInDouble(const Chunk<double>& c, NodalRows&) { return c.f; }
FASCIA_INLINE const NodalRows& forcesInDouble(const Chunk<float>& c, NodalRows& tmp) {
    for (int a = 0; a < 4; ++a)
        for (int q = 0; q < 3; ++q)
            for (int j = 0; j < kLanes; ++j) tmp[a][q][j] = double(c.f[a][q][j]);
    return tmp;
}

/// Runs block bi: its positions into run.rows, forces into run.forces (when Forces) and its energy
/// (summed in double), the element math in T. Visco applies eq. (18)-(20) to the generalised forces
/// (see HEMLForceField.h).
template <class T, class Eval, bool Forces, bool Visco>
double runBlock(Impl& d, size_t bi, const Eval& eval, const BlockRun& run) {
    Chunk<T> c;
    alignas(64) NodalRows fd;  // (float chunks: their nodal forces in double)
    double energy = 0.0;
    const Block& b = d.blocks[bi];
    d.rows.loadRows(bi, run.x, run.rows);
    const double* xin = run.rows;
    double* buf = run.forces;
    const unsigned uses = eval.uses();
    const bool useI4 = (uses & materials::BaseMaterial::UsesI4) != 0;
    const bool useI6 = (uses & materials::BaseMaterial::UsesI6) != 0;
    for (size_t e0 = b.begin; e0 < b.end; e0 += kLanes) {
        // gather the four nodes of each element (node rows padded to 4 doubles, in-register
        // transposes: docs/performance.md, lesson 2)
        for (int j = 0; j < kLanes; j += 4)
            for (int a = 0; a < 4; ++a)
                simd::gather4(xin, d.node[a].data() + e0 + j, 1, &c.px[a][0][j], &c.px[a][1][j], &c.px[a][2][j]);
        edgesAndInvariants<T, Eval>(d, c, e0, useI4, useI6);
        if constexpr (!Eval::spring) eval(c, d.J0);  // the law
        generalisedForces<T, Eval>(d, c, e0, useI4, useI6);
        if constexpr (Forces && Visco) relax(d, c, e0, b.material >= 0 ? d.restShift[size_t(b.material)] : 0.0);
        if constexpr (Forces) nodalForces(d, c, e0);
        for (int j = 0; j < kLanes; ++j) energy += double(c.We[j]);
        // scatter into the block's node buffer, in a fixed order (each row loaded, added and stored
        // before the next, so elements sharing a node add up correctly)
        if constexpr (Forces) {
            const NodalRows& f = forcesInDouble(c, fd);
            for (int j = 0; j < kLanes; j += 4)
                for (int a = 0; a < 4; ++a)
                    simd::scatterAdd4(buf, d.node[a].data() + e0 + j, 1, &f[a][0][j], &f[a][1][j], &f[a][2][j]);
        }
    }
    return energy;
}

} // namespace fascia::heml
