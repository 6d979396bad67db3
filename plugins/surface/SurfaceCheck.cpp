// The closed, edge-manifold, consistently oriented check: fascia/surface/TriangleSurface.h.
#include "fascia/surface/TriangleSurface.h"
#include "fascia/base/Format.h"

#include <algorithm>

namespace fascia::surface {

namespace {
struct HalfEdge {
    int lo, hi;       ///< the undirected edge
    bool forward;     ///< the triangle runs lo -> hi
    long long tri;
    bool operator<(const HalfEdge& o) const {
        if (lo != o.lo) return lo < o.lo;
        if (hi != o.hi) return hi < o.hi;
        return tri < o.tri;
    }
};

std::string at(const Positions& p, int v) {
    const Vec3& x = p[size_t(v)];
    return "(" + core::formatNumber(x[0], 6) + " " + core::formatNumber(x[1], 6) + " " + core::formatNumber(x[2], 6) + ")";
}
} // namespace

double enclosedVolume(const Positions& p, const Triangles& tris) {
    // about the centroid of the vertices, so that a surface far from the origin loses no digits
    Vec3 c = Vec3::Zero();
    for (const auto& x : p) c += x;
    if (!p.empty()) c /= double(p.size());
    double v = 0;
    for (const auto& t : tris) {
        const Vec3 a = p[size_t(t[0])] - c, b = p[size_t(t[1])] - c, d = p[size_t(t[2])] - c;
        v += a.dot(b.cross(d));
    }
    return v / 6;
}

SurfaceReport inspectSurface(const Positions& points, const Triangles& triangles) {
    std::vector<HalfEdge> edges;
    edges.reserve(3 * triangles.size());
    for (size_t i = 0; i < triangles.size(); ++i) {
        const auto& t = triangles[i];
        for (int k = 0; k < 3; ++k) {
            const int a = t[size_t(k)], b = t[size_t((k + 1) % 3)];
            edges.push_back({std::min(a, b), std::max(a, b), a < b, (long long)i});
        }
    }
    std::sort(edges.begin(), edges.end());
    SurfaceReport r;
    auto bad = [&](long long& counter, const HalfEdge& e) {
        ++counter;
        if (r.firstBadTriangle < 0 || e.tri < r.firstBadTriangle) {
            r.firstBadTriangle = e.tri;
            r.firstBadA = e.lo;
            r.firstBadB = e.hi;
        }
    };
    for (size_t i = 0; i < edges.size();) {
        size_t j = i + 1;
        while (j < edges.size() && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi) ++j;
        const size_t uses = j - i;
        if (uses == 1) bad(r.openEdges, edges[i]);
        else if (uses > 2) bad(r.nonManifoldEdges, edges[i + 2]);
        else if (edges[i].forward == edges[i + 1].forward) bad(r.misorientedEdges, edges[i + 1]);
        i = j;
    }
    r.volume = enclosedVolume(points, triangles);
    return r;
}

bool requireClosedSurface(TriangleSurface& s, const std::string& who) {
    const SurfaceReport r = inspectSurface(s.points, s.triangles);
    if (!r.closed()) {
        const size_t tri = size_t(r.firstBadTriangle);
        const std::string edge = "the edge between vertices " + std::to_string(r.firstBadA + 1) + " " + at(s.points, r.firstBadA) +
                                 " and " + std::to_string(r.firstBadB + 1) + " " + at(s.points, r.firstBadB) + " of triangle " +
                                 std::to_string(tri + 1);
        std::string what;
        if (r.openEdges > 0 && (r.nonManifoldEdges == 0 && r.misorientedEdges == 0))
            what = edge + " has no neighbour across it: the surface is open (" + std::to_string(r.openEdges) +
                   " edges on its border); close its holes";
        else if (r.nonManifoldEdges > 0 && r.misorientedEdges == 0 && r.openEdges == 0)
            what = edge + " is shared by three or more triangles: the surface is not edge-manifold (" +
                   std::to_string(r.nonManifoldEdges) + " such edges)";
        else if (r.misorientedEdges > 0 && r.openEdges == 0 && r.nonManifoldEdges == 0)
            what = edge + " runs the same way in both of its triangles: the triangles are not consistently oriented (" +
                   std::to_string(r.misorientedEdges) + " such edges); reorient them so that each edge runs once each way";
        else
            what = "the surface is not closed: " + std::to_string(r.openEdges) + " open, " + std::to_string(r.nonManifoldEdges) +
                   " non-manifold and " + std::to_string(r.misorientedEdges) + " misoriented edges; the first at " + edge;
        core::throwInputError(triangleLocation(s, tri), what + "; " + who + " needs a closed, edge-manifold, "
                                                        "consistently oriented surface");
    }
    if (!(r.volume > 0)) {
        if (r.volume == 0)
            core::throwInputError({s.file, 0}, "the surface encloses no volume; " + who + " needs a closed surface around a solid");
        for (auto& t : s.triangles) std::swap(t[1], t[2]);
        return true;
    }
    return false;
}

} // namespace fascia::surface
