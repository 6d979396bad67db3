// HEMLForceField's precomputation (HEML Algorithm 1, Appendices A-C): node order, materials, the
// element order and the blocks, the per-slot element data (rounded to float for precision="mixed"),
// the blocks' node rows and the viscous states.
#include "HEMLData.h"

#include "fascia/elements/EdgeForm.h"
#include "fascia/elements/Geometry.h"
#include "fascia/elements/NodeOrder.h"
#include "fascia/materials/RelaxationSplit.h"
#include "fascia/viscoelastic/ViscoelasticProny.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <string>

namespace fascia::heml {

using materials::BaseMaterial;
using elements::edgeA;
using elements::edgeB;

namespace {

/// The node rows of the blocks (compact rows: each block's distinct nodes, in internal order; the
/// elements' nodes rewritten to them) and the per-node lists of rows for the ordered sum.
void buildNodeRows(Impl& d) {
    d.rows = elements::CompactBlockBuffers{};
    for (const Block& b : d.blocks) {
        const size_t count = b.end - b.begin;
        d.rows.addBlock({{d.node[0].data() + b.begin, count}, {d.node[1].data() + b.begin, count},
                         {d.node[2].data() + b.begin, count}, {d.node[3].data() + b.begin, count}});
    }
    d.rows.finish(d.nodeOf);
    d.scratch.reserve(d.rows.maxRows(), d.rows.maxRows());
    d.blockEnergy.assign(d.blocks.size(), 0.0);
}

/// The viscoelastic state of eq. (18)-(20), one value per slot, term and link coefficient.
void setUpVisco(Impl& d, const viscoelastic::ViscoelasticProny* visco, size_t S) {
    // viscoelastic state
    d.nTerms = 0;
    d.Yprev.clear();
    d.Ycur.clear();
    d.clock = viscoelastic::HistoryClock{};
    d.restShift.assign(d.materials.size(), 0.0);
    if (visco) {
        d.nTerms = int(visco->termCount());
        d.relaxIso = visco->relaxesIsochoric();
        d.relaxVol = visco->relaxesVolumetric();
        // one part relaxes: move each material's rest-stress term s ln J out of the isochoric part
        if (d.relaxIso != d.relaxVol)
            for (size_t m = 0; m < d.materials.size(); ++m) d.restShift[m] = materials::relaxationSplit(*d.materials[m], d.J0).shift;
        d.Yprev.assign(size_t(d.nTerms * 6), DVec(S, 0.0));
        d.Ycur = d.Yprev;
    }
}

/// precision="mixed": the element arrays rounded to float, the double ones freed (docs/design.md,
/// section 3, "two precisions of the same loop": the element data the loop streams is halved,
/// 80 -> 48 bytes per element with the node indices).
void roundToFloat(Impl& d) {
    d.elf.zip(d.el, [](FVec& f, const DVec& v) { f.assign(v.begin(), v.end()); });
    d.el = ElementArrays<double>{};
}

/// The distinct materials of the elements (d.materials, in first use order) and each element's
/// index among them (-1 in mass-spring mode).
std::vector<int> distinctMaterials(Impl& d, const std::vector<BaseMaterial*>& elementMaterial) {
    const size_t ne = d.nElements;
    std::vector<int> matIndex(ne, -1);
    d.materials.clear();
    if (!d.massSpring) {
        std::map<const BaseMaterial*, int> idx;
        for (size_t e = 0; e < ne; ++e) {
            auto it = idx.find(elementMaterial[e]);
            if (it == idx.end()) {
                it = idx.emplace(elementMaterial[e], int(d.materials.size())).first;
                d.materials.push_back(elementMaterial[e]);
            }
            matIndex[e] = it->second;
        }
    }
    return matIndex;
}

/// The element order: by material, then by lowest internal node (locality of the block buffers).
std::vector<int> elementOrder(const Impl& d, const Tetrahedra& tets, const std::vector<int>& matIndex) {
    const size_t ne = tets.size();
    std::vector<int> order(ne);
    std::iota(order.begin(), order.end(), 0);
    std::vector<int> minNode(ne);
    for (size_t e = 0; e < ne; ++e) {
        int m = d.internalOf[tets[e][0]];
        for (int a = 1; a < 4; ++a) m = std::min(m, d.internalOf[tets[e][a]]);
        minNode[e] = m;
    }
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
        if (matIndex[a] != matIndex[b]) return matIndex[a] < matIndex[b];
        return minNode[a] < minNode[b];
    });
    return order;
}

/// The blocks: per material segment of the order, near kBlockSize elements each, padded to kLanes
/// (d.blocks, d.elementOf, d.nSlots).
void buildBlocks(Impl& d, const std::vector<int>& order, const std::vector<int>& matIndex) {
    const size_t ne = order.size();
    d.blocks.clear();
    d.elementOf.clear();
    for (size_t s = 0; s < ne;) {
        size_t t = s;
        while (t < ne && matIndex[order[t]] == matIndex[order[s]]) ++t;
        const size_t count = t - s, nb = (count + kBlockSize - 1) / kBlockSize;
        for (size_t k = 0; k < nb; ++k) {
            const size_t a = s + count * k / nb, b = s + count * (k + 1) / nb;
            Block blk;
            blk.begin = d.elementOf.size();
            for (size_t i = a; i < b; ++i) d.elementOf.push_back(order[i]);
            while ((d.elementOf.size() - blk.begin) % kLanes) d.elementOf.push_back(-1 - order[b - 1]);  // padding
            blk.end = d.elementOf.size();
            blk.material = matIndex[order[s]];
            d.blocks.push_back(blk);
        }
        s = t;
    }
    d.nSlots = d.elementOf.size();
}

/// The per-slot arrays, zeroed: the node indices, and the element data the mode needs (G for a
/// material, spring stiffness and rest length in mass-spring mode, the fibre rows when used).
void allocateSlots(Impl& d, bool anyI4, bool anyI6) {
    const size_t S = d.nSlots;
    for (auto& v : d.node) v.assign(S, 0);
    ElementArrays<double>& el = d.el;
    el.vol.assign(S, 0.0);
    el.invDetV.assign(S, 0.0);
    for (int k = 0; k < 6; ++k) {
        el.G[k].assign(d.massSpring ? 0 : S, 0.0);
        el.kk[k].assign(d.massSpring ? S : 0, 0.0);
        el.len0[k].assign(d.massSpring ? S : 0, 0.0);
    }
    for (int k = 0; k < 3; ++k) {
        el.w4[k].assign(anyI4 ? S : 0, 0.0);
        el.w6[k].assign(anyI6 ? S : 0, 0.0);
    }
}


/// What the per-slot steps read besides the force field's data.
struct SlotInput {
    const Tetrahedra& tets;
    const Positions& rest;
    const std::vector<Vec3>&dirA, &dirB;  ///< unit fibre directions per element (empty: unused)
    double stiffness;                      ///< mass-spring mode: k of eq. (38)
};

/// Algorithm 1's rest edges of tetrahedron e: V, V^-1, det V and G = V^-1 V^-T; a degenerate
/// element (zero volume at rest) fails.
elements::EdgeRest restEdges(const HEMLForceField& ff, const SlotInput& in, int e) {
    const auto& t = in.tets[e];
    const Positions& rest = in.rest;
    const elements::EdgeRest er = elements::edgeRest(rest[t[0]], rest[t[1]], rest[t[2]], rest[t[3]]);
    const double det = er.det;
    double maxEdge = 0;
    for (int k = 0; k < 6; ++k) maxEdge = std::max(maxEdge, (rest[t[edgeB(k)]] - rest[t[edgeA(k)]]).norm());
    if (!(std::abs(det) > 1e-12 * maxEdge * maxEdge * maxEdge))
        ff.fail("tetrahedron " + std::to_string(e) + " (nodes " + std::to_string(t[0]) + " " + std::to_string(t[1]) + " " +
                std::to_string(t[2]) + " " + std::to_string(t[3]) + ") is degenerate: zero volume at rest");
    return er;
}

/// Mass-spring mode: the rest length and the stiffness share of each edge of element e in its slot
/// (shared edges split k between their tetrahedra; 0 in padding slots).
void springSlot(ElementArrays<double>& el, const SlotInput& in, const elements::EdgeShares& shares, int e, size_t slot, bool pad) {
    const auto& t = in.tets[e];
    for (int k = 0; k < 6; ++k) {
        const int a = t[edgeA(k)], b = t[edgeB(k)];
        el.len0[k][slot] = (in.rest[b] - in.rest[a]).norm();
        el.kk[k][slot] = pad ? 0.0 : in.stiffness / shares.count(a, b);
    }
}

/// Algorithm 1 (Appendix A, C): C_k = V^-T D_k V^-1 enter through G = V^-1 V^-T only
/// (vtr_k = tr(D_k G), Mtr_ij = tr(D_i G D_j G), a0.C_k a0 = (V^-1 a0).D_k (V^-1 a0)).
void materialSlot(ElementArrays<double>& el, const SlotInput& in, const elements::EdgeRest& er, int e, size_t slot) {
    const Mat3& Vi = er.Vi;
    for (int q = 0; q < 6; ++q) el.G[q][slot] = er.G[q];
    if (!in.dirA.empty()) {
        const Vec3 w = in.dirA[e].isZero() ? Vec3::Zero() : Vec3(Vi * in.dirA[e]);
        for (int q = 0; q < 3; ++q) el.w4[q][slot] = w[q];
    }
    if (!in.dirB.empty()) {
        const Vec3 w = in.dirB[e].isZero() ? Vec3::Zero() : Vec3(Vi * in.dirB[e]);
        for (int q = 0; q < 3; ++q) el.w6[q][slot] = w[q];
    }
}

/// precompute's per-slot data (HEML Algorithm 1) from the rest positions: the node indices, Vol and
/// 1 / det V, then the springs' or the material's data (padding slots: their block's last element
/// again, with zero volume and stiffness).
void fillSlots(const HEMLForceField& ff, Impl& d, const SlotInput& in) {
    ElementArrays<double>& el = d.el;
    // edges shared between tetrahedra (mass-spring mode splits k between them)
    const elements::EdgeShares shares(d.massSpring ? in.tets : Tetrahedra{});
    for (size_t slot = 0; slot < d.nSlots; ++slot) {
        const bool pad = d.elementOf[slot] < 0;
        const int e = pad ? -1 - d.elementOf[slot] : d.elementOf[slot];
        if (!pad) d.slotOf[e] = int(slot);
        for (int a = 0; a < 4; ++a) d.node[a][slot] = d.internalOf[in.tets[e][a]];
        const elements::EdgeRest er = restEdges(ff, in, e);
        el.vol[slot] = pad ? 0.0 : std::abs(er.det) / 6.0;
        el.invDetV[slot] = 1.0 / er.det;
        if (d.massSpring) springSlot(el, in, shares, e, slot, pad);
        else materialSlot(el, in, er, e, slot);
    }
}

} // namespace

void HEMLForceField::precompute(const Positions& rest, const std::vector<BaseMaterial*>& elementMaterial) {
    Impl& d = *m_impl;
    const size_t n = rest.size(), ne = m_tets.size();
    d.nNodes = n;
    d.nElements = ne;

    // node order
    // reverse Cuthill-McKee (docs/performance.md, lesson 5): internal -> input node
    d.nodeOf = elements::reverseCuthillMcKee(n, {{m_tets.empty() ? nullptr : m_tets.front().data(), m_tets.size(), 4}});
    d.internalOf.assign(n, 0);
    for (size_t p = 0; p < n; ++p) d.internalOf[d.nodeOf[p]] = int(p);

    {
        const std::vector<int> matIndex = distinctMaterials(d, elementMaterial);
        d.loops.clear();
        for (auto* m : d.materials) d.loops.push_back(loopsFor(m, d.mixed));
        if (d.massSpring) d.loops.push_back(loopsFor(nullptr, d.mixed));
        buildBlocks(d, elementOrder(d, m_tets, matIndex), matIndex);
    }  // (the ordering scratch freed before the per-slot arrays come: 12 bytes an element at the peak)
    d.slotOf.assign(ne, -1);

    // per-slot data (computed in double; precision="mixed" rounds it to float below)
    allocateSlots(d, !m_dirA.empty(), !m_dirB.empty());
    fillSlots(*this, d, {m_tets, rest, m_dirA, m_dirB, m_stiffness.isSet() ? m_stiffness.get() : 0.0});

    d.totalVolume = 0;
    for (size_t s = 0; s < d.nSlots; ++s) d.totalVolume += d.el.vol[s];
    if (d.mixed) roundToFloat(d);

    buildNodeRows(d);
    setUpVisco(d, m_visco, d.nSlots);
}

} // namespace fascia::heml
