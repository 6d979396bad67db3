#include "MeshSource.h"
#include "fascia/surface/BoundaryFaces.h"

namespace fascia::meshio {

void MeshSource::publish(MeshData mesh, const Triangles* boundary) {
    m_boundary = boundary ? *boundary : surface::boundaryTriangles(mesh);
    m_mesh.set(std::move(mesh));
    // the parts are views of the mesh, not copies (a copy of a large mesh's tetrahedra is 16 bytes
    // per element kept for the whole run)
    const MeshData& m = m_mesh.get();
    m_positions.view(&m.points);
    m_tetrahedra.view(&m.tetrahedra);
    m_hexahedra.view(&m.hexahedra);
    m_triangles.view(&m.triangles);
}

} // namespace fascia::meshio
