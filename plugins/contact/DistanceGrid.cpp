#include "DistanceGrid.h"
#include "fascia/sim/Mechanics.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fascia::contact {

std::array<long long, 3> DistanceGrid::nodeCounts(const Vec3& lo, const Vec3& hi, int resolution) {
    const Vec3 ext = hi - lo;
    const double h = ext.maxCoeff() / double(std::max(resolution, 1));
    std::array<long long, 3> n{};
    for (int a = 0; a < 3; ++a) n[size_t(a)] = (long long)std::ceil(ext[a] / h - 1e-9) + 2 * kMarginCells + 1;
    return n;
}

DistanceGrid::DistanceGrid(const TriangleTree& tree, int resolution) : m_tree(tree) {
    const Vec3 lo = tree.lo(), hi = tree.hi();
    m_n = nodeCounts(lo, hi, resolution);
    m_h = (hi - lo).maxCoeff() / double(resolution);
    // centred on the surface's box
    const Vec3 span(double(m_n[0] - 1) * m_h, double(m_n[1] - 1) * m_h, double(m_n[2] - 1) * m_h);
    m_origin = 0.5 * (lo + hi) - 0.5 * span;
    m_phi.assign(size_t(m_n[0] * m_n[1] * m_n[2]), 0.0f);
    const long rows = long(m_n[1] * m_n[2]);
    core::forEachNode(rows, [&](long row) {
        const long long j = row % m_n[1], k = row / m_n[1];
        // along the row, the last node's distance plus a cell bounds the next one's (1-Lipschitz):
        // the tree search starts with that bound
        // (and its nearest triangle, tried first, mostly the answer again)
        double bound = std::numeric_limits<double>::infinity();
        int seed = -1;
        for (long long i = 0; i < m_n[0]; ++i) {
            const Vec3 p = m_origin + m_h * Vec3(double(i), double(j), double(k));
            bool found = false;
            SurfacePoint s = m_tree.nearest(p, bound, found, seed);
            if (!found) s = m_tree.nearest(p, std::numeric_limits<double>::infinity(), found);
            m_phi[size_t(i + m_n[0] * (j + m_n[1] * k))] = float(s.distance);
            bound = std::abs(s.distance) + m_h * (1 + 1e-9);
            seed = s.triangle;
        }
    });
}

bool DistanceGrid::interpolate(const Vec3& p, double& value, Vec3& gradient) const {
    const Vec3 g = (p - m_origin) / m_h;
    long long c[3];
    double f[3];
    for (int a = 0; a < 3; ++a) {
        if (!(g[a] >= 0 && g[a] <= double(m_n[size_t(a)] - 1))) return false;  // outside, or NaN
        c[a] = std::min((long long)g[a], m_n[size_t(a)] - 2);
        f[a] = g[a] - double(c[a]);
    }
    const size_t sx = 1, sy = size_t(m_n[0]), sz = size_t(m_n[0] * m_n[1]);
    const size_t base = size_t(c[0]) * sx + size_t(c[1]) * sy + size_t(c[2]) * sz;
    double v[8];
    for (int q = 0; q < 8; ++q) v[q] = m_phi[base + ((q & 1) ? sx : 0) + ((q & 2) ? sy : 0) + ((q & 4) ? sz : 0)];
    const double x = f[0], y = f[1], z = f[2];
    // along x, then y, then z; the gradient from the same corner values
    const double v00 = v[0] + x * (v[1] - v[0]), v10 = v[2] + x * (v[3] - v[2]);
    const double v01 = v[4] + x * (v[5] - v[4]), v11 = v[6] + x * (v[7] - v[6]);
    const double v0 = v00 + y * (v10 - v00), v1 = v01 + y * (v11 - v01);
    value = v0 + z * (v1 - v0);
    const double dx0 = (1 - y) * (v[1] - v[0]) + y * (v[3] - v[2]), dx1 = (1 - y) * (v[5] - v[4]) + y * (v[7] - v[6]);
    gradient = Vec3((1 - z) * dx0 + z * dx1, (1 - z) * (v10 - v00) + z * (v11 - v01), v1 - v0) / m_h;
    return true;
}

double DistanceGrid::query(const Vec3& p, Vec3& normal) const {
    double value;
    Vec3 gradient;
    if (!interpolate(p, value, gradient)) {
        // outside the grid: outside the surface's box by more than the margin
        const Vec3 q = p.cwiseMax(m_tree.lo()).cwiseMin(m_tree.hi());
        const Vec3 d = p - q;
        const double len = d.norm();
        normal = len > 0 ? Vec3(d / len) : Vec3(0, 0, 1);
        return len > 0 ? len : std::numeric_limits<double>::infinity();  // NaN coordinates: far
    }
    if (std::abs(value) >= kBand * m_h) {
        const double len = gradient.norm();
        normal = len > 0 ? Vec3(gradient / len) : Vec3(0, 0, 1);
        return value;
    }
    // near the surface: the exact closest point, searched within the interpolation's error bound
    bool found = false;
    SurfacePoint s = m_tree.nearest(p, std::abs(value) + kBand * m_h, found);
    if (!found) s = m_tree.nearest(p, std::numeric_limits<double>::infinity(), found);
    normal = s.normal;
    return s.distance;
}

} // namespace fascia::contact
