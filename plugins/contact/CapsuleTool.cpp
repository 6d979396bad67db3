#include "CapsuleTool.h"
#include "ToolDisplay.h"

#include <algorithm>

namespace fascia::contact {

void CapsuleTool::init() {
    const double len = m_axis.get().norm();
    if (!(len > 0) || !std::isfinite(len)) fail(m_axis, "the axis has no direction (length 0)", {"give a non-zero vector, e.g. \"0 0 1\""});
    m_a = m_axis.get() / len;
    initContact();
}

double CapsuleTool::signedDistance(const Vec3& local, Vec3& normal) const {
    const double s = std::clamp(local.dot(m_a), 0.0, m_length.get());  // closest point of the axis segment
    const Vec3 d = local - s * m_a;
    const double r = d.norm();
    if (r > 0) {
        normal = d / r;
    } else {  // on the axis: any direction across it
        normal = m_a.unitOrthogonal();
    }
    return r - m_radius.get();
}

bool CapsuleTool::localBounds(double margin, Vec3& lo, Vec3& hi) const {
    const double r = m_radius.get() + margin;
    const Vec3 tipEnd = m_length.get() * m_a;
    lo = Vec3::Zero().cwiseMin(tipEnd) - Vec3::Constant(r);
    hi = Vec3::Zero().cwiseMax(tipEnd) + Vec3::Constant(r);
    return true;
}

bool CapsuleTool::displayMesh(double, Positions& points, Triangles& triangles) const {
    capsuleMesh(m_radius.get(), m_length.get(), m_a, 16, 32, points, triangles);
    return true;
}

} // namespace fascia::contact
