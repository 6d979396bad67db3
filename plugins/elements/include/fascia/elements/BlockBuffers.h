#pragma once
/// Deterministic block assembly for any element force field, in two layouts of the per-block node
/// buffers. Both cut the elements into fixed blocks (their count depends on the mesh only, never on
/// the thread count), let each block add its element forces into its own node buffer, and sum the
/// buffers per node in block order, so results are bitwise identical for any number of threads
/// (docs/design.md, principle 5; docs/performance.md, lessons 4 and 5):
///
/// - BlockBuffers: a block's buffer covers the range of node indices its elements touch; elements
///   address it by node - lo(b). No copy-in; it grows with the numbering's bandwidth. TLED on
///   narrow ranges, and ElementAssembly for force fields that compute one element at a time.
/// - CompactBlockBuffers: a block's buffer holds one row per distinct node of its elements (compact
///   rows); the elements' node indices are rewritten to rows, the positions are copied into the
///   rows before the block runs, and each node sums its list of rows. It does not grow with the
///   bandwidth, at the price of the copy-in. HEML, and TLED on wide ranges.
///
/// Rows are 4 doubles (x y z and padding, the layout of simd::gather4 and simd::scatterAdd4).
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
#include "fascia/base/Simd.h"
#include "fascia/elements/Hd.h"
#include "fascia/sim/LayoutBytes.h"

#include <algorithm>
#include <cstddef>
#include <initializer_list>
#include <memory>
#include <vector>

namespace fascia::elements {

class BlockBuffers {
public:
    /// Adds a block whose elements use nodes lo..hi (internal numbering); returns its index.
    size_t addBlock(int lo, int hi);
    /// How the blocks fill their buffers: adding into them in place (the sum clears them for the
    /// next evaluation), or each block's rows written whole by commit (nothing to clear).
    enum class Fill { Add, Commit };
    /// Allocates the buffers (zeroed). nodeOf: internal node -> state node (empty: the same).
    void finish(size_t nodeCount, std::vector<int> nodeOf = {}, Fill fill = Fill::Add);
    size_t blockCount() const { return m_lo.size(); }
    int lo(size_t b) const { return m_lo[b]; }
    int hi(size_t b) const { return m_hi[b]; }
    /// Rows of block b's buffer: hi(b) - lo(b) + 1.
    size_t rowCount(size_t b) const { return static_cast<size_t>(m_hi[b] - m_lo[b] + 1); }
    /// The most rows of one block.
    size_t maxRows() const;
    /// The node buffer of block b: row r (4 doubles) is internal node lo(b) + r.
    double* buffer(size_t b) { return m_buf.data() + m_offset[b]; }
    /// Block b's forces (rowCount(b) rows of 4 doubles) become its buffer (BlockScratch).
    void commit(size_t b, const double* forces) { std::copy(forces, forces + 4 * rowCount(b), buffer(b)); }
    /// Node rows of all buffers together.
    size_t rows() const { return m_buf.size() / 4; }
    const std::vector<int>& nodeOf() const { return m_nodeOf; }
    /// f (3 doubles per state node) += the buffers, summed per node in block order; with Fill::Add
    /// the buffers are cleared for the next evaluation. An orphaned "omp for" over tiles of nodes:
    /// call it inside the parallel region of the element loop (or outside any, serially).
    void sumInto(double* f);
    /// What one evaluation moves through the buffers and f (core::LayoutBytes): with Fill::Add the
    /// scatter reads and writes every row, the sum reads and clears it (4 passes), with
    /// Fill::Commit the commit writes it and the sum reads it (2); f is read and written, nodeOf
    /// read. No element data (the force field adds its own).
    core::LayoutBytes stepBytes() const;
    /// The same for the state nodes [lo, hi) only (any thread, disjoint ranges: the threaded step's
    /// sum, fascia/sim/ThreadedStep.h). Without renumbering a tile of the buffers' rows; renumbered, each
    /// state node's rows through a per-node list in block order. Either way each node's rows are
    /// added in block order from 0 and the total added to f, as sumInto does: the same bits.
    void sumRange(double* f, long lo, long hi);

private:
    std::vector<int> m_lo, m_hi;
    std::vector<size_t> m_offset;
    std::vector<double> m_buf;
    std::vector<int> m_nodeOf;
    std::vector<int> m_internalOf;       ///< renumbered: state node -> internal node (-1: none)
    std::vector<size_t> m_nodeRowStart;  ///< renumbered: the rows of internal node p in block order are
    std::vector<size_t> m_nodeRows;      ///< m_nodeRows[m_nodeRowStart[p] .. [p + 1]] (offsets in doubles)
    size_t m_nodes = 0, m_size = 0;
    bool m_clear = true;  ///< Fill::Add: the sum clears what it read
};

/// Per-thread rows for one run of a block: the positions it gathers from (compact rows) and the
/// forces it adds into. A block writes nothing shared until it has claimed its result
/// (core::claimTask), and then copies its force rows into its buffer (commit), so two runs of one
/// block (the step team's takeover, fascia/sim/StepTeam.h) never write the same memory. Thread t's
/// rows are allocated by thread t on first use, at the sizes given to reserve; the positions also
/// stay in the thread's cache instead of a shared array.
class BlockScratch {
public:
    static constexpr int kThreads = 64;  ///< thread numbers 0 .. 63 (the step team's most)
    /// At init, before any run: the most position rows and force rows one block needs.
    void reserve(size_t positionRows, size_t forceRows);
    /// Thread t's position rows (4 doubles each).
    double* positions(int t) { return rowsOf(t).x.data(); }
    /// Thread t's force rows, the first `rows` of them cleared.
    double* forces(int t, size_t rows);

private:
    struct Rows {
        simd::DVec x, f;
    };
    Rows& rowsOf(int t);
    std::vector<std::unique_ptr<Rows>> m_rows;
    size_t m_xRows = 0, m_fRows = 0;
};

/// Compact rows (see the top of this file): a sibling of BlockBuffers rather than a second layout
/// of it, because the two share the contract (fixed blocks, one buffer each, the sum in block
/// order) but no data: this one rewrites the elements' connectivity, keeps positions per row and
/// sums per-node lists of rows, that one keeps a node range per block and sums tiles of nodes, so a
/// class holding both would branch on the layout in every accessor of the hot loop.
///
///   CompactBlockBuffers rows;
///   for each block: rows.addBlock({{nodes of corner 0, count}, ...});  // rewrites them to rows
///   rows.finish(nodeOf);
///   #pragma omp parallel
///   {
///     const double* xi = rows.positionsIn(x);                 // orphaned omp for (large meshes)
///     #pragma omp for schedule(dynamic, 1)
///     for each block b: rows.loadRows(b, xi, scratch.positions(t)); gather from them at the
///                       rewritten rows, scatter forces into scratch.forces(t, rows.rowCount(b)),
///                       rows.commit(b, those forces)
///     rows.sumInto(f);                                        // orphaned omp for
///   }
class CompactBlockBuffers {
public:
    /// count node indices at nodes (one corner of a block's elements, say).
    struct Nodes {
        int* nodes = nullptr;
        size_t count = 0;
    };
    /// Adds a block whose elements use the internal nodes listed in parts (any order, repeats
    /// allowed) and rewrites every entry to the node's row in the block: the block's distinct nodes
    /// in increasing order are its rows 0, 1, ... Returns the block's index.
    size_t addBlock(std::initializer_list<Nodes> parts);
    /// Where loadBlock reads the node values from.
    enum class Source {
        Auto,     ///< the state's positions: directly below about 20k nodes (they stay in cache;
                  ///< docs/performance.md, lesson 5), above from a copy in internal order
                  ///< (positionsIn), where a block's rows are close together
        Internal  ///< rows the caller keeps in internal order, 4 doubles per internal node (TLED's
                  ///< displacements): no copy of its own; stepBytes leaves them to the caller
    };
    /// Allocates the rows and buffers and builds, per node, its rows in block order. nodeOf:
    /// internal node -> state node, one entry per node.
    void finish(std::vector<int> nodeOf, Source source = Source::Auto);

    size_t blockCount() const { return m_rowStart.size() - 1; }
    size_t rowBegin(size_t b) const { return m_rowStart[b]; }
    size_t rowEnd(size_t b) const { return m_rowStart[b + 1]; }
    size_t rowCount(size_t b) const { return m_rowStart[b + 1] - m_rowStart[b]; }
    /// The most rows of one block.
    size_t maxRows() const;
    /// Rows of all blocks together.
    size_t rows() const { return m_rowInternal.size(); }
    /// The internal node of each row.
    const std::vector<int>& rowInternal() const { return m_rowInternal; }
    const std::vector<int>& nodeOf() const { return m_nodeOf; }
    bool directGather() const { return m_directGather; }

    /// The positions the blocks load from, given the state's x (3 doubles per node): x itself when
    /// directGather() (or, with Source::Internal, the caller's rows), else x copied into internal
    /// order (4 doubles per node). An orphaned
    /// "omp for": call it inside the parallel region of the element loop (or outside any).
    const double* positionsIn(const double* x);
    /// Block b's node values from xi (positionsIn's result, or the caller's rows) into out, 4
    /// doubles a row, rowCount(b) rows (a BlockScratch's positions). Inline: it runs per block,
    /// inside the element loop.
    FASCIA_INLINE void loadRows(size_t b, const double* xi, double* out) const;
    /// Block b's force buffer, row r at 4 r.
    double* buffer(size_t b) { return m_buf.data() + 4 * m_rowStart[b]; }
    const double* buffer(size_t b) const { return m_buf.data() + 4 * m_rowStart[b]; }
    /// Block b's forces (rowCount(b) rows of 4 doubles) become its buffer.
    void commit(size_t b, const double* forces) { std::copy(forces, forces + 4 * rowCount(b), buffer(b)); }
    /// f (3 doubles per state node) += the buffers, each node's rows summed in block order (commit
    /// overwrites a block's buffer: nothing to clear). An orphaned "omp for", as positionsIn.
    void sumInto(double* f) const;
    /// What one evaluation moves through the rows and f (core::LayoutBytes): positionsIn reads x
    /// and writes the internal copy (above the direct-gather size), loadRows reads its row lists
    /// and the positions (once per node) into a thread's rows (in its cache, not counted), commit
    /// writes the force rows, the sum reads the lists and the rows and reads and writes f. No
    /// element data (the force field adds its own).
    core::LayoutBytes stepBytes() const;
    /// positionsIn's copy for the internal nodes [lo, hi) only (nothing when directGather()), and
    /// sumInto for the state nodes [lo, hi) only: any thread, disjoint ranges (the threaded step,
    /// fascia/sim/ThreadedStep.h). The same bits as positionsIn and sumInto.
    void positionsRange(const double* x, long lo, long hi);
    const double* positionsBase(const double* x) const { return m_ownCopy ? m_xin.data() : x; }
    void sumRange(double* f, long lo, long hi) const;

private:
    std::vector<size_t> m_rowStart{0};  ///< rows of block b: [m_rowStart[b], m_rowStart[b + 1])
    std::vector<int> m_rowInternal;     ///< internal node of each row
    std::vector<int> m_rowNode;         ///< state node of each row
    std::vector<int> m_nodeOf;          ///< internal node -> state node
    std::vector<int> m_internalOf;      ///< state node -> internal node (-1: none)
    std::vector<int> m_nodeRowStart;    ///< per internal node p: its rows are m_nodeRows[start[p] .. [p + 1])
    std::vector<int> m_nodeRows;        ///< rows of each node, in block order
    bool m_directGather = false;
    bool m_ownCopy = true;  ///< positions in internal order kept here (Source::Auto above the direct size)
    bool m_prefetchSum = false;  ///< renumbered nodes: the sum prefetches rows ahead
    simd::DVec m_xin;   ///< positions in internal order, 4 doubles per node
    simd::DVec m_buf;   ///< forces per row (the per-block node buffers)
};

FASCIA_INLINE void CompactBlockBuffers::loadRows(size_t b, const double* xi, double* out) const {
    const size_t r0 = m_rowStart[b], r1 = m_rowStart[b + 1];
    if (m_directGather) {
        // small meshes: straight from the state's positions (they sit in cache), one barrier less
        for (size_t r = r0; r < r1; ++r) {
            const double* p = xi + 3 * size_t(m_rowNode[r]);
            double* q = out + 4 * (r - r0);
            q[0] = p[0];
            q[1] = p[1];
            q[2] = p[2];
            q[3] = 0.0;
        }
    } else {
        // from the values in internal order, where the rows of a block are close together
        for (size_t r = r0; r < r1; ++r) {
            const double* p = xi + 4 * size_t(m_rowInternal[r]);
            double* q = out + 4 * (r - r0);
            for (int k = 0; k < 4; ++k) q[k] = p[k];
        }
    }
}

} // namespace fascia::elements
