#include "BoxROI.h"
#include "fascia/scene/Node.h"

namespace fascia::meshio {

void BoxROI::init() {
    const auto& b = m_box.get();
    for (int a = 0; a < 3; ++a)
        if (b[a] > b[a + 3]) fail(m_box, "box min exceeds max along axis " + std::to_string(a) + " (give xmin ymin zmin xmax ymax zmax)");
    const MeshData* mesh = nullptr;
    if (auto* topo = node()->findInContext<core::BaseTopology>()) mesh = &topo->meshData();
    const Positions* pts = nullptr;
    if (m_position.isSet()) pts = &m_position.get();
    else if (mesh) pts = &mesh->points;
    else fail("no points: set position or put a mesh source (MeshLoader, GridMesh) in the context");
    std::vector<char> inside(pts->size(), 0);
    IndexList idx;
    for (size_t i = 0; i < pts->size(); ++i) {
        const Vec3& p = (*pts)[i];
        if (p[0] >= b[0] && p[1] >= b[1] && p[2] >= b[2] && p[0] <= b[3] && p[1] <= b[4] && p[2] <= b[5]) {
            inside[i] = 1;
            idx.push_back(int(i));
        }
    }
    if (idx.empty()) warn("the box selects no node");
    m_indices.set(std::move(idx));
    if (mesh && !m_position.isSet()) {
        IndexList tets, hexes;
        for (size_t e = 0; e < mesh->tetrahedra.size(); ++e) {
            bool all = true;
            for (int n : mesh->tetrahedra[e]) all = all && inside[n];
            if (all) tets.push_back(int(e));
        }
        for (size_t e = 0; e < mesh->hexahedra.size(); ++e) {
            bool all = true;
            for (int n : mesh->hexahedra[e]) all = all && inside[n];
            if (all) hexes.push_back(int(e));
        }
        m_tetrahedronIndices.set(std::move(tets));
        m_hexahedronIndices.set(std::move(hexes));
    }
}

} // namespace fascia::meshio
