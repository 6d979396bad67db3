#include "StepSetup.h"

#include "DeviceLaws.h"
#include "fascia/base/Error.h"
#include "fascia/elements/FibreField.h"
#include "fascia/elements/EdgeForm.h"
#include "fascia/elements/Geometry.h"
#include "fascia/elements/GroupMaterials.h"
#include "fascia/materials/RelaxationSplit.h"
#include "fascia/scene/Node.h"
#include "fascia/viscoelastic/HistoryClock.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace fascia::cuda {

namespace {

template <class P>
const P* paramOf(const core::Component& c, const std::string& name) {
    return dynamic_cast<const P*>(c.findParam(name));
}

[[noreturn]] void unsupported(const core::Component& c, const std::string& what) {
    c.fail(what + " is not on the GPU step yet (CudaStep in the root node runs the whole step on the device, with no "
                  "fallback to the host)",
           {"remove CudaStep to run this scene on the CPU"});
}

/// The same located at c's parameter p.
[[noreturn]] void unsupported(const core::Component& c, const core::BaseParam& p, const std::string& what) {
    c.fail(p,
           what + " is not on the GPU step yet (CudaStep in the root node runs the whole step on the device, with no "
                  "fallback to the host)",
           {"remove CudaStep to run this scene on the CPU"});
}

/// The integrator and its parameters: SemiImplicitEuler or CentralDifference.
void readIntegrator(const core::BaseIntegrator& integ, StepSetup& s) {
    if (integ.className() == "CentralDifference") s.scheme = StepSetup::Scheme::CentralDifference;
    else if (integ.className() != "SemiImplicitEuler")
        unsupported(integ, integ.className() + " (the device step integrates with SemiImplicitEuler or CentralDifference)");
    if (const auto* d = paramOf<core::Param<double>>(integ, "damping")) s.damping = d->get();
    if (const auto* h = paramOf<core::Param<bool>>(integ, "halfStepStart")) s.halfStepStart = h->get();
}

/// The Prony series beside the TLED force field, as TLEDForceField takes them (TLEDForceField.cpp
/// init): every ViscoelasticProny of its node in order, each part relaxed by one series at most,
/// the parts a series relaxes stress-free at rest for every material group (materials/
/// RelaxationSplit.h, a located error at the series' apply otherwise), s ln J of each group's
/// material moved between the parts when a series relaxes one alone.
void readSeries(const core::BaseForceField& ff, StepSetup& s) {
    if (!ff.node()) return;
    for (const core::Component* c : ff.node()->findAllLocal<core::Component>()) {
        if (c->className() != "ViscoelasticProny") continue;
        const auto* p = dynamic_cast<const viscoelastic::ViscoelasticProny*>(c);
        if (!p) unsupported(*c, "this ViscoelasticProny (not the class the device step knows)");
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

/// The mesh TLEDForceField takes its elements, groups and cell arrays from (TLEDForceField.cpp
/// init): its `mesh`, else, without tetrahedra or hexahedra given, the mesh source in its context;
/// null for elements given as lists.
const MeshData* meshOf(const core::BaseForceField& ff) {
    if (const auto* m = paramOf<core::Param<MeshData>>(ff, "mesh"); m && m->isSet()) return &m->get();
    for (const char* name : {"tetrahedra", "hexahedra"})
        if (const auto* p = ff.findParam(name); p && p->isSet()) return nullptr;
    const auto* source = ff.node() ? ff.node()->findInContext<core::BaseTopology>() : nullptr;
    return source ? &source->meshData() : nullptr;
}

/// The material of each element and the groups of elements by material, in order of first
/// appearance (tetrahedra, then hexahedra), from TLEDForceField's material and groupMaterials as it
/// assigns them (elements::assignMaterials, TLEDElements.cpp precompute); a material that is not a
/// law of DeviceLaws.h is a located error naming it. Returns the materials per cell (tetrahedra,
/// then hexahedra).
std::vector<const materials::BaseMaterial*> readGroups(const core::BaseForceField& ff, const MeshData* mesh, size_t nT, size_t nH,
                                                       StepSetup& s) {
    const auto* groups = paramOf<core::Param<elements::GroupMaterialList>>(ff, "groupMaterials");
    const auto* link = paramOf<core::Link<materials::BaseMaterial>>(ff, "material");
    if (!groups || !link) unsupported(ff, "this TLEDForceField (its parameters are not the ones the device step knows)");
    const elements::MaterialAssignment assigned =
        elements::assignMaterials(ff, *groups, elements::defaultMaterial(ff, *link, *groups), mesh, nT, nH);
    std::vector<const materials::BaseMaterial*> cell(assigned.tetrahedra.begin(), assigned.tetrahedra.end());
    cell.insert(cell.end(), assigned.hexahedra.begin(), assigned.hexahedra.end());
    const auto groupOf = [&](const materials::BaseMaterial* m) {
        for (size_t g = 0; g < s.groups.size(); ++g)
            if (s.groups[g].material == m) return g;
        const bool onDevice = selectDeviceLaw(m, [](auto tag, const materials::BaseMaterial*) {
            return !std::is_same_v<typename decltype(tag)::type, elements::GenericLaw>;
        });
        const std::string laws = " (the device step runs " + deviceLawNames() + ")";
        // a group's material: at the groupMaterials that names it; the force field's one material: at the material
        if (!onDevice && groups->isSet() && m != link->get())
            unsupported(ff, *groups, "groupMaterials: the material " + m->className() + " '" + m->name() + "'" + laws);
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
    return cell;
}

/// The fibre directions per element from TLEDForceField's fibreArray and fibreArray2, as it
/// resolves them (elements::resolveFibres: unit length, the material's own where a direction has no
/// array), into the rows of StepArrays fa, fb, hfa, hfb; nothing without an array (each group's
/// material then gives its elements' directions, StepSetup::Group a0, b0).
void readFibres(const core::BaseForceField& ff, const MeshData* mesh, const std::vector<const materials::BaseMaterial*>& cell, size_t nT,
                StepSetup& s) {
    elements::FibreField field[2];
    for (int w = 0; w < 2; ++w) {
        const auto* array = paramOf<core::Param<std::string>>(ff, w == 0 ? "fibreArray" : "fibreArray2");
        if (!array) unsupported(ff, "this TLEDForceField (its parameters are not the ones the device step knows)");
        const unsigned bit = w == 0 ? materials::BaseMaterial::UsesI4 : materials::BaseMaterial::UsesI6;
        // (a direction no material reads: TLEDForceField warned about its array already)
        if (std::any_of(cell.begin(), cell.end(), [&](const materials::BaseMaterial* m) { return (m->uses() & bit) != 0; }))
            field[w] = elements::resolveFibres(ff, w, *array, mesh, cell, nT);
    }
    s.fibresPerElement = field[0].perElement || field[1].perElement;
    if (!s.fibresPerElement) return;
    const size_t nH = cell.size() - nT;
    for (int w = 0; w < 2; ++w) {
        if (!field[w].used) continue;
        std::vector<double>& t = w == 0 ? s.fa : s.fb;
        std::vector<double>& h = w == 0 ? s.hfa : s.hfb;
        t.assign(3 * nT, 0.0);
        h.assign(3 * nH, 0.0);
        for (size_t c = 0; c < cell.size(); ++c) {
            // (a cell whose material does not read this direction: (1 0 0) or (0 1 0), never read)
            const Vec3 d = field[w].dir[c] == Vec3::Zero() ? Vec3(w == 0 ? 1 : 0, w == 0 ? 0 : 1, 0) : field[w].dir[c];
            for (size_t i = 0; i < 3; ++i) {
                if (c < nT) t[i * nT + c] = d[static_cast<Eigen::Index>(i)];
                else h[i * nH + c - nT] = d[static_cast<Eigen::Index>(i)];
            }
        }
    }
}

/// The materials and the options of the TLED force field, each checked against what the device
/// step runs: a material per group (groupMaterials) or one for all, fibre directions per material
/// or per element (fibreArray, fibreArray2), the Prony series.
void readTLED(const core::BaseForceField& ff, StepSetup& s) {
    if (const auto* j0 = paramOf<core::Param<double>>(ff, "J0")) s.J0 = j0->get();
    if (const auto* k = paramOf<core::Param<double>>(ff, "hourglassStiffness")) s.hourglass = k->get();
    const size_t nT = ff.tetrahedra() ? ff.tetrahedra()->size() : 0, nH = ff.hexahedra() ? ff.hexahedra()->size() : 0;
    const MeshData* mesh = meshOf(ff);
    const std::vector<const materials::BaseMaterial*> cell = readGroups(ff, mesh, nT, nH, s);
    readFibres(ff, mesh, cell, nT, s);
    readSeries(ff, s);
}

/// The materials and the options of the HEML force field (HEMLForceField.cpp init), checked as
/// readTLED does: its mass-spring mode (`stiffness`, no material), else a material per group or one
/// for all, fibre arrays, and one Prony series (HEMLForceField takes one, and refuses a second).
void readHEML(const core::BaseForceField& ff, StepSetup& s) {
    s.form = StepSetup::Form::Edges;
    if (const auto* j0 = paramOf<core::Param<double>>(ff, "J0")) s.J0 = j0->get();
    const auto* k = paramOf<core::Param<double>>(ff, "stiffness");
    if (!k) unsupported(ff, "this HEMLForceField (its parameters are not the ones the device step knows)");
    s.springs = k->isSet();
    if (s.springs) return;  // (HEMLForceField refuses a material and a Prony series in this mode)
    const size_t nT = ff.tetrahedra() ? ff.tetrahedra()->size() : 0;
    const MeshData* mesh = meshOf(ff);
    const std::vector<const materials::BaseMaterial*> cell = readGroups(ff, mesh, nT, 0, s);
    readFibres(ff, mesh, cell, nT, s);
    readSeries(ff, s);
    if (s.series.size() > 1) unsupported(*s.series[1].prony, "a second ViscoelasticProny beside a HEMLForceField (it takes one)");
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
        unsupported(ff, "a ConstantForce with a load curve beyond the first " + std::to_string(kMaxLoads) + " (the device step takes " +
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

/// Rest geometry of the tetrahedra: dN_a/dX for a = 1..3 (rows of Dm^-1) and the volumes.
void tetGeometry(const core::BaseForceField& ff, const Positions& X, const Tetrahedra& tets, StepSetup& s) {
    const elements::TetRest rest = elements::tetRest(ff, X, tets);
    const size_t n = tets.size();
    s.tet.resize(4 * n);
    s.dN.resize(9 * n);
    s.vol = rest.volume;
    for (size_t e = 0; e < n; ++e) {
        for (int a = 0; a < 4; ++a) s.tet[static_cast<size_t>(a) * n + e] = tets[e][static_cast<size_t>(a)];
        for (int a = 0; a < 3; ++a)
            for (int i = 0; i < 3; ++i) s.dN[static_cast<size_t>(3 * a + i) * n + e] = rest.DmInv[e](a, i);
    }
}

/// The fibre direction w (0: a0, 1: b0) of each tetrahedron: its own (StepSetup fa, fb) or its
/// material group's.
std::vector<Vec3> tetFibres(const StepSetup& s, int w, size_t n) {
    std::vector<Vec3> dir(n, Vec3::Zero());
    for (const StepSetup::Group& g : s.groups) {
        const elements::Vec33<double>& d = w == 0 ? g.a0 : g.b0;
        const Vec3 v(d.x, d.y, d.z);
        if (g.tets.empty() && s.groups.size() == 1) std::fill(dir.begin(), dir.end(), v);
        for (int e : g.tets) dir[static_cast<size_t>(e)] = v;
    }
    const std::vector<double>& own = w == 0 ? s.fa : s.fb;
    if (s.fibresPerElement && !own.empty())
        for (size_t e = 0; e < n; ++e) dir[e] = Vec3(own[e], own[n + e], own[2 * n + e]);
    return dir;
}

/// Rest geometry of HEML's tetrahedra (StepSetup::Form::Edges, HEMLForceField.cpp precompute):
/// the rest edges, 1 / det V, G and the volumes (elements::edgeRest), V^-1 a0 and V^-1 b0 where a
/// material reads them; in mass-spring mode each edge's share of the stiffness and rest length.
void edgeGeometry(const core::BaseForceField& ff, const Positions& X, const Tetrahedra& tets, StepSetup& s) {
    const size_t n = tets.size();
    s.tet.resize(4 * n);
    s.vol.resize(n);
    s.eV.resize(9 * n);
    s.eInvDetV.resize(n);
    bool uses[2] = {false, false};
    for (const StepSetup::Group& g : s.groups)
        for (int w = 0; w < 2; ++w) uses[w] |= (g.material->uses() & (w == 0 ? materials::BaseMaterial::UsesI4 : materials::BaseMaterial::UsesI6)) != 0;
    const std::vector<Vec3> dir[2] = {uses[0] ? tetFibres(s, 0, n) : std::vector<Vec3>{}, uses[1] ? tetFibres(s, 1, n) : std::vector<Vec3>{}};
    s.eG.assign(s.springs ? 0 : 6 * n, 0.0);
    s.ew4.assign(uses[0] ? 3 * n : 0, 0.0);
    s.ew6.assign(uses[1] ? 3 * n : 0, 0.0);
    s.ekk.assign(s.springs ? 6 * n : 0, 0.0);
    s.elen0.assign(s.springs ? 6 * n : 0, 0.0);
    const auto* k = paramOf<core::Param<double>>(ff, "stiffness");
    const elements::EdgeShares shares(s.springs ? tets : Tetrahedra{});
    for (size_t e = 0; e < n; ++e) {
        const auto& t = tets[e];
        for (size_t a = 0; a < 4; ++a) {
            if (t[a] < 0 || static_cast<size_t>(t[a]) >= X.size()) ff.fail("tetrahedron " + std::to_string(e) + " has a node out of range");
            s.tet[a * n + e] = t[a];
        }
        const elements::EdgeRest r = elements::edgeRest(X[size_t(t[0])], X[size_t(t[1])], X[size_t(t[2])], X[size_t(t[3])]);
        s.vol[e] = std::abs(r.det) / 6.0;
        s.eInvDetV[e] = 1.0 / r.det;
        for (int a = 0; a < 3; ++a)
            for (int i = 0; i < 3; ++i) s.eV[static_cast<size_t>(3 * a + i) * n + e] = r.V(i, a);
        for (int q = 0; q < 6 && !s.springs; ++q) s.eG[static_cast<size_t>(q) * n + e] = r.G[q];
        for (int w = 0; w < 2; ++w) {
            if (!uses[w]) continue;
            const Vec3 v = r.Vi * dir[w][e];
            for (int i = 0; i < 3; ++i) (w == 0 ? s.ew4 : s.ew6)[static_cast<size_t>(i) * n + e] = v[i];
        }
        for (int q = 0; q < 6 && s.springs; ++q) {
            const int a = t[static_cast<size_t>(elements::edgeA(q))], b = t[static_cast<size_t>(elements::edgeB(q))];
            s.elen0[static_cast<size_t>(q) * n + e] = (X[size_t(b)] - X[size_t(a)]).norm();
            s.ekk[static_cast<size_t>(q) * n + e] = k->get() / shares.count(a, b);
        }
    }
    s.fa.clear();  // (in ew4, ew6 now: the edge form does not read the directions themselves)
    s.fb.clear();
}

/// Rest geometry of the hexahedra: the uniform-strain dN_a/dX, volumes, hourglass vectors c_q and
/// stiffnesses K (of each element's material), as TLEDForceField computes them
/// (plugins/tled/TLEDElements.cpp).
void hexGeometry(const core::BaseForceField& ff, const Positions& X, const Hexahedra& hexes, StepSetup& s) {
    const size_t n = hexes.size();
    std::vector<const materials::BaseMaterial*> material(n, n > 0 ? s.groups.front().material : nullptr);
    for (const StepSetup::Group& g : s.groups)
        for (int e : g.hexes) material[static_cast<size_t>(e)] = g.material;
    s.hex.resize(8 * n);
    s.hdN.resize(24 * n);
    s.hgC.resize(12 * n);
    s.hvol.resize(n);
    s.hgK.resize(n);
    for (size_t e = 0; e < n; ++e) {
        Vec3 P[8];
        for (size_t a = 0; a < 8; ++a) {
            const int node = hexes[e][a];
            if (node < 0 || static_cast<size_t>(node) >= X.size()) ff.fail("hexahedron " + std::to_string(e) + " has a node out of range");
            P[a] = X[static_cast<size_t>(node)];
            s.hex[a * n + e] = node;
        }
        double V, dN[24], sumDN2, c[12];
        elements::hexUniformStrain(P, V, dN, sumDN2);
        elements::hexHourglassVectors(P, c);
        for (size_t r = 0; r < 24; ++r) s.hdN[r * n + e] = dN[r];
        for (size_t r = 0; r < 12; ++r) s.hgC[r * n + e] = c[r];
        s.hvol[e] = std::abs(V);
        s.hgK[e] = elements::hexHourglassStiffness(s.hourglass, *material[e], s.hvol[e], sumDN2);
    }
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
    core::BaseForceField*& elastic = s.elastic;  // the element force field: TLED or HEML
    const size_t nNodes = state.size();
    s.ext.assign(3 * nNodes, 0.0);
    Positions ext(nNodes, Vec3::Zero());
    for (core::BaseForceField* ff : g.forceFields) {
        if (ff->className() == "TLEDForceField" || ff->className() == "HEMLForceField") {
            if (elastic) unsupported(*ff, "a second element force field (" + ff->className() + " beside " + elastic->className() + ") on one state");
            elastic = ff;
            if (ff->className() == "TLEDForceField") readTLED(*ff, s);
            else readHEML(*ff, s);
        } else if (ff->className() == "ConstantForce") {
            const auto* c = ff->findParam("curve");
            const auto* load = dynamic_cast<const core::NodalLoad*>(ff);
            if (!c || !c->isSet()) ff->addForce(state, ext, 0.0);  // constant: its force once, summed with the others
            else if (load) addCurvedLoad(*ff, *load, nNodes, s);
            else unsupported(*ff, "this ConstantForce with a load curve (it does not give its load's terms, core::NodalLoad)");
        } else if (ff->className() == "SurfacePressure") {
            const auto* p = dynamic_cast<const core::PressureLoad*>(ff);
            if (!p) unsupported(*ff, "this SurfacePressure (it does not give its faces, core::PressureLoad)");
            if (s.pressures.size() == static_cast<size_t>(kMaxPressures))
                unsupported(*ff, "a SurfacePressure beyond the first " + std::to_string(kMaxPressures) + " on one body");
            s.pressures.push_back(p);
        } else {
            unsupported(*ff, ff->className());
        }
    }
    if (!elastic) owner.fail("the state '" + state.path() + "' has no TLEDForceField or HEMLForceField: the device step runs those only");
    for (const core::BaseConstraint* c : g.constraints)
        if (c->className() != "FixedConstraint" && c->className() != "PrescribedDisplacement") unsupported(*c, c->className());
    const Tetrahedra noTets;
    const Hexahedra noHexes;
    const Tetrahedra& tets = elastic->tetrahedra() ? *elastic->tetrahedra() : noTets;
    const Hexahedra& hexes = elastic->hexahedra() ? *elastic->hexahedra() : noHexes;
    // (the slots hold 8 e + a in 32 bits; every array index stays below 2^31)
    if (nNodes >= (size_t(1) << 29) || tets.size() + hexes.size() >= (size_t(1) << 26))
        owner.fail("the mesh is too large for the device step's 32-bit indices");
    if (6 * static_cast<size_t>(s.pronyTerms()) * std::max(tets.size(), hexes.size()) >= (size_t(1) << 31))
        owner.fail("the mesh is too large for the device step's 32-bit indices of its " + std::to_string(s.pronyTerms()) +
                   " Prony terms' states (6 per term and element)");
    for (size_t i = 0; i < nNodes; ++i)
        for (int c = 0; c < 3; ++c) s.ext[3 * i + static_cast<size_t>(c)] = ext[i][c];
    s.nNodes = static_cast<int>(nNodes);
    s.nTets = static_cast<int>(tets.size());
    s.nHexes = static_cast<int>(hexes.size());
    if (s.form == StepSetup::Form::TLED) tetGeometry(*elastic, state.x0(), tets, s);
    else edgeGeometry(*elastic, state.x0(), tets, s);
    hexGeometry(*elastic, state.x0(), hexes, s);
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
