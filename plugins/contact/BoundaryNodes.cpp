#include "BoundaryNodes.h"

#include <algorithm>

namespace fascia::contact {

namespace {
/// Faces as sorted node tuples (the fourth -1 for a triangle); those that occur once are boundary.
void addOnceFaces(std::vector<std::array<int, 4>>& faces, std::vector<char>& onBoundary) {
    std::sort(faces.begin(), faces.end());
    for (size_t k = 0; k < faces.size();) {
        size_t e = k + 1;
        while (e < faces.size() && faces[e] == faces[k]) ++e;
        if (e - k == 1)
            for (int v : faces[k])
                if (v >= 0 && size_t(v) < onBoundary.size()) onBoundary[size_t(v)] = 1;
        k = e;
    }
}
} // namespace

IndexList boundaryNodes(const MeshData& mesh) {
    std::vector<char> onBoundary(mesh.points.size(), 0);
    std::vector<std::array<int, 4>> faces;
    // tetrahedron faces opposite each corner
    static const int kTet[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
    for (const auto& t : mesh.tetrahedra)
        for (const auto& f : kTet) {
            std::array<int, 4> k{t[f[0]], t[f[1]], t[f[2]], -1};
            std::sort(k.begin(), k.begin() + 3);
            faces.push_back(k);
        }
    // hexahedron faces in VTK order (0-3 bottom, 4-7 top)
    static const int kHex[6][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
    for (const auto& h : mesh.hexahedra)
        for (const auto& f : kHex) {
            std::array<int, 4> k{h[f[0]], h[f[1]], h[f[2]], h[f[3]]};
            std::sort(k.begin(), k.end());
            faces.push_back(k);
        }
    addOnceFaces(faces, onBoundary);
    IndexList out;
    for (size_t i = 0; i < onBoundary.size(); ++i)
        if (onBoundary[i]) out.push_back(int(i));
    return out;
}

} // namespace fascia::contact
