#include "SurfaceTool.h"
#include "fascia/base/Format.h"
#include "fascia/surface/TriangleSurface.h"

#include <filesystem>

namespace fascia::contact {

namespace {
std::string mib(double bytes) { return core::formatNumber(bytes / (1024.0 * 1024.0), 4) + " MiB"; }
} // namespace

SurfaceTool::SurfaceTool() = default;
SurfaceTool::~SurfaceTool() = default;

void SurfaceTool::init() {
    const FilePath& file = m_mesh.get();
    std::error_code ec;
    if (!std::filesystem::exists(file.resolved, ec))
        fail(m_mesh, "mesh file '" + file.written + "' does not exist (looked for '" + file.resolved + "')",
             {"the path is relative to the scene file's folder"});
    surface::TriangleSurface s;
    try {
        s = surface::readSurface(file.resolved);
        surface::requireClosedSurface(s, className() + " '" + name() + "'");
    } catch (const core::Error& e) {
        auto notes = e.notes();
        notes.push_back("read by " + className() + " '" + name() + "' at " + loc().str());
        throw core::Error(e.kind(), e.loc().empty() ? loc() : e.loc(), e.message(), notes);
    }
    for (size_t t = 0; t < s.triangles.size(); ++t) {
        const auto& v = s.triangles[t];
        const Vec3 &a = s.points[size_t(v[0])], &b = s.points[size_t(v[1])], &c = s.points[size_t(v[2])];
        if (!((b - a).cross(c - a).norm() > 0))
            core::throwInputError(surface::triangleLocation(s, t),
                                  "triangle " + std::to_string(t + 1) + " has no area (its vertices are on one line): " + className() +
                                      " '" + name() + "' needs a normal on every triangle",
                                  {"read by " + className() + " '" + name() + "' at " + loc().str()});
    }
    m_tree = std::make_unique<TriangleTree>(std::move(s.points), std::move(s.triangles));
    try {
        m_grid = std::make_unique<DistanceGrid>(*m_tree, m_resolution.get(), kMaxGridBytes);
    } catch (const DistanceGrid::TooLarge&) {
        const auto n = DistanceGrid::nodeCounts(m_tree->lo(), m_tree->hi(), m_resolution.get());
        fail(m_resolution, "resolution = " + std::to_string(m_resolution.get()) + ": the signed distance grid (" +
                               std::to_string(n[0]) + " x " + std::to_string(n[1]) + " x " + std::to_string(n[2]) + " nodes, " +
                               mib(DistanceGrid::bytesFor(n)) + ") and the triangle lists of its cells near the surface take more than the limit of " +
                               mib(kMaxGridBytes),
             {"lower the resolution: the exact closest point near the surface does not depend on it"});
    }
    m_size = (m_tree->hi() - m_tree->lo()).norm();
    initContact();
}

double SurfaceTool::signedDistance(const Vec3& local, Vec3& normal) const { return m_grid->query(local, normal); }

bool SurfaceTool::localBounds(double margin, Vec3& lo, Vec3& hi) const {
    lo = m_tree->lo() - Vec3::Constant(margin);
    hi = m_tree->hi() + Vec3::Constant(margin);
    return true;
}

bool SurfaceTool::displayMesh(double, Positions& points, Triangles& triangles) const {
    if (!m_tree) return false;
    points = m_tree->points();
    triangles = m_tree->triangles();
    return true;
}

} // namespace fascia::contact
