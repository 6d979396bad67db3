#pragma once
#include "fascia/sim/LoadCurve.h"
#include "fascia/sim/LoadTerms.h"
#include "fascia/sim/Mechanics.h"

namespace fascia::mechanics {

/// A pressure on boundary faces, following the surface as it deforms, scaled by a load curve:
/// p(t) = c(t) p. Positive pressure pushes inwards. Each face gets the follower load -p n dA:
/// - a triangle the force -p A n (n its outward unit normal, A its current area), a third on each corner;
/// - a quadrilateral face of a hexahedron, a bilinear patch x(xi, eta) = sum_a N_a x_a on [-1, 1]^2,
///   the nodal forces f_a = -p int N_a (dx/dxi x dx/deta) dxi deta, which 2x2 Gauss points integrate
///   exactly (the integrand is of degree 2 in xi and in eta). Summed over a closed surface these are
///   -p dV/dx_a, V the volume it encloses.
/// The triangles are the mesh's boundary triangles (or, when the mesh has none, the faces of its
/// tetrahedra used by one tetrahedron only), the quadrilaterals the faces of its hexahedra used by one
/// hexahedron only; restricted to a physical group of triangles (`triangleGroup`) or to a node group
/// (`nodeGroup`: faces with all their nodes in it), and oriented outwards from the element they bound.
class SurfacePressure : public core::BaseForceField, public core::PressureLoad {
public:
    void init() override;
    void addForce(core::BaseMechanicalState& s, Positions& f, double t) override;
    size_t triangleCount() const { return m_tris.size(); }
    size_t quadCount() const { return m_quads.size(); }
    const Triangles& pressureTriangles() const override { return m_tris; }
    const std::vector<std::array<int, 4>>& pressureQuads() const override { return m_quads; }
    double pressureAt(double t) const override;

    core::Param<double> m_pressure{this, core::ParamSpec("pressure").unit("Pa").required().help("pressure p (positive pushes into the body)")};
    core::Param<int> m_triangleGroup{this, core::ParamSpec("triangleGroup").min(0).help("physical group tag of the triangles (0: all)"), 0};
    core::Param<std::string> m_nodeGroup{this, core::ParamSpec("nodeGroup").help("only faces whose nodes all belong to this node group (e.g. a GridMesh face \"zmax\")")};
    core::Param<double> m_rampTime{this, core::ParamSpec("rampTime").unit("s").min(0).help("the pressure grows linearly from 0 over this time (0: at once); the same as curve=\"ramp T\""), 0.0};
    core::CurveParam m_curve{this, core::curveSpec("curve", "the pressure, p(t) = c(t) p")};

private:
    void collectTriangles(const MeshData& mesh, const Positions& X);
    void collectQuads(const MeshData& mesh, const Positions& X);
    /// Keeps the candidate faces whose nodes all belong to nodeGroup (all of them when it is unset).
    template <class Faces> void keepNodeGroup(const MeshData& mesh, Faces& faces) const;
    Triangles m_tris;
    std::vector<std::array<int, 4>> m_quads;  ///< counterclockwise seen from outside
    core::Curve m_ramp;                       ///< the curve rampTime stands for
};

} // namespace fascia::mechanics
