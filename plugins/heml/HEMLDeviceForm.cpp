// HEMLForceField's device form (fascia/elements/DeviceForm.h): what its precompute holds per slot
// (HEMLElements.cpp precompute, HEMLData.h ElementArrays) back in input order, and the rest
// edges V_a = X_a - X_0, which its loop does not keep (it forms the current edges from positions),
// as the differences of its rest positions (elements::edgeRest forms them so).
#include "fascia/heml/HEMLForceField.h"
#include "HEMLData.h"

#include "fascia/viscoelastic/ViscoelasticProny.h"

namespace fascia::heml {

void HEMLForceField::deviceForm(elements::DeviceForm& out) const {
    if (!m_impl) fail("used before init()");
    const Impl& d = *m_impl;
    if (d.mixed)
        fail(m_precision, "precision=\"mixed\" keeps the element data in float only, and a step backend (CudaStep) takes them in double",
             {"remove precision=\"mixed\": CudaStep's own precision (\"float\" or \"double\") is the device step's"});
    out = elements::DeviceForm{};
    out.kind = d.massSpring ? elements::DeviceForm::Kind::Springs : elements::DeviceForm::Kind::Edges;
    out.J0 = d.J0;
    out.tetrahedra = &m_tets;
    const size_t n = m_tets.size();
    if (!d.massSpring) {
        out.cellMaterial.resize(n);
        for (size_t e = 0; e < n; ++e) out.cellMaterial[e] = materialOf(e);
        out.material = elements::defaultMaterial(*this, m_material, m_groupMaterials);
        out.groupMaterials = m_groupMaterials.isSet() ? &m_groupMaterials : nullptr;
    }
    if (m_visco) out.series.push_back(m_visco);

    const ElementArrays<double>& el = d.el;
    out.tetVolume.resize(n);
    out.edgeV.resize(9 * n);
    out.edgeInvDetV.resize(n);
    out.edgeG.resize(d.massSpring ? 0 : 6 * n);
    for (int w = 0; w < 2; ++w) out.edgeW[w].resize((w == 0 ? el.w4 : el.w6)[0].empty() ? 0 : 3 * n);
    out.springK.resize(d.massSpring ? 6 * n : 0);
    out.springLength.resize(d.massSpring ? 6 * n : 0);
    for (size_t e = 0; e < n; ++e) {
        const size_t slot = static_cast<size_t>(d.slotOf[e]);
        const auto& t = m_tets[e];
        out.tetVolume[e] = el.vol[slot];
        out.edgeInvDetV[e] = el.invDetV[slot];
        for (size_t a = 0; a < 3; ++a)
            for (int i = 0; i < 3; ++i)
                out.edgeV[9 * e + 3 * a + static_cast<size_t>(i)] = m_rest[static_cast<size_t>(t[a + 1])][i] - m_rest[static_cast<size_t>(t[0])][i];
        for (size_t q = 0; q < out.edgeG.size() / n; ++q) out.edgeG[6 * e + q] = el.G[q][slot];
        for (int w = 0; w < 2; ++w)
            for (size_t i = 0; i < out.edgeW[w].size() / n; ++i) out.edgeW[w][3 * e + i] = (w == 0 ? el.w4 : el.w6)[i][slot];
        for (size_t q = 0; q < out.springK.size() / n; ++q) {
            out.springK[6 * e + q] = el.kk[q][slot];
            out.springLength[6 * e + q] = el.len0[q][slot];
        }
    }
}

} // namespace fascia::heml
