// The boundary faces of a volume mesh (fascia/surface/BoundaryFaces.h).
#include "fascia/surface/BoundaryFaces.h"
#include "fascia/surface/TriangleSurface.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <random>

using namespace fascia;
using namespace fascia::surface;

namespace {
/// A box of nx ny nz unit cells, 6 tetrahedra per cell around the diagonal 0-6 (or one hexahedron).
MeshData box(int nx, int ny, int nz, bool hexahedra) {
    MeshData m;
    auto id = [&](int i, int j, int k) { return i + (nx + 1) * (j + (ny + 1) * k); };
    for (int k = 0; k <= nz; ++k)
        for (int j = 0; j <= ny; ++j)
            for (int i = 0; i <= nx; ++i) m.points.emplace_back(i, j, k);
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                const int c[8] = {id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k),
                                  id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)};
                if (hexahedra) {
                    m.hexahedra.push_back({c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]});
                    continue;
                }
                static const int T[6][4] = {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6}, {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}};
                for (auto& t : T) m.tetrahedra.push_back({c[t[0]], c[t[1]], c[t[2]], c[t[3]]});
            }
    return m;
}
} // namespace

TEST_CASE("The boundary of one tetrahedron is its four faces turned outwards", "[BoundaryFaces]") {
    MeshData m;
    m.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
    m.tetrahedra = {{0, 1, 2, 3}};
    const Triangles b = boundaryTriangles(m);
    REQUIRE(b.size() == 4);
    const Vec3 c(0.25, 0.25, 0.25);
    for (const auto& t : b) {
        const Vec3 n = (m.points[t[1]] - m.points[t[0]]).cross(m.points[t[2]] - m.points[t[0]]);
        CHECK(n.dot(m.points[t[0]] - c) > 0);
    }
    CHECK(enclosedVolume(m.points, b) == Approx(1.0 / 6).epsilon(1e-14));
}

TEST_CASE("The boundary of a tetrahedral and of a hexahedral box is closed, outward and encloses the box", "[BoundaryFaces]") {
    const bool hex = GENERATE(false, true);
    const MeshData m = box(3, 2, 2, hex);
    const Triangles b = boundaryTriangles(m);
    CHECK(b.size() == size_t(4 * (3 * 2 + 2 * 2 + 2 * 3)));
    const SurfaceReport r = inspectSurface(m.points, b);
    CHECK(r.closed());
    CHECK(r.volume == Approx(12.0).epsilon(1e-13));
    for (const auto& t : b)
        for (int n : t) {
            const Vec3& p = m.points[size_t(n)];
            CHECK((p[0] == 0 || p[0] == 3 || p[1] == 0 || p[1] == 2 || p[2] == 0 || p[2] == 2));
        }
}

TEST_CASE("The boundary does not depend on the order of the elements and a surface filter changes nothing", "[BoundaryFaces]") {
    MeshData m = box(3, 3, 2, false);
    const Triangles ref = boundaryTriangles(m);
    auto onSurface = [&](int n) {
        const Vec3& p = m.points[size_t(n)];
        return p[0] == 0 || p[0] == 3 || p[1] == 0 || p[1] == 3 || p[2] == 0 || p[2] == 2;
    };
    CHECK(boundaryTriangles(m, onSurface) == ref);
    std::mt19937 rng(7);
    std::shuffle(m.tetrahedra.begin(), m.tetrahedra.end(), rng);
    const Triangles shuffled = boundaryTriangles(m);
    REQUIRE(shuffled.size() == ref.size());
    // the same faces in the same order; a face may start at another corner
    for (size_t i = 0; i < ref.size(); ++i) {
        auto a = ref[i], b = shuffled[i];
        std::sort(a.begin(), a.end());
        std::sort(b.begin(), b.end());
        CHECK(a == b);
    }
    CHECK(enclosedVolume(m.points, shuffled) == Approx(18.0).epsilon(1e-13));
}
