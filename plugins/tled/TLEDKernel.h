#pragma once
/// Internal to TLEDForceField: the element loop of one block (TLED eq. (1)-(3), (10), (24), (30)),
/// a short driver over inline stages that each run one vectorised pass over a batch of kBatch
/// elements (docs/performance.md, lesson 3):
///   gather u -> gradient and invariants (F, C, I1, I2, J, I4, I6; hexahedra: hourglass modes)
///   -> the law (W and dW/dI for the whole batch) -> stress (P directly; or S, relaxed by the
///   Prony series, then P = F S) -> energy -> nodal forces f_a = -V P dN_a/dX -> scatter.
/// The per-element formulas are the element layer's (fascia/elements/Tensor3.h, BatchView.h).
///
/// Every stage is templated on the scalar type T of the element data and the arithmetic: double
/// (precision "double"), or float (precision "mixed"). u, the block buffers and the energy sum stay
/// double in both: in float the gather forms u_a - u_0 in double before rounding (F needs only the
/// differences, and the hourglass modes too, since each h_q sums to zero), so a rigid translation of
/// the mesh costs no digits; the element forces are widened to double before the scatter.
#include "TLEDData.h"

#include "fascia/elements/BatchView.h"
#include "fascia/elements/Hourglass.h"
#include "fascia/materials/Material.h"

#include <algorithm>
#include <type_traits>

namespace fascia::tled::kernel {

using namespace elements;
using materials::BaseMaterial;
using Impl = TLEDForceField::Impl;

/// Per-batch scratch of the element loop, as structure of arrays (index k = element in the batch).
template <int NN, class T = double>
struct Batch {
    static constexpr bool kMixed = std::is_same_v<T, float>;
    static constexpr int kWide = kMixed ? NN : 1;  ///< nodes of the double copies below (1: unused)
    NodalBatch<NN, kBatch, T> u;           ///< nodal displacements x - X (mixed: u_a - u_0)
    NodalBatch<kWide, kBatch> uWide, fWide;  ///< mixed: u as gathered and the forces to scatter, in double
    MatBatch<kBatch, T> F;                 ///< deformation gradient
    alignas(64) T I1[kBatch], I2[kBatch], J[kBatch], I4[kBatch], I6[kBatch];
    ResponseBatch<kBatch, T> r;            ///< the law's response
    MatBatch<kBatch, T> P;                 ///< first Piola-Kirchhoff stress
    SymBatch<kBatch, T> Siso, Svol, S;     ///< viscous path: S and its parts
    alignas(64) double Ytmp[kBatch];       ///< viscous path: a state row on its way to a streaming store
    alignas(64) double Y6[6][kBatch];      ///< the same for the six rows of a one-term series
    NodalBatch<NN, kBatch, T> f;           ///< element nodal forces
    alignas(64) T Kh[NN == 8 ? 12 : 1][kBatch];  ///< hexahedra: hourglass displacements h_q, rows 3q + j
};

/// Fibre directions of a batch: rows a0 x y z, b0 x y z (per element, or the group's copied across).
template <class T>
struct Fibres {
    NodeRows<kBatch, T> rows;
    FASCIA_INLINE Vec33<T> a(int k) const { return rows.vec(0, k); }
    FASCIA_INLINE Vec33<T> b(int k) const { return rows.vec(1, k); }
};

/// Gathers u of the batch's nodes (precomputed per node, padded to 4; forming F from displacements
/// keeps it accurate) into ub.
template <int NN>
FASCIA_INLINE void gatherInto(const ElementSet<NN>& es, size_t e0, int n, const double* __restrict u4, NodalBatch<NN, kBatch>& ub) {
    auto& s = ub;
    int kq = 0;
    for (; kq + 4 <= n; kq += 4) {
        const int* nd = &es.nodes[(e0 + static_cast<size_t>(kq)) * NN];
        for (int a = 0; a < NN; ++a) simd::gather4(u4, nd + a, NN, &s.v[a][0][kq], &s.v[a][1][kq], &s.v[a][2][kq]);
    }
    for (int k = kq; k < n; ++k) {
        const int* nd = &es.nodes[(e0 + static_cast<size_t>(k)) * NN];
        for (int a = 0; a < NN; ++a) {
            const double* up = u4 + 4 * static_cast<size_t>(nd[a]);
            s.v[a][0][k] = up[0];
            s.v[a][1][k] = up[1];
            s.v[a][2][k] = up[2];
        }
    }
}

/// u of the batch: gathered straight into s.u in double; in float gathered in double, then
/// u_a - u_0 rounded to float (u_0 = 0: F and the hourglass modes see differences only).
template <int NN, class T>
FASCIA_INLINE void gather(const ElementSet<NN>& es, size_t e0, int n, const double* __restrict u4, Batch<NN, T>& s) {
    if constexpr (!Batch<NN, T>::kMixed) {
        gatherInto(es, e0, n, u4, s.u);
    } else {
        gatherInto(es, e0, n, u4, s.uWide);
        for (int i = 0; i < 3; ++i) {
            const double* __restrict u0 = s.uWide.v[0][i];
#pragma omp simd
            for (int k = 0; k < kBatch; ++k) s.u.v[0][i][k] = 0.0f;
            for (int a = 1; a < NN; ++a) {
                const double* __restrict ua = s.uWide.v[a][i];
                T* __restrict out = s.u.v[a][i];
#pragma omp simd
                for (int k = 0; k < n; ++k) out[k] = static_cast<T>(ua[k] - u0[k]);
            }
        }
    }
}

/// F = I + sum_a u_a (x) dN_a/dX and the invariants of C = F^T F the law uses (U: BaseMaterial::Uses).
template <int NN, unsigned U, class T>
FASCIA_INLINE void gradientAndInvariants(Batch<NN, T>& s, int n, const T* __restrict G, const Fibres<T>& fib) {
    const NodeRows<kBatch, T> dN{G};
#pragma omp simd
    for (int k = 0; k < n; ++k) {
        Mat33<T> F;
        if constexpr (NN == 4) F = deformationGradientTet(s.u, dN, k);
        else F = deformationGradient(s.u, dN, k);
        s.F.set(k, F);
        if constexpr (NN == 8) {
            // computed here, where u and F are at hand (a pass of its own reloaded them)
            hourglassModes(s.u, NodeRows<kBatch, T>{G + ElementSet<NN>::kHgRow * kBatch}, k, F, s.Kh[0]);
        }
        const Invariants3<T> in = invariants<(U & BaseMaterial::UsesI2) != 0>(F);
        s.I1[k] = in.I1;
        s.J[k] = in.J;
        s.I2[k] = in.I2;
        T I4 = 1, I6 = 1;
        if constexpr ((U & BaseMaterial::UsesI4) != 0) I4 = fibreInvariant(F, fib.a(k));
        if constexpr ((U & BaseMaterial::UsesI6) != 0) I6 = fibreInvariant(F, fib.b(k));
        s.I4[k] = I4;
        s.I6[k] = I6;
    }
}

/// Without viscosity: P from the law's response directly (Tensor3.h firstPiola).
template <int NN, unsigned U, class T>
FASCIA_INLINE void elasticStress(Batch<NN, T>& s, int n, const Fibres<T>& fib) {
    constexpr bool i2 = (U & BaseMaterial::UsesI2) != 0, i4 = (U & BaseMaterial::UsesI4) != 0, i6 = (U & BaseMaterial::UsesI6) != 0;
#pragma omp simd
    for (int k = 0; k < n; ++k)
        s.P.set(k, firstPiola<i2, i4, i6>(s.F.get(k), s.I1[k], s.r.coefficients(k), fib.a(k), fib.b(k)));
}

/// Moves s ln J from the isochoric to the volumetric part of the response (dJiso -= s/J, dJvol +=
/// s/J, their sum unchanged), so that each part a series relaxes is stress-free at rest
/// (materials/RelaxationSplit.h). max(J0, J) keeps unused lanes finite. (The formula of
/// fascia/elements/Relaxation.h restShift, and below A R + B Y its pronyState, written inline here:
/// see there why.)
template <int NN, class T>
FASCIA_INLINE void restSplit(Batch<NN, T>& s, int n, double shift, double J0) {
    const T sh = static_cast<T>(shift), j0 = static_cast<T>(J0);
#pragma omp simd
    for (int k = 0; k < n; ++k) {
        const T q = sh / std::max(j0, s.J[k]);
        s.r.dJi[k] -= q;
        s.r.dJv[k] += q;
    }
}

/// S of TLED eq. (10) in its isochoric and volumetric parts (Tensor3.h secondPiola).
template <unsigned U, int NN, class T>
FASCIA_INLINE void splitStress(const Batch<NN, T>& s, int k, const Fibres<T>& fib, Sym33<T>& Si, Sym33<T>& Sv) {
    constexpr bool i2 = (U & BaseMaterial::UsesI2) != 0, i4 = (U & BaseMaterial::UsesI4) != 0, i6 = (U & BaseMaterial::UsesI6) != 0;
    secondPiola<i2, i4, i6>(s.F.get(k), s.I1[k], s.J[k], s.r.coefficients(k), fib.a(k), fib.b(k), Si, Sv);
}

/// One series of one term (the TLED paper's models): S, Y = A Phi + B Y^(n-1), S - Y and P = F S in
/// one pass (TLED eq. (24), (30)).
/// (In float, S and P in float, the states and the relaxation in double.)
template <int NN, unsigned U, class T>
FASCIA_INLINE void viscousStressOneTerm(Batch<NN, T>& s, int n, const Fibres<T>& fib, const ViscoSet& vs, const double* __restrict Yh,
                                        double* __restrict Yn) {
    const double A1 = vs.A[0], B1 = vs.B[0];
    const double wIso = vs.iso ? 1.0 : 0.0, wVol = vs.vol ? 1.0 : 0.0;  // (weights 0 or 1: no branch in the loop)
#pragma omp simd
    for (int k = 0; k < n; ++k) {
        Sym33<T> Si, Sv;
        splitStress<U>(s, k, fib, Si, Sv);
        const auto relax = [&](T a, T b, int i) {
            const double Y = A1 * (wIso * a + wVol * b) + B1 * Yh[i * kBatch + k];
            Yn[i * kBatch + k] = Y;
            return static_cast<T>((a + b) - Y);
        };
        const Sym33<T> Sr{relax(Si.xx, Sv.xx, 0), relax(Si.yy, Sv.yy, 1), relax(Si.zz, Sv.zz, 2),
                              relax(Si.xy, Sv.xy, 3), relax(Si.yz, Sv.yz, 4), relax(Si.xz, Sv.xz, 5)};
        s.P.set(k, firstPiolaOf(s.F.get(k), Sr));
    }
}

/// Any number of series and terms: S and its parts, then one short loop per series, term and
/// component: S^n = Phi^n - sum_i Y_i^n, Y_i^n = A_i Phi^n + B_i Y_i^(n-1) (TLED eq. (24), (30)), then P = F S.
template <int NN, unsigned U, class T>
FASCIA_INLINE void viscousStress(Batch<NN, T>& s, int n, const Fibres<T>& fib, const Impl& im, const KernelIO& io, size_t batch) {
#pragma omp simd
    for (int k = 0; k < n; ++k) {
        Sym33<T> Si, Sv;
        splitStress<U>(s, k, fib, Si, Sv);
        s.Siso.set(k, Si);
        s.Svol.set(k, Sv);
        s.S.set(k, Si + Sv);
    }
    for (size_t v = 0; v < im.visco.size(); ++v) {
        const ViscoSet& vs = im.visco[v];
        // (no coefficients yet, i.e. no time step: no relaxation)
        const int terms = vs.A.size() == static_cast<size_t>(vs.terms) ? vs.terms : 0;
        const size_t slot = batch * static_cast<size_t>(vs.terms) * 6 * kBatch;
        // large states: Y goes to a scratch row, then to memory with streaming stores
        const bool stream = io.streamY && n == kBatch;
        for (int t = 0; t < terms; ++t) {
            const double A = vs.A[static_cast<size_t>(t)], Bc = vs.B[static_cast<size_t>(t)];
            for (int i = 0; i < 6; ++i) {
                const size_t row = slot + (6 * static_cast<size_t>(t) + static_cast<size_t>(i)) * kBatch;
                const double* __restrict Yh = io.Yhist[v] + row;
                double* __restrict Yn = stream ? s.Ytmp : io.Ynew[v] + row;
                const T* __restrict Ri = s.Siso.s[i];
                const T* __restrict Rv = s.Svol.s[i];
                T* __restrict Si = s.S.s[i];
                if (vs.iso && vs.vol) {
#pragma omp simd
                    for (int k = 0; k < n; ++k) {
                        const double Y = A * (Ri[k] + Rv[k]) + Bc * Yh[k];
                        Si[k] = static_cast<T>(Si[k] - Y);
                        Yn[k] = Y;
                    }
                } else {
                    const T* __restrict R = vs.iso ? Ri : Rv;  // one part only
#pragma omp simd
                    for (int k = 0; k < n; ++k) {
                        const double Y = A * R[k] + Bc * Yh[k];
                        Si[k] = static_cast<T>(Si[k] - Y);
                        Yn[k] = Y;
                    }
                }
                if (stream) simd::streamCopy(io.Ynew[v] + row, s.Ytmp, kBatch);
            }
        }
    }
#pragma omp simd
    for (int k = 0; k < n; ++k) s.P.set(k, firstPiolaOf(s.F.get(k), s.S.get(k)));
}

/// Stress output (S and F per cell, scalar): S with the viscous history read but not advanced
/// unless io.Ynew is given (with the coefficients io.A, io.B where given), then P = F S.
template <int NN, unsigned U, class T>
FASCIA_INLINE void stressOutput(Batch<NN, T>& s, int n, const Fibres<T>& fib, const Impl& im, const ElementSet<NN>& es,
                                const KernelIO& io, size_t e0, size_t batch, size_t cellOff) {
    for (int k = 0; k < n; ++k) {
        Sym33<T> Si, Sv;
        splitStress<U>(s, k, fib, Si, Sv);
        double S[6] = {Si.xx + Sv.xx, Si.yy + Sv.yy, Si.zz + Sv.zz, Si.xy + Sv.xy, Si.yz + Sv.yz, Si.xz + Sv.xz};
        const double siso[6] = {Si.xx, Si.yy, Si.zz, Si.xy, Si.yz, Si.xz}, svol[6] = {Sv.xx, Sv.yy, Sv.zz, Sv.xy, Sv.yz, Sv.xz};
        for (size_t v = 0; v < im.visco.size(); ++v) {
            const ViscoSet& vs = im.visco[v];
            double R[6];
            for (int i = 0; i < 6; ++i) R[i] = (vs.iso ? siso[i] : 0.0) + (vs.vol ? svol[i] : 0.0);
            const size_t at = batch * static_cast<size_t>(vs.terms) * 6 * kBatch + static_cast<size_t>(k);
            const double* Yh = io.Yhist[v] + at;  // term t, component i at (6 t + i) kBatch
            double* Yn = io.Ynew[v] ? io.Ynew[v] + at : nullptr;
            const int terms = io.A[v] || vs.A.size() == static_cast<size_t>(vs.terms) ? vs.terms : 0;
            const double* Av = io.A[v] ? io.A[v] : vs.A.data();
            const double* Bv = io.B[v] ? io.B[v] : vs.B.data();
            for (int t = 0; t < terms; ++t) {
                const double A = Av[t], Bc = Bv[t];
                for (int i = 0; i < 6; ++i) {
                    const size_t row = (6 * static_cast<size_t>(t) + static_cast<size_t>(i)) * kBatch;
                    const double Y = A * R[i] + Bc * Yh[row];
                    S[i] -= Y;
                    if (Yn) Yn[row] = Y;
                }
            }
        }
        const Mat33<T> F = s.F.get(k);
        const auto t = [&](int i) { return static_cast<T>(S[i]); };
        s.P.set(k, firstPiolaOf(F, Sym33<T>{t(0), t(1), t(2), t(3), t(4), t(5)}));
        const size_t cell = cellOff + static_cast<size_t>(es.orig[e0 + static_cast<size_t>(k)]);
        if (io.S)
            for (int i = 0; i < 6; ++i) io.S[6 * cell + static_cast<size_t>(i)] = S[i];
        if (io.F)
            for (int i = 0; i < 9; ++i) io.F[9 * cell + static_cast<size_t>(i)] = s.F.m[i][k];
    }
}

/// energy += the elastic energy of the batch, hourglass energy K/2 sum_q |h_q|^2 included (element
/// by element into the block's running sum).
template <int NN, class T>
FASCIA_INLINE void addEnergy(const Batch<NN, T>& s, int n, const ElementSet<NN>& es, size_t e0, double& energy) {
    for (int k = 0; k < n; ++k) energy += es.vol[e0 + static_cast<size_t>(k)] * s.r.W[k];
    if constexpr (NN == 8) {
        const double* __restrict K = es.hgK.data() + e0;
        for (int k = 0; k < n; ++k) {
            T w = 0;
            for (int r = 0; r < 12; ++r) w += s.Kh[r][k] * s.Kh[r][k];
            energy += 0.5 * K[k] * w;
        }
    }
}

/// f_a = -V P dN_a/dX (TLED eq. (1)-(3)); hexahedra with hourglass control:
/// f_a = -(V P - M) dN_a/dX - K sum_q h_qa h_q (hexNodalForces, fascia/elements/Hourglass.h).
/// (In float the volume comes from the pack's volume row.)
template <int NN, class T>
FASCIA_INLINE void nodalForces(Batch<NN, T>& s, int n, const ElementSet<NN>& es, size_t e0, const T* __restrict G) {
    const NodeRows<kBatch, T> dN{G};
    const T* __restrict vrow = Batch<NN, T>::kMixed ? G + es.volRow * kBatch : nullptr;
#pragma omp simd
    for (int k = 0; k < n; ++k) {
        const size_t e = e0 + static_cast<size_t>(k);
        T V;
        if constexpr (Batch<NN, T>::kMixed) V = vrow[k];
        else V = es.vol[e];
        const Mat33<T> P{V * s.P.m[0][k], V * s.P.m[1][k], V * s.P.m[2][k], V * s.P.m[3][k], V * s.P.m[4][k],
                         V * s.P.m[5][k], V * s.P.m[6][k], V * s.P.m[7][k], V * s.P.m[8][k]};
        if constexpr (NN == 4) {
            // (components as scalars: a Vec33 here is privatised by omp simd into an array of
            // structs, which the float loop cannot store 16 lanes at a time)
            T s0 = 0, s1 = 0, s2 = 0;
            for (int a = 1; a < 4; ++a) {
                const T g0 = dN.at(a - 1, 0, k), g1 = dN.at(a - 1, 1, k), g2 = dN.at(a - 1, 2, k);
                const T fx = -(P.xx * g0 + P.xy * g1 + P.xz * g2), fy = -(P.yx * g0 + P.yy * g1 + P.yz * g2),
                        fz = -(P.zx * g0 + P.zy * g1 + P.zz * g2);  // nodalForce (BatchView.h)
                s.f.v[a][0][k] = fx;
                s.f.v[a][1][k] = fy;
                s.f.v[a][2][k] = fz;
                s0 += fx;
                s1 += fy;
                s2 += fz;
            }
            s.f.v[0][0][k] = -s0;
            s.f.v[0][1][k] = -s1;
            s.f.v[0][2][k] = -s2;
        } else {
            const NodeRows<kBatch, T> h{s.Kh[0]}, hgC{G + ElementSet<NN>::kHgRow * kBatch};
            hexNodalForces(P, static_cast<T>(es.hgK[e]), h, hgC, dN, k, s.f);
        }
    }
}

/// Adds the batch's nodal forces into the block's node buffer (a fixed order: batch quads, then
/// nodes, then elements).
template <int NN>
FASCIA_INLINE void scatterFrom(const NodalBatch<NN, kBatch>& fb, int n, const ElementSet<NN>& es, size_t e0, double* __restrict buf, int lo) {
    const auto& s = fb;
    int kq = 0;
    for (; kq + 4 <= n; kq += 4) {
        const int* nd = &es.nodes[(e0 + static_cast<size_t>(kq)) * NN];
        for (int a = 0; a < NN; ++a) simd::scatterAdd4(buf, nd + a, NN, &s.v[a][0][kq], &s.v[a][1][kq], &s.v[a][2][kq], lo);
    }
    for (int k = kq; k < n; ++k) {
        const int* nd = &es.nodes[(e0 + static_cast<size_t>(k)) * NN];
        for (int a = 0; a < NN; ++a) {
            double* fa = buf + 4 * static_cast<size_t>(nd[a] - lo);
            fa[0] += s.v[a][0][k];
            fa[1] += s.v[a][1][k];
            fa[2] += s.v[a][2][k];
        }
    }
}

/// The batch's forces into the buffer; in float widened to double first.
template <int NN, class T>
FASCIA_INLINE void scatter(Batch<NN, T>& s, int n, const ElementSet<NN>& es, size_t e0, double* __restrict buf, int lo) {
    if constexpr (!Batch<NN, T>::kMixed) {
        scatterFrom(s.f, n, es, e0, buf, lo);
    } else {
        for (int a = 0; a < NN; ++a)
            for (int i = 0; i < 3; ++i) {
                const T* __restrict in = s.f.v[a][i];
                double* __restrict out = s.fWide.v[a][i];
#pragma omp simd
                for (int k = 0; k < n; ++k) out[k] = in[k];
            }
        scatterFrom(s.fWide, n, es, e0, buf, lo);
    }
}

/// Prefetches the element data two batches ahead (at the block's start, the next one too): a batch
/// reads its data as short streams that the hardware prefetchers pick up late; and, with viscosity,
/// the next batch's states (docs/performance.md, lesson 11).
template <int NN, class T>
FASCIA_INLINE void prefetchAhead(const Impl& im, const ElementSet<NN>& es, const Block& b, size_t e0, const T* G,
                                 bool visco, const KernelIO& io, size_t batch) {
    const size_t len = static_cast<size_t>(es.rows) * kBatch;
    for (size_t ahead = e0 == b.begin ? 1 : 2; ahead <= 2; ++ahead)
        if (e0 + ahead * kBatch < b.end) simd::prefetch(G + ahead * len, len * sizeof(T));
    if (visco && e0 + kBatch < b.end)
        for (size_t v = 0; v < im.visco.size(); ++v) {
            const size_t l = static_cast<size_t>(im.visco[v].terms) * 6 * kBatch;
            simd::prefetch(io.Yhist[v] + (batch + 1) * l, l * sizeof(double));
        }
}

/// The element loop of one block. U: the invariants the law uses (BaseMaterial::Uses bits), a
/// compile-time constant so that the vector loops carry no dead branches.
template <int NN, unsigned U, class T, class Eval>
void runKernel(const Impl& im, const Block& b, const Eval& eval, const KernelIO& io) {
    const ElementSet<NN>& es = im.template set<NN>();
    // stress output: the scalar path; forces with viscosity: the viscous path; otherwise (and for
    // the energy alone, which is the elastic one) P directly
    const bool needS = io.S || io.F;
    const bool viscoP = !needS && io.buf && !im.visco.empty();
    const ViscoSet* one = viscoP && im.visco.size() == 1 && im.visco[0].terms == 1 && im.visco[0].A.size() == 1 ? &im.visco[0] : nullptr;
    // fibre directions: per element, or the group's copied across a batch-wide row (same loops)
    const Impl::Group& grp = im.groups[static_cast<size_t>(b.group)];
    alignas(64) T uniformFibre[6][kBatch];
    if (!im.fibresPerElement && (U & (BaseMaterial::UsesI4 | BaseMaterial::UsesI6)))
        for (int c = 0; c < 3; ++c)
            for (int k = 0; k < kBatch; ++k) {
                uniformFibre[c][k] = static_cast<T>(grp.a0[c]);
                uniformFibre[3 + c][k] = static_cast<T>(grp.b0[c]);
            }
    const bool packFibres = im.fibresPerElement && es.rows - (es.volRow >= 0 ? 1 : 0) > ElementSet<NN>::kFibreRow;  // (mixed: + the volume row)
    Batch<NN, T> s;
    double energy = 0;
    for (size_t e0 = b.begin; e0 < b.end; e0 += kBatch) {
        const int n = static_cast<int>(std::min<size_t>(kBatch, b.end - e0));
        const size_t batch = b.batchBase + (e0 - b.begin) / kBatch;  // slot of the viscous states
        const T* __restrict G = es.template batchData<T>(b, e0);     // row r at G + r kBatch
        prefetchAhead(im, es, b, e0, G, viscoP, io, batch);
        const Fibres<T> fib{{packFibres ? G + ElementSet<NN>::kFibreRow * kBatch : uniformFibre[0]}};
        gather(es, e0, n, io.u, s);
        gradientAndInvariants<NN, U>(s, n, G, fib);
        eval(s, n);
        if (one) {
            if (grp.restShift != 0.0) restSplit(s, n, grp.restShift, im.J0);
            const bool stream = io.streamY && n == kBatch;
            double* Yn = stream ? s.Y6[0] : io.Ynew[0] + batch * 6 * kBatch;
            viscousStressOneTerm<NN, U>(s, n, fib, *one, io.Yhist[0] + batch * 6 * kBatch, Yn);
            if (stream) simd::streamCopy(io.Ynew[0] + batch * 6 * kBatch, s.Y6[0], 6 * kBatch);
        } else if (viscoP) {
            if (grp.restShift != 0.0) restSplit(s, n, grp.restShift, im.J0);
            viscousStress<NN, U>(s, n, fib, im, io, batch);
        } else if (!needS) {
            elasticStress<NN, U>(s, n, fib);
        } else {
            if (grp.restShift != 0.0) restSplit(s, n, grp.restShift, im.J0);
            stressOutput<NN, U>(s, n, fib, im, es, io, e0, batch, NN == 4 ? 0 : im.nTetCells);
        }
        if (io.energy) addEnergy(s, n, es, e0, energy);
        if (io.buf) {
            nodalForces(s, n, es, e0, G);
            scatter(s, n, es, e0, io.buf, io.bufLo);
        }
    }
    if (io.energy) *io.energy += energy;
}

} // namespace fascia::tled::kernel
