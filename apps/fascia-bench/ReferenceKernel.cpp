// The reference TLED step (ReferenceKernel.h): plain loops, no framework, the yardstick of the
// force fields' element loops (docs/performance.md, Method).
#include "ReferenceKernel.h"

#include "fascia/materials/Laws.h"  // materials::invCbrt only, inlined (header only: no link to the plugin)

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace fascia::bench {

ReferenceTLED::ReferenceTLED(const Tetrahedra& tets, const Positions& X, double mu, double kappa,
                             const std::vector<double>& m, const IndexList& fixed, int threads)
    : m_mu(mu), m_kappa(kappa), m_threads(std::max(1, threads)) {
    const size_t n = X.size();
    m_X.resize(3 * n);
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) m_X[3 * i + size_t(c)] = X[i][c];
    m_x = m_X;
    m_v.assign(3 * n, 0.0);
    m_invMass.assign(n, 0.0);
    for (size_t i = 0; i < n && i < m.size(); ++i) m_invMass[i] = m[i] > 0 ? 1.0 / m[i] : 0.0;
    for (int i : fixed) m_invMass[size_t(i)] = 0.0;
    // elements sorted by their lowest node: the threads' node ranges overlap little
    std::vector<size_t> order(tets.size());
    std::iota(order.begin(), order.end(), 0);
    const auto lowest = [&](size_t e) { return *std::min_element(tets[e].begin(), tets[e].end()); };
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return lowest(a) < lowest(b); });
    for (auto& v : m_node) v.reserve(tets.size());
    for (size_t e : order) {
        Mat3 Dm;  // rest edge matrix [X1 - X0, X2 - X0, X3 - X0]
        for (int a = 0; a < 4; ++a) m_node[a].push_back(tets[e][size_t(a)]);
        for (int k = 0; k < 3; ++k) Dm.col(k) = X[size_t(tets[e][size_t(k + 1)])] - X[size_t(tets[e][0])];
        m_V0.push_back(std::abs(Dm.determinant()) / 6.0);  // TLED eq. (3)
        // dN_a/dX for a = 1..3: the rows of Dm^-1
        const Mat3 inv = Dm.inverse();
        for (int a = 1; a < 4; ++a)
            for (int c = 0; c < 3; ++c) m_dN[3 * (a - 1) + c].push_back(inv(a - 1, c));
    }
    // a batch's loads stay inside the arrays: kBatch zeros at the end (lanes past a thread's last
    // element compute a rest state and are not scattered)
    m_count = m_V0.size();
    for (auto& v : m_dN) v.resize(m_count + kBatch, 0.0);
    m_V0.resize(m_count + kBatch, 0.0);
    // thread t: a contiguous range of elements and a buffer over the nodes they use
    m_begin.resize(size_t(m_threads) + 1);
    m_lo.resize(size_t(m_threads));
    m_hi.resize(size_t(m_threads));
    m_buf.resize(size_t(m_threads));
    for (int t = 0; t <= m_threads; ++t) m_begin[size_t(t)] = m_count * size_t(t) / size_t(m_threads);
    for (int t = 0; t < m_threads; ++t) {
        int lo = int(n), hi = -1;
        for (size_t e = m_begin[size_t(t)]; e < m_begin[size_t(t) + 1]; ++e)
            for (const auto& nd : m_node) lo = std::min(lo, nd[e]), hi = std::max(hi, nd[e]);
        if (hi < lo) lo = 0, hi = -1;
        m_lo[size_t(t)] = lo;
        m_hi[size_t(t)] = hi;
        m_buf[size_t(t)].assign(3 * size_t(hi - lo + 1), 0.0);
    }
}

void ReferenceTLED::setState(const Positions& x, const Positions& v) {
    for (size_t i = 0; i < nodeCount(); ++i)
        for (int c = 0; c < 3; ++c) {
            const bool fixed = m_invMass[i] == 0.0;
            m_x[3 * i + size_t(c)] = fixed ? m_X[3 * i + size_t(c)] : x[i][c];
            m_v[3 * i + size_t(c)] = fixed || v.empty() ? 0.0 : v[i][c];
        }
}

void ReferenceTLED::batchForces(size_t e0, int n, double (&fe)[4][3][kBatch]) const {
    // gather u = x - X of the batch's nodes (padding lanes: zeros, a rest state)
    alignas(64) double u[4][3][kBatch] = {};
    for (int k = 0; k < n; ++k)
        for (int a = 0; a < 4; ++a) {
            const size_t p = 3 * size_t(m_node[a][e0 + size_t(k)]);
            for (int c = 0; c < 3; ++c) u[a][c][k] = m_x[p + size_t(c)] - m_X[p + size_t(c)];
        }
    const double* dN[9];
    for (int r = 0; r < 9; ++r) dN[r] = m_dN[r].data() + e0;
    const double* V0 = m_V0.data() + e0;
    const double mu = m_mu, kappa = m_kappa;
    // (GCC ivdep, not omp simd: omp simd would keep the small local arrays in memory)
#pragma GCC ivdep
    for (int k = 0; k < kBatch; ++k) {
        // F = I + sum_a u_a (x) dN_a/dX = I + sum_{a=1..3} (u_a - u_0) (x) dN_a/dX (TLED eq. (1)-(3))
        double F[3][3];
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                double s = i == j ? 1.0 : 0.0;
                for (int a = 1; a < 4; ++a) s += (u[a][i][k] - u[0][i][k]) * dN[3 * (a - 1) + j][k];
                F[i][j] = s;
            }
        // C = F^T F, J = det F, C^-1 = cof(C) / J^2
        double C[3][3];
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) C[i][j] = F[0][i] * F[0][j] + F[1][i] * F[1][j] + F[2][i] * F[2][j];
        const double J = F[0][0] * (F[1][1] * F[2][2] - F[1][2] * F[2][1]) - F[0][1] * (F[1][0] * F[2][2] - F[1][2] * F[2][0]) +
                         F[0][2] * (F[1][0] * F[2][1] - F[1][1] * F[2][0]);
        const double t = materials::invCbrt(J), iJ = t * t * t, iJ2 = iJ * iJ;
        double Ci[3][3];
        Ci[0][0] = (C[1][1] * C[2][2] - C[1][2] * C[2][1]) * iJ2;
        Ci[1][1] = (C[0][0] * C[2][2] - C[0][2] * C[2][0]) * iJ2;
        Ci[2][2] = (C[0][0] * C[1][1] - C[0][1] * C[1][0]) * iJ2;
        Ci[0][1] = Ci[1][0] = (C[0][2] * C[2][1] - C[0][1] * C[2][2]) * iJ2;
        Ci[1][2] = Ci[2][1] = (C[0][2] * C[1][0] - C[0][0] * C[1][2]) * iJ2;
        Ci[0][2] = Ci[2][0] = (C[0][1] * C[1][2] - C[0][2] * C[1][1]) * iJ2;
        // S = mu J^(-2/3) (I - I1/3 C^-1) + kappa J (J - 1) C^-1 (TLED eq. (31)-(32) without fibres)
        const double I1 = C[0][0] + C[1][1] + C[2][2];
        const double a = mu * t * t, b = kappa * J * (J - 1.0) - a * I1 / 3.0;
        double S[3][3];
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) S[i][j] = (i == j ? a : 0.0) + b * Ci[i][j];
        // f_a = -V0 F S dN_a/dX, f_0 = -(f_1 + f_2 + f_3)
        const double V = V0[k];
        double P[3][3];
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) P[i][j] = V * (F[i][0] * S[0][j] + F[i][1] * S[1][j] + F[i][2] * S[2][j]);
        for (int i = 0; i < 3; ++i) {
            double f0 = 0.0;
            for (int q = 1; q < 4; ++q) {
                const double g0 = dN[3 * (q - 1)][k], g1 = dN[3 * (q - 1) + 1][k], g2 = dN[3 * (q - 1) + 2][k];
                const double f = -(P[i][0] * g0 + P[i][1] * g1 + P[i][2] * g2);
                fe[q][i][k] = f;
                f0 -= f;
            }
            fe[0][i][k] = f0;
        }
    }
}

template <bool Update>
void ReferenceTLED::run(double dt, double* f) {
    const long n = long(nodeCount());
#pragma omp parallel num_threads(m_threads)
    {
        // element range t on thread t (on fewer threads than asked for, the ranges in turn)
        for (size_t t = size_t(omp_get_thread_num()); t < size_t(m_threads); t += size_t(omp_get_num_threads())) {
            std::vector<double>& buf = m_buf[t];
            std::fill(buf.begin(), buf.end(), 0.0);
            const int lo = m_lo[t];
            alignas(64) double fe[4][3][kBatch];
            for (size_t e0 = m_begin[t]; e0 < m_begin[t + 1]; e0 += kBatch) {
                const int nb = int(std::min<size_t>(kBatch, m_begin[t + 1] - e0));
                batchForces(e0, nb, fe);
                for (int k = 0; k < nb; ++k)
                    for (int a = 0; a < 4; ++a) {
                        double* row = buf.data() + 3 * size_t(m_node[a][e0 + size_t(k)] - lo);
                        for (int c = 0; c < 3; ++c) row[c] += fe[a][c][k];
                    }
            }
        }
#pragma omp barrier
        // per node, the buffers in thread order, then the node update
#pragma omp for schedule(static)
        for (long i = 0; i < n; ++i) {
            double fi[3] = {0, 0, 0};
            for (size_t s = 0; s < m_buf.size(); ++s)
                if (i >= m_lo[s] && i <= m_hi[s])
                    for (int c = 0; c < 3; ++c) fi[c] += m_buf[s][3 * size_t(i - m_lo[s]) + size_t(c)];
            const size_t p = 3 * size_t(i);
            if constexpr (Update) {
                for (int c = 0; c < 3; ++c) {
                    m_v[p + size_t(c)] += dt * fi[c] * m_invMass[size_t(i)];
                    m_x[p + size_t(c)] += dt * m_v[p + size_t(c)];
                }
            } else {
                for (int c = 0; c < 3; ++c) f[p + size_t(c)] = fi[c];
            }
        }
    }
}

void ReferenceTLED::forces(std::vector<double>& f) {
    f.assign(3 * nodeCount(), 0.0);
    run<false>(0.0, f.data());
}

void ReferenceTLED::step(double dt) { run<true>(dt, nullptr); }

core::LayoutBytes ReferenceTLED::layoutBytes() const {
    constexpr size_t D = sizeof(double);
    core::LayoutBytes b;
    for (const auto& v : m_node) b.elementData += v.size() * sizeof(int);
    for (const auto& v : m_dN) b.elementData += v.size() * D;
    b.elementData += m_V0.size() * D;
    // X, x, 1/m read; v and x read and written (x counted once read, once written)
    b.nodeRows = (m_X.size() + m_x.size() + m_invMass.size()) * D + (m_v.size() + m_x.size()) * D + m_v.size() * D;
    // each buffer cleared, read and written by the elements, read by the sum
    for (const auto& buf : m_buf) b.buffers += 4 * buf.size() * D;
    return b;
}

} // namespace fascia::bench
