#include "TriangleTree.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace fascia::contact {

Vec3 closestOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, TriangleFeature& feature) {
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) {
        feature = TriangleFeature::VertexA;
        return a;
    }
    const Vec3 bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) {
        feature = TriangleFeature::VertexB;
        return b;
    }
    const double vc = d1 * d4 - d3 * d2;  // the (signed, scaled) barycentric weight of c
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        feature = TriangleFeature::EdgeAB;
        return Vec3(a + (d1 / (d1 - d3)) * ab);
    }
    const Vec3 cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) {
        feature = TriangleFeature::VertexC;
        return c;
    }
    const double vb = d5 * d2 - d1 * d6;  // weight of b
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        feature = TriangleFeature::EdgeCA;
        return Vec3(a + (d2 / (d2 - d6)) * ac);
    }
    const double va = d3 * d6 - d5 * d4;  // weight of a
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
        feature = TriangleFeature::EdgeBC;
        return Vec3(b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b));
    }
    feature = TriangleFeature::Face;
    const double s = 1 / (va + vb + vc);
    return a + (vb * s) * ab + (vc * s) * ac;
}

namespace {
/// Squared distance from p to the box [lo, hi] (0 inside).
double boxDistance2(const Vec3& p, const Vec3& lo, const Vec3& hi) {
    const Vec3 d = (lo - p).cwiseMax(Vec3::Zero()).cwiseMax(p - hi);
    return d.squaredNorm();
}
/// The angle of the triangle at corner a (between ab and ac).
double cornerAngle(const Vec3& a, const Vec3& b, const Vec3& c) {
    return std::atan2((b - a).cross(c - a).norm(), (b - a).dot(c - a));
}
} // namespace

TriangleTree::TriangleTree(Positions points, Triangles triangles) : m_p(std::move(points)), m_tris(std::move(triangles)) {
    const size_t nt = m_tris.size();
    // face normals, and the angle-weighted vertex pseudonormals (Baerentzen and Aanaes, eq. 5)
    m_faceNormal.assign(nt, Vec3::Zero());
    m_vertexNormal.assign(m_p.size(), Vec3::Zero());
    for (size_t t = 0; t < nt; ++t) {
        const auto& v = m_tris[t];
        const Vec3 &a = m_p[size_t(v[0])], &b = m_p[size_t(v[1])], &c = m_p[size_t(v[2])];
        m_faceNormal[t] = (b - a).cross(c - a).normalized();
        m_vertexNormal[size_t(v[0])] += cornerAngle(a, b, c) * m_faceNormal[t];
        m_vertexNormal[size_t(v[1])] += cornerAngle(b, c, a) * m_faceNormal[t];
        m_vertexNormal[size_t(v[2])] += cornerAngle(c, a, b) * m_faceNormal[t];
    }
    for (Vec3& n : m_vertexNormal) n.normalize();
    // edge pseudonormals: the sum of the two faces' normals (an edge of a closed surface has two)
    struct HalfEdge { int lo, hi, tri, k; };
    std::vector<HalfEdge> half;
    half.reserve(3 * nt);
    for (size_t t = 0; t < nt; ++t)
        for (int k = 0; k < 3; ++k) {
            const int a = m_tris[t][size_t(k)], b = m_tris[t][size_t((k + 1) % 3)];
            half.push_back({std::min(a, b), std::max(a, b), int(t), k});
        }
    std::sort(half.begin(), half.end(), [](const HalfEdge& x, const HalfEdge& y) {
        return x.lo != y.lo ? x.lo < y.lo : x.hi != y.hi ? x.hi < y.hi : x.tri < y.tri;
    });
    m_edge.assign(nt, {0, 0, 0});
    for (size_t i = 0; i < half.size();) {
        size_t j = i;
        Vec3 n = Vec3::Zero();
        for (; j < half.size() && half[j].lo == half[i].lo && half[j].hi == half[i].hi; ++j) {
            n += m_faceNormal[size_t(half[j].tri)];
            m_edge[size_t(half[j].tri)][size_t(half[j].k)] = int(m_edgeNormal.size());
        }
        m_edgeNormal.push_back(n.normalized());
        i = j;
    }
    // the tree
    std::vector<Vec3> centroid(nt);
    for (size_t t = 0; t < nt; ++t)
        centroid[t] = (m_p[size_t(m_tris[t][0])] + m_p[size_t(m_tris[t][1])] + m_p[size_t(m_tris[t][2])]) / 3;
    m_order.resize(nt);
    std::iota(m_order.begin(), m_order.end(), 0);
    if (nt) build(0, int(nt), centroid);
    m_lo = m_boxes.empty() ? Vec3::Zero() : m_boxes[0].lo;
    m_hi = m_boxes.empty() ? Vec3::Zero() : m_boxes[0].hi;
}

int TriangleTree::build(int first, int count, std::vector<Vec3>& centroid) {
    const int id = int(m_boxes.size());
    m_boxes.push_back({Vec3::Zero(), Vec3::Zero(), 0, 0, -1, -1});
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    Vec3 clo = lo, chi = hi;
    for (int k = first; k < first + count; ++k) {
        const auto& v = m_tris[size_t(m_order[size_t(k)])];
        for (int c : v) lo = lo.cwiseMin(m_p[size_t(c)]), hi = hi.cwiseMax(m_p[size_t(c)]);
        const Vec3& m = centroid[size_t(m_order[size_t(k)])];
        clo = clo.cwiseMin(m), chi = chi.cwiseMax(m);
    }
    constexpr int kLeaf = 4;
    if (count <= kLeaf) {
        m_boxes[size_t(id)] = {lo, hi, first, count, -1, -1};
        return id;
    }
    int axis = 0;
    (chi - clo).maxCoeff(&axis);
    const int half = count / 2;
    // the median along the longest axis of the centroids (ties by triangle index: one answer)
    auto begin = m_order.begin() + first;
    std::nth_element(begin, begin + half, begin + count, [&](int a, int b) {
        const double ca = centroid[size_t(a)][axis], cb = centroid[size_t(b)][axis];
        return ca != cb ? ca < cb : a < b;
    });
    const int left = build(first, half, centroid);
    const int right = build(first + half, count - half, centroid);
    m_boxes[size_t(id)] = {lo, hi, first, 0, left, right};
    return id;
}

Vec3 TriangleTree::pseudonormal(int t, TriangleFeature f) const {
    const auto& v = m_tris[size_t(t)];
    const auto& e = m_edge[size_t(t)];
    switch (f) {
    case TriangleFeature::Face: return m_faceNormal[size_t(t)];
    case TriangleFeature::VertexA: return m_vertexNormal[size_t(v[0])];
    case TriangleFeature::VertexB: return m_vertexNormal[size_t(v[1])];
    case TriangleFeature::VertexC: return m_vertexNormal[size_t(v[2])];
    case TriangleFeature::EdgeAB: return m_edgeNormal[size_t(e[0])];
    case TriangleFeature::EdgeBC: return m_edgeNormal[size_t(e[1])];
    case TriangleFeature::EdgeCA: return m_edgeNormal[size_t(e[2])];
    }
    return m_faceNormal[size_t(t)];
}

SurfacePoint TriangleTree::nearest(const Vec3& p, double bound, bool& found, int seed) const {
    SurfacePoint out;
    found = false;
    if (m_boxes.empty()) return out;
    double best2 = std::isfinite(bound) ? bound * bound : std::numeric_limits<double>::infinity();
    TriangleFeature bestFeature = TriangleFeature::Face;
    if (seed >= 0 && size_t(seed) < m_tris.size()) {  // a likely answer first: a tight bound from the start
        const auto& v = m_tris[size_t(seed)];
        const Vec3 q = closestOnTriangle(p, m_p[size_t(v[0])], m_p[size_t(v[1])], m_p[size_t(v[2])], bestFeature);
        const double d2 = (p - q).squaredNorm();
        if (d2 <= best2) {
            best2 = d2;
            out.point = q;
            out.triangle = seed;
            found = true;
        }
    }
    int stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Box& b = m_boxes[size_t(stack[--top])];
        if (boxDistance2(p, b.lo, b.hi) > best2) continue;
        if (b.count > 0) {
            for (int k = b.first; k < b.first + b.count; ++k) {
                const int t = m_order[size_t(k)];
                TriangleFeature f;
                Vec3 q;
                const double d2 = distance2(p, t, q, f);
                // ties to the lowest index: the same answer for any search order (DistanceGrid's cell lists)
                if (d2 < best2 || (!found && d2 <= best2) || (d2 == best2 && t < out.triangle)) {
                    best2 = d2;
                    out.point = q;
                    out.triangle = t;
                    bestFeature = f;
                    found = true;
                }
            }
            continue;
        }
        // the nearer child last on the stack: searched first, so that it tightens the bound
        const Box &l = m_boxes[size_t(b.left)], &r = m_boxes[size_t(b.right)];
        const bool leftFirst = boxDistance2(p, l.lo, l.hi) <= boxDistance2(p, r.lo, r.hi);
        stack[top++] = leftFirst ? b.right : b.left;
        stack[top++] = leftFirst ? b.left : b.right;
    }
    if (!found) return out;
    return result(p, out.triangle, out.point, bestFeature, best2);
}

double TriangleTree::distance2(const Vec3& p, int t, Vec3& q, TriangleFeature& feature) const {
    const auto& v = m_tris[size_t(t)];
    q = closestOnTriangle(p, m_p[size_t(v[0])], m_p[size_t(v[1])], m_p[size_t(v[2])], feature);
    return (p - q).squaredNorm();
}

SurfacePoint TriangleTree::result(const Vec3& p, int t, const Vec3& q, TriangleFeature feature, double d2) const {
    SurfacePoint out;
    out.point = q;
    out.triangle = t;
    // the sign from the feature's pseudonormal; on a face the face's normal (p - q is along it)
    const Vec3 pn = pseudonormal(t, feature);
    const Vec3 d = p - q;
    const double len = std::sqrt(d2);
    if (feature == TriangleFeature::Face) {
        out.distance = d.dot(pn);
        out.normal = pn;
    } else {
        const bool outside = d.dot(pn) >= 0;
        out.distance = outside ? len : -len;
        // off the surface, the direction to the point (a projection lands on the closest point);
        // on it (within round-off of the tool's size), the pseudonormal
        const double scale = (m_hi - m_lo).norm();
        out.normal = len > 1e-12 * scale ? Vec3(d / out.distance) : pn;
    }
    return out;
}

void TriangleTree::within(const Vec3& p, double radius, std::vector<int>& out) const {
    out.clear();
    if (m_boxes.empty() || !(radius >= 0)) return;
    const double r2 = radius * radius;
    int stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Box& b = m_boxes[size_t(stack[--top])];
        if (boxDistance2(p, b.lo, b.hi) > r2) continue;
        if (b.count == 0) {
            stack[top++] = b.left;
            stack[top++] = b.right;
            continue;
        }
        for (int k = b.first; k < b.first + b.count; ++k) {
            const int t = m_order[size_t(k)];
            TriangleFeature f;
            Vec3 q;
            if (distance2(p, t, q, f) <= r2) out.push_back(t);
        }
    }
    std::sort(out.begin(), out.end());
}

size_t TriangleTree::bytes() const {
    return m_p.size() * sizeof(Vec3) * 2 + m_tris.size() * (sizeof(m_tris[0]) + sizeof(Vec3) + sizeof(m_edge[0]) + sizeof(int)) +
           m_edgeNormal.size() * sizeof(Vec3) + m_boxes.size() * sizeof(Box);
}

} // namespace fascia::contact
