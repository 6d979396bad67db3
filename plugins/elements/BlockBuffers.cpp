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

} // namespace fascia::elements
