#pragma once
/// HEMLForceField: the Hyper-Elastic Mass Links method of Goulette and Chen (2015) on linear
/// tetrahedra, for any invariant-based material of the materials plugin.
///
/// Precomputation (HEML Algorithm 1, Appendices A-C): per tetrahedron the rest edge matrix V, its
/// volume Vol, and what the six tensors C_k = V^-T D_k V^-1 (eq. (A.6)) enter through: with
/// G = V^-1 V^-T, vtr_k = tr C_k = tr(D_k G) and Mtr_ij = tr(C_i C_j) = tr(D_i G D_j G) (Appendix C),
/// so the loop stores the 6 numbers of G instead of the 27 of vtr and Mtr, and evaluates Mtr l as
/// (tr(D_k G D(l) G))_k with D(l) of eq. (A.4); a0.C_k a0 = w.D_k w with w = V^-1 a0 for fibres.
/// (The tests check this against Algorithm 2 written literally with C_k, vtr, Mtr and DLM_i.)
/// Per step (Algorithm 2): the six squared edge lengths l_k give
///   C = sum_k l_k C_k,  I1 = vtr.l,  tr(C^2) = l^T Mtr l,  I2 = (I1^2 - tr C^2)/2     (eq. (C.1))
///   dI1/dl = vtr (C.2),  dI2/dl = I1 vtr - Mtr l (C.3),  I4 = sum_k l_k a0.C_k a0,
/// J = det(v1, v2, v3) / det(V1, V2, V3) (signed volume ratio), and the forces (eq. (12)-(13), (29)-(30))
///   g_k = Vol dW/dl_k:  -2 g_k (x_a - x_b) on node a of edge k, the opposite on b (eq. (B.1)-(B.2)),
///   -Vol dW/dJ dJ/dx_i with dvol/dx_i from eq. (C.4).
/// Flat and inverted elements (section 4.4): J is signed and below J0 the law continues along its
/// tangent at J0 (materials::evaluateLaw), so forces stay finite and push back through J = 0.
///
/// Mass-spring mode (section 5.3): setting `stiffness` replaces the material by the energy of
/// eq. (38), one spring of stiffness k per mesh edge, W = k/2 (l - l0)^2, whose HEML forces are the
/// classical spring forces (eq. (41) = eq. (36)). Shared edges are split between their tetrahedra
/// (k / number of tetrahedra on the edge in each), so the total is one spring of stiffness k per edge.
///
/// Viscoelasticity (section 3.5): a ViscoelasticProny component in the same node makes the
/// per-tetrahedron forces visco-hyperelastic by the recurrence of eq. (18)-(20),
///   gamma_i^n = A_i R^n + B_i gamma_i^(n-1),   g_k - sum_i gamma_i,
/// applied not to the Cartesian nodal forces but to the second Piola-Kirchhoff stress of the relaxed
/// part (`apply`) written as six link coefficients R_k = Vol/2 S : C_k (the I terms' g_k and the
/// relaxed J coefficient through dJ/dl_k): TLED's model (TLED eq. (24), (30)) in HEML's variables, and
/// objective (a rigid rotation of a stressed body does not relax). See HEMLKernel.h (relax) and
/// docs/materials.md, section 3. The history advances when forces are asked for at a new time,
/// over the time elapsed since the last evaluation (fascia/viscoelastic/HistoryClock.h).
///
/// Mixed precision (precision="mixed", docs/design.md, section 3): the element arrays (Vol, 1/det V, G, the fibre
/// w and the spring data) are stored in float and the element math runs in float: positions are
/// gathered in double and the edges x_b - x_a formed in double (accurate differences), then rounded
/// to float; the element's nodal forces are converted to double as they are added to the block's
/// double node rows, and the energy is summed in double. Element data 48 instead of 80 bytes per
/// element. The Prony history stays double. A user material with only the double evaluate() gets
/// the float invariants as double and its response is rounded back. Still bitwise the same for any
/// thread count.
///
/// Performance (docs/performance.md, lessons 1 to 5): elements as structure of arrays (80 bytes each) in
/// blocks of about 1024 (the block count depends on the mesh only, never on the thread count);
/// nodes renumbered internally by reverse Cuthill-McKee (the state's order is unchanged) and the
/// elements sorted along it; each block copies its nodes' positions into its own rows (4 doubles,
/// gathered with in-register transposes), adds its forces into its own node buffer, and the
/// buffers are summed per node in block order: results are bitwise identical for any number of
/// threads. No libm call and no pow in the loop (materials::invCbrt, fastLog). Built-in laws run an
/// inlined, vectorised loop (dispatch once per block on Material<Law>); other materials are
/// evaluated by one virtual call per 16 elements.
#include "fascia/elements/DeviceForm.h"
#include "fascia/elements/GroupMaterials.h"
#include "fascia/elements/StagedForceField.h"
#include "fascia/elements/TetMesh.h"
#include "fascia/materials/Material.h"
#include "fascia/viscoelastic/ElementHistory.h"

#include <memory>
#include <string>
#include <vector>

namespace fascia::viscoelastic {
class ViscoelasticProny;
}

namespace fascia::heml {

class HEMLForceField : public elements::StagedForceField, public viscoelastic::ElementHistory, public elements::DeviceFormSource {
public:
    HEMLForceField();
    ~HEMLForceField() override;

    void init() override;
    std::vector<core::Component*> dependencies() const override;

    /// The stages of addForce (elements/StagedForceField.h): the history and checks, the positions in
    /// internal order (large meshes), the blocks, the ordered sum of the node rows.
    void beginForces(core::BaseMechanicalState& state, double t) override;
    long prepareNodes() const override;
    void prepareRange(long lo, long hi) override;
    bool rerunnableBlocks() const override;
    void runForceBlock(long b, int thread) override;
    void sumForceRange(double* f, long lo, long hi) override;
    size_t blockCount() const override;
    bool usesFastPath() const override;
    /// Elastic energy sum_e Vol_e W_e (J) at the state's positions (viscous history not included).
    double potentialEnergy(const core::BaseMechanicalState& state) const override;
    /// min over elements of h_e / c_e: h_e the shortest altitude 3 Vol / (largest face area) of the
    /// rest element, c_e the material's dilatational wave speed sqrt((K + 4/3 mu)/rho) with rho from
    /// the BaseMass in the context (its density, else its total mass over the mesh volume). In
    /// mass-spring mode: 2 / sqrt(max_i sum_j k_ij (1/m_i + 1/m_j)) (Gershgorin bound, lumped masses).
    /// Infinity when no mass is found.
    double stableTimeStep(const core::BaseMechanicalState& state) const override;
    /// "J" (volume ratio, signed) and "vonMises" (Pa, von Mises stress of the Cauchy stress
    /// tau / max(J, J0), tau the Kirchhoff stress), per tetrahedron in the input order.
    void cellData(const core::BaseMechanicalState& state, std::vector<core::CellField>& out) const override;
    size_t elementCount() const override;
    /// elements::worstElement on its tetrahedra.
    bool worstElement(const core::BaseMechanicalState& state, core::ElementReport& out) const override;
    /// What addForce() moves through memory, from the arrays after init (HEMLLayout.cpp): element
    /// data (the slots' arrays the loop reads, viscous states read and written), node rows and the
    /// compact block rows (elements::CompactBlockBuffers::stepBytes).
    core::LayoutBytes layoutBytes() const override;
    /// The viscous history: gamma_i of eq. (20) per term, relaxed part and slot, committed and current,
    /// and the history clock (viscoelastic/HistoryClock.h); nothing without a ViscoelasticProny.
    void saveState(core::StateWriter& out) const override;
    void restoreState(core::StateReader& in) override;
    /// The viscous history gamma as a step backend advanced it (viscoelastic/ElementHistory.h: per
    /// term and link coefficient, input order), into its slots, committed and current, and the
    /// backend's clock (Yh: none, HEML has no hexahedra).
    void adoptHistory(const std::vector<double>& Yt, const std::vector<double>& Yh, const viscoelastic::HistoryClock& clock) override;
    const Tetrahedra* tetrahedra() const override { return &m_tets; }
    /// Its tetrahedra, materials, series and rest data for a step backend (elements/DeviceForm.h),
    /// from the slots of its precompute back in input order (HEMLDeviceForm.cpp).
    void deviceForm(elements::DeviceForm& out) const override;

    /// f += forces at positions x; x and f hold 3 doubles per node in the state's order (a
    /// Positions array's data()), with the viscous history of the last addForce, not advanced.
    /// For benchmarks and embedding programs.
    void addForceRaw(const double* x, double* f);
    /// The material of each element (input order); null in mass-spring mode.
    const materials::BaseMaterial* materialOf(size_t element) const;

    core::Link<materials::BaseMaterial> m_material{this, core::ParamSpec("material").help(
        "the material (a component of the materials plugin), e.g. \"@liverMat\"; default: the material in the node's context")};
    core::Param<elements::GroupMaterialList> m_groupMaterials{this, core::ParamSpec("groupMaterials").help(
        "per element group materials: pairs of a mesh group (tag number or group name) and a material path, e.g. "
        "\"1 @liverMat 2 @tumourMat\"; groups not listed use 'material' (needs a mesh with groups)")};
    core::Param<double> m_J0{this, core::ParamSpec("J0").min(0, true).max(1, true).help(
        "volume ratio below which the volumetric response continues along its tangent (HEML section 4.4)"), 0.4};
    core::Param<MeshData> m_mesh{this, elements::tetMeshParam()};
    core::Param<Tetrahedra> m_tetrahedra{this, elements::tetrahedraParam()};
    core::Param<double> m_stiffness{this, core::ParamSpec("stiffness").unit("N/m").above(0).help(
        "mass-spring mode (HEML section 5.3, eq. (38)-(41)): one spring of this stiffness per mesh edge instead of a material")};
    core::Param<std::string> m_fibreArray{this, core::ParamSpec("fibreArray").help(
        "name of a mesh cell array with a fibre direction a0 per tetrahedron (3 numbers each); default: the material's direction")};
    core::Param<std::string> m_fibreArray2{this, core::ParamSpec("fibreArray2").help(
        "name of a mesh cell array with the second fibre direction b0 per tetrahedron (orthotropic materials)")};
    core::Param<std::string> m_precision{this, core::ParamSpec("precision").choices({"double", "mixed"}).help(
        "scalar type of the element loop: \"double\" throughout, or \"mixed\": element data (48 instead of 80 bytes "
        "per element) and the per-element math in float, positions, edge differences, nodal force sums and the "
        "energy sum in double (viscous history double too). Mixed forces differ from double by about 1e-7 / strain "
        "of the largest nodal force (5e-6 at 3 % strain, 5e-7 at 30 %), the energy by about 1e-6 relative at 3 %: "
        "float rounding, relatively larger at small strains; use double for verification and convergence studies"), "double"};

    struct Impl;

protected:
    long forceNodes(const core::BaseMechanicalState& state, const Positions& f) const override;

private:
    /// Node order, blocks, element loops, per-slot element data and viscous states (HEMLElements.cpp).
    void precompute(const Positions& rest, const std::vector<materials::BaseMaterial*>& elementMaterial);
    void checkState(const core::BaseMechanicalState& state) const;

    Tetrahedra m_tets;                                         // input order
    Positions m_rest;                                          // rest positions (state order)
    std::vector<Vec3> m_dirA, m_dirB;                          // unit fibre directions per element (empty: unused)
    viscoelastic::ViscoelasticProny* m_visco = nullptr;
    std::unique_ptr<Impl> m_impl;
};

} // namespace fascia::heml
