#include "PlaneTool.h"
#include "ToolDisplay.h"

namespace fascia::contact {

void PlaneTool::init() {
    const double len = m_normal.get().norm();
    if (!(len > 0) || !std::isfinite(len)) fail(m_normal, "the normal has no direction (length 0)", {"give a non-zero vector, e.g. \"0 0 1\""});
    m_n = m_normal.get() / len;
    initContact();
}

double PlaneTool::signedDistance(const Vec3& local, Vec3& normal) const {
    normal = m_n;
    return m_n.dot(local);
}

bool PlaneTool::displayMesh(double extent, Positions& points, Triangles& triangles) const {
    squareMesh(m_n, extent, points, triangles);
    return true;
}

} // namespace fascia::contact
