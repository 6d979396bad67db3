#include "SphereTool.h"
#include "ToolDisplay.h"

namespace fascia::contact {

double SphereTool::signedDistance(const Vec3& local, Vec3& normal) const {
    const double r = local.norm();
    normal = r > 0 ? Vec3(local / r) : Vec3(0, 0, 1);  // the centre: any direction is the closest
    return r - m_radius.get();
}

bool SphereTool::localBounds(double margin, Vec3& lo, Vec3& hi) const {
    hi = Vec3::Constant(m_radius.get() + margin);
    lo = -hi;
    return true;
}

bool SphereTool::displayMesh(double, Positions& points, Triangles& triangles) const {
    capsuleMesh(m_radius.get(), 0.0, Vec3(0, 0, 1), 16, 32, points, triangles);
    return true;
}

} // namespace fascia::contact
