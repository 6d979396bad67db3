#include "GridMesh.h"
#include "fascia/surface/BoundaryFaces.h"

#include <Eigen/Dense>

#include <algorithm>

namespace fascia::meshio {

namespace {
/// (1-t) lo + t hi with t = i/n: exact at both ends, so faces sit exactly on the box.
double lerp(double lo, double hi, int i, int n) {
    const double t = double(i) / n;
    return (1 - t) * lo + t * hi;
}
double signedVolume(const Positions& p, const std::array<int, 4>& t) {
    return (p[t[1]] - p[t[0]]).dot((p[t[2]] - p[t[0]]).cross(p[t[3]] - p[t[0]])) / 6.0;
}
} // namespace

MeshData makeGrid(const Vec3& lo, const Vec3& hi, int nx, int ny, int nz, const std::string& element) {
    MeshData m;
    const int sx = nx + 1, sy = ny + 1, sz = nz + 1;
    auto id = [&](int i, int j, int k) { return i + sx * (j + sy * k); };
    m.points.resize(size_t(sx) * sy * sz);
    const size_t cells = size_t(nx) * ny * nz;
    if (element == "hexahedra") m.hexahedra.reserve(cells);
    else m.tetrahedra.reserve((element == "tetrahedra6" ? 6 : 5) * cells);
    for (int k = 0; k < sz; ++k)
        for (int j = 0; j < sy; ++j)
            for (int i = 0; i < sx; ++i)
                m.points[id(i, j, k)] = Vec3(lerp(lo[0], hi[0], i, nx), lerp(lo[1], hi[1], j, ny), lerp(lo[2], hi[2], k, nz));
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                // corners in VTK hexahedron order
                const int c[8] = {id(i, j, k),         id(i + 1, j, k),         id(i + 1, j + 1, k),
                                  id(i, j + 1, k),     id(i, j, k + 1),         id(i + 1, j, k + 1),
                                  id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)};
                if (element == "hexahedra") {
                    m.hexahedra.push_back({c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]});
                } else if (element == "tetrahedra6") {
                    // six tetrahedra around the diagonal 0-6 (conforming on every face)
                    static const int T[6][4] = {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6},
                                                {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}};
                    for (auto& t : T) m.tetrahedra.push_back({c[t[0]], c[t[1]], c[t[2]], c[t[3]]});
                } else {
                    // five tetrahedra; the split alternates with the cell parity so faces conform
                    static const int A[5][4] = {{0, 1, 3, 4}, {1, 2, 3, 6}, {1, 4, 5, 6}, {3, 4, 6, 7}, {1, 3, 4, 6}};
                    static const int B[5][4] = {{0, 1, 2, 5}, {0, 2, 3, 7}, {0, 4, 5, 7}, {2, 5, 6, 7}, {0, 2, 5, 7}};
                    const auto& S = ((i + j + k) % 2 == 0) ? A : B;
                    for (auto& t : S) m.tetrahedra.push_back({c[t[0]], c[t[1]], c[t[2]], c[t[3]]});
                }
            }
    for (auto& t : m.tetrahedra)
        if (signedVolume(m.points, t) < 0) std::swap(t[1], t[2]);
    m.tetrahedronGroup.assign(m.tetrahedra.size(), 0);
    m.hexahedronGroup.assign(m.hexahedra.size(), 0);
    auto onSurface = [&](int n) {
        const Vec3& p = m.points[size_t(n)];
        for (int a = 0; a < 3; ++a)
            if (p[a] == lo[a] || p[a] == hi[a]) return true;
        return false;
    };
    // only faces with every node on the box can be boundary faces: the work grows with the surface
    m.triangles = surface::boundaryTriangles(m, onSurface);
    m.triangleGroup.assign(m.triangles.size(), 0);
    const char* names[3][2] = {{"xmin", "xmax"}, {"ymin", "ymax"}, {"zmin", "zmax"}};
    const int res[3] = {nx, ny, nz};
    for (int k = 0; k < sz; ++k)
        for (int j = 0; j < sy; ++j)
            for (int i = 0; i < sx; ++i) {
                const int ijk[3] = {i, j, k};
                for (int a = 0; a < 3; ++a) {
                    if (ijk[a] == 0) m.nodeGroups[names[a][0]].push_back(id(i, j, k));
                    if (ijk[a] == res[a]) m.nodeGroups[names[a][1]].push_back(id(i, j, k));
                }
            }
    return m;
}

void GridMesh::init() {
    const Vec3 lo = m_min.get(), hi = m_max.get();
    for (int a = 0; a < 3; ++a)
        if (!(hi[a] > lo[a])) fail(m_max, "max must exceed min along every axis (axis " + std::to_string(a) + ")");
    const auto& r = m_resolution.get();
    const double cells = double(r[0]) * r[1] * r[2];
    if (cells > 5e7) fail(m_resolution, "resolution gives " + std::to_string(cells) + " cells; at most 5e7");
    MeshData m = makeGrid(lo, hi, r[0], r[1], r[2], m_element.get());
    const Triangles boundary = m.triangles;  // the grid's triangles are its boundary
    publish(std::move(m), &boundary);
}

} // namespace fascia::meshio
