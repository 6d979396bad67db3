#pragma once
/// The data layout of the device step (docs/design.md, section 4.7): every array of the mesh as a
/// plain pointer, structure of arrays over the whole mesh (the Prony states and the fibre directions
/// per element too), so that consecutive threads (elements, nodes) read consecutive addresses. The
/// GPU path (CudaRunner.cu) and the CPU emulation (EmulatedRunner.h) both fill it from the same host
/// arrays (StepArraysHost, StepSetup.h) and run the same kernel bodies over it (StepKernels.h). With
/// materials per mesh group (TLEDForceField's groupMaterials) the element kernels of each group run
/// over that group's element list (StepSetup::Group); each element still writes its own slots.
#include "fascia/elements/Tensor3.h"

#include <cstdint>

namespace fascia::cuda {

/// The arrays of one step, scalar T (float or double). Tetrahedron e, corner a (0..3), component i:
///   tet[a nTets + e]             node of corner a
///   dN[(3 (a-1) + i) nTets + e]  dN_a/dX_i for a = 1..3 (dN_0 = -(dN_1 + dN_2 + dN_3))
///   vol[e]                       rest volume
///   ef[3 (4 e + a) + i]          the element's force on its corner a (written by the element
///                                kernel, each element to its own slots: no atomics), by element
///                                and corner so that the node kernel reads a slot's three
///                                components from one 32-byte sector (a row per component took
///                                three), and a warp's writes cover one contiguous range
/// With HEMLForceField instead of TLED (StepSetup::Form::Edges: HEML's edge form, fascia/elements/
/// EdgeForm.h), tetrahedron e keeps tet, vol and ef, and reads instead of dN:
///   eV[(3 (a-1) + i) nTets + e]  rest edge V_a = X_a - X_0 (a = 1..3): the current edges are
///                                these plus u_a - u_0 (accurate in float, as for the faces)
///   eG[q nTets + e]              G = V^-1 V^-T (xx yy zz xy yz xz)
///   eInvDetV[e]                  1 / det V (signed)
///   ew4[i nTets + e], ew6[...]   V^-1 a0 and V^-1 b0 of its fibre directions (empty when no
///                                material reads I4, I6)
///   ekk[k nTets + e], elen0[...] mass-spring mode (HEML eq. (38)): the stiffness share and rest
///                                length of edge k (empty otherwise)
/// Hexahedron e (uniform strain with hourglass control, fascia/elements/Hourglass.h), corner a (0..7):
///   hex[a nHexes + e]            node of corner a (VTK order)
///   hdN[(3 a + i) nHexes + e]    volume-averaged dN_a/dX_i
///   hgC[(3 q + i) nHexes + e]    hourglass vector c_q (q = 0..3)
///   hvol[e], hgK[e]              rest volume, hourglass stiffness K
///   hef[3 (8 e + a) + i]         the element's force on its corner a
/// Fibre directions per element (TLEDForceField's fibreArray, fibreArray2: unit length, those of the
/// element's material where its array is not given; empty when no array is given, and the element
/// kernels then read the directions of the group's material, ElementParams):
///   fa[i nTets + e], fb[i nTets + e]    a0, b0 of tetrahedron e (fb empty when no material reads b0,
///                                       fa when none reads a0)
///   hfa[i nHexes + e], hfb[i nHexes + e]  the same for hexahedron e
/// Prony series (ViscoelasticProny beside the TLEDForceField, TLED eq. (24), (30); PronyParams),
/// term k counting the terms of every series in order (term t of series s at k = the terms of the
/// series before s + t), stress component c (xx yy zz xy yz xz):
///   Y[(6 k + c) nTets + e]       the state Y_k of tetrahedron e, updated in place by its element
///                                kernel, once per element pass (zero at the start; empty without
///                                a series)
///   hY[(6 k + c) nHexes + e]     the same for hexahedron e
///                                (with HEML: one series, and c counts the six link coefficients
///                                R_k of its relaxed part instead, HEMLForceField.h)
/// Faces under a SurfacePressure (its follower load, fascia/elements/Pressure.h), triangle f and
/// quadrilateral f, corner a:
///   tri[a nTris + f], quad[a nQuads + f]   node of corner a (turned outwards)
///   triD[(3 (a-1) + i) nTris + f]          rest difference X_a - X_0 (a = 1, 2), quadD likewise
///                                (a = 1..3): the current ones are these plus u_a - u_0
///   triLoad[f], quadLoad[f]      the face's SurfacePressure (FaceParams::p)
///   tf[3 f + i]                  the force on each corner of triangle f (one for all three)
///   qf[3 (4 f + a) + i]          the force on corner a of quadrilateral f
/// The corner forces in node order instead (CudaStep forceOrder="node", for a GPU to compare the two):
///   tetSlot[4 e + a], hexSlot[8 e + a], triSlot[3 f + a], quadSlot[4 f + a]
///                                the position of each corner's slot in `slots` (below)
///   sf[3 s + i]                  the force of slot s: each element writes its corners there (a
///                                triangle its one force to its 3 corners), so that the node kernel
///                                reads its slots' forces as one contiguous run, in the same order
///                                (the same bits); ef, hef, tf and qf are then empty
/// Node n, component i:
///   slots[slotStart[n] .. slotStart[n + 1])  its (element, corner) pairs as 8 e + a, e counting the
///                                tetrahedra, then the hexahedra (e - nTets), then the triangles
///                                and the quadrilaterals under pressure, by element then corner:
///                                the fixed order of the sum (docs/design.md, principle 5)
///   u[3 n + i], v[3 n + i]       displacement from the rest position, velocity (u, not x: F is
///                                formed from displacements, accurate in float; lesson 6)
///   ext[3 n + i]                 external force (ConstantForce), mass[n], invMass[n] (0: no mass)
///   loadF[3 (k nNodes + n) + i]  the force of curved load k (a ConstantForce with a curve) at c = 1,
///                                k < nLoads: the node adds NodeParams::load[k] times it
///   hold[3 n + i]                axis i of node n: 0 free, 1 held at rest (FixedConstraint), 2 + j
///                                following target j (PrescribedDisplacement): its force removed,
///                                then u = tu[j], v = tv[j] at the end of the step (the last
///                                constraint that holds the axis decides, as in projectState)
///   tu[j], tv[j]                 the targets' displacement and velocity at t + dt (set every step)
///   du[3 n + i]                  CentralDifference: the increment u(n) - u(n-1) of the last step
///   react[3 n + i]               the reaction at a held axis: minus the force its constraint
///                                removed in the last node pass (MechanicalGroup::applyConstraints'
///                                f after - f before); 0 on a free axis (never written)
///   bad[0]                       the first step whose node pass left a u or v that is not finite
///                                (all ones: none; the state stays on the device, so the host reads
///                                this one number to check it: CudaStep's checkEvery)
/// (StepArrays below: the pointers of the rows of FASCIA_STEP_ARRAYS, and the counts of StepCounts.)

/// The counts the arrays' lengths are made of (and the kernels' loops run to).
struct StepCounts {
    int nTets = 0, nHexes = 0, nNodes = 0;
    int nTris = 0, nQuads = 0;
    int nLoads = 0;
};

/// The arrays above, each declared once, here: one row per array,
///   X(type, name, extent, width, need, from)
///   type   the element as the kernels see it (const: they only read it)
///   extent, width  its length: width values per tetrahedron (Tets), hexahedron (Hexes), triangle or
///          quadrilateral under pressure (Tris, Quads), node (Nodes), node and curved load
///          (NodeLoads: nNodes nLoads), slot (Corners: 4 nTets + 8 nHexes + 3 nTris + 4 nQuads),
///          Prony term and element (TetTerms, HexTerms: StepSetup::pronyTerms), target of a
///          PrescribedDisplacement (Targets); NodesAndOne: nNodes + 1 values; One: one value
///   need   All: always that length; Some: that length or none, as the setup gives it (the form,
///          the laws, the fibre arrays, see above); ByElement, ByNode: that length with the corner
///          forces by element (resp. in node order, CudaStep forceOrder="node"), else none
///   from   Setup: StepSetup's array of the same name, in the element type; Zero: zeros; Unset:
///          every bit set (bad: no bad step yet)
/// The rows declare StepArrays' pointers (below), StepArraysHost's vectors and CudaRunner.cu's
/// device buffers (StepStores, StepSetup.h), and what fills and checks them visits them
/// (forEachStepArray: toArrays, view, the uploads, checkLayout), so that an array is added by a row
/// here (and the StepSetup code that fills it, and the kernels that read it). An X-macro rather than
/// a constexpr table of member pointers: StepArrays, what the kernels take, has to be a plain struct
/// of named pointers, and member pointers can only point at members declared elsewhere (here, in
/// StepArraysHost and CudaRunner.cu again: the copies these rows replace); the rows also give each
/// array its name as text (#name, for checkLayout's messages), and are plain text to nvcc's device
/// pass. A row names the scalar T: it expands where T is the step's scalar.
#define FASCIA_STEP_ARRAYS(X)                             \
    X(const int, tet, Tets, 4, All, Setup)                \
    X(const T, dN, Tets, 9, Some, Setup)                  \
    X(const T, vol, Tets, 1, All, Setup)                  \
    X(T, ef, Tets, 12, ByElement, Zero)                   \
    X(const T, eV, Tets, 9, Some, Setup)                  \
    X(const T, eG, Tets, 6, Some, Setup)                  \
    X(const T, eInvDetV, Tets, 1, Some, Setup)            \
    X(const T, ew4, Tets, 3, Some, Setup)                 \
    X(const T, ew6, Tets, 3, Some, Setup)                 \
    X(const T, ekk, Tets, 6, Some, Setup)                 \
    X(const T, elen0, Tets, 6, Some, Setup)               \
    X(const int, hex, Hexes, 8, All, Setup)               \
    X(const T, hdN, Hexes, 24, All, Setup)                \
    X(const T, hgC, Hexes, 12, All, Setup)                \
    X(const T, hvol, Hexes, 1, All, Setup)                \
    X(const T, hgK, Hexes, 1, All, Setup)                 \
    X(T, hef, Hexes, 24, ByElement, Zero)                 \
    X(const T, fa, Tets, 3, Some, Setup)                  \
    X(const T, fb, Tets, 3, Some, Setup)                  \
    X(const T, hfa, Hexes, 3, Some, Setup)                \
    X(const T, hfb, Hexes, 3, Some, Setup)                \
    X(T, Y, TetTerms, 6, All, Zero)                       \
    X(T, hY, HexTerms, 6, All, Zero)                      \
    X(const int, tri, Tris, 3, All, Setup)                \
    X(const int, quad, Quads, 4, All, Setup)              \
    X(const T, triD, Tris, 6, All, Setup)                 \
    X(const T, quadD, Quads, 9, All, Setup)               \
    X(const int, triLoad, Tris, 1, All, Setup)            \
    X(const int, quadLoad, Quads, 1, All, Setup)          \
    X(T, tf, Tris, 3, ByElement, Zero)                    \
    X(T, qf, Quads, 12, ByElement, Zero)                  \
    X(const std::uint32_t, tetSlot, Tets, 4, ByNode, Setup)   \
    X(const std::uint32_t, hexSlot, Hexes, 8, ByNode, Setup)  \
    X(const std::uint32_t, triSlot, Tris, 3, ByNode, Setup)   \
    X(const std::uint32_t, quadSlot, Quads, 4, ByNode, Setup) \
    X(T, sf, Corners, 3, ByNode, Zero)                    \
    X(const int, slotStart, NodesAndOne, 1, All, Setup)   \
    X(const std::uint32_t, slots, Corners, 1, All, Setup) \
    X(const T, ext, Nodes, 3, All, Setup)                 \
    X(const T, loadF, NodeLoads, 3, All, Setup)           \
    X(const T, mass, Nodes, 1, All, Setup)                \
    X(const T, invMass, Nodes, 1, All, Setup)             \
    X(const std::uint32_t, hold, Nodes, 3, All, Setup)    \
    X(const T, tu, Targets, 1, All, Zero)                 \
    X(const T, tv, Targets, 1, All, Zero)                 \
    X(T, u, Nodes, 3, All, Zero)                          \
    X(T, v, Nodes, 3, All, Zero)                          \
    X(T, du, Nodes, 3, All, Zero)                         \
    X(T, react, Nodes, 3, All, Zero)                      \
    X(unsigned long long, bad, One, 1, All, Unset)

/// The arrays of one step, scalar T (float or double), as documented above: a pointer per row of
/// FASCIA_STEP_ARRAYS (null for an array of no values), and the counts.
template <class T>
struct StepArrays : StepCounts {
#define FASCIA_STEP_POINTER(type, name, ...) type* name = nullptr;
    FASCIA_STEP_ARRAYS(FASCIA_STEP_POINTER)
#undef FASCIA_STEP_POINTER
};

/// The most Prony series (one per part of the response, or one for both) and terms per series the
/// element kernels take (PronyParams); more is a located error at setup (StepSetup.cpp).
constexpr int kMaxSeries = 2, kMaxTerms = 8;

/// The Prony series of the element kernels (TLED eq. (24), (30)): series s relaxes the isochoric
/// part of S (iso[s]), the volumetric part (vol[s]) or both, with terms[s] terms of coefficients
/// A[s][t], B[s][t] (those of the step's time step, set every time they change; zero: no
/// relaxation); restShift is the s of s ln J moved from the isochoric to the volumetric part of the
/// response (materials/RelaxationSplit.h; 0 unless a series relaxes one part alone). series = 0:
/// the elastic kernels, unchanged.
template <class T>
struct PronyParams {
    int series = 0;
    int terms[kMaxSeries] = {};
    bool iso[kMaxSeries] = {}, vol[kMaxSeries] = {};
    T A[kMaxSeries][kMaxTerms] = {}, B[kMaxSeries][kMaxTerms] = {};
    T restShift = 0;
};

/// What the element kernel needs besides the arrays, for one material group: the law (by value,
/// its parameters as the material holds them), J0, the fibre directions of the material (those of
/// every element of the group, unless given per element: StepArrays fa, fb) and the Prony series
/// (with the group's restShift).
template <class Law, class T>
struct ElementParams {
    Law law;
    T J0;
    elements::Vec33<T> a0, b0;
    PronyParams<T> prony;
};

/// The node kernel's step: g(t) (gravity, scaled by its curve), dt and the damping alpha; for
/// SemiImplicitEuler (HEML eq. (32)) the velocity kick of this step (dt, or dt/2 on the first step of
/// the leapfrog start); for CentralDifference (TLED section 2) a = alpha dt/2 and b = a / (1 + a)
/// (its c2 = 1 - a and c1 = 1 / (1 + a) = 1 - b, which in float would hold a to 1e-3 only: b and a
/// keep it to 1e-7), whether this step (re)starts the scheme (x(-1) from x(0), v(0), a(0)) and
/// whether a step with this dt came before (the backward-difference velocity); the step's number
/// (MechanicalGroup::stepIndex), kept in StepArrays::bad when the step leaves a state that is not
/// finite; the factors c_k(t) of the curved loads at the start of the step (ConstantForce's F(t) = c(t) F).
/// The most ConstantForce components with a load curve the node kernel takes (a located error beyond).
constexpr int kMaxLoads = 4;

/// The most SurfacePressure components the face kernel takes (a located error beyond).
constexpr int kMaxPressures = 4;

/// The face kernel's step: the pressure c(t) p of each SurfacePressure at the start of the step.
template <class T>
struct FaceParams {
    T p[kMaxPressures] = {};
};

template <class T>
struct NodeParams {
    T g[3];
    T load[kMaxLoads] = {};  ///< c_k(t) of the curved loads (StepArrays::loadF)
    T dt, kick, alpha;
    T a = 0, b = 0;
    bool start = false, twoSteps = false;
    unsigned long long step = 0;
};

} // namespace fascia::cuda
