#include "ToolOutput.h"
#include "PvdSeries.h"
#include "SurfaceSeries.h"
#include "fascia/scene/Node.h"

#include <algorithm>
#include <limits>

namespace fascia::meshio {

namespace {
/// The half-side of a plane's square: 1.5 times the half-diagonal of the body's rest bounding box
/// (the body's footprint in any orientation, with a margin).
double planeExtent(const core::BaseMechanicalState& body) {
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const Vec3& p : body.x0()) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    return body.size() ? 0.75 * (hi - lo).norm() : 1.0;
}
} // namespace

void ToolOutput::start(const core::Component& owner, const core::BaseParam& param, const core::BaseMechanicalState& body,
                       const std::string& base, const std::string& compression, const std::vector<std::string>& taken) {
    m_owner = &owner;
    m_dir = owner.node()->context().outputDir;
    m_compression = compression;
    m_tools.clear();
    const double extent = planeExtent(body);
    for (core::BaseTool* t : owner.node()->root()->findAllInSubtree<core::BaseTool>()) {
        if (t->body() != &body) continue;
        Tool tool{t, base + "_" + t->name(), {}, {}};
        if (!t->displayMesh(extent, tool.local, tool.triangles)) continue;  // no shape to draw
        checkName(param, *t, tool.stem, taken);
        m_tools.push_back(std::move(tool));
    }
}

void ToolOutput::checkName(const core::BaseParam& param, const core::BaseTool& t, const std::string& stem,
                           const std::vector<std::string>& taken) const {
    if (t.name().empty() || t.name().find('/') != std::string::npos)
        m_owner->fail(param, "tool '" + t.path() + "' has no name to give its files", {"name the tool, or give tools=\"false\""});
    for (const Tool& other : m_tools)
        if (other.stem == stem)
            m_owner->fail(param, "tools '" + other.tool->path() + "' and '" + t.path() + "' touch its body under one name: their " +
                                     "files " + stem + "_<step>.vtp would be the same",
                          {"rename one of them, or give tools=\"false\""});
    if (std::find(taken.begin(), taken.end(), stem) != taken.end())
        m_owner->fail(param, "tool '" + t.path() + "' would write " + stem + "_<step>.vtp, the files of its own " + stem +
                                 " series",
                      {"rename the tool, or give tools=\"false\""});
}

std::vector<std::string> ToolOutput::write(long step) {
    std::vector<std::string> names;
    for (const Tool& t : m_tools) {
        const core::Pose pose = t.tool->pose();
        m_world.resize(t.local.size());
        for (size_t i = 0; i < t.local.size(); ++i) m_world[i] = pose.position + pose.orientation * t.local[i];
        SurfaceFrame frame;
        frame.points = &m_world;
        frame.triangles = &t.triangles;
        frame.fields = {{"force", t.tool->force()}, {"torque", t.tool->torque()}};
        const SeriesFile file = seriesFile(m_dir, t.stem, step, ".vtp");
        writeSurfaceFile(*m_owner, frame, file.path, m_compression);
        names.push_back(file.name);
    }
    return names;
}

} // namespace fascia::meshio
