#pragma once
/// Total Lagrangian explicit dynamics (TLED) internal forces, Taylor et al. (2009) section 2.
///
/// Per element, at each evaluation:
///   F = I + sum_a u_a (x) dN_a/dX          (u = x - X; shape-function derivatives precomputed)
///   S = 2 dW/dC = 2 (dI1 I + dI2 (I1 I - C) + dI4 A0 + dI6 B0) + (dJiso + dJvol) J C^-1
///   f_a = -V P dN_a/dX,  P = F S            (TLED eq. (1)-(3): f = V B^T S, with the sign of a force
///                                            acting on the node: the paper's f~ is subtracted)
/// with W from the shared material library (fascia/materials/Laws.h), so every law runs here and
/// in HEMLForceField unchanged. Without viscosity P is formed directly as
///   P = 2 dI1 F + 2 dI2 (I1 F - F C) + 2 dI4 (F a0)(x)a0 + 2 dI6 (F b0)(x)b0 + (dJiso + dJvol) cof F
/// (F J C^-1 = cof F), which needs no inverse and no division (docs/performance.md, lesson 1).
///
/// Elements
/// - 4-node tetrahedra: constant derivatives, V = |det[X1-X0, X2-X0, X3-X0]| / 6 (TLED eq. (3)).
/// - 8-node hexahedra (VTK/Gmsh node order), one integration point (TLED eq. (2)) in the uniform-strain
///   form of Flanagan and Belytschko (1981): dN_a/dX is the volume average (1/V) int dN_a/dX dV and V
///   the exact volume (both by 2x2x2 Gauss quadrature, exact for trilinear geometry). For
///   parallelepipeds this is the centre-point B_l and 8 det J of eq. (2); for distorted elements it
///   keeps the patch test exact.
///   Hourglass control (Flanagan and Belytschko 1981, in the total Lagrangian form of Joldes, Wittek
///   and Miller 2008): with the hourglass base vectors h_1..4 = (xi eta, eta zeta, zeta xi,
///   xi eta zeta) at the nodes,
///     gamma_k = h_k - (h_k . X) dN/dX    (8 values per k, orthogonal to every linear field)
///     f_a^HG = -K sum_k gamma_ka sum_b gamma_kb u_b,   K = kappa_HG (lambda + 2 mu) V (sum_a |dN_a/dX|^2) / 8
///   kappa_HG = hourglassStiffness, lambda + 2 mu = bulk + 4/3 shear modulus of the element's material.
///   It is the gradient of the energy K/2 sum_k |sum_b gamma_kb u_b|^2 (included in potentialEnergy),
///   vanishes for rigid motions and linear displacement fields, and resists only the hourglass modes.
///   The loop keeps c_k = sum_a h_ka X_a (12 numbers) instead of gamma (32): sum_b gamma_kb u_b =
///   sum_b h_kb u_b - (F - I) c_k, and the force folds into the element's P dN/dX term.
///
/// Materials: `material` (default: the material in the context), or per mesh group with
/// groupMaterials="1 @soft 2 @stiff" (group tag or name, then a material path). Fibre directions a0
/// (and b0 for orthotropic laws) per element from a mesh cell array (fibreArray, fibreArray2: 3 values
/// per cell, tetrahedra first then hexahedra, as MeshLoader provides them), else per group from the
/// element's material (BaseMaterial::fibreDirection). They are normalised.
/// Fibre convention: the built-in transversely isotropic law uses W_fibre = eta/4 (I4bar - 1)^2, whose
/// stress eta J^(-2/3) (I4bar - 1)(A0 - I4/3 C^-1) is TLED eq. (33) and Appendix A (eq. (31) prints
/// eta/2, a factor 2 off; see materials/Laws.h).
/// Flat and inverted elements: the HEML section 4.4 treatment of the shared library (J0 parameter;
/// evaluated as materials::evaluateLaw does, written branch-free so that the law loop vectorises).
/// The built-in laws run inlined (dispatch once per block on Material<Law>); other materials through
/// BaseMaterial::evaluate, one call per batch of 32 elements.
///
/// Viscoelasticity (TLED sections 3-4): a ViscoelasticProny in the same node relaxes the isochoric
/// part (everything but the pure-J term), the volumetric (pure-J) part, or both, of S:
///   S^n = Phi^n - sum_i Y_i^n,  Y_i^n = A_i Phi^n + B_i Y_i^(n-1)          TLED eq. (24), (30)
/// with one 6-component state per element and Prony term (stored batch by batch, 32 elements per
/// row, so that a step reads and writes one contiguous stream; large states are written with
/// streaming stores, see streamStates), updated in the vectorised element loop; A_i, B_i are
/// recomputed in dtChanged().
/// Two ViscoelasticProny components (one isochoric, one volumetric) may be combined. The history
/// advances when addForce() is called at a new time t (repeated calls at the same t recompute the
/// same step), i.e. once per step for the explicit integrators. potentialEnergy() is the elastic
/// (instantaneous) energy.
///
/// Parallelism (docs/design.md, determinism): elements are split into fixed blocks (independent of the thread
/// count); each block adds into its own node buffer and the buffers are summed per node in block
/// order, so results are bitwise identical for any thread count. A block's buffer spans the range of
/// node indices its elements use, so the mesh file's numbering matters: when it makes the buffers
/// more than twice as large as a reverse Cuthill-McKee numbering of the nodes with the elements
/// sorted by their lowest node (a Gmsh file's order: blocks that span every node), the force field
/// works in that order internally; the state's order is unchanged. Where the ranges stay wide (large
/// meshes: a block's range is about a plane of the mesh) each buffer holds instead one row per node
/// its elements use (nodeBuffers="auto").
#include "fascia/elements/DeviceForm.h"
#include "fascia/elements/GroupMaterials.h"
#include "fascia/elements/StagedForceField.h"
#include "fascia/materials/Material.h"
#include "fascia/viscoelastic/ElementHistory.h"

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace fascia::viscoelastic {
class ViscoelasticProny;
}

namespace fascia::tled {

class TLEDForceField : public elements::StagedForceField, public viscoelastic::ElementHistory, public elements::DeviceFormSource {
public:
    TLEDForceField();
    ~TLEDForceField() override;

    void init() override;
    void dtChanged(double dt) override;
    std::vector<core::Component*> dependencies() const override;

    /// The stages of addForce (elements/StagedForceField.h): the history and checks, u = x - X per
    /// internal node, the blocks, the ordered sum of the block buffers.
    void beginForces(core::BaseMechanicalState& state, double t) override;
    long prepareNodes() const override;
    void prepareRange(long lo, long hi) override;
    bool rerunnableBlocks() const override;
    void runForceBlock(long b, int thread) override;
    void sumForceRange(double* f, long lo, long hi) override;
    size_t blockCount() const override;
    bool usesFastPath() const override;
    /// Elastic strain energy (J) at the current positions, hourglass energy included.
    double potentialEnergy(const core::BaseMechanicalState& state) const override;
    /// min over elements of L_e / c (TLED section 7): L_e the smallest altitude 3V/A_max of a
    /// tetrahedron, V/A_max for a hexahedron; c the material's dilatational wave speed
    /// (BaseMaterial::waveSpeed, fibre stiffness included) at the density of the mass in the context.
    /// Infinity when no mass with a density is found.
    double stableTimeStep(const core::BaseMechanicalState& state) const override;
    /// "S" (second Piola-Kirchhoff, 6: xx yy zz xy yz xz), "cauchyStress" (6), "vonMises" (1, of the
    /// Cauchy stress) and "J" (1), per element: tetrahedra first, then hexahedra, in input order. The
    /// stresses are those of the state at the scene's time, viscous history included (stresses() at
    /// that time): what an observer writes is the stress of the state it writes.
    void cellData(const core::BaseMechanicalState& state, std::vector<core::CellField>& out) const override;
    size_t elementCount() const override { return m_tets.size() + m_hexes.size(); }
    const Tetrahedra* tetrahedra() const override { return &m_tets; }
    const Hexahedra* hexahedra() const override { return &m_hexes; }
    /// elements::worstElement on its tetrahedra and hexahedra (cell order).
    bool worstElement(const core::BaseMechanicalState& state, core::ElementReport& out) const override;
    /// What addForce() moves through memory, from the arrays after init (TLEDLayout.cpp): element
    /// data (the packed rows, volumes, connectivity, hourglass stiffness, viscous states read and
    /// written), node rows (x and X read, u written and read, f read and written) and the block buffers.
    core::LayoutBytes layoutBytes() const override;
    /// The viscous history (TLED eq. (30)): per Prony series the states Y_i of the last step and of
    /// the current evaluation, and the time of that evaluation (nothing without a ViscoelasticProny).
    void saveState(core::StateWriter& out) const override;
    void restoreState(core::StateReader& in) override;
    /// The Prony states as a step backend advanced them (viscoelastic/ElementHistory.h), into the
    /// batch slots of its series, both the committed and the current ones, and the backend's clock.
    void adoptHistory(const std::vector<double>& Yt, const std::vector<double>& Yh, const viscoelastic::HistoryClock& clock) override;
    /// Its elements, materials, fibres, series and rest data for a step backend (elements/DeviceForm.h),
    /// unpacked from the packed rows of its precompute (TLEDDeviceForm.cpp).
    void deviceForm(elements::DeviceForm& out) const override;

    /// Second Piola-Kirchhoff stress of every element (6 per element, xx yy zz xy yz xz, cell order)
    /// as addForce() at time t would compute it, viscous history included, without advancing it.
    void stresses(const core::BaseMechanicalState& state, double t, std::vector<double>& S) const;
    /// Rest volume (m^3) of element e in cell order (tetrahedra first); a linear search, for tests.
    double restVolume(size_t e) const;
    /// Stable time step (s) of element e alone at density rho, see stableTimeStep(); a linear search.
    double elementTimeStep(size_t e, double rho) const;
    /// Node rows of the blocks' force buffers, all blocks together (for tests of the node ordering).
    size_t bufferRows() const;
    /// True when the blocks' force buffers are compact rows (nodeBuffers), false for node ranges.
    bool compactBuffers() const;

    core::Param<MeshData> m_mesh{this, core::ParamSpec("mesh").help(
        "mesh to take the elements (tetrahedra and hexahedra), group tags and cell arrays from, e.g. "
        "\"@loader.mesh\"; default: the mesh source in the context when neither tetrahedra nor hexahedra is given")};
    core::Param<Tetrahedra> m_tetrahedra{this, core::ParamSpec("tetrahedra").help(
        "4-node tetrahedra (instead of mesh), e.g. \"@loader.tetrahedra\"")};
    core::Param<Hexahedra> m_hexahedra{this, core::ParamSpec("hexahedra").help(
        "8-node hexahedra in VTK node order (instead of mesh)")};
    core::Link<materials::BaseMaterial> m_material{this, core::ParamSpec("material").help(
        "material of the elements (with groupMaterials: of the groups it does not list); default, without "
        "groupMaterials: the material in the context")};
    core::Param<elements::GroupMaterialList> m_groupMaterials{this, core::ParamSpec("groupMaterials").help(
        "materials per mesh group: pairs of a group tag or name and a material path, e.g. \"1 @liver 2 @vessel\"")};
    core::Param<std::string> m_fibreArray{this, core::ParamSpec("fibreArray").help(
        "name of a mesh cell array with the fibre direction a0 per element (3 values per cell); "
        "default: the direction of the element's material")};
    core::Param<std::string> m_fibreArray2{this, core::ParamSpec("fibreArray2").help(
        "name of a mesh cell array with the second fibre direction b0 per element (orthotropic materials)")};
    core::Param<double> m_J0{this, core::ParamSpec("J0").above(0).below(1).help(
        "volume ratio below which the law is linearised (HEML section 4.4): flat and inverted elements push back "
        "with finite forces"), 0.4};
    core::Param<double> m_hourglass{this, core::ParamSpec("hourglassStiffness").min(0).help(
        "dimensionless hourglass control coefficient kappa_HG of the reduced-integration hexahedra "
        "(Flanagan-Belytschko / Joldes et al. 2008 form, see the class documentation); 0 disables it"), 0.075};
    core::Param<std::string> m_streamStates{this, core::ParamSpec("streamStates").choices({"auto", "on", "off"}).help(
        "performance: write the viscous state variables with streaming (cache-bypassing) stores; auto: when "
        "they take more than 8 MiB, where they no longer fit the caches beside the element data. Results are "
        "the same either way"), "auto"};
    core::Param<std::string> m_nodeBuffers{this, core::ParamSpec("nodeBuffers").choices({"auto", "range", "compact"}).help(
        "performance: the layout of the blocks' force buffers. range: a block's buffer covers the range of node "
        "indices its elements use (no copy, but it grows with the numbering's bandwidth); compact: one row per "
        "distinct node of the block, the displacements copied in per block; auto: compact when the ranges take "
        "more than 1.5 times the rows of compact. Results are the same either way"), "auto"};
    core::Param<std::string> m_precision{this, core::ParamSpec("precision").choices({"double", "mixed"}).help(
        "double: everything in double. mixed: the element data (shape-function derivatives, volumes, "
        "hourglass and fibre vectors) and the element loop in float, the displacements, forces, block sums, "
        "viscous states and energy in double; half the element data and 8-wide vectors. Forces agree with "
        "double to about 1e-6 of the largest (docs/performance.md, mixed precision)"), "double"};

    struct Impl;

protected:
    long forceNodes(const core::BaseMechanicalState& state, const Positions& f) const override;

private:
    /// Elements, materials, fibres, node order, blocks and packed element data (TLEDElements.cpp).
    void precompute(const MeshData* mesh, const Positions& X);
    Tetrahedra m_tets;
    Hexahedra m_hexes;
    std::unique_ptr<Impl> m_impl;
};

} // namespace fascia::tled
