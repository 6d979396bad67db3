#include "DistanceGrid.h"
#include "fascia/sim/Mechanics.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace fascia::contact {

std::array<long long, 3> DistanceGrid::nodeCounts(const Vec3& lo, const Vec3& hi, int resolution) {
    const Vec3 ext = hi - lo;
    const double h = ext.maxCoeff() / double(std::max(resolution, 1));
    std::array<long long, 3> n{};
    for (int a = 0; a < 3; ++a) n[size_t(a)] = (long long)std::ceil(ext[a] / h - 1e-9) + 2 * kMarginCells + 1;
    return n;
}

DistanceGrid::DistanceGrid(const TriangleTree& tree, int resolution, double maxBytes) : m_tree(tree) {
    const Vec3 lo = tree.lo(), hi = tree.hi();
    m_n = nodeCounts(lo, hi, resolution);
    const double nodeBytes = bytesFor(m_n) + sizeof(uint32_t);  // and the offsets' last one
    if (!(nodeBytes <= maxBytes)) throw TooLarge("DistanceGrid: the grid's nodes take more than the memory allowed");
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
    cellLists(std::floor((maxBytes - nodeBytes) / double(sizeof(Entry))));
}

void DistanceGrid::cellLists(double maxEntries) {
    const long long n0 = m_n[0], n1 = m_n[1], n2 = m_n[2];
    const double band = kBand * m_h * (1 + 1e-6);  // the query's band, and a margin for its round-off
    const double r = 0.5 * std::sqrt(3.0) * m_h;   // the cells' half diagonal
    const long rows = long((n1 - 1) * (n2 - 1));
    std::vector<std::vector<Entry>> rowList(size_t(std::max(rows, 0L)));
    std::vector<std::vector<uint32_t>> rowCount(rowList.size());
    // the entries listed so far, over all threads: past the limit every thread skips its remaining
    // rows (whichever rows were listed, the total is then above the limit: the same answer, TooLarge)
    const double limit = std::min(maxEntries, double(std::numeric_limits<uint32_t>::max()));
    std::atomic<size_t> listed{0};
    std::atomic<bool> over{false};
    core::forEachNode(rows, [&](long row) {
        if (over.load(std::memory_order_relaxed)) return;
        const long long j = row % (n1 - 1), k = row / (n1 - 1);
        std::vector<int> near;
        rowCount[size_t(row)].assign(size_t(n0 - 1), 0);
        for (long long i = 0; i + 1 < n0; ++i) {
            float lo = std::numeric_limits<float>::infinity(), hi = -lo;
            for (int q = 0; q < 8; ++q) {
                const float v = at(i + (q & 1), j + ((q >> 1) & 1), k + ((q >> 2) & 1));
                lo = std::min(lo, v), hi = std::max(hi, v);
            }
            if (!(double(lo) < band && double(hi) > -band)) continue;  // the query never refines here
            const Vec3 c = m_origin + m_h * Vec3(double(i) + 0.5, double(j) + 0.5, double(k) + 0.5);
            bool found = false;
            const SurfacePoint s0 = m_tree.nearest(c, std::numeric_limits<double>::infinity(), found);
            double U = 0;
            for (int q = 0; q < 8; ++q) {
                const Vec3 corner = c + 0.5 * m_h * Vec3((q & 1) ? 1 : -1, (q & 2) ? 1 : -1, (q & 4) ? 1 : -1);
                Vec3 point;
                TriangleFeature f;
                U = std::max(U, std::sqrt(m_tree.distance2(corner, s0.triangle, point, f)));
            }
            m_tree.within(c, (U + r) * (1 + 1e-9) + 1e-9 * m_h, near);
            std::vector<Entry>& list = rowList[size_t(row)];
            const size_t first = list.size();
            for (int t : near) {
                Vec3 point;
                TriangleFeature f;
                const double d = std::sqrt(m_tree.distance2(c, t, point, f));
                float key = float(d);
                if (double(key) > d) key = std::nextafter(key, -std::numeric_limits<float>::infinity());
                list.push_back({key, t});
            }
            std::sort(list.begin() + long(first), list.end(), [](const Entry& a, const Entry& b) {
                return a.centre != b.centre ? a.centre < b.centre : a.triangle < b.triangle;
            });
            rowCount[size_t(row)][size_t(i)] = uint32_t(list.size() - first);
        }
        const size_t all = listed.fetch_add(rowList[size_t(row)].size()) + rowList[size_t(row)].size();
        if (double(all) > limit) over = true;
    });
    if (over) throw TooLarge("DistanceGrid: the cell lists take more than the memory allowed");
    // in node order (a cell by its lowest node): the same arrays for any thread count
    m_offset.assign(size_t(n0 * n1 * n2) + 1, 0);
    size_t total = 0;
    for (long long node = 0; node < n0 * n1 * n2; ++node) {
        m_offset[size_t(node)] = uint32_t(total);
        const long long i = node % n0, j = (node / n0) % n1, k = node / (n0 * n1);
        if (i + 1 < n0 && j + 1 < n1 && k + 1 < n2) total += rowCount[size_t(j + (n1 - 1) * k)][size_t(i)];
    }
    m_offset.back() = uint32_t(total);
    m_list.reserve(total);
    for (long row = 0; row < rows; ++row) m_list.insert(m_list.end(), rowList[size_t(row)].begin(), rowList[size_t(row)].end());
}

bool DistanceGrid::interpolate(const Vec3& p, double& value, Vec3& gradient) const {
    size_t cell;
    return interpolate(p, value, gradient, cell);
}

bool DistanceGrid::interpolate(const Vec3& p, double& value, Vec3& gradient, size_t& cell) const {
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
    cell = base;
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

double DistanceGrid::outside(const Vec3& p, Vec3& normal) const {
    // outside the grid: outside the surface's box by more than the margin
    const Vec3 q = p.cwiseMax(m_tree.lo()).cwiseMin(m_tree.hi());
    const Vec3 d = p - q;
    const double len = d.norm();
    normal = len > 0 ? Vec3(d / len) : Vec3(0, 0, 1);
    return len > 0 ? len : std::numeric_limits<double>::infinity();  // NaN coordinates: far
}

SurfacePoint DistanceGrid::nearestListed(const Vec3& p, size_t cell) const {
    const long long i = (long long)cell % m_n[0], j = ((long long)cell / m_n[0]) % m_n[1], k = (long long)cell / (m_n[0] * m_n[1]);
    const Vec3 c = m_origin + m_h * Vec3(double(i) + 0.5, double(j) + 0.5, double(k) + 0.5);
    const double pc = (p - c).norm() + 1e-9 * m_h;  // and a margin for round-off: stops later, never earlier
    double best2 = std::numeric_limits<double>::infinity(), best = best2;
    int bestT = -1;
    Vec3 bestQ = Vec3::Zero();
    TriangleFeature bestF = TriangleFeature::Face;
    for (uint32_t e = m_offset[cell]; e < m_offset[cell + 1]; ++e) {
        const Entry& en = m_list[e];
        if (double(en.centre) - pc > best) break;  // |p - T| >= |c - T| - |p - c|: this and every later one farther
        Vec3 q;
        TriangleFeature f;
        const double d2 = m_tree.distance2(p, en.triangle, q, f);
        if (d2 < best2 || (d2 == best2 && en.triangle < bestT)) {  // ties as TriangleTree::nearest
            best2 = d2, best = std::sqrt(d2), bestT = en.triangle, bestQ = q, bestF = f;
        }
    }
    if (bestT < 0) {  // not a listed cell (cannot happen in the band): the tree
        bool found = false;
        return m_tree.nearest(p, std::numeric_limits<double>::infinity(), found);
    }
    return m_tree.result(p, bestT, bestQ, bestF, best2);
}

double DistanceGrid::query(const Vec3& p, Vec3& normal) const {
    double value;
    Vec3 gradient;
    size_t cell;
    if (!interpolate(p, value, gradient, cell)) return outside(p, normal);
    if (std::abs(value) >= kBand * m_h) {
        const double len = gradient.norm();
        normal = len > 0 ? Vec3(gradient / len) : Vec3(0, 0, 1);
        return value;
    }
    // near the surface: the exact closest point among the cell's listed triangles
    const SurfacePoint s = nearestListed(p, cell);
    normal = s.normal;
    return s.distance;
}

double DistanceGrid::queryTree(const Vec3& p, Vec3& normal) const {
    double value;
    Vec3 gradient;
    if (!interpolate(p, value, gradient)) return outside(p, normal);
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
