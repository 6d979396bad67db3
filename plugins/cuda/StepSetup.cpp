#include "StepSetup.h"

#include "DeviceLaws.h"
#include "fascia/base/Error.h"
#include "fascia/elements/DeviceForm.h"
#include "fascia/materials/RelaxationSplit.h"
#include "fascia/sim/StepTerms.h"
#include "fascia/viscoelastic/HistoryClock.h"
#include "fascia/viscoelastic/ViscoelasticProny.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace fascia::cuda {

namespace {

/// The message of a component the device step does not run: what, and why nothing falls back.
std::string notOnDevice(const std::string& what) {
    return what + " is not on the GPU step yet (CudaStep in the root node runs the whole step on the device, with no "
                  "fallback to the host)";
}

[[noreturn]] void unsupported(const core::Component& c, const std::string& what) {
    c.fail(notOnDevice(what), {"remove CudaStep to run this scene on the CPU"});
}

/// The same located at c's parameter p.
[[noreturn]] void unsupported(const core::Component& c, const core::BaseParam& p, const std::string& what) {
    c.fail(p, notOnDevice(what), {"remove CudaStep to run this scene on the CPU"});
}

/// The integrator's scheme and its parameters (core::ExplicitScheme, fascia/sim/StepTerms.h):
/// SemiImplicitEuler or CentralDifference.
void readIntegrator(const core::BaseIntegrator& integ, StepSetup& s) {
    const auto* scheme = dynamic_cast<const core::ExplicitScheme*>(&integ);
    if (!scheme)
        unsupported(integ, integ.className() + " (the device step integrates with SemiImplicitEuler or CentralDifference: an integrator "
                                               "that gives its scheme, core::ExplicitScheme)");
    const core::ExplicitScheme::Terms t = scheme->schemeTerms();
    s.scheme = t.update == core::ExplicitScheme::Update::CentralDifference ? StepSetup::Scheme::CentralDifference
                                                                             : StepSetup::Scheme::SemiImplicitEuler;
    s.damping = t.damping;
    s.halfStepStart = t.halfStepStart;
}

/// The Prony series the element force field relaxes with (elements::DeviceForm::series), as
/// TLEDForceField takes them (TLEDForceField.cpp init): in its order, each part relaxed by one series
/// at most, the parts a series relaxes stress-free at rest for every material group (materials/
/// RelaxationSplit.h, a located error at the series' apply otherwise: read from the series now, so
/// that a series changed after init is checked too), s ln J of each group's material moved between
/// the parts when a series relaxes one alone.
void readSeries(const elements::DeviceForm& form, StepSetup& s) {
    for (const core::Component* c : form.series) {
        const auto* p = dynamic_cast<const viscoelastic::ViscoelasticProny*>(c);
        if (!p) unsupported(*c, c->className() + " (a relaxation that is not the ViscoelasticProny the device step knows)");
        StepSetup::Series x{p, p->relaxesIsochoric(), p->relaxesVolumetric(), static_cast<int>(p->termCount())};
        for (const StepSetup::Series& y : s.series)
            if ((x.iso && y.iso) || (x.vol && y.vol)) unsupported(*c, "a second ViscoelasticProny relaxing the same part of the stress");
        if (x.terms > kMaxTerms)
            unsupported(*c, "a Prony series of " + std::to_string(x.terms) + " terms (the device step runs at most " +
                                std::to_string(kMaxTerms) + " per series)");
        if (s.series.size() == size_t(kMaxSeries))
            unsupported(*c, "a third ViscoelasticProny (the device step runs at most " + std::to_string(kMaxSeries) + " series)");
        s.series.push_back(x);
    }
    if (s.series.empty()) return;
    bool onePartAlone = false;
    for (const StepSetup::Series& x : s.series) onePartAlone |= x.iso != x.vol;
    for (StepSetup::Group& g : s.groups) {
        const materials::RelaxationSplit split = materials::relaxationSplit(*g.material, s.J0);
        for (const StepSetup::Series& x : s.series) {
            const std::string err = materials::relaxationRestError(split, x.iso, x.vol, g.material->className() + " '" + g.material->name() + "'");
            if (!err.empty()) x.prony->failApply(err);
        }
        g.restShift = onePartAlone ? split.shift : 0.0;
    }
}

/// The groups of elements by material, in order of first appearance (tetrahedra, then hexahedra),
/// from the material of each cell as the force field assigned them (elements::DeviceForm::
/// cellMaterial); a material that is not a law of DeviceLaws.h is a located error naming it, at the
/// force field's groupMaterials when that names it, else at the material.
void readGroups(const core::BaseForceField& ff, const elements::DeviceForm& form, size_t nT, StepSetup& s) {
    const std::vector<const materials::BaseMaterial*>& cell = form.cellMaterial;
    const auto groupOf = [&](const materials::BaseMaterial* m) {
        for (size_t g = 0; g < s.groups.size(); ++g)
            if (s.groups[g].material == m) return g;
        if (!m) ff.fail("its device form has a cell without a material");
        const bool onDevice = selectDeviceLaw(m, [](auto tag, const materials::BaseMaterial*) {
            return !std::is_same_v<typename decltype(tag)::type, elements::GenericLaw>;
        });
        const std::string laws = " (the device step runs " + deviceLawNames() + ")";
        // a group's material: at the groupMaterials that names it; the force field's one material: at the material
        if (!onDevice && form.groupMaterials && m != form.material)
            unsupported(ff, *form.groupMaterials, "groupMaterials: the material " + m->className() + " '" + m->name() + "'" + laws);
        if (!onDevice) unsupported(*m, "the material " + m->className() + laws);
        StepSetup::Group g;
        g.material = m;
        for (int w = 0; w < 2; ++w)
            if (const Vec3* d = m->fibreDirection(w)) {
                const Vec3 n = *d / d->norm();  // (as TLEDElements.cpp and elements/FibreField.cpp)
                (w == 0 ? g.a0 : g.b0) = elements::Vec33<double>{n[0], n[1], n[2]};
            }
        s.groups.push_back(g);
        return s.groups.size() - 1;
    };
    for (size_t c = 0; c < cell.size(); ++c) {
        StepSetup::Group& g = s.groups[groupOf(cell[c])];
        if (c < nT) g.tets.push_back(static_cast<int>(c));
        else g.hexes.push_back(static_cast<int>(c - nT));
    }
    if (s.groups.size() == 1) {
        s.groups[0].tets.clear();  // one material: its kernels run over every element, with no list
        s.groups[0].hexes.clear();
    }
}

/// The fibre directions per element of TLED's form (elements::DeviceForm::fibre: from its
/// fibreArray and fibreArray2, unit, (1 0 0) or (0 1 0) where a cell's material does not read
/// them) into the rows of StepArrays fa, fb, hfa, hfb; nothing without an array (each group's
/// material then gives its elements' directions, StepSetup::Group a0, b0).
void readFibres(const elements::DeviceForm& form, size_t nT, size_t nH, StepSetup& s) {
    s.fibresPerElement = form.fibresPerElement;
    if (!s.fibresPerElement) return;
    for (int w = 0; w < 2; ++w) {
        const std::vector<double>& dir = form.fibre[w];
        if (dir.empty()) continue;
        std::vector<double>& t = w == 0 ? s.fa : s.fb;
        std::vector<double>& h = w == 0 ? s.hfa : s.hfb;
        t.assign(3 * nT, 0.0);
        h.assign(3 * nH, 0.0);
        for (size_t c = 0; c < nT + nH; ++c)
            for (size_t i = 0; i < 3; ++i) {
                if (c < nT) t[i * nT + c] = dir[3 * c + i];
                else h[i * nH + c - nT] = dir[3 * c + i];
            }
    }
}

/// A device form's array of `per` values for each of n elements, else a located error naming it.
const std::vector<double>& sized(const core::BaseForceField& ff, const std::vector<double>& a, size_t per, size_t n, const char* name) {
    if (a.size() != per * n)
        ff.fail("its device form has " + std::to_string(a.size()) + " values of " + name + " for " + std::to_string(n) +
                " elements (" + std::to_string(per) + " each)");
    return a;
}

/// The element force field's device form (elements/DeviceForm.h) checked against what the device
/// step runs: the form of its elements (TLED's, or HEML's edge form or its mass-spring mode, which
/// has no material and no series), J0, a material per group or one for all, fibre directions per
/// material or per element, its Prony series (HEMLForceField takes one).
void readForm(const core::BaseForceField& ff, const elements::DeviceForm& form, StepSetup& s) {
    s.form = form.kind == elements::DeviceForm::Kind::TLED ? StepSetup::Form::TLED : StepSetup::Form::Edges;
    s.springs = form.kind == elements::DeviceForm::Kind::Springs;
    s.J0 = form.J0;
    s.hourglass = form.hourglass;
    if (s.springs) return;
    const size_t nT = form.tetrahedra ? form.tetrahedra->size() : 0, nH = form.hexahedra ? form.hexahedra->size() : 0;
    if (form.cellMaterial.size() != nT + nH)
        ff.fail("its device form has " + std::to_string(form.cellMaterial.size()) + " materials for " + std::to_string(nT + nH) + " cells");
    readGroups(ff, form, nT, s);
    // (HEML's edge form: its fibres are in its rest data, w = V^-1 a0)
    if (s.form == StepSetup::Form::TLED) readFibres(form, nT, nH, s);
    readSeries(form, s);
    if (s.form == StepSetup::Form::Edges && s.series.size() > 1)
        unsupported(*s.series[1].prony, "a second ViscoelasticProny beside a HEMLForceField (it takes one)");
}

/// The faces of the SurfacePressure components (s.pressures), in their order: node indices, rest
/// differences from the first corner, and their load (StepArrays tri, quad, ...).
void pressureFaces(const Positions& X, StepSetup& s) {
    const auto put = [&](const int* nodes, int corners, size_t n, size_t f, std::vector<int>& at, std::vector<double>& D) {
        for (int a = 0; a < corners; ++a) {
            at[static_cast<size_t>(a) * n + f] = nodes[a];
            if (a > 0)
                for (int i = 0; i < 3; ++i)
                    D[static_cast<size_t>(3 * (a - 1) + i) * n + f] = X[static_cast<size_t>(nodes[a])][i] - X[static_cast<size_t>(nodes[0])][i];
        }
    };
    size_t nTri = 0, nQ = 0;
    for (const core::PressureLoad* p : s.pressures) nTri += p->pressureTriangles().size(), nQ += p->pressureQuads().size();
    s.nTris = static_cast<int>(nTri);
    s.nQuads = static_cast<int>(nQ);
    s.tri.resize(3 * nTri);
    s.quad.resize(4 * nQ);
    s.triD.resize(6 * nTri);
    s.quadD.resize(9 * nQ);
    s.triLoad.clear();
    s.quadLoad.clear();
    for (size_t k = 0; k < s.pressures.size(); ++k) {
        for (const auto& t : s.pressures[k]->pressureTriangles()) {
            put(t.data(), 3, nTri, s.triLoad.size(), s.tri, s.triD);
            s.triLoad.push_back(static_cast<int>(k));
        }
        for (const auto& q : s.pressures[k]->pressureQuads()) {
            put(q.data(), 4, nQ, s.quadLoad.size(), s.quad, s.quadD);
            s.quadLoad.push_back(static_cast<int>(k));
        }
    }
}

/// A ConstantForce with a load curve: its force at c = 1 in a load array of its own (StepArrays
/// loadF), scaled by c(t) in the node kernel.
void addCurvedLoad(const core::BaseForceField& ff, const core::NodalLoad& load, size_t nNodes, StepSetup& s) {
    if (s.loads.size() == static_cast<size_t>(kMaxLoads))
        unsupported(ff, "a " + ff.className() + " with a load curve beyond the first " + std::to_string(kMaxLoads) + " (the device step takes " +
                            std::to_string(kMaxLoads) + ")");
    IndexList nodes;
    Positions F;
    load.unscaledLoad(nodes, F);
    const size_t k = s.loads.size();
    s.loads.push_back(&load);
    s.loadF.resize(3 * nNodes * (k + 1), 0.0);
    for (size_t j = 0; j < nodes.size(); ++j)
        for (int i = 0; i < 3; ++i) s.loadF[3 * (k * nNodes + static_cast<size_t>(nodes[j])) + static_cast<size_t>(i)] += F[j][i];
}

/// The nodes of each element in the rows of StepArrays tet or hex (corner a of element e at a n + e),
/// each checked against the state's nodes.
template <size_t NN>
void connectivity(const core::BaseForceField& ff, const std::vector<std::array<int, NN>>& elements, size_t nNodes, const char* kind,
                  std::vector<int>& out) {
    const size_t n = elements.size();
    out.resize(NN * n);
    for (size_t e = 0; e < n; ++e)
        for (size_t a = 0; a < NN; ++a) {
            const int node = elements[e][a];
            if (node < 0 || static_cast<size_t>(node) >= nNodes) ff.fail(std::string(kind) + " " + std::to_string(e) + " has a node out of range");
            out[a * n + e] = node;
        }
}

/// The values of a device form's array (per values for each of n elements, element by element)
/// into the rows of a StepArrays array (value r of element e at r n + e).
void toRows(const std::vector<double>& a, size_t per, size_t n, std::vector<double>& out) {
    out.resize(per * n);
    for (size_t e = 0; e < n; ++e)
        for (size_t r = 0; r < per; ++r) out[r * n + e] = a[per * e + r];
}

/// The rest data of TLED's tetrahedra from its device form: dN_a/dX for a = 1..3 (the rows of
/// Dm^-1) and the volumes, as TLEDForceField's precompute computed them (TLEDElements.cpp).
void tetGeometry(const core::BaseForceField& ff, const elements::DeviceForm& form, const Tetrahedra& tets, size_t nNodes, StepSetup& s) {
    const size_t n = tets.size();
    connectivity(ff, tets, nNodes, "tetrahedron", s.tet);
    toRows(sized(ff, form.tetDN, 9, n, "tetrahedron dN/dX"), 9, n, s.dN);
    s.vol = sized(ff, form.tetVolume, 1, n, "tetrahedron volumes");
}

/// The rest data of HEML's tetrahedra from its device form (StepSetup::Form::Edges, as
/// HEMLForceField's precompute computed them, HEMLElements.cpp): the rest edges, 1 / det V, G and
/// the volumes (elements::edgeRest), V^-1 a0 and V^-1 b0 where a material reads them; in
/// mass-spring mode each edge's share of the stiffness and rest length.
void edgeGeometry(const core::BaseForceField& ff, const elements::DeviceForm& form, const Tetrahedra& tets, size_t nNodes, StepSetup& s) {
    const size_t n = tets.size();
    connectivity(ff, tets, nNodes, "tetrahedron", s.tet);
    s.vol = sized(ff, form.tetVolume, 1, n, "tetrahedron volumes");
    toRows(sized(ff, form.edgeV, 9, n, "rest edges"), 9, n, s.eV);
    s.eInvDetV = sized(ff, form.edgeInvDetV, 1, n, "1 / det V");
    toRows(sized(ff, form.edgeG, s.springs ? 0 : 6, n, "G"), 6, s.springs ? 0 : n, s.eG);
    for (int w = 0; w < 2; ++w) {
        const std::vector<double>& a = form.edgeW[w];
        if (!a.empty()) toRows(sized(ff, a, 3, n, "V^-1 a0 or V^-1 b0"), 3, n, w == 0 ? s.ew4 : s.ew6);
    }
    toRows(sized(ff, form.springK, s.springs ? 6 : 0, n, "spring stiffnesses"), 6, s.springs ? n : 0, s.ekk);
    toRows(sized(ff, form.springLength, s.springs ? 6 : 0, n, "spring rest lengths"), 6, s.springs ? n : 0, s.elen0);
}

/// The rest data of TLED's hexahedra from its device form: the uniform-strain dN_a/dX, volumes,
/// hourglass vectors c_q and stiffnesses K (of each element's material), as TLEDForceField's
/// precompute computed them (TLEDElements.cpp).
void hexGeometry(const core::BaseForceField& ff, const elements::DeviceForm& form, const Hexahedra& hexes, size_t nNodes, StepSetup& s) {
    const size_t n = hexes.size();
    connectivity(ff, hexes, nNodes, "hexahedron", s.hex);
    toRows(sized(ff, form.hexDN, 24, n, "hexahedron dN/dX"), 24, n, s.hdN);
    toRows(sized(ff, form.hexC, 12, n, "hourglass vectors"), 12, n, s.hgC);
    s.hvol = sized(ff, form.hexVolume, 1, n, "hexahedron volumes");
    s.hgK = sized(ff, form.hexK, 1, n, "hourglass stiffnesses");
}

/// The hold codes of the nodes' axes (StepArrays::hold), the constraints in their order so that the
/// last one that holds an axis decides, as in projectState; a moving axis gets a target of its own.
void holdCodes(const core::MechanicalGroup& g, StepSetup& s) {
    s.hold.assign(3 * static_cast<size_t>(s.nNodes), 0);
    s.targetAt.clear();
    for (const core::BaseConstraint* c : g.constraints) {
        const std::array<bool, 3> axes = c->constrainedAxes();
        for (int node : c->constrainedNodes())
            for (int i = 0; i < 3; ++i) {
                if (!axes[static_cast<size_t>(i)]) continue;
                std::uint32_t& h = s.hold[3 * static_cast<size_t>(node) + static_cast<size_t>(i)];
                if (!c->prescribesMotion()) {
                    h = 1;
                } else if (h < 2) {
                    h = static_cast<std::uint32_t>(2 + s.targetAt.size());
                    s.targetAt.push_back(3 * node + i);
                }
            }
    }
}

/// The group's force fields, each by the role it gives: the element force field's device form
/// (elements::DeviceFormSource: TLEDForceField, HEMLForceField), read into s (readForm) and
/// returned; the loads' terms (core::NodalLoad: ConstantForce, its force added once to s.ext
/// without a load curve, else a load array of its own; core::PressureLoad: SurfacePressure). Any
/// other force field, a second element force field or none is a located error.
elements::DeviceForm readForceFields(const core::Component& owner, const core::MechanicalGroup& g, StepSetup& s) {
    core::BaseMechanicalState& state = *g.state;
    const size_t nNodes = state.size();
    core::BaseForceField*& elastic = s.elastic;  // the element force field
    elements::DeviceForm form;
    Positions ext(nNodes, Vec3::Zero());
    for (core::BaseForceField* ff : g.forceFields) {
        if (const auto* source = dynamic_cast<const elements::DeviceFormSource*>(ff)) {
            if (elastic) unsupported(*ff, "a second element force field (" + ff->className() + " beside " + elastic->className() + ") on one state");
            elastic = ff;
            source->deviceForm(form);
            readForm(*ff, form, s);
        } else if (const auto* load = dynamic_cast<const core::NodalLoad*>(ff)) {
            if (!load->curved()) ff->addForce(state, ext, 0.0);  // constant: its force once, summed with the others
            else addCurvedLoad(*ff, *load, nNodes, s);
        } else if (const auto* p = dynamic_cast<const core::PressureLoad*>(ff)) {
            if (s.pressures.size() == static_cast<size_t>(kMaxPressures))
                unsupported(*ff, "a " + ff->className() + " beyond the first " + std::to_string(kMaxPressures) + " on one body");
            s.pressures.push_back(p);
        } else {
            unsupported(*ff, ff->className() + " (a force field that gives neither its device form, elements::DeviceFormSource, nor its "
                                               "load's terms, core::NodalLoad or core::PressureLoad)");
        }
    }
    if (!elastic)
        owner.fail("the state '" + state.path() + "' has no element force field with a device form (TLEDForceField, HEMLForceField): the device "
                   "step runs those only");
    s.ext.resize(3 * nNodes);
    for (size_t i = 0; i < nNodes; ++i)
        for (int c = 0; c < 3; ++c) s.ext[3 * i + static_cast<size_t>(c)] = ext[i][c];
    return form;
}

} // namespace

void buildSlots(StepSetup& s) {
    const size_t nT = static_cast<size_t>(s.nTets), nH = static_cast<size_t>(s.nHexes);
    s.slotStart.assign(static_cast<size_t>(s.nNodes) + 1, 0);
    for (int node : s.tet) ++s.slotStart[static_cast<size_t>(node) + 1];
    for (int node : s.hex) ++s.slotStart[static_cast<size_t>(node) + 1];
    for (int node : s.tri) ++s.slotStart[static_cast<size_t>(node) + 1];
    for (int node : s.quad) ++s.slotStart[static_cast<size_t>(node) + 1];
    for (size_t i = 0; i < static_cast<size_t>(s.nNodes); ++i) s.slotStart[i + 1] += s.slotStart[i];
    std::vector<int> fill(s.slotStart.begin(), s.slotStart.end() - 1);
    s.slots.resize(s.tet.size() + s.hex.size() + s.tri.size() + s.quad.size());
    // by element (tetrahedra, then hexahedra), then corner: the order of the node's sum (a node is one
    // corner of an element at most)
    // (and each corner's position among the slots, StepArrays tetSlot ... for the forces in node order)
    const auto add = [&](int node, size_t element, size_t a) {
        const std::uint32_t at = static_cast<std::uint32_t>(fill[static_cast<size_t>(node)]++);
        s.slots[at] = static_cast<std::uint32_t>(8 * element + a);
        return at;
    };
    const size_t nTri = static_cast<size_t>(s.nTris), nQ = static_cast<size_t>(s.nQuads);
    s.tetSlot.resize(4 * nT);
    s.hexSlot.resize(8 * nH);
    s.triSlot.resize(3 * nTri);
    s.quadSlot.resize(4 * nQ);
    for (size_t e = 0; e < nT; ++e)
        for (size_t a = 0; a < 4; ++a) s.tetSlot[4 * e + a] = add(s.tet[a * nT + e], e, a);
    for (size_t e = 0; e < nH; ++e)
        for (size_t a = 0; a < 8; ++a) s.hexSlot[8 * e + a] = add(s.hex[a * nH + e], nT + e, a);
    for (size_t f = 0; f < nTri; ++f)
        for (size_t a = 0; a < 3; ++a) s.triSlot[3 * f + a] = add(s.tri[a * nTri + f], nT + nH + f, a);
    for (size_t f = 0; f < nQ; ++f)
        for (size_t a = 0; a < 4; ++a) s.quadSlot[4 * f + a] = add(s.quad[a * nQ + f], nT + nH + nTri + f, a);
}

StepSetup buildStepSetup(const core::Component& owner, const core::MechanicalGroup& g) {
    StepSetup s;
    core::BaseMechanicalState& state = *g.state;
    readIntegrator(*g.integrator, s);
    const size_t nNodes = state.size();
    const elements::DeviceForm form = readForceFields(owner, g, s);
    for (const core::BaseConstraint* c : g.constraints)
        if (!dynamic_cast<const core::AxisHold*>(c))
            unsupported(*c, c->className() + " (the device step holds axes of nodes, FixedConstraint and PrescribedDisplacement: a constraint "
                                             "that gives its terms, core::AxisHold)");
    const Tetrahedra noTets;
    const Hexahedra noHexes;
    const Tetrahedra& tets = form.tetrahedra ? *form.tetrahedra : noTets;
    const Hexahedra& hexes = form.hexahedra ? *form.hexahedra : noHexes;
    // (the slots hold 8 e + a in 32 bits; every array index stays below 2^31)
    if (nNodes >= (size_t(1) << 29) || tets.size() + hexes.size() >= (size_t(1) << 26))
        owner.fail("the mesh is too large for the device step's 32-bit indices");
    if (6 * static_cast<size_t>(s.pronyTerms()) * std::max(tets.size(), hexes.size()) >= (size_t(1) << 31))
        owner.fail("the mesh is too large for the device step's 32-bit indices of its " + std::to_string(s.pronyTerms()) +
                   " Prony terms' states (6 per term and element)");
    s.nNodes = static_cast<int>(nNodes);
    s.nTets = static_cast<int>(tets.size());
    s.nHexes = static_cast<int>(hexes.size());
    if (s.form == StepSetup::Form::TLED) tetGeometry(*s.elastic, form, tets, nNodes, s);
    else edgeGeometry(*s.elastic, form, tets, nNodes, s);
    hexGeometry(*s.elastic, form, hexes, nNodes, s);
    pressureFaces(state.x0(), s);
    if (tets.size() + hexes.size() + s.tri.size() / 3 + s.quad.size() / 4 >= (size_t(1) << 26))
        owner.fail("the mesh and its faces under pressure are too many for the device step's 32-bit slots");
    buildSlots(s);
    s.mass = g.mass;
    s.invMass = g.invMass;
    holdCodes(g, s);
    return s;
}

StepCounts stepCounts(const StepSetup& s) { return {s.nTets, s.nHexes, s.nNodes, s.nTris, s.nQuads, static_cast<int>(s.loads.size())}; }

size_t stepLength(const StepArrayInfo& a, const StepSetup& s) {
    using E = StepArrayInfo::Extent;
    const size_t nT = static_cast<size_t>(s.nTets), nH = static_cast<size_t>(s.nHexes), n = static_cast<size_t>(s.nNodes);
    const size_t nTri = static_cast<size_t>(s.nTris), nQ = static_cast<size_t>(s.nQuads), terms = static_cast<size_t>(s.pronyTerms());
    size_t extent = 1;
    switch (a.extent) {
    case E::One: break;
    case E::Tets: extent = nT; break;
    case E::Hexes: extent = nH; break;
    case E::Tris: extent = nTri; break;
    case E::Quads: extent = nQ; break;
    case E::Nodes: extent = n; break;
    case E::NodesAndOne: extent = n + 1; break;
    case E::NodeLoads: extent = n * s.loads.size(); break;
    case E::Corners: extent = 4 * nT + 8 * nH + 3 * nTri + 4 * nQ; break;
    case E::TetTerms: extent = terms * nT; break;
    case E::HexTerms: extent = terms * nH; break;
    case E::Targets: extent = s.targetAt.size(); break;
    }
    return a.width * extent;
}

bool inForceOrder(const StepArrayInfo& a, const StepSetup& s) {
    if (a.need == StepArrayInfo::Need::ByElement) return !s.forcesInNodeOrder;
    if (a.need == StepArrayInfo::Need::ByNode) return s.forcesInNodeOrder;
    return true;
}

void requireLayout(const std::vector<std::string>& errors) {
    if (errors.empty()) return;
    std::string text;
    for (const std::string& e : errors) text += "\n  " + e;
    throw core::Error(core::ErrorKind::Internal, {},
                      "[CudaStep] the device step's arrays do not match their table (fascia/cuda/StepLayout.h):" + text);
}

NodeParams<double> nodeParams(const core::MechanicalGroup& g, const StepSetup& s, double t, double dt, double kick) {
    const double c = g.gravityCurve ? g.gravityCurve->value(t) : 1.0;
    NodeParams<double> p;
    for (int i = 0; i < 3; ++i) p.g[i] = c * g.gravity[i];
    p.dt = dt;
    p.kick = kick;
    p.alpha = s.damping;
    for (size_t k = 0; k < s.loads.size(); ++k) p.load[k] = s.loads[k]->loadFactor(t);
    p.a = 0.5 * s.damping * dt;  // CentralDifference's c2 = 1 - a, c1 = 1 - b
    p.b = p.a / (1.0 + p.a);
    return p;
}

void motionTargets(core::MechanicalGroup& g, const StepSetup& s, double tEnd, std::vector<double>& tu, std::vector<double>& tv) {
    tu.resize(s.targetAt.size());
    tv.resize(s.targetAt.size());
    if (s.targetAt.empty()) return;
    g.projectState(tEnd);
    const Positions& x = g.state->x();
    const Positions& X = g.state->x0();
    const Positions& v = g.state->v();
    for (size_t j = 0; j < s.targetAt.size(); ++j) {
        const size_t n = static_cast<size_t>(s.targetAt[j] / 3);
        const int i = s.targetAt[j] % 3;
        tu[j] = x[n][i] - X[n][i];
        tv[j] = v[n][i];
    }
}

void pronyCoefficients(const StepSetup& s, double elapsed, double dt, std::vector<double>& A, std::vector<double>& B) {
    A.clear();
    B.clear();
    std::vector<double> a, b;
    for (const StepSetup::Series& x : s.series) {
        viscoelastic::stepCoefficients(*x.prony, elapsed, dt, a, b);
        A.insert(A.end(), a.begin(), a.end());
        B.insert(B.end(), b.begin(), b.end());
    }
}

std::string deviceLawNames() {
    std::string out;
    materials::detail::forEachIn([&](auto* tag) { out += (out.empty() ? "" : ", ") + std::string(std::decay_t<decltype(*tag)>::kName); },
                                 DeviceMaterials{});
    return out;
}

} // namespace fascia::cuda
