#include "fascia/elements/BlockBuffers.h"

#include <algorithm>

namespace fascia::elements {

namespace {
/// Nodes per tile of the reduction (its sums, 3 doubles a node, stay in L1).
constexpr int kNodeTile = 1024;
} // namespace

size_t BlockBuffers::addBlock(int lo, int hi) {
    m_lo.push_back(lo);
    m_hi.push_back(hi);
    m_offset.push_back(m_size);
    m_size += 4 * static_cast<size_t>(hi - lo + 1);
    return m_lo.size() - 1;
}

void BlockBuffers::finish(size_t nodeCount, std::vector<int> nodeOf) {
    m_nodes = nodeCount;
    m_nodeOf = std::move(nodeOf);
    m_buf.assign(m_size, 0.0);
}

void BlockBuffers::sumInto(double* fp) {
    const long nNodes = static_cast<long>(m_nodes);
    const long nTiles = (nNodes + kNodeTile - 1) / kNodeTile;
    const bool renumbered = !m_nodeOf.empty();
    const size_t nb = m_lo.size();
#pragma omp for schedule(static)
    for (long tile = 0; tile < nTiles; ++tile) {
        const int lo = static_cast<int>(tile * kNodeTile);
        const int hi = static_cast<int>(std::min<long>(nNodes, (tile + 1) * kNodeTile)) - 1;
        // renumbered nodes: the tile's sums first, in internal order, then into f
        alignas(64) double acc[3 * kNodeTile];
        double* __restrict sum = renumbered ? acc : fp + 3 * static_cast<size_t>(lo);
        if (renumbered) std::fill(acc, acc + 3 * (hi - lo + 1), 0.0);
        for (size_t b = 0; b < nb; ++b) {
            const int a = std::max(lo, m_lo[b]), z = std::min(hi, m_hi[b]);
            if (a > z) continue;
            double* __restrict src = m_buf.data() + m_offset[b] + 4 * static_cast<size_t>(a - m_lo[b]);
            double* __restrict dst = sum + 3 * static_cast<size_t>(a - lo);
            const size_t rows = static_cast<size_t>(z - a + 1);
            for (size_t k = 0; k < rows; ++k)
                for (size_t c = 0; c < 3; ++c) dst[3 * k + c] += src[4 * k + c];
            // cleared while in the cache, for the next evaluation
            std::fill(src, src + 4 * rows, 0.0);
        }
        for (int q = lo; q <= hi && renumbered; ++q) {
            double* __restrict dst = fp + 3 * static_cast<size_t>(m_nodeOf[static_cast<size_t>(q)]);
            for (size_t c = 0; c < 3; ++c) dst[c] += acc[3 * static_cast<size_t>(q - lo) + c];
        }
    }
}

core::LayoutBytes BlockBuffers::stepBytes() const {
    core::LayoutBytes b;
    b.buffers = 4 * m_buf.size() * sizeof(double);
    b.nodeRows = 2 * 3 * m_nodes * sizeof(double) + m_nodeOf.size() * sizeof(int);
    return b;
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

void CompactBlockBuffers::finish(std::vector<int> nodeOf) {
    m_nodeOf = std::move(nodeOf);
    const size_t n = m_nodeOf.size(), rows = m_rowInternal.size();
    m_rowNode.resize(rows);
    for (size_t r = 0; r < rows; ++r) m_rowNode[r] = m_nodeOf[static_cast<size_t>(m_rowInternal[r])];
    m_directGather = n * 3 * sizeof(double) <= (size_t(1) << 19);
    m_xin.assign(4 * n, 0.0);
    m_xrow.assign(4 * rows, 0.0);
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
    if (m_directGather) return x;
    const size_t n = m_nodeOf.size();
#pragma omp for schedule(static)
    for (size_t p = 0; p < n; ++p) {
        const double* s = x + 3 * size_t(m_nodeOf[p]);
        double* q = m_xin.data() + 4 * p;
        q[0] = s[0];
        q[1] = s[1];
        q[2] = s[2];
        q[3] = 0.0;
    }
    return m_xin.data();
}

void CompactBlockBuffers::sumInto(double* fp) const {
    const size_t n = m_nodeOf.size();
#pragma omp for schedule(static)
    for (size_t p = 0; p < n; ++p) {
        double a0 = 0.0, a1 = 0.0, a2 = 0.0;
        for (int k = m_nodeRowStart[p]; k < m_nodeRowStart[p + 1]; ++k) {
            const double* r = m_buf.data() + 4 * size_t(m_nodeRows[static_cast<size_t>(k)]);
            a0 += r[0];
            a1 += r[1];
            a2 += r[2];
        }
        double* q = fp + 3 * size_t(m_nodeOf[p]);
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
    if (m_directGather) b.nodeRows = 3 * n * D;
    else b.nodeRows = n * I + 3 * n * D + 2 * m_xin.size() * D;
    // the sum: the node's row lists, nodeOf, f read and written
    b.nodeRows += m_nodeRowStart.size() * I + n * I + 2 * 3 * n * D;
    // loadBlock: a row list (rowNode or rowInternal), the row positions written, the force rows
    // cleared; the kernel: positions read, forces read and written; the sum: rows and lists read
    b.buffers = (m_directGather ? m_rowNode.size() : m_rowInternal.size()) * I + 2 * m_xrow.size() * D +
                4 * m_buf.size() * D + m_nodeRows.size() * I;
    return b;
}

} // namespace fascia::elements
