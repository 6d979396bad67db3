#pragma once
// Closed triangle surfaces for the SurfaceTool tests, made in code: the boundary of a set of
// voxels (a finely tessellated box, a cube with a notch) and an icosphere; their exact signed
// distances; and OBJ, ASCII STL and .vtp files of them in a temporary folder.
#include "fascia/base/Types.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace surfacetest {

using fascia::Positions;
using fascia::Triangles;
using fascia::Vec3;

struct Mesh {
    Positions points;
    Triangles triangles;
};

/// A set of voxels of size `cell` on a lattice from `origin`, nx x ny x nz of them.
struct Voxels {
    Vec3 origin = Vec3::Zero(), cell = Vec3::Ones();
    int n[3] = {1, 1, 1};
    std::vector<char> full;
    bool at(int i, int j, int k) const {
        return i >= 0 && j >= 0 && k >= 0 && i < n[0] && j < n[1] && k < n[2] && full[size_t(i + n[0] * (j + n[1] * k))];
    }
    Vec3 lo(int i, int j, int k) const { return origin + cell.cwiseProduct(Vec3(i, j, k)); }

    /// Every voxel full: the box [lo, hi] cut into nx x ny x nz voxels.
    static Voxels box(const Vec3& lo, const Vec3& hi, int nx, int ny, int nz) {
        Voxels v;
        v.origin = lo;
        v.n[0] = nx, v.n[1] = ny, v.n[2] = nz;
        v.cell = (hi - lo).cwiseQuotient(Vec3(nx, ny, nz));
        v.full.assign(size_t(nx * ny * nz), 1);
        return v;
    }

    /// The faces between a full voxel and an empty one (or the outside), each split into two
    /// triangles turned away from the full voxel; lattice points shared.
    Mesh surface() const {
        Mesh m;
        std::map<std::array<int, 3>, int> index;
        auto vertex = [&](std::array<int, 3> q) {
            auto it = index.find(q);
            if (it != index.end()) return it->second;
            index[q] = int(m.points.size());
            m.points.push_back(origin + cell.cwiseProduct(Vec3(q[0], q[1], q[2])));
            return int(m.points.size()) - 1;
        };
        for (int k = 0; k < n[2]; ++k)
            for (int j = 0; j < n[1]; ++j)
                for (int i = 0; i < n[0]; ++i) {
                    if (!at(i, j, k)) continue;
                    for (int a = 0; a < 3; ++a)
                        for (int side = 0; side < 2; ++side) {
                            std::array<int, 3> nb{i, j, k};
                            nb[size_t(a)] += side ? 1 : -1;
                            if (at(nb[0], nb[1], nb[2])) continue;
                            const int b = (a + 1) % 3, c = (a + 2) % 3;  // e_b x e_c = e_a
                            int quad[4];
                            const int du[4] = {0, 1, 1, 0}, dv[4] = {0, 0, 1, 1};
                            for (int q = 0; q < 4; ++q) {
                                std::array<int, 3> p{i, j, k};
                                p[size_t(a)] += side;
                                p[size_t(b)] += du[q];
                                p[size_t(c)] += dv[q];
                                quad[q] = vertex(p);
                            }
                            if (!side) std::swap(quad[1], quad[3]);  // facing -e_a
                            m.triangles.push_back({quad[0], quad[1], quad[2]});
                            m.triangles.push_back({quad[0], quad[2], quad[3]});
                        }
                }
        return m;
    }

    /// The exact signed distance: outside, the distance to the nearest full voxel; inside, minus
    /// the distance to the nearest empty voxel or to the outside of the lattice's box.
    double distance(const Vec3& p) const {
        auto boxDistance = [&](int i, int j, int k) {
            const Vec3 l = lo(i, j, k), h = l + cell;
            return (l - p).cwiseMax(Vec3::Zero()).cwiseMax(p - h).norm();
        };
        const Vec3 rel = (p - origin).cwiseQuotient(cell);
        const int ci = int(std::floor(rel[0])), cj = int(std::floor(rel[1])), ck = int(std::floor(rel[2]));
        const bool inside = at(ci, cj, ck);
        double best = 1e300;
        if (inside) {  // to the outside of the lattice's box
            const Vec3 l = origin, h = origin + cell.cwiseProduct(Vec3(n[0], n[1], n[2]));
            best = std::min((p - l).minCoeff(), (h - p).minCoeff());
        }
        for (int k = 0; k < n[2]; ++k)
            for (int j = 0; j < n[1]; ++j)
                for (int i = 0; i < n[0]; ++i)
                    if (bool(at(i, j, k)) != inside) best = std::min(best, boxDistance(i, j, k));
        return inside ? -best : best;
    }
};

/// The icosahedron subdivided `level` times (each triangle into four at its edge midpoints), its
/// vertices pushed onto the sphere of radius r about c: 20 4^level triangles, turned outwards.
inline Mesh icosphere(int level, double r, const Vec3& c) {
    const double t = (1 + std::sqrt(5.0)) / 2;
    Positions p = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                   {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (Vec3& v : p) v.normalize();
    Triangles f = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                   {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                   {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
    for (int l = 0; l < level; ++l) {
        std::map<std::pair<int, int>, int> mid;
        auto middle = [&](int a, int b) {
            const auto key = std::minmax(a, b);
            auto it = mid.find(key);
            if (it != mid.end()) return it->second;
            p.push_back((p[size_t(a)] + p[size_t(b)]).normalized());
            return mid[key] = int(p.size()) - 1;
        };
        Triangles g;
        for (const auto& tri : f) {
            const int a = middle(tri[0], tri[1]), b = middle(tri[1], tri[2]), d = middle(tri[2], tri[0]);
            g.push_back({tri[0], a, d});
            g.push_back({tri[1], b, a});
            g.push_back({tri[2], d, b});
            g.push_back({a, b, d});
        }
        f = g;
    }
    for (Vec3& v : p) v = c + r * v;
    return {p, f};
}

/// The smallest distance from c to the planes of the triangles (a tessellated sphere's inradius).
inline double inradius(const Mesh& m, const Vec3& c) {
    double r = 1e300;
    for (const auto& t : m.triangles) {
        const Vec3 &a = m.points[size_t(t[0])], &b = m.points[size_t(t[1])], &d = m.points[size_t(t[2])];
        r = std::min(r, std::abs((b - a).cross(d - a).normalized().dot(a - c)));
    }
    return r;
}

/// A fresh temporary folder for one test (removed with it).
struct TempDir {
    std::filesystem::path path;
    explicit TempDir(const std::string& tag)
        : path(std::filesystem::temp_directory_path() / ("fascia_surfacetool_" + tag + "_" + std::to_string(getpid()))) {
        std::filesystem::remove_all(path);
        std::filesystem::create_directories(path);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path, ec);
    }
    std::string file(const std::string& name) const { return (path / name).string(); }
};

/// Writes the mesh as OBJ (17 significant digits: the points read back exactly), `skip` triangles
/// left out from the end and `extra` lines added; returns the path.
inline std::string writeObj(const std::string& path, const Mesh& m, size_t skip = 0, const std::string& extra = "") {
    std::ofstream o(path);
    o.precision(17);
    for (const Vec3& v : m.points) o << "v " << v[0] << " " << v[1] << " " << v[2] << "\n";
    for (size_t t = 0; t + skip < m.triangles.size(); ++t)
        o << "f " << m.triangles[t][0] + 1 << " " << m.triangles[t][1] + 1 << " " << m.triangles[t][2] + 1 << "\n";
    o << extra;
    return path;
}

/// Writes the mesh as ASCII STL (17 significant digits: the points read back exactly), `skip`
/// triangles left out from the end; returns the path.
inline std::string writeStl(const std::string& path, const Mesh& m, size_t skip = 0) {
    std::ofstream o(path);
    o.precision(17);
    o << "solid mesh\n";
    for (size_t t = 0; t + skip < m.triangles.size(); ++t) {
        o << "facet normal 0 0 0\nouter loop\n";
        for (int k : m.triangles[t]) o << "vertex " << m.points[size_t(k)][0] << " " << m.points[size_t(k)][1] << " " << m.points[size_t(k)][2] << "\n";
        o << "endloop\nendfacet\n";
    }
    o << "endsolid mesh\n";
    return path;
}

/// Writes the mesh as a .vtp (VTK XML PolyData, ascii data: no VTK needed to write it), its
/// triangles as polygons, `skip` left out from the end; returns the path.
inline std::string writeVtp(const std::string& path, const Mesh& m, size_t skip = 0) {
    const size_t n = m.triangles.size() - skip;
    std::ofstream o(path);
    o.precision(17);
    o << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <PolyData>\n"
      << "    <Piece NumberOfPoints=\"" << m.points.size() << "\" NumberOfPolys=\"" << n << "\">\n"
      << "      <Points>\n        <DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (const Vec3& v : m.points) o << "          " << v[0] << " " << v[1] << " " << v[2] << "\n";
    o << "        </DataArray>\n      </Points>\n      <Polys>\n        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (size_t t = 0; t < n; ++t) o << "          " << m.triangles[t][0] << " " << m.triangles[t][1] << " " << m.triangles[t][2] << "\n";
    o << "        </DataArray>\n        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    for (size_t t = 0; t < n; ++t) o << "          " << 3 * (t + 1) << "\n";
    o << "        </DataArray>\n      </Polys>\n    </Piece>\n  </PolyData>\n</VTKFile>\n";
    return path;
}

} // namespace surfacetest
