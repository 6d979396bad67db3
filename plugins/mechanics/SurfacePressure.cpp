#include "SurfacePressure.h"
#include "NodeSelection.h"
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
/// Corners of the bilinear patch in (xi, eta), in the face's node order.
constexpr double kXi[4] = {-1, 1, 1, -1}, kEta[4] = {-1, -1, 1, 1};
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

void SurfacePressure::addForce(core::BaseMechanicalState& s, Positions& f, double t) {
    const double p = m_pressure.get() * (m_curve.isSet() ? m_curve.value(t) : m_ramp.value(t));
    const Positions& x = s.x();
    for (auto& tr : m_tris) {
        // -p A n = -p/2 (x1 - x0) x (x2 - x0), a third on each corner
        const Vec3 fa = (-p / 6.0) * (x[tr[1]] - x[tr[0]]).cross(x[tr[2]] - x[tr[0]]);
        f[tr[0]] += fa;
        f[tr[1]] += fa;
        f[tr[2]] += fa;
    }
    // bilinear quadrilaterals: f_a = -p sum_g N_a(g) (x_xi x x_eta)(g), 2x2 Gauss points of weight 1
    const double g = 1.0 / std::sqrt(3.0);
    for (auto& q : m_quads) {
        Vec3 fq[4] = {Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
        for (int gp = 0; gp < 4; ++gp) {
            const double xi = kXi[gp] * g, eta = kEta[gp] * g;
            Vec3 dxi = Vec3::Zero(), deta = Vec3::Zero();
            for (int a = 0; a < 4; ++a) {
                dxi += (0.25 * kXi[a] * (1 + kEta[a] * eta)) * x[q[a]];
                deta += (0.25 * kEta[a] * (1 + kXi[a] * xi)) * x[q[a]];
            }
            const Vec3 n = dxi.cross(deta);
            for (int a = 0; a < 4; ++a) fq[a] += (0.25 * (1 + kXi[a] * xi) * (1 + kEta[a] * eta)) * n;
        }
        for (int a = 0; a < 4; ++a) f[q[a]] -= p * fq[a];
    }
}

} // namespace fascia::mechanics
