#pragma once
/// A signed distance grid over a closed triangle surface (docs/design.md, section 4.5): the exact
/// signed distance (TriangleTree) sampled once at the nodes of a regular grid of cubic cells over the
/// surface's box plus a margin, stored as floats; a query interpolates it trilinearly (value and
/// gradient) and, near the surface, replaces it with the exact closest point of the triangles.
#include "TriangleTree.h"

#include <cstdint>
#include <vector>

namespace fascia::contact {

class DistanceGrid {
public:
    /// The margin around the surface's box, in cells.
    static constexpr int kMarginCells = 3;

    /// The grid's node counts for `resolution` cells along the longest side of the box [lo, hi].
    static std::array<long long, 3> nodeCounts(const Vec3& lo, const Vec3& hi, int resolution);
    /// Its memory: 4 bytes a node.
    static double bytesFor(const std::array<long long, 3>& n) { return 4.0 * double(n[0]) * double(n[1]) * double(n[2]); }

    /// Samples the tree's signed distance at every node (rows of nodes on the OpenMP threads, each
    /// node on its own: the same grid for any thread count).
    DistanceGrid(const TriangleTree& tree, int resolution);

    /// Signed distance of p (negative inside) and the unit outward normal. Within kBand cells of the
    /// surface (by the interpolated value) the exact closest point: a point moved by -distance along
    /// normal lands on the surface. Farther, the interpolated value (within sqrt(3) cells of the
    /// exact one, the distance being 1-Lipschitz) and the normalised interpolated gradient. Outside
    /// the grid, the distance to the surface's box: below the exact one, above the margin.
    double query(const Vec3& p, Vec3& normal) const;

    /// The interpolated value alone (no exact refinement), and whether p is in the grid.
    bool interpolate(const Vec3& p, double& value, Vec3& gradient) const;
    /// The stored value at node (i, j, k).
    float at(long long i, long long j, long long k) const { return m_phi[size_t(i + m_n[0] * (j + m_n[1] * k))]; }
    const std::array<long long, 3>& counts() const { return m_n; }
    double cell() const { return m_h; }
    const Vec3& origin() const { return m_origin; }
    size_t bytes() const { return m_phi.size() * sizeof(float); }

private:
    /// Within this many cells (by the interpolated value) a query takes the exact closest point:
    /// above sqrt(3), the interpolation's largest error in cells, so that farther points are
    /// certainly off the surface and on the side the interpolation says.
    static constexpr double kBand = 2.0;

    const TriangleTree& m_tree;
    std::array<long long, 3> m_n{0, 0, 0};
    Vec3 m_origin = Vec3::Zero();
    double m_h = 0;
    std::vector<float> m_phi;
};

} // namespace fascia::contact
