#pragma once
/// Deterministic block assembly for any element force field: elements are split into fixed blocks
/// (their count depends on the mesh only, never on the thread count); each block adds its element
/// forces into its own node buffer, which covers the range of node indices its elements touch
/// (4 doubles per node: x y z and padding, the layout of simd::scatterAdd4); then sumInto() adds
/// the buffers per node in block order. Results are bitwise identical for any number of threads
/// (docs/design.md, "determinism"; docs/performance.md, lessons: block buffers).
///
///   BlockBuffers bb;
///   for each block: bb.addBlock(lowestNode, highestNode);      // at init
///   bb.finish(nodeCount, nodeOf);
///   #pragma omp parallel
///   {
///     #pragma omp for schedule(dynamic, 1)
///     for each block b: scatter forces into bb.buffer(b) at rows node - bb.lo(b)
///     bb.sumInto(f);                                           // orphaned omp for, clears the buffers
///   }
#include <cstddef>
#include <vector>

namespace fascia::elements {

class BlockBuffers {
public:
    /// Adds a block whose elements use nodes lo..hi (internal numbering); returns its index.
    size_t addBlock(int lo, int hi);
    /// Allocates the buffers (zeroed). nodeOf: internal node -> state node (empty: the same).
    void finish(size_t nodeCount, std::vector<int> nodeOf = {});
    size_t blockCount() const { return m_lo.size(); }
    int lo(size_t b) const { return m_lo[b]; }
    int hi(size_t b) const { return m_hi[b]; }
    /// The node buffer of block b: row r (4 doubles) is internal node lo(b) + r.
    double* buffer(size_t b) { return m_buf.data() + m_offset[b]; }
    /// Node rows of all buffers together.
    size_t rows() const { return m_buf.size() / 4; }
    const std::vector<int>& nodeOf() const { return m_nodeOf; }
    /// f (3 doubles per state node) += the buffers, summed per node in block order; the buffers are
    /// cleared for the next evaluation. An orphaned "omp for" over tiles of nodes: call it inside the
    /// parallel region of the element loop (or outside any, serially).
    void sumInto(double* f);

private:
    std::vector<int> m_lo, m_hi;
    std::vector<size_t> m_offset;
    std::vector<double> m_buf;
    std::vector<int> m_nodeOf;
    size_t m_nodes = 0, m_size = 0;
};

} // namespace fascia::elements
