#include "StepSetup.h"

#include "DeviceLaws.h"
#include "fascia/elements/Geometry.h"
#include "fascia/elements/GroupMaterials.h"
#include "fascia/scene/Node.h"

#include <algorithm>
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

/// The integrator's parameters: SemiImplicitEuler only.
void readIntegrator(const core::BaseIntegrator& integ, StepSetup& s) {
    if (integ.className() != "SemiImplicitEuler") unsupported(integ, integ.className() + " (the device step integrates with SemiImplicitEuler)");
    if (const auto* d = paramOf<core::Param<double>>(integ, "damping")) s.damping = d->get();
    if (const auto* h = paramOf<core::Param<bool>>(integ, "halfStepStart")) s.halfStepStart = h->get();
}

/// The material and the options of the TLED force field, each checked against what the device
/// step runs.
void readTLED(const core::BaseForceField& ff, StepSetup& s) {
    if (ff.hexahedra() && !ff.hexahedra()->empty()) unsupported(ff, "TLEDForceField on hexahedra");
    const auto* groups = paramOf<core::Param<elements::GroupMaterialList>>(ff, "groupMaterials");
    const auto* link = paramOf<core::Link<materials::BaseMaterial>>(ff, "material");
    if (!groups || !link) unsupported(ff, "this TLEDForceField (its parameters are not the ones the device step knows)");
    if (groups->isSet()) unsupported(ff, "groupMaterials (materials per mesh group)");
    for (const char* name : {"fibreArray", "fibreArray2"})
        if (const auto* p = ff.findParam(name); p && p->isSet()) unsupported(ff, std::string(name) + " (fibre directions per element)");
    if (const auto* j0 = paramOf<core::Param<double>>(ff, "J0")) s.J0 = j0->get();
    const materials::BaseMaterial* m = elements::defaultMaterial(ff, *link, *groups);
    if (!m) unsupported(ff, "a TLEDForceField without a material");
    const bool onDevice = selectDeviceLaw(m, [](auto tag, const materials::BaseMaterial*) {
        return !std::is_same_v<typename decltype(tag)::type, elements::GenericLaw>;
    });
    if (!onDevice) unsupported(*m, "the material " + m->className() + " (the device step runs " + deviceLawNames() + ")");
    s.material = m;
    for (int w = 0; w < 2; ++w)
        if (const Vec3* d = m->fibreDirection(w)) {
            const Vec3 n = d->normalized();
            (w == 0 ? s.a0 : s.b0) = {n[0], n[1], n[2]};
        }
    // a viscous model beside the force field relaxes its stress: not on the device yet
    if (ff.node())
        for (const core::Component* c : ff.node()->findAllLocal<core::Component>())
            if (c->className() == "ViscoelasticProny") unsupported(*c, "ViscoelasticProny");
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

} // namespace

void buildSlots(int nTets, int nNodes, const std::vector<int>& tet, std::vector<int>& slotStart, std::vector<std::uint32_t>& slots) {
    const size_t n = static_cast<size_t>(nTets);
    slotStart.assign(static_cast<size_t>(nNodes) + 1, 0);
    for (size_t k = 0; k < 4 * n; ++k) ++slotStart[static_cast<size_t>(tet[k]) + 1];
    for (size_t i = 0; i < static_cast<size_t>(nNodes); ++i) slotStart[i + 1] += slotStart[i];
    std::vector<int> fill(slotStart.begin(), slotStart.end() - 1);
    slots.resize(4 * n);
    // by element, then corner: the order of the node's sum (a node is one corner of an element at most)
    for (size_t e = 0; e < n; ++e)
        for (size_t a = 0; a < 4; ++a) {
            const int node = tet[a * n + e];
            slots[static_cast<size_t>(fill[static_cast<size_t>(node)]++)] = static_cast<std::uint32_t>(4 * e + a);
        }
}

StepSetup buildStepSetup(const core::Component& owner, const core::MechanicalGroup& g) {
    StepSetup s;
    core::BaseMechanicalState& state = *g.state;
    readIntegrator(*g.integrator, s);
    const core::BaseForceField* tled = nullptr;
    const size_t nNodes = state.size();
    s.ext.assign(3 * nNodes, 0.0);
    Positions ext(nNodes, Vec3::Zero());
    for (core::BaseForceField* ff : g.forceFields) {
        if (ff->className() == "TLEDForceField") {
            if (tled) unsupported(*ff, "a second TLEDForceField on one state");
            tled = ff;
            readTLED(*ff, s);
        } else if (ff->className() == "ConstantForce") {
            if (const auto* c = ff->findParam("curve"); c && c->isSet()) unsupported(*ff, "ConstantForce with a load curve");
            ff->addForce(state, ext, 0.0);  // constant: its force once, summed with the others
        } else {
            unsupported(*ff, ff->className());
        }
    }
    if (!tled) owner.fail("the state '" + state.path() + "' has no TLEDForceField: the device step runs TLED only");
    for (const core::BaseConstraint* c : g.constraints)
        if (c->className() != "FixedConstraint") unsupported(*c, c->className());
    if (nNodes >= (size_t(1) << 31) || tled->tetrahedra()->size() >= (size_t(1) << 30))
        owner.fail("the mesh is too large for the device step's 32-bit indices");
    for (size_t i = 0; i < nNodes; ++i)
        for (int c = 0; c < 3; ++c) s.ext[3 * i + static_cast<size_t>(c)] = ext[i][c];
    s.nNodes = static_cast<int>(nNodes);
    s.nTets = static_cast<int>(tled->tetrahedra()->size());
    tetGeometry(*tled, state.x0(), *tled->tetrahedra(), s);
    buildSlots(s.nTets, s.nNodes, s.tet, s.slotStart, s.slots);
    s.mass = g.mass;
    s.invMass = g.invMass;
    s.fixed.assign(nNodes, 0);
    for (const core::BaseConstraint* c : g.constraints) {
        const std::array<bool, 3> axes = c->constrainedAxes();
        const std::uint8_t bits = static_cast<std::uint8_t>((axes[0] ? 1 : 0) | (axes[1] ? 2 : 0) | (axes[2] ? 4 : 0));
        for (int node : c->constrainedNodes()) s.fixed[static_cast<size_t>(node)] |= bits;
    }
    return s;
}

NodeParams<double> nodeParams(const core::MechanicalGroup& g, const StepSetup& s, double t, double dt, double kick) {
    const double c = g.gravityCurve ? g.gravityCurve->value(t) : 1.0;
    NodeParams<double> p;
    for (int i = 0; i < 3; ++i) p.g[i] = c * g.gravity[i];
    p.dt = dt;
    p.kick = kick;
    p.alpha = s.damping;
    return p;
}

std::string deviceLawNames() {
    std::string out;
    materials::detail::forEachIn([&](auto* tag) { out += (out.empty() ? "" : ", ") + std::string(std::decay_t<decltype(*tag)>::kName); },
                                 DeviceMaterials{});
    return out;
}

} // namespace fascia::cuda
