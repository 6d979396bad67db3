#pragma once
/// What MeshLoader and GridMesh share: the mesh, and its parts as linkable outputs
/// ("@loader.positions", "@loader.tetrahedra", "@loader.mesh").
#include "fascia/sim/Mechanics.h"

namespace fascia::meshio {

class MeshSource : public core::BaseTopology {
public:
    const MeshData& meshData() const override { return m_mesh.get(); }

    core::Param<MeshData> m_mesh{this, core::ParamSpec("mesh").output().help("the whole mesh (points, elements, groups, cell arrays)")};
    core::Param<Positions> m_positions{this, core::ParamSpec("positions").output().unit("m").help("node positions")};
    core::Param<Tetrahedra> m_tetrahedra{this, core::ParamSpec("tetrahedra").output().help("tetrahedra (4 node indices each)")};
    core::Param<Hexahedra> m_hexahedra{this, core::ParamSpec("hexahedra").output().help("hexahedra (8 node indices each, VTK order)")};
    core::Param<Triangles> m_triangles{this, core::ParamSpec("triangles").output().help("boundary triangles: a GridMesh's, turned outwards; a file's triangles as the file has them")};

protected:
    /// Publishes a mesh to the outputs, with the boundary of its volume elements
    /// (BaseTopology::boundaryTriangles; computed here unless given).
    void publish(MeshData mesh, const Triangles* boundary = nullptr);
};

} // namespace fascia::meshio
