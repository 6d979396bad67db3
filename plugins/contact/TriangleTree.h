#pragma once
/// The exact signed distance to a closed triangle surface: the closest point over all triangles,
/// found in a bounding volume tree (axis-aligned boxes, median splits), and its sign from the
/// angle-weighted pseudonormal of the feature (face, edge or vertex) the closest point lies on.
/// Baerentzen and Aanaes, "Signed distance computation using the angle weighted pseudonormal"
/// (IEEE TVCG 11(3), 2005): for a closed, edge-manifold, consistently oriented surface, the vector
/// from the closest point to the query point has a positive dot product with that feature's
/// pseudonormal exactly when the point is outside. Unlike a ray's parity count it has no special
/// case where a ray grazes an edge or a vertex.
#include "fascia/base/Types.h"

#include <vector>

namespace fascia::contact {

/// Where the closest point of a triangle (a, b, c) to a point lies.
enum class TriangleFeature : signed char { Face, VertexA, VertexB, VertexC, EdgeAB, EdgeBC, EdgeCA };

/// The closest point of the triangle (a, b, c) to p, and the feature it lies on (the Voronoi region
/// of p: the vertices' and edges' regions by the signs of dot products, else the face's; Ericson,
/// "Real-Time Collision Detection", section 5.1.5).
Vec3 closestOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, TriangleFeature& feature);

/// A signed distance query's answer.
struct SurfacePoint {
    double distance = 0;  ///< signed: negative inside
    Vec3 point = Vec3::Zero();   ///< the closest surface point
    Vec3 normal = Vec3::Zero();  ///< unit outward direction at it: (p - point) / distance, or the feature's pseudonormal on the surface
    int triangle = -1;
};

class TriangleTree {
public:
    /// The surface must be closed, edge-manifold, consistently oriented outwards and without
    /// degenerate triangles (surface::requireClosedSurface and SurfaceTool check this).
    TriangleTree(Positions points, Triangles triangles);

    /// The exact signed distance of p, searching only triangles nearer than `bound` (pass a
    /// distance known to be at least the answer's, or infinity); `found` is false when none is.
    /// `seed`, when given, is a triangle tried first (a neighbour's nearest: its distance bounds
    /// the search at once).
    /// Of triangles at the same distance, the one of the lowest index (whatever the search order).
    SurfacePoint nearest(const Vec3& p, double bound, bool& found, int seed = -1) const;

    /// The triangles whose distance to p is at most `radius`, in increasing index order.
    void within(const Vec3& p, double radius, std::vector<int>& out) const;
    /// The squared distance from p to triangle t, its closest point q and feature.
    double distance2(const Vec3& p, int t, Vec3& q, TriangleFeature& feature) const;
    /// The answer of nearest() once its closest triangle t (point q, feature, squared distance d2) is
    /// known: the sign and the normal.
    SurfacePoint result(const Vec3& p, int t, const Vec3& q, TriangleFeature feature, double d2) const;

    const Vec3& lo() const { return m_lo; }
    const Vec3& hi() const { return m_hi; }
    size_t triangleCount() const { return m_tris.size(); }
    const Positions& points() const { return m_p; }
    const Triangles& triangles() const { return m_tris; }
    /// Memory held (bytes), for the documentation's figures.
    size_t bytes() const;

private:
    struct Box {
        Vec3 lo, hi;
        int first, count;  ///< a leaf's triangles (m_order[first .. first + count)); count 0: an inner box
        int left, right;   ///< an inner box's children
    };
    int build(int first, int count, std::vector<Vec3>& centroid);
    /// The outward unit pseudonormal of triangle t's feature.
    Vec3 pseudonormal(int t, TriangleFeature f) const;

    Positions m_p;
    Triangles m_tris;
    std::vector<int> m_order;       ///< triangles in leaf order
    std::vector<Box> m_boxes;       ///< m_boxes[0] the root
    Positions m_faceNormal;         ///< unit
    std::vector<std::array<int, 3>> m_edge;  ///< per triangle: its edges ab, bc, ca as indices into m_edgeNormal
    Positions m_edgeNormal, m_vertexNormal;  ///< unit pseudonormals
    Vec3 m_lo = Vec3::Zero(), m_hi = Vec3::Zero();
};

} // namespace fascia::contact
