#include "TLEDForceField.h"

#include "ViscoelasticProny.h"
#include "fascia/base/Error.h"
#include "fascia/base/NodeOrder.h"
#include "fascia/base/Simd.h"
#include "fascia/materials/ArrudaBoyce.h"
#include "fascia/materials/HolzapfelGasserOgden.h"
#include "fascia/materials/Laws.h"
#include "fascia/materials/UncoupledMooneyRivlin.h"
#include "fascia/scene/Node.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <sstream>
#include <type_traits>

namespace fascia::tled {

using materials::BaseMaterial;
using materials::Invariants;
using materials::Response;

namespace {

/// Elements per block of the deterministic reduction (fixed: never depends on the thread count):
/// tetrahedra, and hexahedra (about 4 times the work each; smaller blocks balance the threads).
constexpr size_t kBlockTets = 2048, kBlockHexes = 512;
/// Elements per batch inside a block: F, invariants and responses of a batch stay in L1.
constexpr int kBatch = 32;
/// Nodes per tile of the buffer reduction (its sums, 3 doubles a node, stay in L1).
constexpr int kNodeTile = 1024;

std::string fmt(double v) {
    std::ostringstream s;
    s.precision(6);
    s << v;
    return s.str();
}

/// Precomputed data of one element kind, in internal order (grouped by material). Filled element by
/// element (AoS), then packed by finish() batch by batch: the batch in slot m (the blocks' batches
/// in order, see Block::batchBase and batchOffset) holds its rows one after the other, row r at
/// pack[(m rows + r) kBatch + k] for element k of the batch. A batch's data is then one contiguous
/// stream at constant offsets from one pointer: with a row of all elements per component (the
/// earlier layout) the element loop needed one pointer per row (36 for a hexahedron) and spilled
/// them to the stack (docs/performance.md).
template <int NN>
struct ElementSet {
    /// rows of the pack: dN_a/dX (tetrahedra: nodes 1-3 only, dN_0 = -(dN_1 + dN_2 + dN_3)), then
    /// for hexahedra the hourglass c_q, then the fibre directions a0 and b0 when given per element
    static constexpr int kDnRows = NN == 4 ? 9 : 24;
    static constexpr int kHgRow = kDnRows;                         ///< hexahedra: c_q, rows kHgRow + 3q + i
    static constexpr int kFibreRow = NN == 8 ? kDnRows + 12 : kDnRows;  ///< a0 x y z, then b0 x y z

    std::vector<int> nodes;     ///< NN per element (AoS)
    std::vector<double> dN;     ///< AoS dN_a/dX, 3 per node (emptied by finish())
    std::vector<double> vol;    ///< rest volume (m^3)
    std::vector<double> a0, b0; ///< AoS fibre directions per element (empty unless a fibre array gives them; emptied by finish())
    std::vector<int> orig;      ///< index in the input list of its kind
    std::vector<double> length; ///< characteristic length L_e (m)
    std::vector<double> hgC;    ///< AoS hexahedra: c_q = sum_a h_qa X_a of the 4 hourglass base vectors h_q, 3q + i (emptied by finish())
    std::vector<double> hgK;    ///< hexahedra: hourglass stiffness K (N/m)
    simd::DVec pack;            ///< the rows above, batch by batch
    int rows = 0;               ///< rows per batch in pack
    size_t batchOffset = 0;     ///< Block::batchBase of the first batch of this kind
    size_t size() const { return vol.size(); }
    /// the pack of the batch starting at element e0 of block b
    template <class Block> const double* batchData(const Block& b, size_t e0) const {
        return pack.data() + (b.batchBase - batchOffset + (e0 - b.begin) / kBatch) * static_cast<size_t>(rows) * kBatch;
    }
    /// packs the AoS arrays; batches: first element and size of every batch, in slot order
    void finish(const std::vector<std::pair<size_t, size_t>>& batches) {
        if (size() == 0) return;
        const bool fibres = !a0.empty() || !b0.empty();
        rows = kFibreRow + (fibres ? 6 : 0);
        pack.assign(batches.size() * static_cast<size_t>(rows) * kBatch, 0.0);
        for (size_t m = 0; m < batches.size(); ++m) {
            double* P = pack.data() + m * static_cast<size_t>(rows) * kBatch;
            for (size_t k = 0; k < batches[m].second; ++k) {
                const size_t e = batches[m].first + k;
                for (int r = 0; r < kDnRows; ++r) P[r * kBatch + k] = dN[e * 3 * NN + (NN == 4 ? 3 : 0) + static_cast<size_t>(r)];
                if constexpr (NN == 8)
                    for (int r = 0; r < 12; ++r) P[(kHgRow + r) * kBatch + k] = hgC[e * 12 + static_cast<size_t>(r)];
                for (int c = 0; c < 3 && fibres; ++c) {
                    P[(kFibreRow + c) * kBatch + k] = a0.empty() ? (c == 0 ? 1.0 : 0.0) : a0[3 * e + static_cast<size_t>(c)];
                    P[(kFibreRow + 3 + c) * kBatch + k] = b0.empty() ? (c == 1 ? 1.0 : 0.0) : b0[3 * e + static_cast<size_t>(c)];
                }
            }
        }
        dN = {};
        hgC = {};
        a0 = {};
        b0 = {};
    }
};

// natural coordinates of the 8 nodes of a hexahedron, VTK order
constexpr double kHexXi[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                 {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
// hourglass base vectors xi eta, eta zeta, zeta xi, xi eta zeta at the nodes (Flanagan-Belytschko)
constexpr double kHourglass[4][8] = {{1, -1, 1, -1, 1, -1, 1, -1},
                                     {1, 1, -1, -1, -1, -1, 1, 1},
                                     {1, -1, -1, 1, -1, 1, 1, -1},
                                     {-1, 1, -1, 1, 1, -1, 1, -1}};
constexpr int kHexFaces[6][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};

double det3(const double m[9]) {
    return m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) + m[2] * (m[3] * m[7] - m[4] * m[6]);
}
/// cofactor matrix (row-major): cof(M) = det(M) M^-T
void cof3(const double m[9], double c[9]) {
    c[0] = m[4] * m[8] - m[5] * m[7];
    c[1] = m[5] * m[6] - m[3] * m[8];
    c[2] = m[3] * m[7] - m[4] * m[6];
    c[3] = m[2] * m[7] - m[1] * m[8];
    c[4] = m[0] * m[8] - m[2] * m[6];
    c[5] = m[1] * m[6] - m[0] * m[7];
    c[6] = m[1] * m[5] - m[2] * m[4];
    c[7] = m[2] * m[3] - m[0] * m[5];
    c[8] = m[0] * m[4] - m[1] * m[3];
}

/// One Prony series acting on the isochoric and/or volumetric part of S.
struct ViscoSet {
    viscoelastic::ViscoelasticProny* prony = nullptr;
    bool iso = false, vol = false;
    int terms = 0;
    std::vector<double> A, B;
    /// the states Y_i of the last step and of the current evaluation, batch by batch (one contiguous
    /// stream per array): batch m of the elements (Block::batchBase + local batch) holds, for each
    /// term t and stress component c (xx yy zz xy yz xz), kBatch values at ((m terms + t) 6 + c) kBatch
    simd::DVec Yprev, Ycur;
};

} // namespace

/// What a kernel call writes (any output may be null).
struct KernelIO {
    const double* u = nullptr; ///< nodal displacements x - X, 4 per internal node (padded)
    double* buf = nullptr;     ///< the block's node buffer (4 per internal node from Block::nodeLo, padded)
    double* energy = nullptr;  ///< energy of the block (added to)
    double* S = nullptr;       ///< 6 per cell (cell order)
    double* F = nullptr;       ///< 9 per cell (cell order)
    const double* Yhist[2] = {nullptr, nullptr};
    double* Ynew[2] = {nullptr, nullptr};
    bool streamY = false;      ///< write Ynew with streaming stores (large states)
};

struct TLEDForceField::Impl {
    using KernelFn = void (*)(const Impl&, const Block&, const KernelIO&);
    struct Group {
        int kind = 0;
        const BaseMaterial* material = nullptr;
        unsigned uses = 0;
        double pModulus = 0;        ///< bulk + 4/3 shear (Pa)
        const void* law = nullptr;  ///< the inlined law, when the material is a built-in one
        KernelFn fn = nullptr;
        double a0[3] = {1, 0, 0}, b0[3] = {0, 1, 0};  ///< fibre directions when not given per element
    };
    bool fibresPerElement = false;  ///< a fibre array gives the directions (ElementSet::a0, b0), else Group::a0, b0
    ElementSet<4> tet;
    ElementSet<8> hex;
    std::vector<Group> groups;
    std::vector<ViscoSet> visco;
    double J0 = 0.4;
    size_t nodeCount = 0;  ///< 1 + largest node index
    std::vector<int> nodeOf;  ///< internal node -> state node when the nodes are renumbered (empty: the state's order); ElementSet::nodes are internal
    size_t nTetCells = 0;  ///< number of tetrahedra (cell offset of the hexahedra)
    bool haveCur = false;
    double curTime = 0;
    std::vector<double> buf;
    std::vector<double> u;  ///< displacements of the last addForce, 4 per internal node

    template <int NN> const ElementSet<NN>& set() const {
        if constexpr (NN == 4) return tet; else return hex;
    }
    template <int NN> ElementSet<NN>& set() {
        if constexpr (NN == 4) return tet; else return hex;
    }
    size_t batches = 0;        ///< element batches of all blocks (the viscous states hold one slot per batch)
    bool streamStates = false; ///< viscous states too large for the caches: streaming stores
};

namespace {

using Impl = TLEDForceField::Impl;

/// Per-batch scratch of the element loop, as structure of arrays (index k = element in the batch).
template <int NN>
struct Batch {
    alignas(64) double u[NN][3][kBatch];   ///< nodal displacements x - X
    alignas(64) double F[9][kBatch];       ///< deformation gradient, row-major
    alignas(64) double I1[kBatch], I2[kBatch], J[kBatch], I4[kBatch], I6[kBatch];
    alignas(64) double W[kBatch], d1[kBatch], d2[kBatch], d4[kBatch], d6[kBatch], dJi[kBatch], dJv[kBatch];
    alignas(64) double P[9][kBatch];       ///< first Piola-Kirchhoff stress, row-major
    alignas(64) double Siso[6][kBatch], Svol[6][kBatch], S[6][kBatch];  ///< viscous path: S and its parts
    alignas(64) double Ytmp[kBatch];       ///< viscous path: a state row on its way to a streaming store
    alignas(64) double Y6[6][kBatch];      ///< the same for the six rows of a one-term series
    alignas(64) double f[NN][3][kBatch];   ///< element nodal forces
    alignas(64) double Kh[NN == 8 ? 12 : 1][kBatch];  ///< hexahedra: hourglass displacements h_q, rows 3q + j
};

/// The element loop of one block, in short passes over batches of elements (PERFORMANCE.md lessons
/// 1-3): gather displacements; F and the invariants; the law for the whole batch; P; nodal forces;
/// scatter into the block's node buffer.
/// U: the invariants the law uses (BaseMaterial::Uses bits), a compile-time constant so that the
/// vector loops carry no dead branches (and no masked loads from absent fibre arrays).
template <int NN, unsigned U, class Block, class Eval>
void runKernel(const Impl& im, const Block& b, const Eval& eval, const KernelIO& io) {
    const ElementSet<NN>& es = im.template set<NN>();
    constexpr bool useI2 = (U & BaseMaterial::UsesI2) != 0;
    constexpr bool useI4 = (U & BaseMaterial::UsesI4) != 0;
    constexpr bool useI6 = (U & BaseMaterial::UsesI6) != 0;
    // stress output: the scalar path; forces with viscosity: the vectorised viscous path; otherwise
    // (and for the energy alone, which is the elastic one) P directly
    const bool needS = io.S || io.F;
    const bool viscoP = !needS && io.buf && !im.visco.empty();
    const size_t cellOff = NN == 4 ? 0 : im.nTetCells;
    // fibre directions: per element, or the group's, copied across a batch-wide row (same loops)
    const Impl::Group& grp = im.groups[static_cast<size_t>(b.group)];
    alignas(64) double uniformFibre[6][kBatch];
    if (!im.fibresPerElement && (useI4 || useI6))
        for (int c = 0; c < 3; ++c)
            for (int k = 0; k < kBatch; ++k) {
                uniformFibre[c][k] = grp.a0[c];
                uniformFibre[3 + c][k] = grp.b0[c];
            }
    const double* __restrict vol = es.vol.data();
    const double* __restrict u4 = io.u;

    Batch<NN> s;
    double energy = 0;

    for (size_t e0 = b.begin; e0 < b.end; e0 += kBatch) {
        const int n = static_cast<int>(std::min<size_t>(kBatch, b.end - e0));
        const size_t batch = b.batchBase + (e0 - b.begin) / kBatch;  // slot of the viscous states
        // the batch's element data: row r at G + r kBatch (ElementSet::pack)
        const double* __restrict G = es.batchData(b, e0);
        const double* __restrict dN = G;
        // the element data two batches ahead (at the block's start, the next one too): a batch reads
        // its data as 9-42 rows of 4 cache lines each, short streams that the hardware prefetchers
        // pick up late (docs/performance.md: 10-40 % on large meshes; two ahead measured faster than one)
        for (size_t ahead = e0 == b.begin ? 1 : 2; ahead <= 2; ++ahead)
            if (e0 + ahead * kBatch < b.end)
                simd::prefetch(G + ahead * static_cast<size_t>(es.rows) * kBatch, static_cast<size_t>(es.rows) * kBatch * sizeof(double));
        const bool packFibres = im.fibresPerElement && es.rows > ElementSet<NN>::kFibreRow;
        const double* __restrict fib = packFibres ? G + ElementSet<NN>::kFibreRow * kBatch : uniformFibre[0];
        const double* __restrict A0x = fib, *__restrict A0y = fib + kBatch, *__restrict A0z = fib + 2 * kBatch;
        const double* __restrict B0x = fib + 3 * kBatch, *__restrict B0y = fib + 4 * kBatch, *__restrict B0z = fib + 5 * kBatch;
        if (viscoP && e0 + kBatch < b.end)
            // the states of the next batch are read once per step, usually from memory: ask early
            for (size_t v = 0; v < im.visco.size(); ++v) {
                const size_t len = static_cast<size_t>(im.visco[v].terms) * 6 * kBatch;
                simd::prefetch(io.Yhist[v] + (batch + 1) * len, len * sizeof(double));
            }

        // gather u = x - X (precomputed per node, padded to 4; forming F from displacements keeps it
        // accurate, lesson 6)
        int kq = 0;
        for (; kq + 4 <= n; kq += 4) {
            const int* nd = &es.nodes[(e0 + static_cast<size_t>(kq)) * NN];
            for (int a = 0; a < NN; ++a) simd::gather4(u4, nd + a, NN, &s.u[a][0][kq], &s.u[a][1][kq], &s.u[a][2][kq]);
        }
        for (int k = kq; k < n; ++k) {
            const int* nd = &es.nodes[(e0 + static_cast<size_t>(k)) * NN];
            for (int a = 0; a < NN; ++a) {
                const double* up = u4 + 4 * static_cast<size_t>(nd[a]);
                s.u[a][0][k] = up[0];
                s.u[a][1][k] = up[1];
                s.u[a][2][k] = up[2];
            }
        }

        // F = I + sum_a u_a (x) dN_a/dX and the invariants of C = F^T F
#pragma omp simd
        for (int k = 0; k < n; ++k) {
            double F0 = 1, F1 = 0, F2 = 0, F3 = 0, F4 = 1, F5 = 0, F6 = 0, F7 = 0, F8 = 1;
            if constexpr (NN == 4) {
                // dN_0 = -(dN_1 + dN_2 + dN_3): sum_a u_a dN_a = sum_{a>0} (u_a - u_0) dN_a
                for (int a = 1; a < 4; ++a) {
                    const double g0 = dN[(3 * (a - 1)) * kBatch + k], g1 = dN[(3 * (a - 1) + 1) * kBatch + k],
                                 g2 = dN[(3 * (a - 1) + 2) * kBatch + k];
                    const double v0 = s.u[a][0][k] - s.u[0][0][k], v1 = s.u[a][1][k] - s.u[0][1][k],
                                 v2 = s.u[a][2][k] - s.u[0][2][k];
                    F0 += v0 * g0; F1 += v0 * g1; F2 += v0 * g2;
                    F3 += v1 * g0; F4 += v1 * g1; F5 += v1 * g2;
                    F6 += v2 * g0; F7 += v2 * g1; F8 += v2 * g2;
                }
            } else {
                for (int a = 0; a < NN; ++a) {
                    const double g0 = dN[(3 * a) * kBatch + k], g1 = dN[(3 * a + 1) * kBatch + k], g2 = dN[(3 * a + 2) * kBatch + k];
                    const double v0 = s.u[a][0][k], v1 = s.u[a][1][k], v2 = s.u[a][2][k];
                    F0 += v0 * g0; F1 += v0 * g1; F2 += v0 * g2;
                    F3 += v1 * g0; F4 += v1 * g1; F5 += v1 * g2;
                    F6 += v2 * g0; F7 += v2 * g1; F8 += v2 * g2;
                }
            }
            s.F[0][k] = F0; s.F[1][k] = F1; s.F[2][k] = F2;
            s.F[3][k] = F3; s.F[4][k] = F4; s.F[5][k] = F5;
            s.F[6][k] = F6; s.F[7][k] = F7; s.F[8][k] = F8;
            if constexpr (NN == 8) {
                // hourglass control (Flanagan-Belytschko): h_q = sum_a gamma_qa u_a with gamma_qa = h_qa - c_q . dN_a/dX,
                // c_q = sum_b h_qb X_b precomputed, so h_q = sum_a h_qa u_a - (F - I) c_q (F - I = grad u); energy
                // K/2 sum_q |h_q|^2. The sums over the nodes with the +-1 entries of kHourglass are sums and
                // differences of node pairs (18 additions per component instead of 32 multiply-adds). Computed
                // here, where u and F are at hand (a pass of its own reloaded them).
                const double* __restrict C = G + ElementSet<NN>::kHgRow * kBatch;  // c_q: row 3q + i at C + (3q + i) kBatch
                const auto hourglass = [&](int j, double g0, double g1, double g2) {  // component j, g = row j of F - I
                    const double d01 = s.u[0][j][k] - s.u[1][j][k], d23 = s.u[2][j][k] - s.u[3][j][k],
                                 d45 = s.u[4][j][k] - s.u[5][j][k], d67 = s.u[6][j][k] - s.u[7][j][k];
                    const double a01 = s.u[0][j][k] + s.u[1][j][k], a23 = s.u[2][j][k] + s.u[3][j][k],
                                 a45 = s.u[4][j][k] + s.u[5][j][k], a67 = s.u[6][j][k] + s.u[7][j][k];
                    const double X = d01 + d23, Y = d45 + d67;
                    s.Kh[j][k] = (X + Y) - (g0 * C[k] + g1 * C[kBatch + k] + g2 * C[2 * kBatch + k]);  // ( 1,-1, 1,-1, 1,-1, 1,-1)
                    s.Kh[3 + j][k] = (a01 - a23) + (a67 - a45) -
                                     (g0 * C[3 * kBatch + k] + g1 * C[4 * kBatch + k] + g2 * C[5 * kBatch + k]);  // ( 1, 1,-1,-1,-1,-1, 1, 1)
                    s.Kh[6 + j][k] = (d01 - d23) + (d67 - d45) -
                                     (g0 * C[6 * kBatch + k] + g1 * C[7 * kBatch + k] + g2 * C[8 * kBatch + k]);  // ( 1,-1,-1, 1,-1, 1, 1,-1)
                    s.Kh[9 + j][k] = (Y - X) - (g0 * C[9 * kBatch + k] + g1 * C[10 * kBatch + k] + g2 * C[11 * kBatch + k]);  // (-1, 1,-1, 1, 1,-1, 1,-1)
                };
                hourglass(0, F0 - 1, F1, F2);
                hourglass(1, F3, F4 - 1, F5);
                hourglass(2, F6, F7, F8 - 1);
            }
            const double C00 = F0 * F0 + F3 * F3 + F6 * F6;
            const double C11 = F1 * F1 + F4 * F4 + F7 * F7;
            const double C22 = F2 * F2 + F5 * F5 + F8 * F8;
            const double I1 = C00 + C11 + C22;
            s.I1[k] = I1;
            s.J[k] = F0 * (F4 * F8 - F5 * F7) - F1 * (F3 * F8 - F5 * F6) + F2 * (F3 * F7 - F4 * F6);
            double I2 = 3;
            if constexpr (useI2) {
                const double C01 = F0 * F1 + F3 * F4 + F6 * F7;
                const double C02 = F0 * F2 + F3 * F5 + F6 * F8;
                const double C12 = F1 * F2 + F4 * F5 + F7 * F8;
                I2 = 0.5 * (I1 * I1 - (C00 * C00 + C11 * C11 + C22 * C22 + 2 * (C01 * C01 + C02 * C02 + C12 * C12)));
            }
            s.I2[k] = I2;
            double I4 = 1, I6 = 1;
            if constexpr (useI4) {
                const double a0 = A0x[k], a1 = A0y[k], a2 = A0z[k];
                const double f0 = F0 * a0 + F1 * a1 + F2 * a2, f1 = F3 * a0 + F4 * a1 + F5 * a2, f2 = F6 * a0 + F7 * a1 + F8 * a2;
                I4 = f0 * f0 + f1 * f1 + f2 * f2;  // a0 . C a0
            }
            if constexpr (useI6) {
                const double b0 = B0x[k], b1 = B0y[k], b2 = B0z[k];
                const double f0 = F0 * b0 + F1 * b1 + F2 * b2, f1 = F3 * b0 + F4 * b1 + F5 * b2, f2 = F6 * b0 + F7 * b1 + F8 * b2;
                I6 = f0 * f0 + f1 * f1 + f2 * f2;  // b0 . C b0
            }
            s.I4[k] = I4;
            s.I6[k] = I6;
        }

        // the law: W and dW/dI for the whole batch (inlined for built-in laws, one call otherwise)
        eval(s, n);

        if (viscoP) {
            // S in 6 components (xx yy zz xy yz xz): isochoric and volumetric parts, TLED eq. (10), as in
            // the scalar path below but vectorised. One series of one term (the TLED paper's models) is
            // relaxed and turned into P in the same loop; otherwise short loops per series, term and
            // component follow (PERFORMANCE.md lesson 3).
            const ViscoSet* one = im.visco.size() == 1 && im.visco[0].terms == 1 && im.visco[0].A.size() == 1 ? &im.visco[0] : nullptr;
            const double A1 = one ? one->A[0] : 0.0, B1 = one ? one->B[0] : 0.0;
            const double wIso = one && one->iso ? 1.0 : 0.0, wVol = one && one->vol ? 1.0 : 0.0;
            const bool stream1 = one && io.streamY && n == kBatch;
            const double* __restrict Yh1 = one ? io.Yhist[0] + batch * 6 * kBatch : nullptr;
            double* __restrict Yn1 = one ? (stream1 ? s.Y6[0] : io.Ynew[0] + batch * 6 * kBatch) : nullptr;
            auto stressLoop = [&](auto fusedTag) {
                constexpr bool fused = decltype(fusedTag)::value;
#pragma omp simd
                for (int k = 0; k < n; ++k) {
                    const double F0 = s.F[0][k], F1 = s.F[1][k], F2 = s.F[2][k], F3 = s.F[3][k], F4 = s.F[4][k],
                                 F5 = s.F[5][k], F6 = s.F[6][k], F7 = s.F[7][k], F8 = s.F[8][k];
                    // cofactor matrix of F
                    const double cf0 = F4 * F8 - F5 * F7, cf1 = F5 * F6 - F3 * F8, cf2 = F3 * F7 - F4 * F6,
                                 cf3 = F2 * F7 - F1 * F8, cf4 = F0 * F8 - F2 * F6, cf5 = F1 * F6 - F0 * F7,
                                 cf6 = F1 * F5 - F2 * F4, cf7 = F2 * F3 - F0 * F5, cf8 = F0 * F4 - F1 * F3;
                    const double c1 = 2 * s.d1[k];
                    const double J = s.J[k];
                    const double iJ = 1.0 / (std::abs(J) > 1e-300 ? J : (J < 0 ? -1e-300 : 1e-300));
                    // J C^-1 = cof(F)^T cof(F) / J
                    const double JCi0 = (cf0 * cf0 + cf3 * cf3 + cf6 * cf6) * iJ;
                    const double JCi1 = (cf1 * cf1 + cf4 * cf4 + cf7 * cf7) * iJ;
                    const double JCi2 = (cf2 * cf2 + cf5 * cf5 + cf8 * cf8) * iJ;
                    const double JCi3 = (cf0 * cf1 + cf3 * cf4 + cf6 * cf7) * iJ;
                    const double JCi4 = (cf1 * cf2 + cf4 * cf5 + cf7 * cf8) * iJ;
                    const double JCi5 = (cf0 * cf2 + cf3 * cf5 + cf6 * cf8) * iJ;
                    double S0 = c1, S1 = c1, S2 = c1, S3 = 0, S4 = 0, S5 = 0;
                    if constexpr (useI2) {
                        const double c2 = 2 * s.d2[k], I1 = s.I1[k];
                        S0 += c2 * (I1 - (F0 * F0 + F3 * F3 + F6 * F6));
                        S1 += c2 * (I1 - (F1 * F1 + F4 * F4 + F7 * F7));
                        S2 += c2 * (I1 - (F2 * F2 + F5 * F5 + F8 * F8));
                        S3 -= c2 * (F0 * F1 + F3 * F4 + F6 * F7);
                        S4 -= c2 * (F1 * F2 + F4 * F5 + F7 * F8);
                        S5 -= c2 * (F0 * F2 + F3 * F5 + F6 * F8);
                    }
                    if constexpr (useI4) {
                        const double c4 = 2 * s.d4[k];
                        const double a0 = A0x[k], a1 = A0y[k], a2 = A0z[k];
                        S0 += c4 * a0 * a0; S1 += c4 * a1 * a1; S2 += c4 * a2 * a2;
                        S3 += c4 * a0 * a1; S4 += c4 * a1 * a2; S5 += c4 * a0 * a2;
                    }
                    if constexpr (useI6) {
                        const double c6 = 2 * s.d6[k];
                        const double b0 = B0x[k], b1 = B0y[k], b2 = B0z[k];
                        S0 += c6 * b0 * b0; S1 += c6 * b1 * b1; S2 += c6 * b2 * b2;
                        S3 += c6 * b0 * b1; S4 += c6 * b1 * b2; S5 += c6 * b0 * b2;
                    }
                    const double dJi = s.dJi[k], dJv = s.dJv[k];
                    S0 += dJi * JCi0; S1 += dJi * JCi1; S2 += dJi * JCi2;
                    S3 += dJi * JCi3; S4 += dJi * JCi4; S5 += dJi * JCi5;
                    const double V0 = dJv * JCi0, V1 = dJv * JCi1, V2 = dJv * JCi2, V3 = dJv * JCi3, V4 = dJv * JCi4,
                                 V5 = dJv * JCi5;
                    if constexpr (!fused) {
                        s.Siso[0][k] = S0; s.Siso[1][k] = S1; s.Siso[2][k] = S2;
                        s.Siso[3][k] = S3; s.Siso[4][k] = S4; s.Siso[5][k] = S5;
                        s.Svol[0][k] = V0; s.Svol[1][k] = V1; s.Svol[2][k] = V2;
                        s.Svol[3][k] = V3; s.Svol[4][k] = V4; s.Svol[5][k] = V5;
                        s.S[0][k] = S0 + V0; s.S[1][k] = S1 + V1; s.S[2][k] = S2 + V2;
                        s.S[3][k] = S3 + V3; s.S[4][k] = S4 + V4; s.S[5][k] = S5 + V5;
                    } else {
                        // one term: Y = A Phi + B Y^(n-1) and S = Siso + Svol - Y (TLED eq. (24), (30)), then P = F S
                        // (scalars, not small arrays: "omp simd" would move arrays to memory)
                        const auto relax = [&](double Si, double Sv, int i) {
                            const double R = wIso * Si + wVol * Sv;  // (weights 0 or 1: no branch in the loop)
                            const double Y = A1 * R + B1 * Yh1[i * kBatch + k];
                            Yn1[i * kBatch + k] = Y;
                            return (Si + Sv) - Y;
                        };
                        const double T0 = relax(S0, V0, 0), T1 = relax(S1, V1, 1), T2 = relax(S2, V2, 2),
                                     T3 = relax(S3, V3, 3), T4 = relax(S4, V4, 4), T5 = relax(S5, V5, 5);
                        s.P[0][k] = F0 * T0 + F1 * T3 + F2 * T5;
                        s.P[1][k] = F0 * T3 + F1 * T1 + F2 * T4;
                        s.P[2][k] = F0 * T5 + F1 * T4 + F2 * T2;
                        s.P[3][k] = F3 * T0 + F4 * T3 + F5 * T5;
                        s.P[4][k] = F3 * T3 + F4 * T1 + F5 * T4;
                        s.P[5][k] = F3 * T5 + F4 * T4 + F5 * T2;
                        s.P[6][k] = F6 * T0 + F7 * T3 + F8 * T5;
                        s.P[7][k] = F6 * T3 + F7 * T1 + F8 * T4;
                        s.P[8][k] = F6 * T5 + F7 * T4 + F8 * T2;
                    }
                }
            };
            if (one) {
                stressLoop(std::true_type{});
                if (stream1) simd::streamCopy(io.Ynew[0] + batch * 6 * kBatch, s.Y6[0], 6 * kBatch);
            } else {
                stressLoop(std::false_type{});
                // viscoelastic relaxation: S^n = Phi^n - sum_i Y_i^n, Y_i^n = A_i Phi^n + B_i Y_i^(n-1)
                // (TLED eq. (24), (30)), one short loop per series, term and component over the batch
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
                            const double* __restrict Ri = s.Siso[i];
                            const double* __restrict Rv = s.Svol[i];
                            double* __restrict Si = s.S[i];
                            if (vs.iso && vs.vol) {
#pragma omp simd
                                for (int k = 0; k < n; ++k) {
                                    const double Y = A * (Ri[k] + Rv[k]) + Bc * Yh[k];
                                    Si[k] -= Y;
                                    Yn[k] = Y;
                                }
                            } else {
                                // one part only (apply is isochoric, volumetric or both)
                                const double* __restrict R = vs.iso ? Ri : Rv;
#pragma omp simd
                                for (int k = 0; k < n; ++k) {
                                    const double Y = A * R[k] + Bc * Yh[k];
                                    Si[k] -= Y;
                                    Yn[k] = Y;
                                }
                            }
                            if (stream) simd::streamCopy(io.Ynew[v] + row, s.Ytmp, kBatch);
                        }
                    }
                }
                // P = F S
#pragma omp simd
                for (int k = 0; k < n; ++k) {
                    const double S0 = s.S[0][k], S1 = s.S[1][k], S2 = s.S[2][k], S3 = s.S[3][k], S4 = s.S[4][k],
                                 S5 = s.S[5][k];
                    for (int i = 0; i < 3; ++i) {
                        const double f0 = s.F[3 * i][k], f1 = s.F[3 * i + 1][k], f2 = s.F[3 * i + 2][k];
                        s.P[3 * i + 0][k] = f0 * S0 + f1 * S3 + f2 * S5;
                        s.P[3 * i + 1][k] = f0 * S3 + f1 * S1 + f2 * S4;
                        s.P[3 * i + 2][k] = f0 * S5 + f1 * S4 + f2 * S2;
                    }
                }
            }
        } else if (!needS) {
            // P = 2 dI1 F + 2 dI2 (I1 F - F C) + 2 dI4 (F a0)(x)a0 + 2 dI6 (F b0)(x)b0 + dW/dJ cof F
#pragma omp simd
            for (int k = 0; k < n; ++k) {
                const double F0 = s.F[0][k], F1 = s.F[1][k], F2 = s.F[2][k], F3 = s.F[3][k], F4 = s.F[4][k],
                             F5 = s.F[5][k], F6 = s.F[6][k], F7 = s.F[7][k], F8 = s.F[8][k];
                const double c1 = 2 * s.d1[k], cj = s.dJi[k] + s.dJv[k];
                double P0 = c1 * F0 + cj * (F4 * F8 - F5 * F7), P1 = c1 * F1 + cj * (F5 * F6 - F3 * F8),
                       P2 = c1 * F2 + cj * (F3 * F7 - F4 * F6), P3 = c1 * F3 + cj * (F2 * F7 - F1 * F8),
                       P4 = c1 * F4 + cj * (F0 * F8 - F2 * F6), P5 = c1 * F5 + cj * (F1 * F6 - F0 * F7),
                       P6 = c1 * F6 + cj * (F1 * F5 - F2 * F4), P7 = c1 * F7 + cj * (F2 * F3 - F0 * F5),
                       P8 = c1 * F8 + cj * (F0 * F4 - F1 * F3);
                if constexpr (useI2) {
                    // I1 F - F C with F C = (F F^T) F
                    const double c2 = 2 * s.d2[k], I1 = s.I1[k];
                    const double B00 = F0 * F0 + F1 * F1 + F2 * F2, B11 = F3 * F3 + F4 * F4 + F5 * F5,
                                 B22 = F6 * F6 + F7 * F7 + F8 * F8, B01 = F0 * F3 + F1 * F4 + F2 * F5,
                                 B02 = F0 * F6 + F1 * F7 + F2 * F8, B12 = F3 * F6 + F4 * F7 + F5 * F8;
                    P0 += c2 * (I1 * F0 - (B00 * F0 + B01 * F3 + B02 * F6));
                    P1 += c2 * (I1 * F1 - (B00 * F1 + B01 * F4 + B02 * F7));
                    P2 += c2 * (I1 * F2 - (B00 * F2 + B01 * F5 + B02 * F8));
                    P3 += c2 * (I1 * F3 - (B01 * F0 + B11 * F3 + B12 * F6));
                    P4 += c2 * (I1 * F4 - (B01 * F1 + B11 * F4 + B12 * F7));
                    P5 += c2 * (I1 * F5 - (B01 * F2 + B11 * F5 + B12 * F8));
                    P6 += c2 * (I1 * F6 - (B02 * F0 + B12 * F3 + B22 * F6));
                    P7 += c2 * (I1 * F7 - (B02 * F1 + B12 * F4 + B22 * F7));
                    P8 += c2 * (I1 * F8 - (B02 * F2 + B12 * F5 + B22 * F8));
                }
                if constexpr (useI4) {
                    const double c4 = 2 * s.d4[k];
                    const double a0 = A0x[k], a1 = A0y[k], a2 = A0z[k];
                    const double f0 = c4 * (F0 * a0 + F1 * a1 + F2 * a2), f1 = c4 * (F3 * a0 + F4 * a1 + F5 * a2),
                                 f2 = c4 * (F6 * a0 + F7 * a1 + F8 * a2);
                    P0 += f0 * a0; P1 += f0 * a1; P2 += f0 * a2;
                    P3 += f1 * a0; P4 += f1 * a1; P5 += f1 * a2;
                    P6 += f2 * a0; P7 += f2 * a1; P8 += f2 * a2;
                }
                if constexpr (useI6) {
                    const double c6 = 2 * s.d6[k];
                    const double b0 = B0x[k], b1 = B0y[k], b2 = B0z[k];
                    const double f0 = c6 * (F0 * b0 + F1 * b1 + F2 * b2), f1 = c6 * (F3 * b0 + F4 * b1 + F5 * b2),
                                 f2 = c6 * (F6 * b0 + F7 * b1 + F8 * b2);
                    P0 += f0 * b0; P1 += f0 * b1; P2 += f0 * b2;
                    P3 += f1 * b0; P4 += f1 * b1; P5 += f1 * b2;
                    P6 += f2 * b0; P7 += f2 * b1; P8 += f2 * b2;
                }
                s.P[0][k] = P0; s.P[1][k] = P1; s.P[2][k] = P2;
                s.P[3][k] = P3; s.P[4][k] = P4; s.P[5][k] = P5;
                s.P[6][k] = P6; s.P[7][k] = P7; s.P[8][k] = P8;
            }
        } else {
            for (int k = 0; k < n; ++k) {
                const size_t e = e0 + static_cast<size_t>(k);
                double F[9], cf[9];
                for (int i = 0; i < 9; ++i) F[i] = s.F[i][k];
                cof3(F, cf);
                const double c1 = 2 * s.d1[k], c2 = 2 * s.d2[k], c4 = 2 * s.d4[k], c6 = 2 * s.d6[k];
                // S in 6 components (xx yy zz xy yz xz): isochoric and volumetric parts, TLED eq. (10)
                const double J = s.J[k];
                const double iJ = 1.0 / (std::abs(J) > 1e-300 ? J : (J < 0 ? -1e-300 : 1e-300));
                // J C^-1 = cof(F)^T cof(F) / J
                double JCi[6];
                JCi[0] = (cf[0] * cf[0] + cf[3] * cf[3] + cf[6] * cf[6]) * iJ;
                JCi[1] = (cf[1] * cf[1] + cf[4] * cf[4] + cf[7] * cf[7]) * iJ;
                JCi[2] = (cf[2] * cf[2] + cf[5] * cf[5] + cf[8] * cf[8]) * iJ;
                JCi[3] = (cf[0] * cf[1] + cf[3] * cf[4] + cf[6] * cf[7]) * iJ;
                JCi[4] = (cf[1] * cf[2] + cf[4] * cf[5] + cf[7] * cf[8]) * iJ;
                JCi[5] = (cf[0] * cf[2] + cf[3] * cf[5] + cf[6] * cf[8]) * iJ;
                double Siso[6] = {c1, c1, c1, 0, 0, 0};
                if constexpr (useI2) {
                    const double C[6] = {F[0] * F[0] + F[3] * F[3] + F[6] * F[6], F[1] * F[1] + F[4] * F[4] + F[7] * F[7],
                                         F[2] * F[2] + F[5] * F[5] + F[8] * F[8], F[0] * F[1] + F[3] * F[4] + F[6] * F[7],
                                         F[1] * F[2] + F[4] * F[5] + F[7] * F[8], F[0] * F[2] + F[3] * F[5] + F[6] * F[8]};
                    for (int i = 0; i < 3; ++i) Siso[i] += c2 * (s.I1[k] - C[i]);
                    for (int i = 3; i < 6; ++i) Siso[i] -= c2 * C[i];
                }
                if constexpr (useI4) {
                    const double a[3] = {A0x[k], A0y[k], A0z[k]};
                    Siso[0] += c4 * a[0] * a[0]; Siso[1] += c4 * a[1] * a[1]; Siso[2] += c4 * a[2] * a[2];
                    Siso[3] += c4 * a[0] * a[1]; Siso[4] += c4 * a[1] * a[2]; Siso[5] += c4 * a[0] * a[2];
                }
                if constexpr (useI6) {
                    const double bb[3] = {B0x[k], B0y[k], B0z[k]};
                    Siso[0] += c6 * bb[0] * bb[0]; Siso[1] += c6 * bb[1] * bb[1]; Siso[2] += c6 * bb[2] * bb[2];
                    Siso[3] += c6 * bb[0] * bb[1]; Siso[4] += c6 * bb[1] * bb[2]; Siso[5] += c6 * bb[0] * bb[2];
                }
                double Svol[6], S[6];
                for (int i = 0; i < 6; ++i) {
                    Siso[i] += s.dJi[k] * JCi[i];
                    Svol[i] = s.dJv[k] * JCi[i];
                    S[i] = Siso[i] + Svol[i];
                }
                // viscoelastic relaxation: S^n = Phi^n - sum_i Y_i^n, Y_i^n = A_i Phi^n + B_i Y_i^(n-1)
                // (TLED eq. (24), (30)), Phi the relaxing part of the hyperelastic stress
                for (size_t v = 0; v < im.visco.size(); ++v) {
                    const ViscoSet& vs = im.visco[v];
                    double R[6];
                    for (int i = 0; i < 6; ++i) R[i] = (vs.iso ? Siso[i] : 0.0) + (vs.vol ? Svol[i] : 0.0);
                    const size_t at = batch * static_cast<size_t>(vs.terms) * 6 * kBatch + static_cast<size_t>(k);
                    const double* Yh = io.Yhist[v] + at;  // term t, component i at (6 t + i) kBatch
                    double* Yn = io.Ynew[v] ? io.Ynew[v] + at : nullptr;
                    // (no coefficients yet, i.e. no time step: no relaxation)
                    const int terms = vs.A.size() == static_cast<size_t>(vs.terms) ? vs.terms : 0;
                    for (int t = 0; t < terms; ++t) {
                        const double A = vs.A[static_cast<size_t>(t)], Bc = vs.B[static_cast<size_t>(t)];
                        for (int i = 0; i < 6; ++i) {
                            const size_t row = (6 * static_cast<size_t>(t) + static_cast<size_t>(i)) * kBatch;
                            const double Y = A * R[i] + Bc * Yh[row];
                            S[i] -= Y;
                            if (Yn) Yn[row] = Y;
                        }
                    }
                }
                // P = F S
                for (int i = 0; i < 3; ++i) {
                    const double f0 = F[3 * i], f1 = F[3 * i + 1], f2 = F[3 * i + 2];
                    s.P[3 * i + 0][k] = f0 * S[0] + f1 * S[3] + f2 * S[5];
                    s.P[3 * i + 1][k] = f0 * S[3] + f1 * S[1] + f2 * S[4];
                    s.P[3 * i + 2][k] = f0 * S[5] + f1 * S[4] + f2 * S[2];
                }
                const size_t cell = cellOff + static_cast<size_t>(es.orig[e]);
                if (io.S)
                    for (int i = 0; i < 6; ++i) io.S[6 * cell + static_cast<size_t>(i)] = S[i];
                if (io.F)
                    for (int i = 0; i < 9; ++i) io.F[9 * cell + static_cast<size_t>(i)] = F[i];
            }
        }

        if (io.energy) {
            for (int k = 0; k < n; ++k) energy += vol[e0 + static_cast<size_t>(k)] * s.W[k];
            if constexpr (NN == 8) {
                // hourglass energy K/2 sum_q |h_q|^2
                const double* __restrict K = es.hgK.data() + e0;
                for (int k = 0; k < n; ++k) {
                    double w = 0;
                    for (int r = 0; r < 12; ++r) w += s.Kh[r][k] * s.Kh[r][k];
                    energy += 0.5 * K[k] * w;
                }
            }
        }

        if (io.buf) {
            // f_a = -V P dN_a/dX (TLED eq. (1)-(3))
#pragma omp simd
            for (int k = 0; k < n; ++k) {
                const size_t e = e0 + static_cast<size_t>(k);
                const double V = vol[e];
                double P0 = V * s.P[0][k], P1 = V * s.P[1][k], P2 = V * s.P[2][k], P3 = V * s.P[3][k],
                       P4 = V * s.P[4][k], P5 = V * s.P[5][k], P6 = V * s.P[6][k], P7 = V * s.P[7][k],
                       P8 = V * s.P[8][k];
                if constexpr (NN == 4) {
                    double s0 = 0, s1 = 0, s2 = 0;
                    for (int a = 1; a < 4; ++a) {
                        const double g0 = dN[(3 * (a - 1)) * kBatch + k], g1 = dN[(3 * (a - 1) + 1) * kBatch + k],
                                     g2 = dN[(3 * (a - 1) + 2) * kBatch + k];
                        const double f0 = -(P0 * g0 + P1 * g1 + P2 * g2), f1 = -(P3 * g0 + P4 * g1 + P5 * g2),
                                     f2 = -(P6 * g0 + P7 * g1 + P8 * g2);
                        s.f[a][0][k] = f0;
                        s.f[a][1][k] = f1;
                        s.f[a][2][k] = f2;
                        s0 += f0;
                        s1 += f1;
                        s2 += f2;
                    }
                    s.f[0][0][k] = -s0;
                    s.f[0][1][k] = -s1;
                    s.f[0][2][k] = -s2;
                } else {
                    // with hourglass control: -K sum_q gamma_qa h_q = -K sum_q h_qa h_q + M dN_a/dX, M = K sum_q h_q (x) c_q,
                    // so f_a = -(V P - M) dN_a/dX - K sum_q h_qa h_q
                    const double* __restrict hgC = G + ElementSet<NN>::kHgRow * kBatch;
                    const double K = es.hgK[e];
                    double r[3][8];  // K sum_q h_qa h_q per component, the pair sums of the loop above reversed
#pragma GCC unroll 3
                    for (int j = 0; j < 3; ++j) {
                        const double g0 = K * s.Kh[j][k], g1 = K * s.Kh[3 + j][k], g2 = K * s.Kh[6 + j][k], g3 = K * s.Kh[9 + j][k];
                        const double p = g0 + g2, m = g0 - g2, sp = g1 + g3, sm = g1 - g3;
                        r[j][0] = p + sm;
                        r[j][1] = sp - p;
                        r[j][2] = m - sp;
                        r[j][3] = -m - sm;
                        r[j][4] = m - sm;
                        r[j][5] = -m - sp;
                        r[j][6] = p + sp;
                        r[j][7] = sm - p;
                    }
#pragma GCC unroll 4
                    for (int q = 0; q < 4; ++q) {
                        const double c0 = hgC[(3 * q) * kBatch + k], c1 = hgC[(3 * q + 1) * kBatch + k], c2 = hgC[(3 * q + 2) * kBatch + k];
                        const double k0 = K * s.Kh[3 * q][k], k1 = K * s.Kh[3 * q + 1][k], k2 = K * s.Kh[3 * q + 2][k];
                        P0 -= k0 * c0; P1 -= k0 * c1; P2 -= k0 * c2;
                        P3 -= k1 * c0; P4 -= k1 * c1; P5 -= k1 * c2;
                        P6 -= k2 * c0; P7 -= k2 * c1; P8 -= k2 * c2;
                    }
                    // (fully unrolled: a loop left over the nodes turns the dN loads into emulated gathers)
#pragma GCC unroll 8
                    for (int a = 0; a < NN; ++a) {
                        const double g0 = dN[(3 * a) * kBatch + k], g1 = dN[(3 * a + 1) * kBatch + k], g2 = dN[(3 * a + 2) * kBatch + k];
                        const double f0 = -(P0 * g0 + P1 * g1 + P2 * g2) - r[0][a], f1 = -(P3 * g0 + P4 * g1 + P5 * g2) - r[1][a],
                                     f2 = -(P6 * g0 + P7 * g1 + P8 * g2) - r[2][a];
                        s.f[a][0][k] = f0;
                        s.f[a][1][k] = f1;
                        s.f[a][2][k] = f2;
                    }
                }
            }

            // scatter into the block's node buffer (a fixed order: batch quads, then nodes, then elements)
            double* __restrict buf = io.buf;
            for (kq = 0; kq + 4 <= n; kq += 4) {
                const int* nd = &es.nodes[(e0 + static_cast<size_t>(kq)) * NN];
                for (int a = 0; a < NN; ++a)
                    simd::scatterAdd4(buf, nd + a, NN, &s.f[a][0][kq], &s.f[a][1][kq], &s.f[a][2][kq], b.nodeLo);
            }
            for (int k = kq; k < n; ++k) {
                const int* nd = &es.nodes[(e0 + static_cast<size_t>(k)) * NN];
                for (int a = 0; a < NN; ++a) {
                    double* fa = buf + 4 * static_cast<size_t>(nd[a] - b.nodeLo);
                    fa[0] += s.f[a][0][k];
                    fa[1] += s.f[a][1][k];
                    fa[2] += s.f[a][2][k];
                }
            }
        }
    }
    if (io.energy) *io.energy += energy;
}

/// Copies a batch's response arrays out of law results.
template <class S>
inline void storeResponse(S& s, int k, const Response& r) {
    s.W[k] = r.W;
    s.d1[k] = r.dI1;
    s.d2[k] = r.dI2;
    s.d4[k] = r.dI4;
    s.d6[k] = r.dI6;
    s.dJi[k] = r.dJiso;
    s.dJv[k] = r.dJvol;
}

template <int NN, class Law, class Block>
void kernelLaw(const Impl& im, const Block& b, const KernelIO& io) {
    const Law law = *static_cast<const Law*>(im.groups[static_cast<size_t>(b.group)].law);
    const double J0 = im.J0;
    runKernel<NN, Law::uses>(im, b,
                  [&](auto& s, int n) {
                      // no 'omp simd' here: it would turn the structs into arrays of structs and stop
                      // the vectoriser; plain auto-vectorisation scalarises them
                      for (int k = 0; k < n; ++k) {
                          Invariants in;
                          in.I1 = s.I1[k];
                          in.I2 = s.I2[k];
                          in.J = s.J[k];
                          in.I4 = s.I4[k];
                          in.I6 = s.I6[k];
                          Response r;
                          materials::evaluateLaw(law, in, J0, r);  // branch-free: the batch loop vectorises
                          storeResponse(s, k, r);
                      }
                  },
                  io);
}

template <int NN, unsigned U, class Block>
void kernelGeneric(const Impl& im, const Block& b, const KernelIO& io) {
    const BaseMaterial* m = im.groups[static_cast<size_t>(b.group)].material;
    const double J0 = im.J0;
    runKernel<NN, U>(im, b,
                  [&](auto& s, int n) {
                      Invariants in[kBatch];
                      Response out[kBatch];
                      for (int k = 0; k < n; ++k) {
                          in[k].I1 = s.I1[k];
                          in[k].I2 = s.I2[k];
                          in[k].J = s.J[k];
                          in[k].I4 = s.I4[k];
                          in[k].I6 = s.I6[k];
                      }
                      m->evaluate(in, out, static_cast<size_t>(n), J0);
                      for (int k = 0; k < n; ++k) storeResponse(s, k, out[k]);
                  },
                  io);
}

template <class Law, class Block>
bool tryLaw(Impl::Group& g) {
    auto* m = dynamic_cast<const materials::Material<Law>*>(g.material);
    if (!m) return false;
    g.law = &m->law();
    g.fn = g.kind == 0 ? &kernelLaw<4, Law, Block> : &kernelLaw<8, Law, Block>;
    return true;
}

template <class Block>
void chooseKernel(Impl::Group& g) {
    // the built-in laws run fully inlined; any other material through its batched evaluate()
    if (tryLaw<materials::NeoHookeanLaw, Block>(g) || tryLaw<materials::TransverselyIsotropicLaw, Block>(g) ||
        tryLaw<materials::OrthotropicLaw, Block>(g) || tryLaw<materials::CompressibleNeoHookeanLaw, Block>(g) ||
        tryLaw<materials::CompressibleMooneyRivlinLaw, Block>(g) || tryLaw<materials::StVenantKirchhoffLaw, Block>(g) ||
        tryLaw<materials::IncompressibleNeoHookeanLaw, Block>(g) ||
        tryLaw<materials::IncompressibleMooneyRivlinLaw, Block>(g) ||
        tryLaw<materials::HolzapfelGasserOgdenLaw, Block>(g) || tryLaw<materials::ArrudaBoyceLaw, Block>(g) ||
        tryLaw<materials::UncoupledMooneyRivlinLaw, Block>(g))
        return;
    g.law = nullptr;
    using Fn = Impl::KernelFn;
    static const Fn tet[8] = {&kernelGeneric<4, 0, Block>, &kernelGeneric<4, 1, Block>, &kernelGeneric<4, 2, Block>,
                              &kernelGeneric<4, 3, Block>, &kernelGeneric<4, 4, Block>, &kernelGeneric<4, 5, Block>,
                              &kernelGeneric<4, 6, Block>, &kernelGeneric<4, 7, Block>};
    static const Fn hex[8] = {&kernelGeneric<8, 0, Block>, &kernelGeneric<8, 1, Block>, &kernelGeneric<8, 2, Block>,
                              &kernelGeneric<8, 3, Block>, &kernelGeneric<8, 4, Block>, &kernelGeneric<8, 5, Block>,
                              &kernelGeneric<8, 6, Block>, &kernelGeneric<8, 7, Block>};
    g.fn = (g.kind == 0 ? tet : hex)[g.uses & 7u];
}

/// The mesh source in the context (MeshLoader, GridMesh ...: a core::BaseTopology).
core::BaseTopology* findMeshSource(const core::Component& self) {
    return self.node() ? self.node()->findInContext<core::BaseTopology>() : nullptr;
}

std::vector<std::string> tokens(const std::string& s) {
    std::istringstream is(s);
    std::vector<std::string> out;
    std::string t;
    while (is >> t) out.push_back(t);
    return out;
}

} // namespace

TLEDForceField::TLEDForceField() : m_impl(std::make_unique<Impl>()) {}
TLEDForceField::~TLEDForceField() = default;

// ------------------------------------------------------------------------------------------------
// set-up

namespace {

struct GroupMaterialEntry {
    std::string group;  ///< tag or name as written
    BaseMaterial* material = nullptr;
};

std::vector<GroupMaterialEntry> parseGroupMaterials(const TLEDForceField& ff, const core::Param<std::string>& p) {
    std::vector<GroupMaterialEntry> out;
    const auto t = tokens(p.get());
    if (t.empty()) return out;
    if (t.size() % 2)
        ff.fail(p, "groupMaterials = \"" + p.get() + "\" is not a list of pairs: give a group tag or name, then a "
                                                     "material path, e.g. \"1 @liver 2 @vessel\"");
    for (size_t i = 0; i < t.size(); i += 2) {
        std::string path = t[i + 1];
        if (!path.empty() && path[0] == '@') path = path.substr(1);
        core::Component* c = ff.node() ? ff.node()->resolveComponent(path) : nullptr;
        if (!c) ff.fail(p, "groupMaterials: no component '" + t[i + 1] + "' (for group " + t[i] + ")");
        auto* m = dynamic_cast<BaseMaterial*>(c);
        if (!m)
            ff.fail(p, "groupMaterials: '" + t[i + 1] + "' (for group " + t[i] + ") is a " + c->className() +
                           ", not a material");
        out.push_back({t[i], m});
    }
    return out;
}

} // namespace

std::vector<core::Component*> TLEDForceField::dependencies() const {
    std::vector<core::Component*> deps;
    if (!node()) return deps;
    if (auto* s = node()->findInContext<core::BaseMechanicalState>()) deps.push_back(s);
    if (!m_material.get() && !m_groupMaterials.isSet())
        if (auto* m = node()->findInContext<BaseMaterial>()) deps.push_back(m);
    for (auto& g : parseGroupMaterials(*this, m_groupMaterials)) deps.push_back(g.material);
    for (auto* p : node()->findAllLocal<viscoelastic::ViscoelasticProny>()) deps.push_back(p);
    if (!m_mesh.isSet() && !m_tetrahedra.isSet() && !m_hexahedra.isSet())
        if (auto* src = findMeshSource(*this)) deps.push_back(src);
    return deps;
}

void TLEDForceField::init() {
    Impl& im = *m_impl;
    im = Impl{};
    m_blocks.clear();
    im.J0 = m_J0.get();

    // elements
    const MeshData* mesh = nullptr;
    if (m_mesh.isSet()) {
        if (m_tetrahedra.isSet() || m_hexahedra.isSet())
            fail(m_mesh, "both mesh and tetrahedra/hexahedra are given: give the elements one way");
        mesh = &m_mesh.get();
    } else if (!m_tetrahedra.isSet() && !m_hexahedra.isSet()) {
        auto* src = findMeshSource(*this);
        if (!src)
            fail("no elements: set mesh=\"@loader.mesh\" (or tetrahedra/hexahedra), or put a mesh source "
                 "(MeshLoader, GridMesh) in the node or a parent");
        mesh = &src->meshData();
    }
    if (mesh) {
        m_tets = mesh->tetrahedra;
        m_hexes = mesh->hexahedra;
    } else {
        m_tets = m_tetrahedra.get();
        m_hexes = m_hexahedra.get();
    }
    const size_t nT = m_tets.size(), nH = m_hexes.size();
    if (nT + nH == 0) fail("the mesh has no tetrahedra and no hexahedra");
    im.nTetCells = nT;
    if (!mesh && (m_fibreArray.isSet() || m_fibreArray2.isSet()))
        fail(m_fibreArray.isSet() ? m_fibreArray : m_fibreArray2,
             "fibre arrays come from a mesh's cell arrays: give mesh=\"@loader.mesh\"");

    // state and rest positions
    auto* state = node() ? node()->findInContext<core::BaseMechanicalState>() : nullptr;
    if (!state) fail("no mechanical state (MechanicalObject) in its node or a parent");
    const Positions& X = state->x0();
    int maxNode = -1;
    for (auto& t : m_tets) for (int v : t) maxNode = std::max(maxNode, v);
    for (auto& h : m_hexes) for (int v : h) maxNode = std::max(maxNode, v);
    if (static_cast<size_t>(maxNode) >= X.size())
        fail("elements use node " + std::to_string(maxNode) + " but the state '" + state->name() + "' has " +
             std::to_string(X.size()) + " nodes");
    im.nodeCount = static_cast<size_t>(maxNode + 1);

    // materials: default, then per group
    // with groupMaterials, only an explicit `material` covers the other groups (as in HEMLForceField)
    BaseMaterial* defaultMat = m_material.get();
    if (!defaultMat && !m_groupMaterials.isSet() && node()) defaultMat = node()->findInContext<BaseMaterial>();
    std::map<int, BaseMaterial*> tagMaterial;
    for (auto& g : parseGroupMaterials(*this, m_groupMaterials)) {
        int tag = 0;
        bool found = false;
        try {
            size_t used = 0;
            tag = std::stoi(g.group, &used);
            found = used == g.group.size();
        } catch (...) {
        }
        if (!found && mesh)
            for (auto& [t, name] : mesh->groupNames)
                if (name == g.group) { tag = t; found = true; break; }
        if (!found) {
            std::vector<std::string> names;
            if (mesh) for (auto& kv : mesh->groupNames) names.push_back(kv.second);
            fail(m_groupMaterials, "groupMaterials: '" + g.group + "' is neither a group tag nor a group name of the mesh",
                 names.empty() ? std::vector<std::string>{} : std::vector<std::string>{"group names: " + [&] {
                     std::string s;
                     for (auto& nm : names) s += (s.empty() ? "" : ", ") + nm;
                     return s;
                 }()});
        }
        if (tagMaterial.count(tag)) fail(m_groupMaterials, "groupMaterials: group " + g.group + " is given twice");
        tagMaterial[tag] = g.material;
    }
    auto elementMaterial = [&](int kind, size_t e) -> BaseMaterial* {
        int tag = 0;
        if (mesh) {
            const auto& tags = kind == 0 ? mesh->tetrahedronGroup : mesh->hexahedronGroup;
            if (e < tags.size()) tag = tags[e];
        }
        auto it = tagMaterial.find(tag);
        if (it != tagMaterial.end()) return it->second;
        if (!defaultMat)
            fail("no material for the " + std::string(kind == 0 ? "tetrahedra" : "hexahedra") + " of group " +
                 std::to_string(tag) + ": put a material in the node, set material=\"@...\", or list the group in groupMaterials");
        return defaultMat;
    };

    // fibre arrays (3 per cell, tetrahedra first, then hexahedra)
    auto cellArray = [&](const core::Param<std::string>& p) -> const std::vector<double>* {
        if (!p.isSet() || p.get().empty()) return nullptr;
        auto it = mesh->cellArrays.find(p.get());
        if (it == mesh->cellArrays.end()) {
            std::string names;
            for (auto& kv : mesh->cellArrays) names += (names.empty() ? "" : ", ") + kv.first;
            fail(p, p.name() + " = \"" + p.get() + "\": the mesh has no such cell array",
                 {names.empty() ? "the mesh has no cell arrays" : "cell arrays: " + names});
        }
        if (it->second.size() != 3 * (nT + nH))
            fail(p, p.name() + " = \"" + p.get() + "\" has " + std::to_string(it->second.size()) + " values, expected 3 per cell (" +
                        std::to_string(3 * (nT + nH)) + ")");
        return &it->second;
    };
    const std::vector<double>* fibreA = cellArray(m_fibreArray);
    const std::vector<double>* fibreB = cellArray(m_fibreArray2);

    // groups (kind, material), in order of first appearance; elements sorted by group, stable
    std::vector<std::vector<size_t>> perGroup;
    auto groupOf = [&](int kind, BaseMaterial* m) {
        for (size_t g = 0; g < im.groups.size(); ++g)
            if (im.groups[g].kind == kind && im.groups[g].material == m) return g;
        Impl::Group g;
        g.kind = kind;
        g.material = m;
        g.uses = m->uses();
        g.pModulus = m->bulkModulus() + 4.0 / 3.0 * m->shearModulus();
        chooseKernel<Block>(g);
        im.groups.push_back(g);
        perGroup.emplace_back();
        return im.groups.size() - 1;
    };
    for (int kind = 0; kind < 2; ++kind) {
        const size_t n = kind == 0 ? nT : nH;
        for (size_t e = 0; e < n; ++e) perGroup[groupOf(kind, elementMaterial(kind, e))].push_back(e);
    }
    // node and element order. The blocks' node buffers cover the range of internal node indices their
    // elements use, so they need elements that share nodes with close indices. The file's order is kept
    // unless its buffers are more than twice those of a reverse Cuthill-McKee numbering of the nodes
    // (over both kinds) with each group's elements sorted by their lowest node in it. With a Gmsh
    // file's order, a 200k-tetrahedron mesh had blocks whose buffers spanned all the nodes and ran 7
    // times slower; on a structured grid the file's (lexicographic) order has 1.25 times the buffers of
    // the renumbered one but runs faster (docs/performance.md).
    auto rowsFor = [&](const std::vector<int>& internal, const std::vector<std::vector<size_t>>& lists) {
        size_t total = 0;
        for (size_t gi = 0; gi < im.groups.size(); ++gi) {
            const int nn = im.groups[gi].kind == 0 ? 4 : 8;
            const size_t B = nn == 4 ? kBlockTets : kBlockHexes;
            const std::vector<size_t>& list = lists[gi];
            for (size_t c = 0; c < list.size(); c += B) {
                int lo = std::numeric_limits<int>::max(), hi = -1;
                for (size_t i = c; i < std::min(list.size(), c + B); ++i) {
                    const int* nd = nn == 4 ? m_tets[list[i]].data() : m_hexes[list[i]].data();
                    for (int k = 0; k < nn; ++k) {
                        lo = std::min(lo, internal[static_cast<size_t>(nd[k])]);
                        hi = std::max(hi, internal[static_cast<size_t>(nd[k])]);
                    }
                }
                total += static_cast<size_t>(hi - lo + 1);
            }
        }
        return total;
    };
    std::vector<int> internalOf(im.nodeCount);
    std::iota(internalOf.begin(), internalOf.end(), 0);
    const size_t fileRows = rowsFor(internalOf, perGroup);
    // (every numbering needs at least one row per node in use: below twice that, keep the file's order
    // without computing another)
    std::vector<char> inUse(im.nodeCount, 0);
    for (const auto& t4 : m_tets) for (int v : t4) inUse[static_cast<size_t>(v)] = 1;
    for (const auto& h8 : m_hexes) for (int v : h8) inUse[static_cast<size_t>(v)] = 1;
    const size_t used = static_cast<size_t>(std::count(inUse.begin(), inUse.end(), 1));
    if (fileRows > 2 * used) {
        std::vector<int> rcm = reverseCuthillMcKee(im.nodeCount, {{nT ? m_tets.front().data() : nullptr, nT, 4},
                                                                  {nH ? m_hexes.front().data() : nullptr, nH, 8}});
        std::vector<int> rcmInternal(im.nodeCount);
        for (size_t q = 0; q < im.nodeCount; ++q) rcmInternal[static_cast<size_t>(rcm[q])] = static_cast<int>(q);
        std::vector<std::vector<size_t>> sortedGroups(perGroup.size());
        for (size_t gi = 0; gi < im.groups.size(); ++gi) {
            const int nn = im.groups[gi].kind == 0 ? 4 : 8;
            const std::vector<size_t>& list = perGroup[gi];
            std::vector<int> lowest(list.size());
            for (size_t i = 0; i < list.size(); ++i) {
                const int* nd = nn == 4 ? m_tets[list[i]].data() : m_hexes[list[i]].data();
                int m = rcmInternal[static_cast<size_t>(nd[0])];
                for (int k = 1; k < nn; ++k) m = std::min(m, rcmInternal[static_cast<size_t>(nd[k])]);
                lowest[i] = m;
            }
            std::vector<size_t> idx(list.size());
            std::iota(idx.begin(), idx.end(), size_t(0));
            std::stable_sort(idx.begin(), idx.end(), [&](size_t x, size_t y) { return lowest[x] < lowest[y]; });
            for (size_t i : idx) sortedGroups[gi].push_back(list[i]);
        }
        if (fileRows > 2 * rowsFor(rcmInternal, sortedGroups)) {
            im.nodeOf = std::move(rcm);
            internalOf = std::move(rcmInternal);
            perGroup = std::move(sortedGroups);
        }
    }
    // tetrahedra: within each block, the 4 elements of a SIMD quad come from the 4 quarters of the
    // block, so that they share no node: neighbouring tetrahedra (6 per cube cell share its diagonal)
    // would otherwise add to the same node row back to back in the scatter and wait on each other's
    // stores (7-8 % of the step; no gain for hexahedra, whose neighbours hold a shared node at
    // different local indices)
    for (size_t gi = 0; gi < im.groups.size(); ++gi) {
        if (im.groups[gi].kind != 0) continue;
        std::vector<size_t>& list = perGroup[gi];
        const size_t B = kBlockTets;
        std::vector<size_t> out;
        out.reserve(list.size());
        for (size_t c = 0; c < list.size(); c += B) {
            const size_t m = std::min(B, list.size() - c), q = (m + 3) / 4;
            for (size_t r = 0; r < q; ++r)
                for (size_t l = 0; l < 4; ++l)
                    if (l * q + r < m) out.push_back(list[c + l * q + r]);
        }
        list.swap(out);
    }
    bool anyI4 = false, anyI6 = false;
    for (auto& g : im.groups) {
        anyI4 |= (g.uses & BaseMaterial::UsesI4) != 0;
        anyI6 |= (g.uses & BaseMaterial::UsesI6) != 0;
    }
    if (fibreA && !anyI4) warn("fibreArray is given but no material of this force field uses a fibre direction");
    if (fibreB && !anyI6) warn("fibreArray2 is given but no material of this force field uses a second fibre direction");

    auto direction = [&](int which, const Impl::Group& g, int kind, size_t e) -> Vec3 {
        const std::vector<double>* arr = which == 0 ? fibreA : fibreB;
        Vec3 d;
        if (arr) {
            const size_t cell = (kind == 0 ? 0 : nT) + e;
            d = Vec3((*arr)[3 * cell], (*arr)[3 * cell + 1], (*arr)[3 * cell + 2]);
        } else if (const Vec3* md = g.material->fibreDirection(which)) {
            d = *md;
        } else {
            fail("material '" + g.material->name() + "' uses a " + std::string(which == 0 ? "fibre" : "second fibre") +
                 " direction but gives none: set it on the material or give " + (which == 0 ? "fibreArray" : "fibreArray2"));
        }
        const double len = d.norm();
        if (!(len > 1e-12) || !std::isfinite(len))
            fail((which == 0 ? m_fibreArray : m_fibreArray2),
                 std::string(which == 0 ? "fibre" : "second fibre") + " direction of " + (kind == 0 ? "tetrahedron " : "hexahedron ") +
                     std::to_string(e) + " has length " + fmt(len) + ": directions must be non-zero");
        return d / len;
    };

    // fibre directions: per element from the arrays, else one per group (its material's)
    im.fibresPerElement = fibreA || fibreB;
    if (!im.fibresPerElement)
        for (auto& g : im.groups) {
            if (g.uses & BaseMaterial::UsesI4) {
                const Vec3 a = direction(0, g, g.kind, 0);
                for (int c = 0; c < 3; ++c) g.a0[c] = a[c];
            }
            if (g.uses & BaseMaterial::UsesI6) {
                const Vec3 b = direction(1, g, g.kind, 0);
                for (int c = 0; c < 3; ++c) g.b0[c] = b[c];
            }
        }

    // geometry
    auto fillTet = [&](size_t gi, const std::vector<size_t>& elems) {
        ElementSet<4>& s = im.tet;
        const Impl::Group& g = im.groups[gi];
        for (size_t e : elems) {
            const auto& t = m_tets[e];
            const Vec3 &p0 = X[t[0]], &p1 = X[t[1]], &p2 = X[t[2]], &p3 = X[t[3]];
            Mat3 D;
            D.col(0) = p1 - p0;
            D.col(1) = p2 - p0;
            D.col(2) = p3 - p0;
            const double det = D.determinant();
            double longest = 0;
            const Vec3* pts[4] = {&p0, &p1, &p2, &p3};
            for (int a = 0; a < 4; ++a)
                for (int b2 = a + 1; b2 < 4; ++b2) longest = std::max(longest, (*pts[a] - *pts[b2]).norm());
            if (!(std::abs(det) / 6 > 1e-12 * longest * longest * longest))
                fail("tetrahedron " + std::to_string(e) + " (nodes " + std::to_string(t[0]) + " " + std::to_string(t[1]) +
                     " " + std::to_string(t[2]) + " " + std::to_string(t[3]) + ") is degenerate (volume " + fmt(det / 6) + " m^3)");
            const Mat3 Di = D.inverse();
            double dN[12];
            for (int j = 0; j < 3; ++j) {
                dN[3 + j] = Di(0, j);
                dN[6 + j] = Di(1, j);
                dN[9 + j] = Di(2, j);
                dN[j] = -(Di(0, j) + Di(1, j) + Di(2, j));
            }
            for (int a = 0; a < 4; ++a) s.nodes.push_back(internalOf[static_cast<size_t>(t[a])]);
            s.dN.insert(s.dN.end(), dN, dN + 12);
            const double V = std::abs(det) / 6;
            s.vol.push_back(V);
            s.orig.push_back(static_cast<int>(e));
            // smallest altitude 3 V / largest face area
            const int faces[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
            double amax = 0;
            for (auto& f : faces) amax = std::max(amax, 0.5 * (*pts[f[1]] - *pts[f[0]]).cross(*pts[f[2]] - *pts[f[0]]).norm());
            s.length.push_back(3 * V / amax);
            if (anyI4 && im.fibresPerElement) {
                const Vec3 a = (g.uses & BaseMaterial::UsesI4) ? direction(0, g, 0, e) : Vec3(1, 0, 0);
                s.a0.insert(s.a0.end(), {a[0], a[1], a[2]});
            }
            if (anyI6 && im.fibresPerElement) {
                const Vec3 b = (g.uses & BaseMaterial::UsesI6) ? direction(1, g, 0, e) : Vec3(0, 1, 0);
                s.b0.insert(s.b0.end(), {b[0], b[1], b[2]});
            }
        }
    };
    auto fillHex = [&](size_t gi, const std::vector<size_t>& elems) {
        ElementSet<8>& s = im.hex;
        const Impl::Group& g = im.groups[gi];
        const double gp = 1.0 / std::sqrt(3.0);
        for (size_t e : elems) {
            const auto& h = m_hexes[e];
            Vec3 P[8];
            for (int a = 0; a < 8; ++a) P[a] = X[h[a]];
            // uniform-strain derivatives (1/V) int dN/dX dV = (1/V) int cof(J) dN/dxi dxi and V = int det J dxi,
            // 2x2x2 Gauss points (exact for a trilinear map)
            double V = 0;
            double Bs[8][3] = {};
            for (int q = 0; q < 8; ++q) {
                const double g3[3] = {kHexXi[q][0] * gp, kHexXi[q][1] * gp, kHexXi[q][2] * gp};
                double dxi[8][3];
                for (int a = 0; a < 8; ++a) {
                    const double f[3] = {1 + kHexXi[a][0] * g3[0], 1 + kHexXi[a][1] * g3[1], 1 + kHexXi[a][2] * g3[2]};
                    dxi[a][0] = 0.125 * kHexXi[a][0] * f[1] * f[2];
                    dxi[a][1] = 0.125 * kHexXi[a][1] * f[0] * f[2];
                    dxi[a][2] = 0.125 * kHexXi[a][2] * f[0] * f[1];
                }
                double J[9] = {};
                for (int a = 0; a < 8; ++a)
                    for (int i = 0; i < 3; ++i)
                        for (int j = 0; j < 3; ++j) J[3 * i + j] += P[a][i] * dxi[a][j];
                double cj[9];
                cof3(J, cj);
                V += det3(J);
                for (int a = 0; a < 8; ++a)
                    for (int i = 0; i < 3; ++i)
                        Bs[a][i] += cj[3 * i] * dxi[a][0] + cj[3 * i + 1] * dxi[a][1] + cj[3 * i + 2] * dxi[a][2];
            }
            double longest = 0;
            for (int a = 0; a < 8; ++a)
                for (int b2 = a + 1; b2 < 8; ++b2) longest = std::max(longest, (P[a] - P[b2]).norm());
            if (!(std::abs(V) > 1e-12 * longest * longest * longest)) {
                std::string nodes;
                for (int v : h) nodes += " " + std::to_string(v);
                fail("hexahedron " + std::to_string(e) + " (nodes" + nodes + ") is degenerate (volume " + fmt(V) + " m^3)");
            }
            double dN[24];
            double sumB2 = 0;
            for (int a = 0; a < 8; ++a)
                for (int i = 0; i < 3; ++i) {
                    dN[3 * a + i] = Bs[a][i] / V;
                    sumB2 += dN[3 * a + i] * dN[3 * a + i];
                }
            // hourglass control (Flanagan-Belytschko): gamma_q = h_q - (c_q . dN/dX), c_q = sum_a h_qa X_a; the loop
            // needs c_q only (see runKernel)
            double hc[12] = {};
            for (int q = 0; q < 4; ++q)
                for (int a = 0; a < 8; ++a)
                    for (int i = 0; i < 3; ++i) hc[3 * q + i] += kHourglass[q][a] * P[a][i];
            const double absV = std::abs(V);
            for (int a = 0; a < 8; ++a) s.nodes.push_back(internalOf[static_cast<size_t>(h[a])]);
            s.dN.insert(s.dN.end(), dN, dN + 24);
            s.vol.push_back(absV);
            s.orig.push_back(static_cast<int>(e));
            s.hgC.insert(s.hgC.end(), hc, hc + 12);
            s.hgK.push_back(m_hourglass.get() * g.pModulus * absV * sumB2 / 8.0);
            double amax = 0;
            for (auto& f : kHexFaces)
                amax = std::max(amax, 0.5 * (P[f[2]] - P[f[0]]).cross(P[f[3]] - P[f[1]]).norm());
            s.length.push_back(absV / amax);
            if (anyI4 && im.fibresPerElement) {
                const Vec3 a = (g.uses & BaseMaterial::UsesI4) ? direction(0, g, 1, e) : Vec3(1, 0, 0);
                s.a0.insert(s.a0.end(), {a[0], a[1], a[2]});
            }
            if (anyI6 && im.fibresPerElement) {
                const Vec3 b = (g.uses & BaseMaterial::UsesI6) ? direction(1, g, 1, e) : Vec3(0, 1, 0);
                s.b0.insert(s.b0.end(), {b[0], b[1], b[2]});
            }
        }
    };

    // internal order: tetrahedra by group, then hexahedra by group; fixed blocks within each group
    size_t bufSize = 0;
    auto addBlocks = [&](int kind, size_t gi, size_t begin, size_t end) {
        const size_t blockSize = kind == 0 ? kBlockTets : kBlockHexes;
        for (size_t b0 = begin; b0 < end; b0 += blockSize) {
            Block b;
            b.kind = kind;
            b.group = static_cast<int>(gi);
            b.begin = b0;
            b.end = std::min(end, b0 + blockSize);
            int lo = std::numeric_limits<int>::max(), hi = -1;
            const std::vector<int>& nodes = kind == 0 ? im.tet.nodes : im.hex.nodes;
            const size_t nn = kind == 0 ? 4 : 8;
            for (size_t i = b.begin * nn; i < b.end * nn; ++i) {
                lo = std::min(lo, nodes[i]);
                hi = std::max(hi, nodes[i]);
            }
            b.nodeLo = lo;
            b.nodeHi = hi;
            b.bufOffset = bufSize;
            b.batchBase = im.batches;
            im.batches += (b.end - b.begin + kBatch - 1) / kBatch;
            bufSize += 4 * static_cast<size_t>(hi - lo + 1);
            m_blocks.push_back(b);
        }
    };
    for (int kind = 0; kind < 2; ++kind)
        for (size_t gi = 0; gi < im.groups.size(); ++gi) {
            if (im.groups[gi].kind != kind) continue;
            const size_t begin = kind == 0 ? im.tet.size() : im.hex.size();
            if (kind == 0) fillTet(gi, perGroup[gi]); else fillHex(gi, perGroup[gi]);
            const size_t end = kind == 0 ? im.tet.size() : im.hex.size();
            addBlocks(kind, gi, begin, end);
        }
    if (bufSize > 4 * 16 * im.nodeCount && m_blocks.size() > 16)
        warn("the element blocks span " + std::to_string(bufSize / (4 * im.nodeCount)) +
             " times the node count in their force buffers, in the node order used (the file's, or a reverse "
             "Cuthill-McKee one when that is more than twice as compact): speed and memory suffer");
    im.buf.assign(bufSize, 0.0);
    // pack the element data batch by batch, in the order of the blocks' batches (tetrahedra first)
    std::vector<std::pair<size_t, size_t>> batchStarts[2];
    for (const Block& b : m_blocks) {
        if (batchStarts[b.kind].empty()) (b.kind == 0 ? im.tet.batchOffset : im.hex.batchOffset) = b.batchBase;
        for (size_t e0 = b.begin; e0 < b.end; e0 += kBatch) batchStarts[b.kind].emplace_back(e0, std::min<size_t>(kBatch, b.end - e0));
    }
    im.tet.finish(batchStarts[0]);
    im.hex.finish(batchStarts[1]);

    // viscoelasticity
    bool isoTaken = false, volTaken = false;
    size_t stateBytes = 0;
    for (auto* p : node()->findAllLocal<viscoelastic::ViscoelasticProny>()) {
        ViscoSet vs;
        vs.prony = p;
        vs.iso = p->relaxesIsochoric();
        vs.vol = p->relaxesVolumetric();
        if ((vs.iso && isoTaken) || (vs.vol && volTaken))
            fail("two ViscoelasticProny components in its node relax the same part of the stress; give one series per "
                 "part (apply=\"isochoric\" and apply=\"volumetric\") or one with apply=\"both\"");
        isoTaken |= vs.iso;
        volTaken |= vs.vol;
        vs.terms = static_cast<int>(p->termCount());
        const size_t n = im.batches * static_cast<size_t>(vs.terms) * 6 * kBatch;
        vs.Yprev.assign(n, 0.0);
        vs.Ycur.assign(n, 0.0);
        stateBytes += 2 * n * sizeof(double);
        im.visco.push_back(std::move(vs));
    }
    // states beyond a quarter of a typical L3 (32 MiB here) are written with streaming stores: they
    // are read once per step and would only evict the element data (docs/performance.md)
    const std::string& stream = m_streamStates.get();
    im.streamStates = stream == "on" || (stream == "auto" && stateBytes > (size_t(8) << 20));
    const double dt = node()->context().dt;
    if (dt > 0) dtChanged(dt);
}

void TLEDForceField::dtChanged(double dt) {
    for (auto& vs : m_impl->visco) vs.prony->coefficients(dt, vs.A, vs.B);  // TLED eq. (30)
}

// ------------------------------------------------------------------------------------------------
// evaluation

namespace {

template <class Block>
void runBlock(const Impl& im, const Block& b, const KernelIO& io) {
    im.groups[static_cast<size_t>(b.group)].fn(im, b, io);
}

/// u = x - X for the nodes the elements use, 4 per node in internal order (the 4th is padding). An
/// orphaned "omp for": shared by the threads of the enclosing parallel region (every caller opens its
/// own, so a caller inside a user's parallel region still gets all of u).
void displacements(const Impl& im, const core::BaseMechanicalState& state, std::vector<double>& u) {
    const double* __restrict x = core::flat(state.x());
    const double* __restrict X = core::flat(state.x0());
    const int* __restrict node = im.nodeOf.empty() ? nullptr : im.nodeOf.data();
    const long n = static_cast<long>(im.nodeCount);
    double* __restrict up = u.data();
#pragma omp for schedule(static)
    for (long i = 0; i < n; ++i) {
        const size_t p = 3 * static_cast<size_t>(node ? node[i] : i);
        up[4 * i] = x[p] - X[p];
        up[4 * i + 1] = x[p + 1] - X[p + 1];
        up[4 * i + 2] = x[p + 2] - X[p + 2];
        up[4 * i + 3] = 0.0;
    }
}

/// Runs every block on the state's current displacements; setup(io, block index) chooses the outputs
/// (energy, S, F) and the history. For the outputs other than the forces of a step.
template <class Block, class Setup>
void runBlocksOn(const Impl& im, const std::vector<Block>& blocks, const core::BaseMechanicalState& state, Setup&& setup) {
    std::vector<double> u(4 * im.nodeCount);
#pragma omp parallel if (im.nodeCount > 65536)
    displacements(im, state, u);
    const long nb = static_cast<long>(blocks.size());
#pragma omp parallel for schedule(dynamic, 1) if (nb > 1)
    for (long bi = 0; bi < nb; ++bi) {
        KernelIO io;
        io.u = u.data();
        setup(io, static_cast<size_t>(bi));
        runBlock(im, blocks[static_cast<size_t>(bi)], io);
    }
}

/// The viscous history a stress output at time t reads: the states of the last evaluation when t is
/// a later time than it, else the committed ones.
const double* historyAt(const Impl& im, size_t v, double t) {
    return (im.haveCur && t != im.curTime) ? im.visco[v].Ycur.data() : im.visco[v].Yprev.data();
}

} // namespace

void TLEDForceField::addForce(core::BaseMechanicalState& state, Positions& f, double t) {
    Impl& im = *m_impl;
    if (state.size() < im.nodeCount || f.size() < im.nodeCount)
        core::throwSimulationError(path() + ": its elements use " + std::to_string(im.nodeCount) + " nodes but the state '" +
                                   state.name() + "' has " + std::to_string(state.size()));
    // viscous history: a new time advances it (the last evaluation becomes the previous step)
    if (!im.visco.empty()) {
        for (auto& vs : im.visco)
            if (vs.A.size() != static_cast<size_t>(vs.terms))
                core::throwSimulationError(path() + ": viscoelastic stresses need a time step (dtChanged was not called)");
        if (im.haveCur && t != im.curTime)
            for (auto& vs : im.visco) std::swap(vs.Yprev, vs.Ycur);
        im.haveCur = true;
        im.curTime = t;
    }
    im.u.resize(4 * im.nodeCount);
    const double* u = im.u.data();
    const long nb = static_cast<long>(m_blocks.size());
    const long nNodes = static_cast<long>(im.nodeCount);
    const long nTiles = (nNodes + kNodeTile - 1) / kNodeTile;
    // one parallel region: displacements, the blocks, then the sum of the block buffers
#pragma omp parallel if (nb > 1)
    {
        displacements(im, state, im.u);
#pragma omp for schedule(dynamic, 1)
        for (long bi = 0; bi < nb; ++bi) {
            const Block& b = m_blocks[static_cast<size_t>(bi)];
            double* buf = im.buf.data() + b.bufOffset;  // zero: the sum below cleared it (init zeroes it first)
            KernelIO io;
            io.u = u;
            io.buf = buf;
            for (size_t v = 0; v < im.visco.size(); ++v) {
                io.Yhist[v] = im.visco[v].Yprev.data();
                io.Ynew[v] = im.visco[v].Ycur.data();
            }
            io.streamY = im.streamStates;
            runBlock(im, b, io);
            if (io.streamY) simd::streamFence();
        }
        // sum the block buffers per node, in block order (bitwise the same for any thread count), and
        // clear them for the next call while their rows are in the cache (instead of a pass of its own
        // over the buffers before the element loop)
        double* __restrict fp = core::flat(f);
        const bool renumbered = !im.nodeOf.empty();
#pragma omp for schedule(static)
        for (long tile = 0; tile < nTiles; ++tile) {
            const int lo = static_cast<int>(tile * kNodeTile);
            const int hi = static_cast<int>(std::min<long>(nNodes, (tile + 1) * kNodeTile)) - 1;
            // renumbered nodes: the tile's sums first, in internal order, then into f
            alignas(64) double acc[3 * kNodeTile];
            double* __restrict sum = renumbered ? acc : fp + 3 * static_cast<size_t>(lo);
            if (renumbered) std::fill(acc, acc + 3 * (hi - lo + 1), 0.0);
            for (const Block& b : m_blocks) {
                const int a = std::max(lo, b.nodeLo), z = std::min(hi, b.nodeHi);
                if (a > z) continue;
                double* __restrict src = im.buf.data() + b.bufOffset + 4 * static_cast<size_t>(a - b.nodeLo);
                double* __restrict dst = sum + 3 * static_cast<size_t>(a - lo);
                const size_t rows = static_cast<size_t>(z - a + 1);
                for (size_t k = 0; k < rows; ++k)
                    for (size_t c = 0; c < 3; ++c) dst[3 * k + c] += src[4 * k + c];
                std::fill(src, src + 4 * rows, 0.0);
            }
            for (int q = lo; q <= hi && renumbered; ++q) {
                double* __restrict dst = fp + 3 * static_cast<size_t>(im.nodeOf[static_cast<size_t>(q)]);
                for (size_t c = 0; c < 3; ++c) dst[c] += acc[3 * static_cast<size_t>(q - lo) + c];
            }
        }
    }
}

size_t TLEDForceField::bufferRows() const { return m_impl->buf.size() / 4; }

double TLEDForceField::potentialEnergy(const core::BaseMechanicalState& state) const {
    const Impl& im = *m_impl;
    if (state.size() < im.nodeCount) return std::numeric_limits<double>::quiet_NaN();
    std::vector<double> e(m_blocks.size(), 0.0);
    runBlocksOn(im, m_blocks, state, [&](KernelIO& io, size_t bi) {
        io.energy = &e[bi];
        // the energy is the elastic one (the kernel skips the viscous stresses without forces or
        // stress output); the committed history, should it read one
        for (size_t v = 0; v < im.visco.size(); ++v) io.Yhist[v] = im.visco[v].Yprev.data();
    });
    double sum = 0;
    for (double v : e) sum += v;
    return sum;
}

void TLEDForceField::stresses(const core::BaseMechanicalState& state, double t, std::vector<double>& S) const {
    const Impl& im = *m_impl;
    S.assign(6 * elementCount(), 0.0);
    if (state.size() < im.nodeCount) return;
    runBlocksOn(im, m_blocks, state, [&](KernelIO& io, size_t) {
        io.S = S.data();
        for (size_t v = 0; v < im.visco.size(); ++v) io.Yhist[v] = historyAt(im, v, t);
    });
}

void TLEDForceField::cellData(const core::BaseMechanicalState& state, std::vector<core::CellField>& out) const {
    const Impl& im = *m_impl;
    const size_t n = elementCount();
    if (state.size() < im.nodeCount) return;
    const double t = node() ? node()->context().time : im.curTime;
    std::vector<double> S(6 * n, 0.0), F(9 * n, 0.0);
    runBlocksOn(im, m_blocks, state, [&](KernelIO& io, size_t) {
        io.S = S.data();
        io.F = F.data();
        for (size_t v = 0; v < im.visco.size(); ++v) io.Yhist[v] = historyAt(im, v, t);
    });
    core::CellField fS{"S", 6, "Pa", S};
    core::CellField fSig{"cauchyStress", 6, "Pa", std::vector<double>(6 * n)};
    core::CellField fVM{"vonMises", 1, "Pa", std::vector<double>(n)};
    core::CellField fJ{"J", 1, "", std::vector<double>(n)};
    for (size_t e = 0; e < n; ++e) {
        const double* Fe = &F[9 * e];
        const double* Se = &S[6 * e];
        Mat3 Fm;
        Fm << Fe[0], Fe[1], Fe[2], Fe[3], Fe[4], Fe[5], Fe[6], Fe[7], Fe[8];
        Mat3 Sm;
        Sm << Se[0], Se[3], Se[5], Se[3], Se[1], Se[4], Se[5], Se[4], Se[2];
        const double J = Fm.determinant();
        const Mat3 sig = Fm * Sm * Fm.transpose() / J;  // Cauchy stress
        double* o = &fSig.values[6 * e];
        o[0] = sig(0, 0); o[1] = sig(1, 1); o[2] = sig(2, 2); o[3] = sig(0, 1); o[4] = sig(1, 2); o[5] = sig(0, 2);
        const double d01 = o[0] - o[1], d12 = o[1] - o[2], d20 = o[2] - o[0];
        fVM.values[e] = std::sqrt(0.5 * (d01 * d01 + d12 * d12 + d20 * d20) + 3 * (o[3] * o[3] + o[4] * o[4] + o[5] * o[5]));
        fJ.values[e] = J;
    }
    out.push_back(std::move(fS));
    out.push_back(std::move(fSig));
    out.push_back(std::move(fVM));
    out.push_back(std::move(fJ));
}

double TLEDForceField::restVolume(size_t e) const {
    const Impl& im = *m_impl;
    if (e < im.nTetCells) {
        for (size_t i = 0; i < im.tet.size(); ++i)
            if (static_cast<size_t>(im.tet.orig[i]) == e) return im.tet.vol[i];
    } else {
        for (size_t i = 0; i < im.hex.size(); ++i)
            if (static_cast<size_t>(im.hex.orig[i]) == e - im.nTetCells) return im.hex.vol[i];
    }
    return 0;
}

double TLEDForceField::elementTimeStep(size_t e, double rho) const {
    const Impl& im = *m_impl;
    for (const Block& b : m_blocks) {
        const auto& grp = im.groups[static_cast<size_t>(b.group)];
        for (size_t i = b.begin; i < b.end; ++i) {
            const size_t cell = b.kind == 0 ? static_cast<size_t>(im.tet.orig[i]) : im.nTetCells + static_cast<size_t>(im.hex.orig[i]);
            if (cell == e) return (b.kind == 0 ? im.tet.length[i] : im.hex.length[i]) / grp.material->waveSpeed(rho);
        }
    }
    return std::numeric_limits<double>::infinity();
}

double TLEDForceField::stableTimeStep(const core::BaseMechanicalState&) const {
    const Impl& im = *m_impl;
    const core::BaseMass* mass = node() ? node()->findInContext<core::BaseMass>() : nullptr;
    const double rho = mass ? mass->density() : std::numeric_limits<double>::quiet_NaN();
    if (!(rho > 0) || !std::isfinite(rho)) return std::numeric_limits<double>::infinity();
    double dt = std::numeric_limits<double>::infinity();
    for (size_t gi = 0; gi < im.groups.size(); ++gi) {
        const auto& grp = im.groups[gi];
        const double c = grp.material->waveSpeed(rho);  // TLED section 7: dt_cr = L_e / c
        double Lmin = std::numeric_limits<double>::infinity();
        for (const Block& b : m_blocks) {
            if (static_cast<size_t>(b.group) != gi) continue;
            const std::vector<double>& L = b.kind == 0 ? im.tet.length : im.hex.length;
            for (size_t i = b.begin; i < b.end; ++i) Lmin = std::min(Lmin, L[i]);
        }
        dt = std::min(dt, Lmin / c);
    }
    return dt;
}

} // namespace fascia::tled
