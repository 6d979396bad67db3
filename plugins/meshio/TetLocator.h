#pragma once
/// Finds the tetrahedron of a mesh that holds a point, or, for a point outside the mesh, the one
/// under its nearest boundary triangle: for mapping a visual surface onto a volume mesh.
#include "fascia/base/Types.h"

#include <array>
#include <vector>

namespace fascia::meshio {

/// Where a point is in a tetrahedral mesh.
struct TetLocation {
    int tetrahedron = -1;                 ///< index into the mesh's tetrahedra
    std::array<double, 4> weights{};      ///< barycentric coordinates (some negative outside the mesh); sum 1
    double distance = 0;                  ///< 0 inside the mesh, else the distance to the nearest boundary triangle
};

/// A uniform grid of buckets over the mesh's bounding box, each bucket listing the tetrahedra whose
/// bounding box meets it, and one over the boundary triangles: a point is found by testing the
/// tetrahedra of its bucket (about a handful), and a point outside by searching the boundary
/// triangles ring by ring around it until no nearer one can be left. The grids have about one
/// bucket per element, so building them is O(n) and a search does not grow with the mesh.
class TetLocator {
public:
    /// points: the mesh's nodes; boundary: its boundary triangles (turned any way).
    TetLocator(const Positions& points, const Tetrahedra& tetrahedra, const Triangles& boundary);
    TetLocation locate(const Vec3& p) const;
    /// The barycentric coordinates of p in tetrahedron t (exact for affine maps; sum 1).
    std::array<double, 4> weights(int t, const Vec3& p) const;

private:
    struct Grid {
        Vec3 lo = Vec3::Zero();
        double h = 1;
        std::array<int, 3> n{1, 1, 1};
        std::vector<int> start, items;  ///< bucket b holds items[start[b] .. start[b + 1])
        std::array<int, 3> cell(const Vec3& p) const;
        int index(int i, int j, int k) const { return i + n[0] * (j + n[1] * k); }
        /// Fills the buckets with the items whose box [lo(i), hi(i)] meets them.
        template <class Box>
        void build(const Vec3& lo, const Vec3& hi, size_t count, Box box);
    };
    /// The nearest boundary triangle of p and its distance.
    std::pair<int, double> nearestBoundary(const Vec3& p) const;
    const Positions& m_points;
    const Tetrahedra& m_tets;
    const Triangles& m_boundary;
    std::vector<Mat3> m_inverse;       ///< per tetrahedron, the inverse of [b-a, c-a, d-a]
    std::vector<int> m_boundaryTet;    ///< per boundary triangle, the tetrahedron that has it
    Grid m_tetGrid, m_triGrid;
    Vec3 m_lo, m_hi;                   ///< bounding box of the nodes
};

/// The point of triangle (a, b, c) nearest to p.
Vec3 closestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

} // namespace fascia::meshio
