#include "SurfacePressure.h"
#include "NodeSelection.h"
#include "fascia/elements/Pressure.h"
#include "fascia/scene/Node.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace fascia::mechanics {

namespace {
template <size_t N> std::array<int, N> sortedKey(std::array<int, N> k) {
    std::sort(k.begin(), k.end());
    return k;
}

/// The 6 faces of a hexahedron (VTK/Gmsh node order: 0-3 one face, 4-7 the opposite one),
/// each counterclockwise seen from outside a positively oriented hexahedron.
constexpr int kHexFaces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
} // namespace

template <class Faces> void SurfacePressure::keepNodeGroup(const MeshData& mesh, Faces& faces) const {
    if (!m_nodeGroup.isSet()) return;
    auto it = mesh.nodeGroups.find(m_nodeGroup.get());
    if (it == mesh.nodeGroups.end()) fail(m_nodeGroup, "no node group '" + m_nodeGroup.get() + "' in the mesh");
    const std::set<int> in(it->second.begin(), it->second.end());
    Faces kept;
    for (auto& f : faces)
        if (std::all_of(f.begin(), f.end(), [&](int i) { return in.count(i) > 0; })) kept.push_back(f);
    faces.swap(kept);
}

void SurfacePressure::collectTriangles(const MeshData& mesh, const Positions& X) {
    m_tris.clear();
    // a mesh of hexahedra only: its boundary triangles (a GridMesh publishes them) bound no
    // tetrahedron; its faces are the quadrilaterals of collectQuads
    if (mesh.tetrahedra.empty()) {
        if (m_triangleGroup.get() != 0)
            fail(m_triangleGroup, "the mesh has no tetrahedra, so no triangle groups (select hexahedron faces with nodeGroup)");
        return;
    }
    // each face of a tetrahedron -> the opposite node, and how many tetrahedra use it
    std::map<std::array<int, 3>, std::pair<int, int>> faces;
    for (auto& t : mesh.tetrahedra)
        for (int k = 0; k < 4; ++k) {
            const auto key = sortedKey<3>({t[(k + 1) % 4], t[(k + 2) % 4], t[(k + 3) % 4]});
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
    keepNodeGroup(mesh, candidates);
    m_tris.clear();
    size_t skipped = 0;
    for (auto t : candidates) {
        auto it = faces.find(sortedKey<3>(t));
        if (it == faces.end()) {  // a triangle of no tetrahedron: no inside to orient by
            ++skipped;
            continue;
        }
        const Vec3 n = (X[t[1]] - X[t[0]]).cross(X[t[2]] - X[t[0]]);
        if (n.dot(X[t[0]] - X[it->second.first]) < 0) std::swap(t[1], t[2]);  // outwards
        m_tris.push_back(t);
    }
    if (skipped) warn(std::to_string(skipped) + " triangle(s) are the face of no tetrahedron and were left out");
}

void SurfacePressure::collectQuads(const MeshData& mesh, const Positions& X) {
    // each face of a hexahedron (in its outward order) -> its hexahedron, and how many use it
    std::map<std::array<int, 4>, std::pair<std::array<int, 4>, int>> faces;
    std::map<std::array<int, 4>, int> owner;
    for (size_t h = 0; h < mesh.hexahedra.size(); ++h)
        for (auto& fc : kHexFaces) {
            const auto& e = mesh.hexahedra[h];
            const std::array<int, 4> q{e[fc[0]], e[fc[1]], e[fc[2]], e[fc[3]]};
            auto [it, fresh] = faces.emplace(sortedKey<4>(q), std::make_pair(q, 1));
            if (!fresh) ++it->second.second;
            else owner[it->first] = int(h);
        }
    std::vector<std::array<int, 4>> candidates;
    if (m_triangleGroup.get() == 0)  // quadrilaterals belong to no triangle group
        for (auto& [key, use] : faces)
            if (use.second == 1) candidates.push_back(use.first);
    keepNodeGroup(mesh, candidates);
    m_quads.clear();
    for (auto q : candidates) {
        // outwards from its hexahedron's centre (also for a hexahedron numbered inside out)
        const auto& e = mesh.hexahedra[size_t(owner[sortedKey<4>(q)])];
        Vec3 centre = Vec3::Zero(), faceCentre = Vec3::Zero();
        for (int a : e) centre += X[a] / 8.0;
        for (int a : q) faceCentre += X[a] / 4.0;
        const Vec3 n = (X[q[2]] - X[q[0]]).cross(X[q[3]] - X[q[1]]);
        if (n.dot(faceCentre - centre) < 0) std::swap(q[1], q[3]);
        m_quads.push_back(q);
    }
}

void SurfacePressure::init() {
    auto& state = contextState(*this);
    const MeshData& mesh = contextMesh(*this, state);
    if (m_curve.isSet() && m_rampTime.isSet())
        fail(m_rampTime, "give curve or rampTime, not both (rampTime=\"T\" is curve=\"ramp T\")");
    m_ramp = core::Curve();
    if (m_rampTime.get() > 0)
        core::Curve::make({0.0, 0.0, m_rampTime.get(), 1.0}, core::Curve::Interpolation::Linear, core::Curve::After::Hold, m_ramp);
    const Positions& X = state.x0();
    collectTriangles(mesh, X);
    collectQuads(mesh, X);
    if (m_tris.empty() && m_quads.empty())
        fail(mesh.tetrahedra.empty() && mesh.hexahedra.empty() ? "the mesh has no tetrahedra or hexahedra to bound"
                                                               : "selects no boundary face");
}

double SurfacePressure::pressureAt(double t) const { return m_pressure.get() * (m_curve.isSet() ? m_curve.value(t) : m_ramp.value(t)); }

void SurfacePressure::addForce(core::BaseMechanicalState& s, Positions& f, double t) {
    const double p = pressureAt(t);
    const Positions& x = s.x();
    const auto diff = [&](int a, int b) { return elements::Vec33<double>{x[a][0] - x[b][0], x[a][1] - x[b][1], x[a][2] - x[b][2]}; };
    for (auto& tr : m_tris) {
        // -p A n, a third on each corner (fascia/elements/Pressure.h)
        const elements::Vec33<double> fa = elements::trianglePressureForce(diff(tr[1], tr[0]), diff(tr[2], tr[0]), p);
        for (int a : tr) f[a] += Vec3(fa.x, fa.y, fa.z);
    }
    // bilinear quadrilaterals, 2x2 Gauss points (fascia/elements/Pressure.h)
    for (auto& q : m_quads) {
        const elements::Vec33<double> d[4] = {{0, 0, 0}, diff(q[1], q[0]), diff(q[2], q[0]), diff(q[3], q[0])};
        elements::Vec33<double> fq[4];
        elements::quadPressureForces(d, p, fq);
        for (int a = 0; a < 4; ++a) f[q[a]] += Vec3(fq[a].x, fq[a].y, fq[a].z);
    }
}

} // namespace fascia::mechanics
