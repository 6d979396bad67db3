#include "TetLocator.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fascia::meshio {

Vec3 closestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    // by the Voronoi regions of the vertices, edges and face (Ericson, Real-Time Collision
    // Detection, section 5.1.5)
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) return a;
    const Vec3 bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
    const Vec3 cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
    const double denom = 1 / (va + vb + vc);
    return a + ab * (vb * denom) + ac * (vc * denom);
}

std::array<int, 3> TetLocator::Grid::cell(const Vec3& p) const {
    std::array<int, 3> c;
    for (int a = 0; a < 3; ++a) {
        const double u = std::floor((p[a] - lo[a]) / h);
        c[size_t(a)] = int(std::clamp(u, 0.0, double(n[size_t(a)] - 1)));
    }
    return c;
}

template <class Box>
void TetLocator::Grid::build(const Vec3& boxLo, const Vec3& boxHi, size_t count, Box box) {
    // about one bucket per item, cubic buckets
    const Vec3 ext = (boxHi - boxLo).cwiseMax(1e-300);
    const double vol = std::max(ext[0] * ext[1] * ext[2], 1e-300);
    h = std::cbrt(vol / double(std::max<size_t>(count, 1)));
    h = std::max(h, ext.maxCoeff() / 1024);  // at most 1024 buckets along an axis
    lo = boxLo;
    for (int a = 0; a < 3; ++a) n[size_t(a)] = std::clamp(int(std::ceil(ext[a] / h)), 1, 1024);
    const size_t buckets = size_t(n[0]) * n[1] * n[2];
    std::vector<int> counts(buckets + 1, 0);
    auto forBuckets = [&](size_t i, auto&& f) {
        Vec3 l, u;
        box(i, l, u);
        const auto c0 = cell(l), c1 = cell(u);
        for (int k = c0[2]; k <= c1[2]; ++k)
            for (int j = c0[1]; j <= c1[1]; ++j)
                for (int q = c0[0]; q <= c1[0]; ++q) f(index(q, j, k));
    };
    for (size_t i = 0; i < count; ++i) forBuckets(i, [&](int b) { ++counts[size_t(b) + 1]; });
    for (size_t b = 0; b < buckets; ++b) counts[b + 1] += counts[b];
    start = counts;
    items.resize(size_t(counts[buckets]));
    for (size_t i = 0; i < count; ++i) forBuckets(i, [&](int b) { items[size_t(counts[size_t(b)]++)] = int(i); });
}

TetLocator::TetLocator(const Positions& points, const Tetrahedra& tets, const Triangles& boundary)
    : m_points(points), m_tets(tets), m_boundary(boundary) {
    m_lo = m_hi = points.empty() ? Vec3::Zero() : points[0];
    for (const auto& p : points) {
        m_lo = m_lo.cwiseMin(p);
        m_hi = m_hi.cwiseMax(p);
    }
    m_inverse.resize(tets.size());
    for (size_t t = 0; t < tets.size(); ++t) {
        const Vec3& a = points[size_t(tets[t][0])];
        Mat3 E;
        E << points[size_t(tets[t][1])] - a, points[size_t(tets[t][2])] - a, points[size_t(tets[t][3])] - a;
        m_inverse[t] = E.inverse();
    }
    m_tetGrid.build(m_lo, m_hi, tets.size(), [&](size_t t, Vec3& l, Vec3& u) {
        l = u = points[size_t(tets[t][0])];
        for (int k = 1; k < 4; ++k) {
            l = l.cwiseMin(points[size_t(tets[t][size_t(k)])]);
            u = u.cwiseMax(points[size_t(tets[t][size_t(k)])]);
        }
    });
    m_triGrid.build(m_lo, m_hi, boundary.size(), [&](size_t t, Vec3& l, Vec3& u) {
        l = u = points[size_t(boundary[t][0])];
        for (int k = 1; k < 3; ++k) {
            l = l.cwiseMin(points[size_t(boundary[t][size_t(k)])]);
            u = u.cwiseMax(points[size_t(boundary[t][size_t(k)])]);
        }
    });
    // the tetrahedron of each boundary triangle: the one of its first node's tetrahedra that has all three
    std::vector<int> start(points.size() + 1, 0), list(4 * tets.size());
    for (const auto& t : tets)
        for (int n : t) ++start[size_t(n) + 1];
    for (size_t i = 0; i < points.size(); ++i) start[i + 1] += start[i];
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (size_t t = 0; t < tets.size(); ++t)
        for (int n : tets[t]) list[size_t(fill[size_t(n)]++)] = int(t);
    m_boundaryTet.assign(boundary.size(), -1);
    for (size_t b = 0; b < boundary.size(); ++b) {
        const auto& tri = boundary[b];
        for (int q = start[size_t(tri[0])]; q < start[size_t(tri[0]) + 1]; ++q) {
            const auto& t = tets[size_t(list[size_t(q)])];
            auto has = [&](int n) { return std::find(t.begin(), t.end(), n) != t.end(); };
            if (has(tri[1]) && has(tri[2])) {
                m_boundaryTet[b] = list[size_t(q)];
                break;
            }
        }
    }
}

std::array<double, 4> TetLocator::weights(int t, const Vec3& p) const {
    const Vec3 l = m_inverse[size_t(t)] * (p - m_points[size_t(m_tets[size_t(t)][0])]);
    return {1 - l[0] - l[1] - l[2], l[0], l[1], l[2]};
}

std::pair<int, double> TetLocator::nearestBoundary(const Vec3& p) const {
    const Grid& g = m_triGrid;
    const auto c = g.cell(p);
    // distance from p to the grid's box: every bucket is at least that far
    const Vec3 gridHi = g.lo + g.h * Vec3(g.n[0], g.n[1], g.n[2]);
    const double outside = (g.lo - p).cwiseMax(p - gridHi).cwiseMax(0.0).norm();
    int best = -1;
    double bestD = std::numeric_limits<double>::infinity();
    const int maxRing = std::max({g.n[0], g.n[1], g.n[2]});
    for (int r = 0; r <= maxRing; ++r) {
        // buckets of ring r are at least (r - 1) h away from p (p lies in, or outside, bucket c)
        if (best >= 0 && bestD <= std::max(outside, (r - 1) * g.h)) break;
        for (int k = c[2] - r; k <= c[2] + r; ++k)
            for (int j = c[1] - r; j <= c[1] + r; ++j)
                for (int i = c[0] - r; i <= c[0] + r; ++i) {
                    if (std::max({std::abs(i - c[0]), std::abs(j - c[1]), std::abs(k - c[2])}) != r) continue;
                    if (i < 0 || j < 0 || k < 0 || i >= g.n[0] || j >= g.n[1] || k >= g.n[2]) continue;
                    const int b = g.index(i, j, k);
                    for (int q = g.start[size_t(b)]; q < g.start[size_t(b) + 1]; ++q) {
                        const int t = g.items[size_t(q)];
                        const auto& tri = m_boundary[size_t(t)];
                        const Vec3 x = closestPointOnTriangle(p, m_points[size_t(tri[0])], m_points[size_t(tri[1])], m_points[size_t(tri[2])]);
                        const double d = (x - p).norm();
                        if (d < bestD || (d == bestD && t < best)) {
                            bestD = d;
                            best = t;
                        }
                    }
                }
    }
    return {best, bestD};
}

TetLocation TetLocator::locate(const Vec3& p) const {
    TetLocation loc;
    const Grid& g = m_tetGrid;
    const auto c = g.cell(p);
    const int b = g.index(c[0], c[1], c[2]);
    // inside: the tetrahedron of p's bucket with the largest smallest weight (the most inside one)
    double bestMin = -std::numeric_limits<double>::infinity();
    for (int q = g.start[size_t(b)]; q < g.start[size_t(b) + 1]; ++q) {
        const int t = g.items[size_t(q)];
        const auto w = weights(t, p);
        const double m = std::min({w[0], w[1], w[2], w[3]});
        if (m > bestMin) {
            bestMin = m;
            loc.tetrahedron = t;
            loc.weights = w;
        }
    }
    if (loc.tetrahedron >= 0 && bestMin >= -1e-12) return loc;
    // outside (or in a bucket without a tetrahedron that holds it): under the nearest boundary triangle
    const auto [tri, d] = nearestBoundary(p);
    if (tri < 0 || m_boundaryTet[size_t(tri)] < 0) {
        loc.tetrahedron = -1;
        return loc;
    }
    loc.tetrahedron = m_boundaryTet[size_t(tri)];
    loc.weights = weights(loc.tetrahedron, p);
    loc.distance = d;
    return loc;
}

} // namespace fascia::meshio
