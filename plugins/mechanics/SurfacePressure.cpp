#include "SurfacePressure.h"
#include "NodeSelection.h"
#include "fascia/scene/Node.h"

#include <algorithm>
#include <map>
#include <set>

namespace fascia::mechanics {

namespace {
using Key = std::array<int, 3>;
Key sorted(int a, int b, int c) {
    Key k{a, b, c};
    std::sort(k.begin(), k.end());
    return k;
}
} // namespace

void SurfacePressure::init() {
    auto& state = contextState(*this);
    const MeshData& mesh = contextMesh(*this, state);
    // each face of a tetrahedron -> the opposite node, and how many tetrahedra use it
    std::map<Key, std::pair<int, int>> faces;
    for (auto& t : mesh.tetrahedra)
        for (int k = 0; k < 4; ++k) {
            const Key key = sorted(t[(k + 1) % 4], t[(k + 2) % 4], t[(k + 3) % 4]);
            auto [it, fresh] = faces.emplace(key, std::make_pair(t[k], 1));
            if (!fresh) ++it->second.second;
        }
    Triangles candidates;
    if (!mesh.triangles.empty()) {
        for (size_t i = 0; i < mesh.triangles.size(); ++i)
            if (m_triangleGroup.get() == 0 ||
                (i < mesh.triangleGroup.size() && mesh.triangleGroup[i] == m_triangleGroup.get()))
                candidates.push_back(mesh.triangles[i]);
    } else {
        if (m_triangleGroup.get() != 0) fail(m_triangleGroup, "the mesh has no triangles, so no triangle groups");
        for (auto& [key, use] : faces)
            if (use.second == 1) candidates.push_back(key);
    }
    if (m_nodeGroup.isSet()) {
        auto it = mesh.nodeGroups.find(m_nodeGroup.get());
        if (it == mesh.nodeGroups.end()) fail(m_nodeGroup, "no node group '" + m_nodeGroup.get() + "' in the mesh");
        const std::set<int> in(it->second.begin(), it->second.end());
        Triangles kept;
        for (auto& t : candidates)
            if (in.count(t[0]) && in.count(t[1]) && in.count(t[2])) kept.push_back(t);
        candidates.swap(kept);
    }
    const Positions& X = state.x0();
    m_tris.clear();
    size_t skipped = 0;
    for (auto t : candidates) {
        auto it = faces.find(sorted(t[0], t[1], t[2]));
        if (it == faces.end()) {  // a triangle of no tetrahedron: no inside to orient by
            ++skipped;
            continue;
        }
        const Vec3 n = (X[t[1]] - X[t[0]]).cross(X[t[2]] - X[t[0]]);
        if (n.dot(X[t[0]] - X[it->second.first]) < 0) std::swap(t[1], t[2]);  // outwards
        m_tris.push_back(t);
    }
    if (m_tris.empty())
        fail(mesh.tetrahedra.empty() ? "needs a tetrahedral mesh (faces of hexahedra are not supported)"
                                     : "selects no boundary triangle");
    if (skipped) warn(std::to_string(skipped) + " triangle(s) are the face of no tetrahedron and were left out");
}

void SurfacePressure::addForce(core::BaseMechanicalState& s, Positions& f, double t) {
    const double T = m_rampTime.get();
    const double p = m_pressure.get() * (T > 0 ? std::min(1.0, t / T) : 1.0);
    const Positions& x = s.x();
    for (auto& tr : m_tris) {
        // -p A n = -p/2 (x1 - x0) x (x2 - x0), a third on each corner
        const Vec3 fa = (-p / 6.0) * (x[tr[1]] - x[tr[0]]).cross(x[tr[2]] - x[tr[0]]);
        f[tr[0]] += fa;
        f[tr[1]] += fa;
        f[tr[2]] += fa;
    }
}

} // namespace fascia::mechanics
