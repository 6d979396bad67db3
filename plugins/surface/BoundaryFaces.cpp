#include "fascia/surface/BoundaryFaces.h"

#include <algorithm>
#include <cstdint>
#include <utility>

namespace fascia::surface {

namespace {
/// The quadrilateral faces of a hexahedron (VTK order), each counter-clockwise seen from outside.
const int kHexFaces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};

struct FaceRef {
    std::array<int, 4> key;  ///< sorted nodes; a triangle's fourth is -1, so it sorts first as a shorter list would
    int element;             ///< tetrahedra first, then hexahedra (tets.size() + hexahedron index)
    int face;                ///< local face of the element
};
} // namespace

Triangles boundaryTriangles(const MeshData& m, const std::function<bool(int)>& onSurface) {
    const int nt = int(m.tetrahedra.size());
    auto faceNodes = [&](const FaceRef& f, int* out) {
        if (f.element < nt) {
            const auto& t = m.tetrahedra[size_t(f.element)];
            for (int i = 0; i < 3; ++i) out[i] = t[size_t((f.face + 1 + i) % 4)];
            return 3;
        }
        const auto& h = m.hexahedra[size_t(f.element - nt)];
        for (int i = 0; i < 4; ++i) out[i] = h[size_t(kHexFaces[f.face][i])];
        return 4;
    };
    std::vector<FaceRef> faces;
    faces.reserve(onSurface ? 0 : 4 * m.tetrahedra.size() + 6 * m.hexahedra.size());
    auto add = [&](int element, int face) {
        FaceRef f{{-1, -1, -1, -1}, element, face};
        int nodes[4] = {0, 0, 0, 0};
        const int n = faceNodes(f, nodes);
        for (int i = 0; i < n; ++i) {
            if (onSurface && !onSurface(nodes[i])) return;
            f.key[size_t(i)] = nodes[i];
        }
        std::sort(f.key.begin(), f.key.begin() + n);
        faces.push_back(f);
    };
    for (int e = 0; e < nt; ++e)
        for (int k = 0; k < 4; ++k) add(e, k);
    for (int e = 0; e < int(m.hexahedra.size()); ++e)
        for (int k = 0; k < 6; ++k) add(nt + e, k);
    // equal faces side by side; among them the first element's first (the one a map would keep)
    std::sort(faces.begin(), faces.end(), [](const FaceRef& a, const FaceRef& b) {
        if (a.key != b.key) return a.key < b.key;
        return std::make_pair(a.element, a.face) < std::make_pair(b.element, b.face);
    });

    Triangles out;
    auto centroid = [&](int element) {
        Vec3 c = Vec3::Zero();
        if (element < nt) {
            for (int n : m.tetrahedra[size_t(element)]) c += m.points[size_t(n)];
            return Vec3(c / 4);
        }
        for (int n : m.hexahedra[size_t(element - nt)]) c += m.points[size_t(n)];
        return Vec3(c / 8);
    };
    auto outward = [&](std::array<int, 3> t, const Vec3& inside) {
        const Vec3 n = (m.points[size_t(t[1])] - m.points[size_t(t[0])]).cross(m.points[size_t(t[2])] - m.points[size_t(t[0])]);
        if (n.dot(m.points[size_t(t[0])] - inside) < 0) std::swap(t[1], t[2]);
        out.push_back(t);
    };
    for (size_t i = 0; i < faces.size();) {
        size_t j = i + 1;
        while (j < faces.size() && faces[j].key == faces[i].key) ++j;
        if (j == i + 1) {
            int v[4] = {0, 0, 0, 0};
            const int n = faceNodes(faces[i], v);
            const Vec3 inside = centroid(faces[i].element);
            outward({v[0], v[1], v[2]}, inside);
            if (n == 4) outward({v[0], v[2], v[3]}, inside);
        }
        i = j;
    }
    return out;
}

} // namespace fascia::surface
