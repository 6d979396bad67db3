#pragma once
#include "fascia/sim/Mechanics.h"

namespace fascia::meshio {

/// A volume mesh written in the scene itself: its points, tetrahedra and/or hexahedra, and named
/// node groups. What a Python scene builds from numpy arrays (fascia.Mesh, docs/python.md); checked
/// as a mesh file is (indices in range, no degenerate or inverted element unless fixOrientation).
/// Not a MeshSource: its inputs take the names MeshSource gives its outputs (tetrahedra, hexahedra).
class InlineMesh : public core::BaseTopology {
public:
    void init() override;
    const MeshData& meshData() const override { return m_mesh.get(); }

    core::Param<Positions> m_points{this, core::ParamSpec("points").required().unit("m").help("node positions \"x0 y0 z0 x1 y1 z1 ...\"")};
    core::Param<Tetrahedra> m_tets{this, core::ParamSpec("tetrahedra").help("tetrahedra, 4 node indices each (0-based)")};
    core::Param<Hexahedra> m_hexes{this, core::ParamSpec("hexahedra").help("hexahedra, 8 node indices each (0-based, VTK order)")};
    core::Param<std::string> m_groups{this, core::ParamSpec("nodeGroups").help("named node groups \"name: i j k; other: l m\" (0-based node indices), linkable as the mesh's groups")};
    core::Param<MeshData> m_mesh{this, core::ParamSpec("mesh").output().help("the whole mesh (points, elements, node groups)")};
    core::Param<Positions> m_positions{this, core::ParamSpec("positions").output().unit("m").help("node positions (the points, oriented elements checked)")};
    core::Param<bool> m_fixOrientation{this, core::ParamSpec("fixOrientation").help("flip inverted elements (negative volume) instead of failing"), false};
};

} // namespace fascia::meshio
