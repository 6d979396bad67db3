#pragma once
/// Internal to HEMLForceField: the element data as structure of arrays in padded slots (HEMLElements.cpp
/// fills it), the blocks, what a block's run reads and writes, and the element loops of each material
/// (HEMLKernel.h, instantiated in HEMLKernelDouble.cpp and HEMLKernelFloat.cpp).
#include "fascia/heml/HEMLForceField.h"

#include "fascia/base/Simd.h"
#include "fascia/elements/BlockBuffers.h"
#include "fascia/viscoelastic/HistoryClock.h"

#include <cstddef>
#include <type_traits>
#include <vector>

namespace fascia::heml {

using simd::DVec;
using simd::IVec;
/// 64-byte aligned per-slot array of the element scalar type T.
template <class T>
using SVec = std::vector<T, simd::AlignedAllocator<T>>;
using FVec = SVec<float>;

/// Elements per chunk of the element loop (two AVX-512 vectors of doubles; docs/performance.md, lesson 3).
constexpr int kLanes = 16;
/// Elements per block: the unit of work and of node buffers. Fixed, so the block count depends on
/// the mesh only, never on the thread count (docs/design.md, determinism).
constexpr size_t kBlockSize = 1024;

/// A contiguous range of (padded) element slots with one material. Its elements refer to the
/// block's own node rows (Impl::rows, block of the same index): positions are copied into them
/// before the block runs (so the gather reads from cache) and its forces are added into them.
struct Block {
    size_t begin = 0, end = 0;
    int material = -1;  ///< index into Impl::materials, -1 in mass-spring mode
};

/// The per-slot element arrays the loop reads, in the element scalar type T.
template <class T>
struct ElementArrays {
    SVec<T> vol;      ///< rest volume Vol (0 in padding slots)
    SVec<T> invDetV;  ///< 1 / det(V1, V2, V3) (signed)
    /// G = V^-1 V^-T (symmetric: G11 G22 G33 G12 G23 G13). With D(l) = sum_k l_k D_k (eq. (A.4)-(A.5))
    /// and C_k = V^-T D_k V^-1 (eq. (A.6)), Appendix C's vtr_k = tr C_k = tr(D_k G) and
    /// Mtr_ij = tr(C_i C_j) = tr(D_i G D_j G): the loop evaluates vtr and Mtr l = (tr(D_k G D(l) G))_k
    /// from these 6 numbers instead of loading the 27 of vtr and Mtr (docs/performance.md, lesson 7).
    SVec<T> G[6];
    SVec<T> w4[3], w6[3];    ///< V^-1 a0, V^-1 b0: a0.C_k a0 = w.D_k w (empty when no material reads I4 / I6)
    SVec<T> kk[6], len0[6];  ///< mass-spring mode: stiffness share and rest length per edge

    /// Bytes of the arrays (sizeof(T) each: 4 in mixed mode), for HEMLForceField::layoutBytes.
    size_t bytes() const {
        size_t n = vol.size() + invDetV.size();
        for (int k = 0; k < 6; ++k) n += G[k].size() + kk[k].size() + len0[k].size();
        for (int k = 0; k < 3; ++k) n += w4[k].size() + w6[k].size();
        return n * sizeof(T);
    }
    /// Calls f(mine, other's) on each pair of arrays (the rounding to float of precision="mixed").
    template <class U, class F>
    void zip(const ElementArrays<U>& o, F&& f) {
        f(vol, o.vol);
        f(invDetV, o.invDetV);
        for (int k = 0; k < 6; ++k) f(G[k], o.G[k]), f(kk[k], o.kk[k]), f(len0[k], o.len0[k]);
        for (int k = 0; k < 3; ++k) f(w4[k], o.w4[k]), f(w6[k], o.w6[k]);
    }
};

/// Where a block's run reads and writes: the positions x (Impl::rows.positionsIn's result), and
/// the thread's own rows (elements::BlockScratch) for the block's positions and, cleared, its forces.
struct BlockRun {
    const double* x = nullptr;
    double* rows = nullptr;
    double* forces = nullptr;  ///< (null for the energy alone)
};

/// Everything the element loop reads and writes.
struct HEMLForceField::Impl {
    size_t nNodes = 0, nElements = 0, nSlots = 0;
    std::vector<int> nodeOf;      ///< internal node -> state node (reverse Cuthill-McKee order)
    std::vector<int> internalOf;  ///< state node -> internal node
    std::vector<int> elementOf;   ///< slot -> input element (-1: padding)
    std::vector<int> slotOf;      ///< input element -> slot

    // per slot (structure of arrays)
    IVec node[4];          ///< the block's node rows (in Impl::rows; internal nodes before that)
    /// The element arrays of precision="double" (el) or "mixed" (elf): the other one is empty, so
    /// mixed mode holds 4 + 4 + 6 * 4 bytes per element besides the node indices, not 8 + 8 + 6 * 8.
    ElementArrays<double> el;
    ElementArrays<float> elf;
    bool mixed = false;       ///< precision="mixed": the loop runs in float (elf)
    double totalVolume = 0;   ///< sum of the rest volumes (in double, before any rounding to float)
    template <class T>
    const ElementArrays<T>& arrays() const {
        if constexpr (std::is_same_v<T, float>) return elf;
        else return el;
    }
    /// The rest volume of a slot in double (from whichever arrays are kept).
    double volume(size_t slot) const { return mixed ? double(elf.vol[slot]) : el.vol[slot]; }

    std::vector<Block> blocks;
    std::vector<const materials::BaseMaterial*> materials;
    bool massSpring = false;
    double J0 = 0.4;

    /// the node rows of the blocks (compact rows, 4 doubles each) and their ordered sum
    elements::CompactBlockBuffers rows;
    elements::BlockScratch scratch;  ///< each thread's rows for a block's run (HEMLForceField::runForceBlock)
    std::vector<double> blockEnergy;

    // viscoelasticity (eq. (18)-(20)): per term and link coefficient (6), one value per slot
    int nTerms = 0;
    bool relaxIso = false, relaxVol = false;
    /// per material: the s of s ln J moved from the isochoric to the volumetric part before one of
    /// them relaxes, so that each is stress-free at rest (materials/RelaxationSplit.h); 0 when both relax
    std::vector<double> restShift;
    std::vector<double> A, B;         ///< A_i, B_i of the last evaluation (TLED eq. (30), HEML eq. (20))
    /// the committed history and the last evaluation's; double in both precisions (the loop
    /// converts the relaxed link coefficients to double, and the sum of the terms back to T)
    std::vector<DVec> Yprev, Ycur;
    viscoelastic::HistoryClock clock;  ///< when the history advances and over what time

    /// The element loops of one material (or of the mass springs): with forces and viscosity, with
    /// forces, the energy alone.
    struct Loops {
        using Fn = double (*)(Impl&, size_t, const BlockRun&);
        Fn forcesVisco = nullptr, forces = nullptr, energy = nullptr;
        bool inlined = true;  ///< the inlined loop of a built-in law (false: batched virtual evaluation)
    };
    std::vector<Loops> loops;  ///< per material (Impl::materials), or one, the springs', in mass-spring mode
    const double* evalX = nullptr;  ///< the positions of the evaluation under way (3 per state node)
};

using Impl = HEMLForceField::Impl;

/// The loops of material m (null: the mass springs of HEML eq. (38)), in float when mixed
/// (HEMLKernelDouble.cpp).
Impl::Loops loopsFor(const materials::BaseMaterial* m, bool mixed);
/// The same with the element math in T (HEMLKernelDouble.cpp, HEMLKernelFloat.cpp).
template <class T>
Impl::Loops loopsIn(const materials::BaseMaterial* m);

} // namespace fascia::heml
