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
#include <cstring>
#include <string>
#include <type_traits>
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

/// A row of FASCIA_STEP_ARRAYS (StepLayout.h, where its columns are explained) as the host reads it.
struct StepArrayInfo {
    enum class Extent { One, Tets, Hexes, Tris, Quads, Nodes, NodesAndOne, NodeLoads, Corners, TetTerms, HexTerms, Targets };
    enum class Need { All, Some, ByElement, ByNode };
    enum class From { Setup, Zero, Unset };
    const char* name;
    int index;  ///< its row, from 0
    Extent extent;
    size_t width;
    Need need;
    From from;
};

/// The number of rows of FASCIA_STEP_ARRAYS.
#define FASCIA_STEP_ROW(...) +1
constexpr int kStepArrayRows = 0 FASCIA_STEP_ARRAYS(FASCIA_STEP_ROW);
#undef FASCIA_STEP_ROW

/// width times the extent of row a for s: its length where it has values.
size_t stepLength(const StepArrayInfo& a, const StepSetup& s);

/// Whether row a has values in the order of s's corner forces (false: ByElement in node order, ByNode by element).
bool inForceOrder(const StepArrayInfo& a, const StepSetup& s);

/// The counts of s's arrays.
StepCounts stepCounts(const StepSetup& s);

/// The StepSetup array a row of from=Setup copies (a member pointer), nullptr for the others.
#define FASCIA_STEP_FROM_Setup(name) &StepSetup::name
#define FASCIA_STEP_FROM_Zero(name) nullptr
#define FASCIA_STEP_FROM_Unset(name) nullptr

/// f(info, &StepArrays<T>::name, setup, stores.name...) for each row of FASCIA_STEP_ARRAYS, in its
/// order: setup the StepSetup array it is copied from (a member pointer; nullptr when it is not),
/// stores any number of StepStores (or structs with a member per row), the row's member of each.
template <class T, class F, class... Stores>
void forEachStepArray(F&& f, Stores&... stores) {
    int index = 0;
#define FASCIA_STEP_VISIT(type, name, extent, width, need, from)                                                               \
    f(StepArrayInfo{#name, index++, StepArrayInfo::Extent::extent, width, StepArrayInfo::Need::need, StepArrayInfo::From::from}, \
      &StepArrays<T>::name, FASCIA_STEP_FROM_##from(name), stores.name...);
    FASCIA_STEP_ARRAYS(FASCIA_STEP_VISIT)
#undef FASCIA_STEP_VISIT
}

/// A Store of each row's element type, by the row's name: StepArraysHost's vectors, the device
/// buffers of CudaRunner.cu.
template <class T, template <class...> class Store>
struct StepStores {
#define FASCIA_STEP_STORE(type, name, ...) Store<std::remove_const_t<type>> name;
    FASCIA_STEP_ARRAYS(FASCIA_STEP_STORE)
#undef FASCIA_STEP_STORE
};

/// The arrays of a setup in the scalar T, as host vectors (what an upload copies to the device;
/// the emulation's "device" copy is a second set of them).
template <class T>
struct StepArraysHost : StepCounts, StepStores<T, std::vector> {
    /// The StepArrays over these vectors (a null pointer for an empty one, as on the device).
    StepArrays<T> view() {
        StepArrays<T> d;
        static_cast<StepCounts&>(d) = *this;
        forEachStepArray<T>([&](const StepArrayInfo&, auto at, auto, auto& a) { d.*at = a.empty() ? nullptr : a.data(); }, *this);
        return d;
    }
};

/// The arrays of s converted to T, with u, v, the targets, du and the Prony states zero, each row
/// as its columns say (StepLayout.h).
template <class T>
StepArraysHost<T> toArrays(const StepSetup& s) {
    StepArraysHost<T> h;
    static_cast<StepCounts&>(h) = stepCounts(s);
    forEachStepArray<T>(
        [&](const StepArrayInfo& a, auto, auto setup, auto& to) {
            if (!inForceOrder(a, s)) return;  // (the forces of the other order: none)
            if constexpr (std::is_member_object_pointer_v<decltype(setup)>) {
                to.assign((s.*setup).begin(), (s.*setup).end());
            } else {
                typename std::decay_t<decltype(to)>::value_type x{};
                if (a.from == StepArrayInfo::From::Unset) std::memset(&x, 0xff, sizeof x);
                to.assign(stepLength(a, s), x);
            }
        },
        h);
    return h;
}

/// What in the arrays `dev` (StepArraysHost, or CudaRunner.cu's device buffers: a .size() and a
/// .data() per row) and in d pointing at them does not match the table for s, a line per row (the
/// row's name first): a length that is not the one toArrays gives (an array the upload left out),
/// a pointer that is not its array's (null for no values), an array of the setup whose length is
/// not the one the table gives; and counts that are not s's. Empty when they match.
template <class T, class Stores>
std::vector<std::string> checkLayout(const StepSetup& s, const StepArrays<T>& d, const Stores& dev) {
    std::vector<std::string> out;
    const StepCounts c = stepCounts(s), &dc = d;
    if (dc.nTets != c.nTets || dc.nHexes != c.nHexes || dc.nNodes != c.nNodes || dc.nTris != c.nTris || dc.nQuads != c.nQuads ||
        dc.nLoads != c.nLoads)
        out.push_back("the counts are not the setup's");
    forEachStepArray<T>(
        [&](const StepArrayInfo& a, auto at, auto setup, const auto& held) {
            const std::string name = a.name;
            const size_t full = stepLength(a, s);
            size_t want = inForceOrder(a, s) ? full : 0;
            if constexpr (std::is_member_object_pointer_v<decltype(setup)>) {
                const size_t given = (s.*setup).size();
                if (given != full && !(given == 0 && a.need == StepArrayInfo::Need::Some))
                    out.push_back(name + ": the setup gives " + std::to_string(given) + " values, the table " + std::to_string(full));
                if (want > 0) want = given;
            }
            const size_t n = held.size();
            const void* p = d.*at;
            if (n != want) out.push_back(name + ": " + std::to_string(n) + " values on the device, " + std::to_string(want) + " expected");
            else if (p != (n > 0 ? static_cast<const void*>(held.data()) : nullptr))
                out.push_back(name + (p ? ": its pointer is not its array's" : ": no pointer to its " + std::to_string(n) + " values"));
        },
        dev);
    return out;
}

/// Throws an internal error listing `errors` (checkLayout's) unless there are none: a runner's
/// check of its arrays once uploaded.
void requireLayout(const std::vector<std::string>& errors);

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
