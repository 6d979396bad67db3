#pragma once
/// Internal to TLEDForceField: the precomputed element data (TLEDElements.cpp fills it), the
/// blocks and what a kernel call reads and writes (TLEDKernel.h).
#include "fascia/tled/TLEDForceField.h"

#include "fascia/base/Simd.h"
#include "fascia/elements/BlockBuffers.h"
#include "fascia/viscoelastic/HistoryClock.h"

#include <type_traits>
#include <utility>
#include <vector>

namespace fascia::viscoelastic {
class ViscoelasticProny;
}

namespace fascia::tled {

/// Elements per block of the deterministic reduction (fixed: never depends on the thread count):
/// tetrahedra, and hexahedra (about 4 times the work each; smaller blocks balance the threads).
constexpr size_t kBlockTets = 2048, kBlockHexes = 512;
/// Elements per batch inside a block: F, invariants and responses of a batch stay in L1.
constexpr int kBatch = 32;

/// A fixed block: a range of elements of one kind and one material group.
struct Block {
    int kind = 0;               ///< 0 tetrahedra, 1 hexahedra
    int group = 0;              ///< index into Impl::groups
    size_t begin = 0, end = 0;  ///< internal element range of its kind
    size_t batchBase = 0;       ///< index of its first element batch among all blocks (viscous states)
};

/// Precomputed data of one element kind, in internal order (grouped by material). The rows the
/// kernel reads are written straight into the pack, batch by batch: the batch in slot m (the blocks'
/// batches in order, see Block::batchBase and batchOffset) holds its rows one after the other, row r
/// at pack[(m rows + r) kBatch + k] for element k of the batch. A batch's data is then one contiguous
/// stream at constant offsets from one pointer (docs/performance.md, lesson 2). The slots depend on
/// the groups' sizes only, so they are known before the elements are computed, and no element-by-
/// element copy of the rows exists beside the pack (at 2M tetrahedra it was the peak of the memory).
template <int NN>
struct ElementSet {
    /// rows of the pack: dN_a/dX (tetrahedra: nodes 1-3 only, dN_0 = -(dN_1 + dN_2 + dN_3)), then
    /// for hexahedra the hourglass c_q, then the fibre directions a0 and b0 when given per element
    static constexpr int kDnRows = NN == 4 ? 9 : 24;
    static constexpr int kHgRow = kDnRows;                              ///< hexahedra: c_q, rows kHgRow + 3q + i
    static constexpr int kFibreRow = NN == 8 ? kDnRows + 12 : kDnRows;  ///< a0 x y z, then b0 x y z

    std::vector<int> nodes;     ///< NN per element (AoS; compact buffers: rows of the element's block)
    std::vector<double> vol;    ///< rest volume (m^3)
    std::vector<int> orig;      ///< index in the input list of its kind
    std::vector<double> length; ///< characteristic length L_e (m)
    std::vector<double> hgK;    ///< hexahedra: hourglass stiffness K (N/m)
    simd::DVec pack;            ///< the rows above, batch by batch (precision "double")
    /// precision "mixed": the same rows in float, and one more, the rest volume (row volRow), so that
    /// the kernel reads 4 bytes a number and no double array of the elements but the connectivity
    std::vector<float, simd::AlignedAllocator<float>> packF;
    int rows = 0;               ///< rows per batch in pack (or packF)
    int volRow = -1;            ///< packF: the row of the rest volume (-1: pack in double)
    size_t batchOffset = 0;     ///< Block::batchBase of the first batch of this kind
    size_t size() const { return vol.size(); }
    /// the pack of the batch starting at element e0 of block b (T: double, or float for packF)
    template <class T>
    const T* batchData(const Block& b, size_t e0) const {
        const size_t at = (b.batchBase - batchOffset + (e0 - b.begin) / kBatch) * static_cast<size_t>(rows) * kBatch;
        if constexpr (std::is_same_v<T, float>) return packF.data() + at;
        else return pack.data() + at;
    }
    /// Allocates the pack (zeroed) for `slots` batches: the rows above (fibres: with the fibre
    /// rows), in float with the volume row when mixed.
    void allocate(size_t slots, bool fibres, bool mixed);
    /// Row r of element k of the batch in slot m (in float when mixed).
    void put(size_t m, size_t k, int r, double v) {
        const size_t at = (m * static_cast<size_t>(rows) + static_cast<size_t>(r)) * kBatch + k;
        if (volRow >= 0) packF[at] = static_cast<float>(v);
        else pack[at] = v;
    }
};

/// One Prony series acting on the isochoric and/or volumetric part of S.
struct ViscoSet {
    viscoelastic::ViscoelasticProny* prony = nullptr;
    bool iso = false, vol = false;
    int terms = 0;
    /// A_i, B_i of the last force evaluation (TLED eq. (30), for the time it advanced the history
    /// over; before the first, those of the scene's time step)
    std::vector<double> A, B;
    /// the states Y_i of the last step and of the current evaluation, batch by batch (one contiguous
    /// stream per array): batch m of the elements (Block::batchBase + local batch) holds, for each
    /// term t and stress component c (xx yy zz xy yz xz), kBatch values at ((m terms + t) 6 + c) kBatch
    simd::DVec Yprev, Ycur;
};

/// What a kernel call writes (any output may be null).
struct KernelIO {
    const double* u = nullptr; ///< nodal displacements x - X, 4 per internal node (padded)
    double* buf = nullptr;     ///< the block's node buffer (4 per internal node from its lowest node, padded)
    int bufLo = 0;             ///< the buffer's first node
    double* energy = nullptr;  ///< energy of the block (added to)
    double* S = nullptr;       ///< 6 per cell (cell order)
    double* F = nullptr;       ///< 9 per cell (cell order)
    const double* Yhist[2] = {nullptr, nullptr};
    double* Ynew[2] = {nullptr, nullptr};
    /// stress output: the coefficients A_i, B_i of each series (null: the series' own, ViscoSet::A, B)
    const double* A[2] = {nullptr, nullptr};
    const double* B[2] = {nullptr, nullptr};
    bool streamY = false;      ///< write Ynew with streaming stores (large states)
};

struct TLEDForceField::Impl {
    using KernelFn = void (*)(const Impl&, const Block&, const KernelIO&);
    /// The elements of one kind with one material.
    struct Group {
        int kind = 0;
        const materials::BaseMaterial* material = nullptr;
        unsigned uses = 0;
        const void* law = nullptr;  ///< the inlined law, when the material is a built-in one
        KernelFn fn = nullptr;
        double a0[3] = {1, 0, 0}, b0[3] = {0, 1, 0};  ///< fibre directions when not given per element
        /// s of s ln J moved from the isochoric to the volumetric part of S (s C^-1) on the viscous
        /// paths, so that each part a series relaxes alone is stress-free at rest
        /// (materials/RelaxationSplit.h); 0 when no series relaxes one part alone
        double restShift = 0;
    };
    /// precision="mixed": the element data and the element loop in float, u, the forces and the
    /// block sums in double (TLEDKernel.h)
    bool mixed = false;
    bool fibresPerElement = false;  ///< a fibre array gives the directions (ElementSet::a0, b0), else Group::a0, b0
    ElementSet<4> tet;
    ElementSet<8> hex;
    std::vector<Group> groups;
    std::vector<Block> blocks;
    /// one force buffer per block, summed per node in block order, in one of two layouts
    /// (elements/BlockBuffers.h, TLEDForceField::m_nodeBuffers): node ranges (buffers), or compact
    /// rows (rows: the elements' nodes rewritten to their block's rows, u copied in per block)
    bool compact = false;
    elements::BlockBuffers buffers;
    elements::CompactBlockBuffers rows;
    /// each thread's rows for a block's run (u rows and force rows), committed to the block's
    /// buffer when the run claims its result (TLEDForceField::runForceBlock)
    elements::BlockScratch scratch;
    std::vector<ViscoSet> visco;
    double J0 = 0.4;
    size_t nodeCount = 0;     ///< 1 + largest node index
    std::vector<int> nodeOf;  ///< internal node -> state node when renumbered (empty: the state's order)
    size_t nTetCells = 0;     ///< number of tetrahedra (cell offset of the hexahedra)
    /// when the viscous history advances and over what time (shared with HEML)
    viscoelastic::HistoryClock clock;
    double dt = 0;            ///< the scene's time step (s), from dtChanged (0: none yet)
    std::vector<double> u;    ///< displacements of the last addForce, 4 per internal node
    const core::BaseMechanicalState* evalState = nullptr;  ///< the state of the evaluation under way (beginForces)
    size_t batches = 0;       ///< element batches of all blocks (the viscous states hold one slot per batch)
    bool streamStates = false; ///< viscous states too large for the caches: streaming stores

    template <int NN> const ElementSet<NN>& set() const {
        if constexpr (NN == 4) return tet; else return hex;
    }
    template <int NN> ElementSet<NN>& set() {
        if constexpr (NN == 4) return tet; else return hex;
    }
};

/// The kernel of a group (TLEDKernelDouble.cpp): the inlined loop of its built-in law, else the generic
/// one, in double or (mixed) in float.
void chooseKernel(TLEDForceField::Impl::Group& g, bool mixed);
/// The same for one scalar type (TLEDKernelDouble.cpp, TLEDKernelFloat.cpp).
template <class T>
TLEDForceField::Impl::KernelFn kernelFor(const TLEDForceField::Impl::Group& g, const void*& law);

} // namespace fascia::tled
