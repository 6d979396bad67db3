// TLEDForceField's device form (fascia/elements/DeviceForm.h): what its precompute holds
// (TLEDElements.cpp), unpacked from the blocks' internal order and packed batch rows back to input
// order. Nothing is computed from the rest positions here.
#include "TLEDData.h"

#include "fascia/viscoelastic/ViscoelasticProny.h"

#include <algorithm>

namespace fascia::tled {

using materials::BaseMaterial;
using Impl = TLEDForceField::Impl;

namespace {

/// Calls put(i, e, rows, k) for every element of kind NN: its internal index i, its index e in the
/// input list of its kind, the packed rows of its batch (row r of the element at rows[r kBatch + k]).
template <int NN, class Put>
void forEachElement(const Impl& im, Put&& put) {
    const ElementSet<NN>& s = im.set<NN>();
    for (const Block& b : im.blocks) {
        if (b.kind != (NN == 4 ? 0 : 1)) continue;
        for (size_t i = b.begin; i < b.end; ++i) {
            const size_t k = (i - b.begin) % kBatch;
            put(i, static_cast<size_t>(s.orig[i]), s.template batchData<double>(b, i - k), k);
        }
    }
}

/// Rows [r0, r0 + count) of an element into out at count e.
void unpackRows(const double* rows, size_t k, int r0, int count, size_t e, std::vector<double>& out) {
    for (int r = 0; r < count; ++r) out[static_cast<size_t>(count) * e + static_cast<size_t>(r)] = rows[static_cast<size_t>(r0 + r) * kBatch + k];
}

} // namespace

void TLEDForceField::deviceForm(elements::DeviceForm& out) const {
    const Impl& im = *m_impl;
    if (im.mixed)
        fail(m_precision, "precision=\"mixed\" keeps the element data in float only, and a step backend (CudaStep) takes them in double",
             {"remove precision=\"mixed\": CudaStep's own precision (\"float\" or \"double\") is the device step's"});
    out = elements::DeviceForm{};
    out.kind = elements::DeviceForm::Kind::TLED;
    out.J0 = im.J0;
    out.hourglass = m_hourglass.get();
    out.tetrahedra = &m_tets;
    out.hexahedra = &m_hexes;
    const size_t nT = m_tets.size(), nH = m_hexes.size();

    // the material of each cell: its block's group's
    out.cellMaterial.assign(nT + nH, nullptr);
    for (const Block& b : im.blocks) {
        const std::vector<int>& orig = b.kind == 0 ? im.tet.orig : im.hex.orig;
        for (size_t i = b.begin; i < b.end; ++i)
            out.cellMaterial[(b.kind == 0 ? 0 : nT) + static_cast<size_t>(orig[i])] = im.groups[static_cast<size_t>(b.group)].material;
    }
    out.material = elements::defaultMaterial(*this, m_material, m_groupMaterials);
    out.groupMaterials = m_groupMaterials.isSet() ? &m_groupMaterials : nullptr;
    for (const ViscoSet& vs : im.visco) out.series.push_back(vs.prony);

    // rest data (and the fibre rows, with fibre arrays)
    out.tetDN.resize(9 * nT);
    out.tetVolume.resize(nT);
    forEachElement<4>(im, [&](size_t i, size_t e, const double* rows, size_t k) {
        unpackRows(rows, k, 0, 9, e, out.tetDN);
        out.tetVolume[e] = im.tet.vol[i];
    });
    out.hexDN.resize(24 * nH);
    out.hexC.resize(12 * nH);
    out.hexVolume.resize(nH);
    out.hexK.resize(nH);
    forEachElement<8>(im, [&](size_t i, size_t e, const double* rows, size_t k) {
        unpackRows(rows, k, 0, 24, e, out.hexDN);
        unpackRows(rows, k, ElementSet<8>::kHgRow, 12, e, out.hexC);
        out.hexVolume[e] = im.hex.vol[i];
        out.hexK[e] = im.hex.hgK[i];
    });
    out.fibresPerElement = im.fibresPerElement;
    if (!im.fibresPerElement) return;
    for (int w = 0; w < 2; ++w) {
        const unsigned bit = w == 0 ? BaseMaterial::UsesI4 : BaseMaterial::UsesI6;
        if (std::none_of(im.groups.begin(), im.groups.end(), [&](const Impl::Group& g) { return (g.uses & bit) != 0; })) continue;
        std::vector<double>& dir = out.fibre[w];
        dir.resize(3 * (nT + nH));
        std::vector<double> hexDir(3 * nH);
        forEachElement<4>(im, [&](size_t, size_t e, const double* rows, size_t k) {
            unpackRows(rows, k, ElementSet<4>::kFibreRow + 3 * w, 3, e, dir);
        });
        forEachElement<8>(im, [&](size_t, size_t e, const double* rows, size_t k) {
            unpackRows(rows, k, ElementSet<8>::kFibreRow + 3 * w, 3, e, hexDir);
        });
        std::copy(hexDir.begin(), hexDir.end(), dir.begin() + static_cast<std::ptrdiff_t>(3 * nT));
    }
}

} // namespace fascia::tled
