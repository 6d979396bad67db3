#include "ToolDisplay.h"

#include <cmath>

namespace fascia::contact {

namespace {

/// Two unit vectors completing the unit `n` to a right-handed frame (u, v, n).
void completeFrame(const Vec3& n, Vec3& u, Vec3& v) {
    const Vec3 helper = std::abs(n.x()) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
    u = n.cross(helper).normalized();
    v = n.cross(u);
}

} // namespace

void capsuleMesh(double radius, double length, const Vec3& axis, int rings, int segments, Positions& points,
                 Triangles& triangles) {
    Vec3 u, v;
    completeFrame(axis, u, v);
    points.clear();
    triangles.clear();
    // the pole at the shaft's end (+axis), the rings from there to the tip's pole (-axis); a ring
    // of the half towards +axis is moved out by length * axis (an even count splits the halves)
    if (rings % 2) ++rings;
    points.push_back((radius + length) * axis);
    for (int r = 1; r <= rings; ++r) {
        const double theta = M_PI * r / (rings + 1);  // from +axis
        const double shift = r <= rings / 2 ? length : 0.0;
        for (int s = 0; s < segments; ++s) {
            const double phi = 2 * M_PI * s / segments;
            const Vec3 dir = std::cos(theta) * axis + std::sin(theta) * (std::cos(phi) * u + std::sin(phi) * v);
            points.push_back(radius * dir + shift * axis);
        }
    }
    points.push_back(-radius * axis);
    const int last = int(points.size()) - 1;
    auto at = [&](int r, int s) { return 1 + (r - 1) * segments + s % segments; };
    for (int s = 0; s < segments; ++s) triangles.push_back({0, at(1, s), at(1, s + 1)});
    for (int r = 1; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            triangles.push_back({at(r, s), at(r + 1, s), at(r + 1, s + 1)});
            triangles.push_back({at(r, s), at(r + 1, s + 1), at(r, s + 1)});
        }
    for (int s = 0; s < segments; ++s) triangles.push_back({last, at(rings, s + 1), at(rings, s)});
}

void squareMesh(const Vec3& normal, double extent, Positions& points, Triangles& triangles) {
    Vec3 u, v;
    completeFrame(normal, u, v);
    points = {extent * (-u - v), extent * (u - v), extent * (u + v), extent * (-u + v)};
    triangles = {{0, 1, 2}, {0, 2, 3}};
}

} // namespace fascia::contact
