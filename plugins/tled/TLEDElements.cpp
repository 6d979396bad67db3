// TLEDForceField's precomputation: materials per group, node and element order, the element data
// of tetrahedra and hexahedra (TLED eq. (2)-(3); uniform-strain hexahedra with hourglass control),
// the fixed blocks and the packed, batch-by-batch layout the kernel reads.
#include "TLEDData.h"

#include "fascia/elements/NodeOrder.h"
#include "fascia/base/Format.h"
#include "fascia/elements/FibreField.h"
#include "fascia/elements/Geometry.h"
#include "fascia/elements/GroupMaterials.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace fascia::tled {

using core::formatNumber;

using materials::BaseMaterial;
using Impl = TLEDForceField::Impl;

template <int NN>
void ElementSet<NN>::allocate(size_t slots, bool fibres, bool mixed) {
    rows = kFibreRow + (fibres ? 6 : 0);
    volRow = mixed ? rows++ : -1;
    const size_t n = slots * static_cast<size_t>(rows) * kBatch;
    if (mixed) packF.assign(n, 0.0f);
    else pack.assign(n, 0.0);
}
template struct ElementSet<4>;
template struct ElementSet<8>;

namespace {

/// Everything precompute's steps share.
struct Setup {
    const Tetrahedra& tets;
    const Hexahedra& hexes;
    const Positions& X;
    std::vector<std::vector<size_t>> perGroup;  ///< elements of each group, in their internal order
    std::vector<int> internalOf;                ///< state node -> internal node
    elements::FibreField fibA, fibB;
    const int* nodesOf(int nn, size_t e) const { return nn == 4 ? tets[e].data() : hexes[e].data(); }
};

/// Node rows the blocks' buffers would take with this numbering and these element lists.
size_t rowsFor(const Impl& im, const Setup& su, const std::vector<int>& internal, const std::vector<std::vector<size_t>>& lists) {
    size_t total = 0;
    for (size_t gi = 0; gi < im.groups.size(); ++gi) {
        const int nn = im.groups[gi].kind == 0 ? 4 : 8;
        const size_t B = nn == 4 ? kBlockTets : kBlockHexes;
        const std::vector<size_t>& list = lists[gi];
        for (size_t c = 0; c < list.size(); c += B) {
            int lo = std::numeric_limits<int>::max(), hi = -1;
            for (size_t i = c; i < std::min(list.size(), c + B); ++i) {
                const int* nd = su.nodesOf(nn, list[i]);
                for (int k = 0; k < nn; ++k) {
                    lo = std::min(lo, internal[static_cast<size_t>(nd[k])]);
                    hi = std::max(hi, internal[static_cast<size_t>(nd[k])]);
                }
            }
            total += static_cast<size_t>(hi - lo + 1);
        }
    }
    return total;
}

/// The node and element order. The blocks' node buffers cover the range of internal node indices
/// their elements use, so they need elements that share nodes with close indices. The file's order
/// is kept unless its buffers are more than twice those of a reverse Cuthill-McKee numbering of the
/// nodes (over both kinds) with each group's elements sorted by their lowest node in it (a Gmsh
/// file's order can give blocks whose buffers span every node; docs/performance.md, lesson 5).
void chooseNodeOrder(Impl& im, Setup& su) {
    su.internalOf.resize(im.nodeCount);
    std::iota(su.internalOf.begin(), su.internalOf.end(), 0);
    const size_t fileRows = rowsFor(im, su, su.internalOf, su.perGroup);
    // every numbering needs at least one row per node in use: below twice that, keep the file's order
    std::vector<char> inUse(im.nodeCount, 0);
    for (const auto& t4 : su.tets) for (int v : t4) inUse[static_cast<size_t>(v)] = 1;
    for (const auto& h8 : su.hexes) for (int v : h8) inUse[static_cast<size_t>(v)] = 1;
    const size_t used = static_cast<size_t>(std::count(inUse.begin(), inUse.end(), 1));
    if (fileRows <= 2 * used) return;
    const size_t nT = su.tets.size(), nH = su.hexes.size();
    std::vector<int> rcm = elements::reverseCuthillMcKee(im.nodeCount, {{nT ? su.tets.front().data() : nullptr, nT, 4},
                                                              {nH ? su.hexes.front().data() : nullptr, nH, 8}});
    std::vector<int> rcmInternal(im.nodeCount);
    for (size_t q = 0; q < im.nodeCount; ++q) rcmInternal[static_cast<size_t>(rcm[q])] = static_cast<int>(q);
    std::vector<std::vector<size_t>> sorted(su.perGroup.size());
    for (size_t gi = 0; gi < im.groups.size(); ++gi) {
        const int nn = im.groups[gi].kind == 0 ? 4 : 8;
        const std::vector<size_t>& list = su.perGroup[gi];
        std::vector<int> lowest(list.size());
        for (size_t i = 0; i < list.size(); ++i) {
            const int* nd = su.nodesOf(nn, list[i]);
            int m = rcmInternal[static_cast<size_t>(nd[0])];
            for (int k = 1; k < nn; ++k) m = std::min(m, rcmInternal[static_cast<size_t>(nd[k])]);
            lowest[i] = m;
        }
        std::vector<size_t> idx(list.size());
        std::iota(idx.begin(), idx.end(), size_t(0));
        std::stable_sort(idx.begin(), idx.end(), [&](size_t x, size_t y) { return lowest[x] < lowest[y]; });
        for (size_t i : idx) sorted[gi].push_back(list[i]);
    }
    if (fileRows > 2 * rowsFor(im, su, rcmInternal, sorted)) {
        im.nodeOf = std::move(rcm);
        su.internalOf = std::move(rcmInternal);
        su.perGroup = std::move(sorted);
    }
}

/// Tetrahedra: within each block, the 4 elements of a SIMD quad come from the 4 quarters of the
/// block, so that they share no node: neighbouring tetrahedra would otherwise add to the same node
/// row back to back in the scatter and wait on each other's stores (docs/performance.md, lesson 10; no gain for hexahedra).
void interleaveQuads(const Impl& im, Setup& su) {
    for (size_t gi = 0; gi < im.groups.size(); ++gi) {
        if (im.groups[gi].kind != 0) continue;
        std::vector<size_t>& list = su.perGroup[gi];
        std::vector<size_t> out;
        out.reserve(list.size());
        for (size_t c = 0; c < list.size(); c += kBlockTets) {
            const size_t m = std::min(kBlockTets, list.size() - c), q = (m + 3) / 4;
            for (size_t r = 0; r < q; ++r)
                for (size_t l = 0; l < 4; ++l)
                    if (l * q + r < m) out.push_back(list[c + l * q + r]);
        }
        list.swap(out);
    }
}

/// The fibre directions of an element into its pack rows (only with a fibre array; an unused
/// direction as (1 0 0) or (0 1 0)).
template <int NN>
void putFibres(const Impl& im, const Setup& su, const Impl::Group& g, size_t cell, ElementSet<NN>& s, size_t m, size_t k) {
    if (!im.fibresPerElement) return;
    const Vec3 a = su.fibA.used && (g.uses & BaseMaterial::UsesI4) ? su.fibA.dir[cell] : Vec3(1, 0, 0);
    const Vec3 b = su.fibB.used && (g.uses & BaseMaterial::UsesI6) ? su.fibB.dir[cell] : Vec3(0, 1, 0);
    for (int c = 0; c < 3; ++c) {
        s.put(m, k, ElementSet<NN>::kFibreRow + c, a[c]);
        s.put(m, k, ElementSet<NN>::kFibreRow + 3 + c, b[c]);
    }
}

/// The tetrahedra of group gi, appended in its internal order; their pack rows from batch slot slot0
/// (a group's elements fill its batches in order: its blocks hold whole batches but the last).
void fillTets(const TLEDForceField& ff, Impl& im, const Setup& su, size_t gi, size_t slot0) {
    ElementSet<4>& s = im.tet;
    const Impl::Group& g = im.groups[gi];
    const std::vector<size_t>& list = su.perGroup[gi];
    for (size_t j = 0; j < list.size(); ++j) {
        const size_t e = list[j], m = slot0 + j / kBatch, k = j % kBatch;
        const auto& t = su.tets[e];
        const Vec3 &p0 = su.X[t[0]], &p1 = su.X[t[1]], &p2 = su.X[t[2]], &p3 = su.X[t[3]];
        Mat3 D;
        D.col(0) = p1 - p0;
        D.col(1) = p2 - p0;
        D.col(2) = p3 - p0;
        const double det = D.determinant();
        const double longest = elements::tetLongestEdge(p0, p1, p2, p3);
        if (!(std::abs(det) / 6 > 1e-12 * longest * longest * longest))
            ff.fail("tetrahedron " + std::to_string(e) + " (nodes " + std::to_string(t[0]) + " " + std::to_string(t[1]) + " " +
                    std::to_string(t[2]) + " " + std::to_string(t[3]) + ") is degenerate (volume " + formatNumber(det / 6, 6) + " m^3)");
        const Mat3 Di = D.inverse();
        // dN_1..dN_3 = the rows of D^-1 (dN_0 = -(dN_1 + dN_2 + dN_3) is not stored: the kernel forms it)
        for (int a = 0; a < 3; ++a)
            for (int i = 0; i < 3; ++i) s.put(m, k, 3 * a + i, Di(a, i));
        for (int a = 0; a < 4; ++a) s.nodes.push_back(su.internalOf[static_cast<size_t>(t[a])]);
        const double V = std::abs(det) / 6;
        if (s.volRow >= 0) s.put(m, k, s.volRow, V);
        s.vol.push_back(V);
        s.orig.push_back(static_cast<int>(e));
        s.length.push_back(elements::tetAltitude(p0, p1, p2, p3, V));
        putFibres(im, su, g, e, s, m, k);
    }
}

/// The hexahedra of group gi, as fillTets.
void fillHexes(const TLEDForceField& ff, Impl& im, const Setup& su, size_t gi, size_t slot0, double hourglass) {
    ElementSet<8>& s = im.hex;
    const Impl::Group& g = im.groups[gi];
    const std::vector<size_t>& list = su.perGroup[gi];
    for (size_t j = 0; j < list.size(); ++j) {
        const size_t e = list[j], m = slot0 + j / kBatch, k = j % kBatch;
        const auto& h = su.hexes[e];
        Vec3 P[8];
        for (int a = 0; a < 8; ++a) P[a] = su.X[h[a]];
        double V, dN[24], sumB2;
        elements::hexUniformStrain(P, V, dN, sumB2);
        double longest = 0;
        for (int a = 0; a < 8; ++a)
            for (int b2 = a + 1; b2 < 8; ++b2) longest = std::max(longest, (P[a] - P[b2]).norm());
        if (!(std::abs(V) > 1e-12 * longest * longest * longest)) {
            std::string nodes;
            for (int v : h) nodes += " " + std::to_string(v);
            ff.fail("hexahedron " + std::to_string(e) + " (nodes" + nodes + ") is degenerate (volume " + formatNumber(V, 6) + " m^3)");
        }
        // hourglass control: gamma_q = h_q - (c_q . dN/dX), c_q = sum_a h_qa X_a; the loop needs c_q only
        double hc[12];
        elements::hexHourglassVectors(P, hc);
        const double absV = std::abs(V);
        for (int a = 0; a < 8; ++a) s.nodes.push_back(su.internalOf[static_cast<size_t>(h[a])]);
        for (int r = 0; r < 24; ++r) s.put(m, k, r, dN[r]);
        for (int r = 0; r < 12; ++r) s.put(m, k, ElementSet<8>::kHgRow + r, hc[r]);
        if (s.volRow >= 0) s.put(m, k, s.volRow, absV);
        s.vol.push_back(absV);
        s.orig.push_back(static_cast<int>(e));
        s.hgK.push_back(elements::hexHourglassStiffness(hourglass, *g.material, absV, sumB2));
        s.length.push_back(elements::hexCharacteristicLength(P, absV));
        putFibres(im, su, g, su.tets.size() + e, s, m, k);
    }
}

/// Fixed blocks over the elements [begin, end) of one group (internal order of its kind).
void addBlocks(Impl& im, int kind, size_t gi, size_t begin, size_t end) {
    const size_t blockSize = kind == 0 ? kBlockTets : kBlockHexes;
    for (size_t b0 = begin; b0 < end; b0 += blockSize) {
        Block b;
        b.kind = kind;
        b.group = static_cast<int>(gi);
        b.begin = b0;
        b.end = std::min(end, b0 + blockSize);
        b.batchBase = im.batches;
        im.batches += (b.end - b.begin + kBatch - 1) / kBatch;
        im.blocks.push_back(b);
    }
}

/// The node entries of block b's elements (NN per element, in the connectivity of its kind).
elements::CompactBlockBuffers::Nodes blockNodes(Impl& im, const Block& b) {
    const size_t nn = b.kind == 0 ? 4 : 8;
    std::vector<int>& nodes = b.kind == 0 ? im.tet.nodes : im.hex.nodes;
    return {nodes.data() + b.begin * nn, (b.end - b.begin) * nn};
}

/// The range of internal nodes each block's elements use (the range layout of the buffers).
void addNodeRanges(Impl& im) {
    for (const Block& b : im.blocks) {
        const auto nd = blockNodes(im, b);
        const auto [lo, hi] = std::minmax_element(nd.nodes, nd.nodes + nd.count);
        im.buffers.addBlock(*lo, *hi);
    }
}

/// Rows of the compact layout: the distinct nodes of each block, all blocks together.
size_t compactRows(Impl& im) {
    std::vector<size_t> seenIn(im.nodeCount, ~size_t(0));  // the last block that used the node
    size_t rows = 0;
    for (size_t bi = 0; bi < im.blocks.size(); ++bi) {
        const auto nd = blockNodes(im, im.blocks[bi]);
        for (size_t i = 0; i < nd.count; ++i) {
            size_t& s = seenIn[static_cast<size_t>(nd.nodes[i])];
            if (s != bi) ++rows, s = bi;
        }
    }
    return rows;
}

/// The blocks' force buffers (TLEDForceField::m_nodeBuffers): the node ranges addBlocks recorded,
/// or compact rows where the ranges would take more than 1.5 times as many rows. A compact row
/// costs about 1.5 times a range row per step (the copy-in of u, the per-node row lists of the sum;
/// docs/performance.md, lesson 5).
void finishBuffers(const TLEDForceField& ff, Impl& im, const std::string& choice) {
    size_t rangeRows = 0;
    for (size_t b = 0; b < im.buffers.blockCount(); ++b) rangeRows += im.buffers.rowCount(b);
    im.compact = choice == "compact" || (choice == "auto" && 2 * rangeRows > 3 * compactRows(im));
    if (!im.compact) {
        im.buffers.finish(im.nodeCount, im.nodeOf, elements::BlockBuffers::Fill::Commit);
        if (im.buffers.rows() > 16 * im.nodeCount && im.blocks.size() > 16)
            ff.warn("the element blocks span " + std::to_string(im.buffers.rows() / im.nodeCount) +
                    " times the node count in their force buffers, in the node order used (the file's, or a reverse "
                    "Cuthill-McKee one when that is more than twice as compact): speed and memory suffer; "
                    "nodeBuffers=\"compact\" does not grow with the ranges");
        im.scratch.reserve(0, im.buffers.maxRows());
        return;
    }
    im.buffers = elements::BlockBuffers{};
    for (const Block& b : im.blocks) im.rows.addBlock({blockNodes(im, b)});  // rewritten to the block's rows
    std::vector<int> nodeOf = im.nodeOf;
    if (nodeOf.empty()) {
        nodeOf.resize(im.nodeCount);
        std::iota(nodeOf.begin(), nodeOf.end(), 0);
    }
    im.rows.finish(std::move(nodeOf), elements::CompactBlockBuffers::Source::Internal);
    im.scratch.reserve(im.rows.maxRows(), im.rows.maxRows());
}

} // namespace

void TLEDForceField::precompute(const MeshData* mesh, const Positions& X) {
    Impl& im = *m_impl;
    const size_t nT = m_tets.size(), nH = m_hexes.size();
    Setup su{m_tets, m_hexes, X, {}, {}, {}, {}};
    // materials per element, then groups (kind, material) in order of first appearance
    const auto assigned = elements::assignMaterials(*this, m_groupMaterials, elements::defaultMaterial(*this, m_material, m_groupMaterials),
                                                    mesh, nT, nH);
    auto groupOf = [&](int kind, BaseMaterial* m) {
        for (size_t g = 0; g < im.groups.size(); ++g)
            if (im.groups[g].kind == kind && im.groups[g].material == m) return g;
        Impl::Group g;
        g.kind = kind;
        g.material = m;
        g.uses = m->uses();
        chooseKernel(g, im.mixed);
        im.groups.push_back(g);
        su.perGroup.emplace_back();
        return im.groups.size() - 1;
    };
    for (size_t e = 0; e < nT; ++e) su.perGroup[groupOf(0, assigned.tetrahedra[e])].push_back(e);
    for (size_t e = 0; e < nH; ++e) su.perGroup[groupOf(1, assigned.hexahedra[e])].push_back(e);
    chooseNodeOrder(im, su);
    interleaveQuads(im, su);

    // fibre directions: per element from the arrays, else one per group (its material's)
    std::vector<const BaseMaterial*> cellMaterial(assigned.tetrahedra.begin(), assigned.tetrahedra.end());
    cellMaterial.insert(cellMaterial.end(), assigned.hexahedra.begin(), assigned.hexahedra.end());
    su.fibA = elements::resolveFibres(*this, 0, m_fibreArray, mesh, cellMaterial, nT);
    su.fibB = elements::resolveFibres(*this, 1, m_fibreArray2, mesh, cellMaterial, nT);
    im.fibresPerElement = su.fibA.perElement || su.fibB.perElement;
    if (!im.fibresPerElement)
        for (auto& g : im.groups) {
            const auto unit = [&](int which, double out[3]) {
                const Vec3 d = *g.material->fibreDirection(which);
                const double len = d.norm();
                for (int c = 0; c < 3; ++c) out[c] = d[c] / len;
            };
            if (g.uses & BaseMaterial::UsesI4) unit(0, g.a0);
            if (g.uses & BaseMaterial::UsesI6) unit(1, g.b0);
        }

    // fixed blocks within each group (tetrahedra by group, then hexahedra by group), so the batch
    // slots of every element are known before its data is computed
    std::vector<size_t> slot0(im.groups.size());
    size_t count[2] = {0, 0};
    for (int kind = 0; kind < 2; ++kind) {
        (kind == 0 ? im.tet.batchOffset : im.hex.batchOffset) = im.batches;
        for (size_t gi = 0; gi < im.groups.size(); ++gi) {
            if (im.groups[gi].kind != kind) continue;
            slot0[gi] = im.batches - (kind == 0 ? im.tet.batchOffset : im.hex.batchOffset);
            addBlocks(im, kind, gi, count[kind], count[kind] + su.perGroup[gi].size());
            count[kind] += su.perGroup[gi].size();
        }
    }
    im.tet.allocate(im.hex.batchOffset, im.fibresPerElement, im.mixed);
    im.hex.allocate(im.batches - im.hex.batchOffset, im.fibresPerElement, im.mixed);
    // the element arrays at their exact sizes (push_back alone would leave up to twice their size allocated)
    const auto reserveSet = [&](auto& s, size_t n, size_t nn) {
        s.nodes.reserve(nn * n);
        s.vol.reserve(n);
        s.orig.reserve(n);
        s.length.reserve(n);
    };
    reserveSet(im.tet, nT, 4);
    reserveSet(im.hex, nH, 8);
    im.hex.hgK.reserve(nH);
    for (int kind = 0; kind < 2; ++kind)
        for (size_t gi = 0; gi < im.groups.size(); ++gi) {
            if (im.groups[gi].kind != kind) continue;
            if (kind == 0) fillTets(*this, im, su, gi, slot0[gi]);
            else fillHexes(*this, im, su, gi, slot0[gi], m_hourglass.get());
        }
    addNodeRanges(im);
    finishBuffers(*this, im, m_nodeBuffers.get());
}

} // namespace fascia::tled
