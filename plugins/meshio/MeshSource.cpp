#include "MeshSource.h"
#include "fascia/surface/BoundaryFaces.h"

namespace fascia::meshio {

void MeshSource::publish(MeshData mesh, const Triangles* boundary) {
    m_boundary = boundary ? *boundary : surface::boundaryTriangles(mesh);
    m_positions.set(mesh.points);
    m_tetrahedra.set(mesh.tetrahedra);
    m_hexahedra.set(mesh.hexahedra);
    m_triangles.set(mesh.triangles);
    m_mesh.set(std::move(mesh));
}

} // namespace fascia::meshio
