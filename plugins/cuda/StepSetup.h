#pragma once
/// Host-side setup of the device step, shared by the GPU path and its CPU emulation: what a
/// mechanical group holds, checked against what the device step can run, turned into the arrays
/// of StepLayout.h (once, at init): the material groups with their element lists and the fibre
/// directions per element, resolved as TLEDForceField resolves them (elements/GroupMaterials.h,
/// elements/FibreField.h); and the per-step parameters (the node kernel's, the Prony series'
/// coefficients).
#include "fascia/cuda/StepLayout.h"
#include "fascia/materials/Material.h"
#include "fascia/sim/LoadTerms.h"
#include "fascia/sim/Mechanics.h"

#include <cstdint>
#include <vector>

namespace fascia::viscoelastic {
class ViscoelasticProny;
}

namespace fascia::cuda {

/// Everything the kernels read, in double and in the layout of StepArrays (see there), built once
/// from a group by buildStepSetup.
struct StepSetup {
    int nTets = 0, nHexes = 0, nNodes = 0;
    std::vector<int> tet, hex;
    std::vector<double> dN, vol;
    /// The element force field: TLEDForceField (dN), or HEMLForceField, whose tetrahedra run HEML's
    /// edge form (eV, eG, eInvDetV, ew4, ew6; in its mass-spring mode ekk and elen0, no material)
    enum class Form { TLED, Edges } form = Form::TLED;
    core::BaseForceField* elastic = nullptr;  ///< that force field
    bool springs = false;
    std::vector<double> eV, eG, eInvDetV, ew4, ew6, ekk, elen0;
    std::vector<double> hdN, hgC, hvol, hgK;  ///< hexahedra
    /// faces under pressure (StepArrays tri, quad, triD, quadD, triLoad, quadLoad) and their loads
    int nTris = 0, nQuads = 0;
    std::vector<int> tri, quad, triLoad, quadLoad;
    std::vector<double> triD, quadD;
    std::vector<const core::PressureLoad*> pressures;
    std::vector<int> slotStart;
    std::vector<std::uint32_t> slots;
    /// each corner's position among the slots (StepArrays tetSlot, ...), and whether the element
    /// kernels write their forces there (CudaStep forceOrder="node") or by element
    std::vector<std::uint32_t> tetSlot, hexSlot, triSlot, quadSlot;
    bool forcesInNodeOrder = false;
    std::vector<double> ext, mass, invMass;
    std::vector<const core::NodalLoad*> loads;  ///< the ConstantForce components with a curve (StepArrays loadF)
    std::vector<double> loadF;                  ///< their forces at c = 1, see StepArrays
    std::vector<std::uint32_t> hold;  ///< 3 per node, see StepArrays
    std::vector<int> targetAt;        ///< target j is axis targetAt[j] % 3 of node targetAt[j] / 3
    /// The elements of one material (TLEDForceField's one material, or one of its groupMaterials),
    /// which its law's element kernels run over.
    struct Group {
        const materials::BaseMaterial* material = nullptr;
        /// its tetrahedra and hexahedra (indices of their kind, increasing); both empty when the
        /// setup has this one group, whose kernels then run over every element with no list
        std::vector<int> tets, hexes;
        elements::Vec33<double> a0{1, 0, 0}, b0{0, 1, 0};  ///< the material's fibre directions (unit)
        double restShift = 0;  ///< PronyParams::restShift of the material
    };
    std::vector<Group> groups;  ///< by material, in order of first appearance (tetrahedra, then hexahedra)
    /// fibre directions per element (StepArrays fa, fb, hfa, hfb: row i at i n + e) from
    /// TLEDForceField's fibreArray or fibreArray2; false: each group's a0, b0
    bool fibresPerElement = false;
    std::vector<double> fa, fb, hfa, hfb;
    double J0 = 0.4;
    double hourglass = 0;  ///< TLEDForceField's hourglassStiffness (kappa of the stiffnesses hgK)
    enum class Scheme { SemiImplicitEuler, CentralDifference } scheme = Scheme::SemiImplicitEuler;
    double damping = 0;                                ///< the integrator's alpha
    bool halfStepStart = true;                         ///< SemiImplicitEuler's leapfrog start
    /// A Prony series beside the TLEDForceField (TLED eq. (24), (30)): the parts it relaxes and its
    /// number of terms (its coefficients: pronyCoefficients, each step).
    struct Series {
        const viscoelastic::ViscoelasticProny* prony = nullptr;
        bool iso = false, vol = false;
        int terms = 0;
    };
    std::vector<Series> series;  ///< in the order TLEDForceField takes them (its node's order)
    /// the terms of all series (the states' k, StepArrays Y)
    int pronyTerms() const {
        int n = 0;
        for (const Series& x : series) n += x.terms;
        return n;
    }
};

/// Checks that the device step can run every component of the group (one TLEDForceField on
/// tetrahedra and hexahedra, or one HEMLForceField, with a built-in law of DeviceLaws.h per
/// material, its groupMaterials and fibre arrays, and the ViscoelasticProny series of its node; or
/// HEMLForceField's mass-spring mode; FixedConstraint,
/// PrescribedDisplacement, ConstantForce (at most kMaxLoads with a load curve), the masses,
/// SemiImplicitEuler or CentralDifference) and builds its arrays. Anything else is a located error at
/// the component, raised through owner's message style when the component has no location of its
/// own. The slot lists are built here: node n's (element, corner) pairs by element, then corner.
StepSetup buildStepSetup(const core::Component& owner, const core::MechanicalGroup& g);

/// The slot lists of s's elements (tet and hex as in StepArrays): s.slotStart (nNodes + 1) and s.slots.
void buildSlots(StepSetup& s);

/// The arrays of a setup in the scalar T, as host vectors (what an upload copies to the device;
/// the emulation's "device" copy is a second set of them).
template <class T>
struct StepArraysHost {
    int nTets = 0, nHexes = 0, nNodes = 0;
    std::vector<int> tet, hex, slotStart;
    std::vector<std::uint32_t> slots, tetSlot, hexSlot, triSlot, quadSlot;
    std::vector<T> sf;  ///< the forces in node order (empty by element)
    std::vector<T> eV, eG, eInvDetV, ew4, ew6, ekk, elen0;
    std::vector<T> dN, vol, ef, hdN, hgC, hvol, hgK, hef, Y, hY, ext, loadF, mass, invMass, u, v, tu, tv, du, react;
    std::vector<T> fa, fb, hfa, hfb;  ///< the fibre directions per element (empty without fibre arrays)
    int nLoads = 0;
    int nTris = 0, nQuads = 0;
    std::vector<int> tri, quad, triLoad, quadLoad;
    std::vector<T> triD, quadD, tf, qf;
    std::vector<std::uint32_t> hold;
    unsigned long long bad = ~0ull;

    /// The StepArrays over these vectors.
    StepArrays<T> view() {
        StepArrays<T> d;
        d.nTets = nTets;
        d.nNodes = nNodes;
        d.tet = tet.data();
        d.dN = dN.data();
        d.vol = vol.data();
        d.ef = ef.data();
        d.eV = eV.data();
        d.eG = eG.data();
        d.eInvDetV = eInvDetV.data();
        d.ew4 = ew4.data();
        d.ew6 = ew6.data();
        d.ekk = ekk.data();
        d.elen0 = elen0.data();
        d.nHexes = nHexes;
        d.hex = hex.data();
        d.hdN = hdN.data();
        d.hgC = hgC.data();
        d.hvol = hvol.data();
        d.hgK = hgK.data();
        d.hef = hef.data();
        d.fa = fa.data();
        d.fb = fb.data();
        d.hfa = hfa.data();
        d.hfb = hfb.data();
        d.Y = Y.data();
        d.hY = hY.data();
        d.slotStart = slotStart.data();
        d.slots = slots.data();
        d.ext = ext.data();
        d.nLoads = nLoads;
        d.nTris = nTris;
        d.nQuads = nQuads;
        d.tri = tri.data();
        d.quad = quad.data();
        d.triD = triD.data();
        d.quadD = quadD.data();
        d.triLoad = triLoad.data();
        d.quadLoad = quadLoad.data();
        d.tf = tf.data();
        d.qf = qf.data();
        d.tetSlot = tetSlot.empty() ? nullptr : tetSlot.data();
        d.hexSlot = hexSlot.empty() ? nullptr : hexSlot.data();
        d.triSlot = triSlot.empty() ? nullptr : triSlot.data();
        d.quadSlot = quadSlot.empty() ? nullptr : quadSlot.data();
        d.sf = sf.empty() ? nullptr : sf.data();
        d.loadF = loadF.data();
        d.mass = mass.data();
        d.invMass = invMass.data();
        d.hold = hold.data();
        d.tu = tu.data();
        d.tv = tv.data();
        d.u = u.data();
        d.v = v.data();
        d.du = du.data();
        d.react = react.data();
        d.bad = &bad;
        return d;
    }
};

/// The arrays of s converted to T, with u, v, the targets, du and the Prony states zero.
template <class T>
StepArraysHost<T> toArrays(const StepSetup& s) {
    const auto conv = [](const std::vector<double>& a) { return std::vector<T>(a.begin(), a.end()); };
    StepArraysHost<T> h;
    h.nTets = s.nTets;
    h.nNodes = s.nNodes;
    h.tet = s.tet;
    h.slotStart = s.slotStart;
    h.slots = s.slots;
    h.dN = conv(s.dN);
    h.vol = conv(s.vol);
    const bool byNode = s.forcesInNodeOrder;  // (then the slots' records instead of the elements')
    h.ef.assign(byNode ? 0 : 12 * static_cast<size_t>(s.nTets), T(0));
    h.eV = conv(s.eV);
    h.eG = conv(s.eG);
    h.eInvDetV = conv(s.eInvDetV);
    h.ew4 = conv(s.ew4);
    h.ew6 = conv(s.ew6);
    h.ekk = conv(s.ekk);
    h.elen0 = conv(s.elen0);
    h.nHexes = s.nHexes;
    h.hex = s.hex;
    h.hdN = conv(s.hdN);
    h.hgC = conv(s.hgC);
    h.hvol = conv(s.hvol);
    h.hgK = conv(s.hgK);
    h.hef.assign(byNode ? 0 : 24 * static_cast<size_t>(s.nHexes), T(0));
    h.fa = conv(s.fa);
    h.fb = conv(s.fb);
    h.hfa = conv(s.hfa);
    h.hfb = conv(s.hfb);
    h.Y.assign(6 * static_cast<size_t>(s.pronyTerms()) * static_cast<size_t>(s.nTets), T(0));
    h.hY.assign(6 * static_cast<size_t>(s.pronyTerms()) * static_cast<size_t>(s.nHexes), T(0));
    h.ext = conv(s.ext);
    h.loadF = conv(s.loadF);
    h.nLoads = static_cast<int>(s.loads.size());
    h.nTris = s.nTris;
    h.nQuads = s.nQuads;
    h.tri = s.tri;
    h.quad = s.quad;
    h.triLoad = s.triLoad;
    h.quadLoad = s.quadLoad;
    h.triD = conv(s.triD);
    h.quadD = conv(s.quadD);
    h.tf.assign(byNode ? 0 : 3 * static_cast<size_t>(s.nTris), T(0));
    h.qf.assign(byNode ? 0 : 12 * static_cast<size_t>(s.nQuads), T(0));
    if (byNode) {
        h.tetSlot = s.tetSlot;
        h.hexSlot = s.hexSlot;
        h.triSlot = s.triSlot;
        h.quadSlot = s.quadSlot;
        h.sf.assign(3 * s.slots.size(), T(0));
    }
    h.mass = conv(s.mass);
    h.invMass = conv(s.invMass);
    h.u.assign(3 * static_cast<size_t>(s.nNodes), T(0));
    h.v.assign(3 * static_cast<size_t>(s.nNodes), T(0));
    h.hold = s.hold;
    h.tu.assign(s.targetAt.size(), T(0));
    h.tv.assign(s.targetAt.size(), T(0));
    h.du.assign(3 * static_cast<size_t>(s.nNodes), T(0));
    h.react.assign(3 * static_cast<size_t>(s.nNodes), T(0));
    return h;
}

/// Tracks SemiImplicitEuler's velocity kick across steps as SemiImplicitEuler::step does: dt/2 on
/// the first step with halfStepStart, then (dt_old + dt)/2 (dt without halfStepStart).
struct KickRule {
    bool halfStepStart = true;
    bool started = false;
    double lastDt = 0;
    double next(double dt) {
        double kick = dt;
        if (!started) {
            started = true;
            if (halfStepStart) kick = 0.5 * dt;
        } else if (halfStepStart) {
            kick = 0.5 * (lastDt + dt);
        }
        lastDt = dt;
        return kick;
    }
};

/// Tracks CentralDifference's history across steps as CentralDifference::step does: a (re)start on
/// the first step and after a change of dt (its u(n-1) is for the old step), the backward-difference
/// velocity once a step with this dt was taken.
struct CentralRule {
    bool started = false;
    double lastDt = 0;
    long steps = 0;
    /// sets p.start and p.twoSteps for a step of dt
    void next(double dt, NodeParams<double>& p) {
        p.start = !started || lastDt != dt;
        if (p.start) steps = 0;
        started = true;
        lastDt = dt;
        p.twoSteps = steps > 0;
        ++steps;
    }
};

/// The face kernel's parameters of the step from t: the pressure of each SurfacePressure at t.
template <class T>
FaceParams<T> faceParams(const StepSetup& s, double t) {
    FaceParams<T> q;
    for (size_t k = 0; k < s.pressures.size(); ++k) q.p[k] = T(s.pressures[k]->pressureAt(t));
    return q;
}

/// The same in the scalar T of a runner.
template <class T>
FaceParams<T> faceParamsIn(const FaceParams<double>& q) {
    FaceParams<T> out;
    for (int k = 0; k < kMaxPressures; ++k) out.p[k] = T(q.p[k]);
    return out;
}

/// The node kernel's parameters of the step from t to t + dt in double (g(t) with the group's
/// gravity curve; the kick for SemiImplicitEuler, a and b for CentralDifference).
NodeParams<double> nodeParams(const core::MechanicalGroup& g, const StepSetup& s, double t, double dt, double kick);

/// The same in the scalar T of a runner.
template <class T>
NodeParams<T> nodeParamsIn(const NodeParams<double>& p) {
    NodeParams<T> q;
    for (int i = 0; i < 3; ++i) q.g[i] = T(p.g[i]);
    for (int k = 0; k < kMaxLoads; ++k) q.load[k] = T(p.load[k]);
    q.dt = T(p.dt);
    q.kick = T(p.kick);
    q.alpha = T(p.alpha);
    q.a = T(p.a);
    q.b = T(p.b);
    q.start = p.start;
    q.twoSteps = p.twoSteps;
    q.step = p.step;
    return q;
}

/// A_i and B_i of s's series (TLED eq. (30)) for a history step of `elapsed` s at the scene's time
/// step dt (viscoelastic/HistoryClock.h stepCoefficients), term by term, the series in order.
void pronyCoefficients(const StepSetup& s, double elapsed, double dt, std::vector<double>& A, std::vector<double>& B);

/// The element kernels' Prony series of s in T for the material group g (its restShift), with no
/// relaxation yet (A = B = 0: setCoefficients).
template <class T>
PronyParams<T> pronyParams(const StepSetup& s, const StepSetup::Group& g) {
    PronyParams<T> q;
    q.series = static_cast<int>(s.series.size());
    for (size_t i = 0; i < s.series.size(); ++i) {
        q.terms[i] = s.series[i].terms;
        q.iso[i] = s.series[i].iso;
        q.vol[i] = s.series[i].vol;
    }
    q.restShift = static_cast<T>(g.restShift);
    return q;
}

/// The element kernels' parameters of s's material group g in T, its law `law` (g.material's).
template <class T, class Law>
ElementParams<Law, T> elementParams(const StepSetup& s, const StepSetup::Group& g, const Law& law) {
    ElementParams<Law, T> p{law, static_cast<T>(s.J0), {T(g.a0.x), T(g.a0.y), T(g.a0.z)}, {T(g.b0.x), T(g.b0.y), T(g.b0.z)}, {}};
    p.prony = pronyParams<T>(s, g);
    return p;
}

/// Sets q's coefficients from A and B as pronyCoefficients gives them (term by term, the series in order).
template <class T>
void setCoefficients(PronyParams<T>& q, const std::vector<double>& A, const std::vector<double>& B) {
    size_t k = 0;
    for (int i = 0; i < q.series; ++i)
        for (int t = 0; t < q.terms[i]; ++t, ++k) {
            q.A[i][t] = static_cast<T>(A.at(k));
            q.B[i][t] = static_cast<T>(B.at(k));
        }
}

/// The targets at the end tEnd = t + dt of a step (StepArrays tu, tv): the group's constraints
/// project the host state at tEnd in their order (projectState, through the core's role only),
/// which then gives each target's displacement and velocity (the step's result overwrites the host
/// state after it).
void motionTargets(core::MechanicalGroup& g, const StepSetup& s, double tEnd, std::vector<double>& tu, std::vector<double>& tv);

} // namespace fascia::cuda
