#pragma once
/// A signed distance grid over a closed triangle surface (docs/design.md, section 4.5): the exact
/// signed distance (TriangleTree) sampled once at the nodes of a regular grid of cubic cells over the
/// surface's box plus a margin, stored as floats; a query interpolates it trilinearly (value and
/// gradient) and, near the surface, replaces it with the exact closest point of the triangles, tested
/// among the few triangles a list precomputed for the query's cell holds.
#include "TriangleTree.h"

#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

namespace fascia::contact {

class DistanceGrid {
public:
    /// The margin around the surface's box, in cells.
    static constexpr int kMarginCells = 3;

    /// The grid's node counts for `resolution` cells along the longest side of the box [lo, hi].
    static std::array<long long, 3> nodeCounts(const Vec3& lo, const Vec3& hi, int resolution);
    /// The memory of its nodes, before any cell list: 8 bytes a node (a float sample and a 4-byte
    /// offset into the lists). The lists add 8 bytes an entry.
    static double bytesFor(const std::array<long long, 3>& n) { return 8.0 * double(n[0]) * double(n[1]) * double(n[2]); }

    /// The grid would take more than the memory it was allowed (the nodes, or the nodes and the
    /// lists), or more list entries than 32-bit offsets can address.
    struct TooLarge : std::length_error {
        using std::length_error::length_error;
    };

    /// Samples the tree's signed distance at every node (rows of nodes on the OpenMP threads, each
    /// node on its own: the same grid for any thread count), then lists for every cell of the band the
    /// triangles that can be the closest to a point of the cell (cellLists). Throws TooLarge, before
    /// allocating them, when the nodes would take more than maxBytes, and when the nodes and the
    /// lists would (counted as the lists are built, so that it stops early).
    DistanceGrid(const TriangleTree& tree, int resolution, double maxBytes = std::numeric_limits<double>::infinity());

    /// Signed distance of p (negative inside) and the unit outward normal. Within kBand cells of the
    /// surface (by the interpolated value) the exact closest point: a point moved by -distance along
    /// normal lands on the surface. Farther, the interpolated value (within sqrt(3) cells of the
    /// exact one, the distance being 1-Lipschitz) and the normalised interpolated gradient. Outside
    /// the grid, the distance to the surface's box: below the exact one, above the margin.
    /// The closest point is TriangleTree::nearest's (ties to the lowest triangle index), found among
    /// the cell's listed triangles.
    double query(const Vec3& p, Vec3& normal) const;
    /// The same through the whole tree, for the tests: bitwise the same answer.
    double queryTree(const Vec3& p, Vec3& normal) const;

    /// The interpolated value alone (no exact refinement), and whether p is in the grid.
    bool interpolate(const Vec3& p, double& value, Vec3& gradient) const;
    /// The stored value at node (i, j, k).
    float at(long long i, long long j, long long k) const { return m_phi[size_t(i + m_n[0] * (j + m_n[1] * k))]; }
    const std::array<long long, 3>& counts() const { return m_n; }
    double cell() const { return m_h; }
    const Vec3& origin() const { return m_origin; }
    /// The memory of the samples alone, and of the cell lists.
    size_t bytes() const { return m_phi.size() * sizeof(float); }
    size_t listBytes() const { return m_offset.size() * sizeof(m_offset[0]) + m_list.size() * sizeof(m_list[0]); }
    /// The number of triangles the cell lists hold in all.
    size_t listEntries() const { return m_list.size(); }

private:
    /// A triangle of a cell's list and its distance from the cell's centre.
    struct Entry {
        float centre;  ///< rounded down: a lower bound of the distance
        int triangle;
    };
    /// The lists (docs/design.md, section 4.5). The query refines only where the interpolated value
    /// is within kBand cells of zero; the value being a convex combination of the cell's 8 samples,
    /// that is in the cells whose samples reach into the band. For such a cell (centre c, half
    /// diagonal r): the closest triangle T0 of c bounds the distance of every point of the cell by
    /// U = the largest distance of a corner to T0 (the distance to one triangle is convex), so the
    /// closest triangle of a point p of the cell is within U + r of c. Those are the cell's list,
    /// sorted by their distance from c: the query stops at the first whose distance from c, less
    /// |p - c|, exceeds the best found (no later one can be nearer, or tie). At most maxEntries
    /// entries in all, else TooLarge (for any thread count).
    void cellLists(double maxEntries);
    /// Point p of cell `cell` (its index): the exact closest point among the cell's list.
    SurfacePoint nearestListed(const Vec3& p, size_t cell) const;
    /// The interpolated value, its gradient and the cell of p (its lowest node's index).
    bool interpolate(const Vec3& p, double& value, Vec3& gradient, size_t& cell) const;
    /// Outside the grid: the distance to the surface's box.
    double outside(const Vec3& p, Vec3& normal) const;

    /// Within this many cells (by the interpolated value) a query takes the exact closest point:
    /// above sqrt(3), the interpolation's largest error in cells, so that farther points are
    /// certainly off the surface and on the side the interpolation says.
    static constexpr double kBand = 2.0;

    const TriangleTree& m_tree;
    std::array<long long, 3> m_n{0, 0, 0};
    Vec3 m_origin = Vec3::Zero();
    double m_h = 0;
    std::vector<float> m_phi;
    std::vector<uint32_t> m_offset;  ///< per node (as a cell's lowest corner), then one: its list in m_list (empty off the band)
    std::vector<Entry> m_list;
};

} // namespace fascia::contact
