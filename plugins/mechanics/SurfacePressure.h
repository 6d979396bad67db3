#pragma once
#include "fascia/sim/Mechanics.h"

namespace fascia::mechanics {

/// A pressure on boundary triangles, following the surface as it deforms: each triangle gets the
/// force -p A n (n its outward unit normal, A its current area), a third on each corner. Positive
/// pressure pushes inwards. The triangles are the mesh's boundary triangles (or, when the mesh has
/// none, the faces of its tetrahedra used by one tetrahedron only), restricted to a physical group
/// (`triangleGroup`) or to a node group (`nodeGroup`: triangles with their three nodes in it), and
/// oriented outwards from the tetrahedron they bound.
class SurfacePressure : public core::BaseForceField {
public:
    void init() override;
    void addForce(core::BaseMechanicalState& s, Positions& f, double t) override;
    size_t triangleCount() const { return m_tris.size(); }

    core::Param<double> m_pressure{this, core::ParamSpec("pressure").unit("Pa").required().help("pressure p (positive pushes into the body)")};
    core::Param<int> m_triangleGroup{this, core::ParamSpec("triangleGroup").min(0).help("physical group tag of the triangles (0: all)"), 0};
    core::Param<std::string> m_nodeGroup{this, core::ParamSpec("nodeGroup").help("only triangles whose nodes all belong to this node group (e.g. a GridMesh face \"zmax\")")};
    core::Param<double> m_rampTime{this, core::ParamSpec("rampTime").unit("s").min(0).help("the pressure grows linearly from 0 over this time (0: at once)"), 0.0};

private:
    Triangles m_tris;
};

} // namespace fascia::mechanics
