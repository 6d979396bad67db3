#include "fascia/elements/BlockBuffers.h"

#include <algorithm>

namespace fascia::elements {

namespace {
/// Nodes per tile of the reduction (its sums, 3 doubles a node, stay in L1).
constexpr int kNodeTile = 1024;
/// How many nodes ahead the compact sum prefetches the rows of a renumbered node.
constexpr long kSumAhead = 8;
} // namespace

size_t BlockBuffers::addBlock(int lo, int hi) {
    m_lo.push_back(lo);
    m_hi.push_back(hi);
    m_offset.push_back(m_size);
    m_size += 4 * static_cast<size_t>(hi - lo + 1);
    return m_lo.size() - 1;
}

size_t BlockBuffers::maxRows() const {
    size_t m = 0;
    for (size_t b = 0; b < blockCount(); ++b) m = std::max(m, rowCount(b));
    return m;
}

void BlockBuffers::finish(size_t nodeCount, std::vector<int> nodeOf, Fill how) {
    m_clear = how == Fill::Add;
    m_nodes = nodeCount;
    m_nodeOf = std::move(nodeOf);
    m_buf.assign(m_size, 0.0);
    m_internalOf.clear();
    m_nodeRowStart.clear();
    m_nodeRows.clear();
    if (m_nodeOf.empty()) return;
    // renumbered: per internal node, its buffer rows in block order, and the state -> internal map
    int maxState = -1;
    for (int s : m_nodeOf) maxState = std::max(maxState, s);
    m_internalOf.assign(size_t(maxState + 1), -1);
    for (size_t p = 0; p < m_nodeOf.size(); ++p) m_internalOf[size_t(m_nodeOf[p])] = int(p);
    m_nodeRowStart.assign(m_nodes + 1, 0);
    const size_t nb = m_lo.size();
    for (size_t b = 0; b < nb; ++b)
        for (int p = std::max(0, m_lo[b]); p <= m_hi[b] && size_t(p) < m_nodes; ++p) ++m_nodeRowStart[size_t(p) + 1];
    for (size_t p = 0; p < m_nodes; ++p) m_nodeRowStart[p + 1] += m_nodeRowStart[p];
    m_nodeRows.assign(m_nodeRowStart.back(), 0);
    std::vector<size_t> fill(m_nodeRowStart.begin(), m_nodeRowStart.end() - 1);
    for (size_t b = 0; b < nb; ++b)
        for (int p = std::max(0, m_lo[b]); p <= m_hi[b] && size_t(p) < m_nodes; ++p)
            m_nodeRows[fill[size_t(p)]++] = m_offset[b] + 4 * size_t(p - m_lo[b]);
}

void BlockBuffers::sumInto(double* fp) {
    const long n = static_cast<long>(m_nodeOf.empty() ? m_nodes : m_internalOf.size());
    const long nTiles = (n + kNodeTile - 1) / kNodeTile;
#pragma omp for schedule(dynamic, 1)
    for (long tile = 0; tile < nTiles; ++tile) sumRange(fp, tile * kNodeTile, std::min(n, (tile + 1) * kNodeTile));
}

void BlockBuffers::sumRange(double* fp, long lo, long hi) {
    if (!m_nodeOf.empty()) {
        // renumbered: each state node's rows, in block order, from 0, then into f
        hi = std::min(hi, static_cast<long>(m_internalOf.size()));
        for (long i = lo; i < hi; ++i) {
            const int p = m_internalOf[size_t(i)];
            if (p < 0) continue;
            double a0 = 0.0, a1 = 0.0, a2 = 0.0;
            for (size_t k = m_nodeRowStart[size_t(p)]; k < m_nodeRowStart[size_t(p) + 1]; ++k) {
                double* __restrict r = m_buf.data() + m_nodeRows[k];
                a0 += r[0];
                a1 += r[1];
                a2 += r[2];
                if (m_clear) r[0] = r[1] = r[2] = r[3] = 0.0;  // cleared for the next evaluation
            }
            double* __restrict q = fp + 3 * size_t(i);
            q[0] += a0;
            q[1] += a1;
            q[2] += a2;
        }
        return;
    }
    // tiles of node rows: every block that covers part of one, in block order, summed from 0 and
    // the total added to f (the same bits as the renumbered path and as CompactBlockBuffers)
    hi = std::min(hi, static_cast<long>(m_nodes));
    for (long t0 = lo; t0 < hi; t0 += kNodeTile) {
        const int a0 = static_cast<int>(t0), z0 = static_cast<int>(std::min(hi, t0 + kNodeTile)) - 1;
        alignas(64) double sum[3 * kNodeTile];
        std::fill(sum, sum + 3 * static_cast<size_t>(z0 - a0 + 1), 0.0);
        for (size_t b = 0; b < m_lo.size(); ++b) {
            const int a = std::max(a0, m_lo[b]), z = std::min(z0, m_hi[b]);
            if (a > z) continue;
            double* __restrict src = m_buf.data() + m_offset[b] + 4 * static_cast<size_t>(a - m_lo[b]);
            double* __restrict dst = sum + 3 * static_cast<size_t>(a - a0);
            const size_t rows = static_cast<size_t>(z - a + 1);
            for (size_t k = 0; k < rows; ++k)
                for (size_t c = 0; c < 3; ++c) dst[3 * k + c] += src[4 * k + c];
            // cleared while in the cache, for the next evaluation
            if (m_clear) std::fill(src, src + 4 * rows, 0.0);
        }
        double* __restrict out = fp + 3 * static_cast<size_t>(a0);
        for (size_t k = 0; k < 3 * static_cast<size_t>(z0 - a0 + 1); ++k) out[k] += sum[k];
    }
}

core::LayoutBytes BlockBuffers::stepBytes() const {
    core::LayoutBytes b;
    b.buffers = (m_clear ? 4 : 2) * m_buf.size() * sizeof(double);
    b.nodeRows = 2 * 3 * m_nodes * sizeof(double) + m_nodeOf.size() * sizeof(int);
    return b;
}

void BlockScratch::reserve(size_t positionRows, size_t forceRows) {
    m_xRows = positionRows;
    m_fRows = forceRows;
    m_rows.clear();
    m_rows.resize(kThreads);
}

BlockScratch::Rows& BlockScratch::rowsOf(int t) {
    std::unique_ptr<Rows>& r = m_rows.at(size_t(t));
    if (!r) {
        r = std::make_unique<Rows>();
        r->x.assign(4 * m_xRows, 0.0);
        r->f.assign(4 * m_fRows, 0.0);
    }
    return *r;
}

double* BlockScratch::forces(int t, size_t rows) {
    double* f = rowsOf(t).f.data();
    std::fill(f, f + 4 * rows, 0.0);
    return f;
}

size_t CompactBlockBuffers::maxRows() const {
    size_t m = 0;
    for (size_t b = 0; b < blockCount(); ++b) m = std::max(m, rowCount(b));
    return m;
}

size_t CompactBlockBuffers::addBlock(std::initializer_list<Nodes> parts) {
    // the block's distinct nodes, in increasing order, are its rows
    std::vector<int> nodes;
    for (const Nodes& p : parts) nodes.insert(nodes.end(), p.nodes, p.nodes + p.count);
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    for (const Nodes& p : parts)
        for (size_t i = 0; i < p.count; ++i)
            p.nodes[i] = static_cast<int>(std::lower_bound(nodes.begin(), nodes.end(), p.nodes[i]) - nodes.begin());
    m_rowInternal.insert(m_rowInternal.end(), nodes.begin(), nodes.end());
    m_rowStart.push_back(m_rowInternal.size());
    return m_rowStart.size() - 2;
}

void CompactBlockBuffers::finish(std::vector<int> nodeOf, Source source) {
    m_nodeOf = std::move(nodeOf);
    const size_t n = m_nodeOf.size(), rows = m_rowInternal.size();
    int maxState = -1;
    for (int s : m_nodeOf) maxState = std::max(maxState, s);
    m_internalOf.assign(size_t(maxState + 1), -1);
    for (size_t p = 0; p < n; ++p) m_internalOf[size_t(m_nodeOf[p])] = int(p);
    m_rowNode.resize(rows);
    for (size_t r = 0; r < rows; ++r) m_rowNode[r] = m_nodeOf[static_cast<size_t>(m_rowInternal[r])];
    m_directGather = source == Source::Auto && n * 3 * sizeof(double) <= (size_t(1) << 19);
    m_ownCopy = source == Source::Auto && !m_directGather;
    // the sum prefetches when the rows outgrow a core's L2 and the nodes were renumbered
    m_prefetchSum = false;
    for (size_t p = 0; p < n && !m_prefetchSum && 4 * rows * sizeof(double) > (size_t(2) << 20); ++p) m_prefetchSum = m_nodeOf[p] != int(p);
    m_xin.assign(m_ownCopy ? 4 * n : 0, 0.0);
    m_buf.assign(4 * rows, 0.0);
    // per node, its rows; rows ascend with the block index, so each list is in block order
    m_nodeRowStart.assign(n + 1, 0);
    for (int p : m_rowInternal) ++m_nodeRowStart[static_cast<size_t>(p) + 1];
    for (size_t p = 0; p < n; ++p) m_nodeRowStart[p + 1] += m_nodeRowStart[p];
    m_nodeRows.assign(rows, 0);
    std::vector<int> fill(m_nodeRowStart.begin(), m_nodeRowStart.end() - 1);
    for (size_t r = 0; r < rows; ++r) m_nodeRows[static_cast<size_t>(fill[static_cast<size_t>(m_rowInternal[r])]++)] = static_cast<int>(r);
}

const double* CompactBlockBuffers::positionsIn(const double* x) {
    if (!m_ownCopy) return x;
    const long n = static_cast<long>(m_nodeOf.size());
    const long nTiles = (n + kNodeTile - 1) / kNodeTile;
#pragma omp for schedule(dynamic, 1)
    for (long tile = 0; tile < nTiles; ++tile) positionsRange(x, tile * kNodeTile, std::min(n, (tile + 1) * kNodeTile));
    return m_xin.data();
}

void CompactBlockBuffers::positionsRange(const double* x, long lo, long hi) {
    if (!m_ownCopy) return;
    for (long p = lo; p < hi; ++p) {
        const double* s = x + 3 * size_t(m_nodeOf[size_t(p)]);
        double* q = m_xin.data() + 4 * size_t(p);
        q[0] = s[0];
        q[1] = s[1];
        q[2] = s[2];
        q[3] = 0.0;
    }
}

void CompactBlockBuffers::sumInto(double* fp) const {
    const long n = static_cast<long>(m_internalOf.size());
    const long nTiles = (n + kNodeTile - 1) / kNodeTile;
#pragma omp for schedule(dynamic, 1)
    for (long tile = 0; tile < nTiles; ++tile) sumRange(fp, tile * kNodeTile, std::min(n, (tile + 1) * kNodeTile));
}

void CompactBlockBuffers::sumRange(double* fp, long lo, long hi) const {
    // per state node, its internal node's rows in block order (the same sum as per internal node)
    hi = std::min(hi, static_cast<long>(m_internalOf.size()));
    for (long i = lo; i < hi; ++i) {
        // renumbered nodes: their rows lie apart, where the hardware's prefetchers do not follow;
        // fetch those of the node kSumAhead on (docs/performance.md, "Issue 17: blocks taken over")
        if (m_prefetchSum && i + kSumAhead < hi) {
            const int q = m_internalOf[size_t(i + kSumAhead)];
            if (q >= 0)
                for (int k = m_nodeRowStart[size_t(q)]; k < m_nodeRowStart[size_t(q) + 1]; ++k)
                    simd::prefetch(m_buf.data() + 4 * size_t(m_nodeRows[static_cast<size_t>(k)]), 32);
        }
        const int p = m_internalOf[size_t(i)];
        if (p < 0) continue;
        double a0 = 0.0, a1 = 0.0, a2 = 0.0;
        for (int k = m_nodeRowStart[size_t(p)]; k < m_nodeRowStart[size_t(p) + 1]; ++k) {
            const double* r = m_buf.data() + 4 * size_t(m_nodeRows[static_cast<size_t>(k)]);
            a0 += r[0];
            a1 += r[1];
            a2 += r[2];
        }
        double* q = fp + 3 * size_t(i);
        q[0] += a0;
        q[1] += a1;
        q[2] += a2;
    }
}

core::LayoutBytes CompactBlockBuffers::stepBytes() const {
    constexpr size_t D = sizeof(double), I = sizeof(int);
    const size_t n = m_nodeOf.size();
    core::LayoutBytes b;
    // positionsIn (nodeOf, x, the copy written) and loadBlock's reads of the positions, once a node
    // (Source::Internal: the caller's rows, which it counts)
    if (m_directGather) b.nodeRows = 3 * n * D;
    else if (m_ownCopy) b.nodeRows = n * I + 3 * n * D + 2 * m_xin.size() * D;
    // the sum: the node's row lists, nodeOf, f read and written
    b.nodeRows += m_nodeRowStart.size() * I + n * I + 2 * 3 * n * D;
    // loadRows: a row list (rowNode or rowInternal); commit: the force rows written; the sum: rows
    // and lists read (the thread's rows, positions and forces, stay in its cache)
    b.buffers = (m_directGather ? m_rowNode.size() : m_rowInternal.size()) * I + 2 * m_buf.size() * D + m_nodeRows.size() * I;
    return b;
}

} // namespace fascia::elements
