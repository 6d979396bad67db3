#include "Frame.h"

#include "fascia/base/Error.h"
#include "fascia/scene/Node.h"

#include <algorithm>
#include <unordered_map>

namespace fascia::view {

using core::throwInputError;

Field parseField(const std::string& name) {
    for (Field f : {Field::Displacement, Field::VonMises, Field::J, Field::None})
        if (name == fieldName(f)) return f;
    throwInputError({}, "no field '" + name + "' to colour the surface by", {"the fields are displacement, vonMises, J and none"});
}

const char* fieldName(Field f) {
    switch (f) {
    case Field::Displacement: return "displacement";
    case Field::VonMises: return "vonMises";
    case Field::J: return "J";
    default: return "none";
    }
}

const char* fieldUnit(Field f) {
    switch (f) {
    case Field::Displacement: return "mm";
    case Field::VonMises: return "kPa";
    default: return "";
    }
}

namespace {

/// The components of type T below root whose context state is `state` (as the simulation groups them).
template <class T>
std::vector<T*> actingOn(const core::Node& root, const core::BaseMechanicalState* state) {
    std::vector<T*> out;
    root.visit([&](const core::Node& n) {
        for (auto& c : n.components())
            if (auto* t = dynamic_cast<T*>(c.get()); t && n.findInContext<core::BaseMechanicalState>() == state) out.push_back(t);
    });
    return out;
}

} // namespace

FrameSource::FrameSource(const core::Node& root, Field field, const std::string& surfaceName) : m_field(field) {
    if (!surfaceName.empty()) {
        const core::Component* c = root.findUnique(surfaceName);
        if (!c || !addBody(*c, root))
            throwInputError({}, (c ? "'" + surfaceName + "' is a " + c->className() + ", not a surface to show" : "no component '" + surfaceName + "' in the scene"),
                            {"give a MechanicalObject whose mesh source has volume elements, or a visual surface (BarycentricSurfaceMapping)"});
    } else {
        root.visit([&](const core::Node& n) {
            for (auto& c : n.components())
                if (dynamic_cast<const core::BaseMechanicalState*>(c.get())) addBody(*c, root);
        });
    }
    if (m_bodies.empty())
        throwInputError({}, "the scene has no surface to show: no mechanical state has a mesh source with volume elements "
                            "in its context (MeshLoader, GridMesh, InlineMesh)");
    root.visit([&](const core::Node& n) {
        for (auto& c : n.components())
            if (auto* t = dynamic_cast<core::BaseTool*>(c.get())) m_tools.push_back(t);
    });
    Vec3 lo = Vec3::Constant(1e300), hi = -lo;
    for (auto& b : m_bodies)
        for (auto& p : b.rest) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    m_extent = 0.5 * (hi - lo).norm();  // (a plane is drawn 1.5 times this, as VTKExporter writes it)
    for (auto* t : m_tools) {
        m_toolPoints.emplace_back();
        m_toolTriangles.emplace_back();
        t->displayMesh(1.5 * m_extent, m_toolPoints.back(), m_toolTriangles.back());
    }
}

bool FrameSource::addBody(const core::Component& c, const core::Node& root) {
    Body b;
    const Triangles* triangles = nullptr;
    if (auto* v = dynamic_cast<const core::BaseVisualSurface*>(&c)) {
        b.state = const_cast<core::BaseMechanicalState*>(v->body());
        b.points = &v->points(), triangles = &v->triangles(), b.visual = true;
    } else if (auto* s = dynamic_cast<const core::BaseMechanicalState*>(&c)) {
        const core::BaseTopology* topo = s->node()->findInContext<core::BaseTopology>();
        if (!topo || topo->meshData().points.size() != s->size() || topo->boundaryTriangles().empty()) return false;
        b.state = const_cast<core::BaseMechanicalState*>(s);
        b.points = &s->x(), triangles = &topo->boundaryTriangles();
    }
    if (!triangles || triangles->empty() || !b.state) return false;
    // the surface points: the vertices the triangles use, in increasing order
    std::unordered_map<int, int> local;
    for (auto& t : *triangles)
        for (int v : t) local.emplace(v, 0);
    for (auto& [v, i] : local) b.nodes.push_back(v);
    std::sort(b.nodes.begin(), b.nodes.end());
    for (size_t i = 0; i < b.nodes.size(); ++i) local[b.nodes[i]] = int(i);
    for (auto& t : *triangles) b.triangles.push_back({local[t[0]], local[t[1]], local[t[2]]});
    for (int v : b.nodes) b.rest.push_back(b.visual ? (*b.points)[v] : b.state->x0()[v]);
    b.masses = actingOn<const core::BaseMass>(root, b.state);
    if (!b.visual) {
        for (auto* con : actingOn<core::BaseConstraint>(root, b.state))
            for (int n : con->constrainedNodes())
                if (auto it = local.find(n); it != local.end()) b.constrained.push_back(it->second);
        std::sort(b.constrained.begin(), b.constrained.end());
        b.constrained.erase(std::unique(b.constrained.begin(), b.constrained.end()), b.constrained.end());
        for (auto* ff : actingOn<core::BaseForceField>(root, b.state))
            if (ff->tetrahedra() || ff->hexahedra()) b.elementFields.push_back(ff);
    }
    b.name = c.path();
    m_bodies.push_back(std::move(b));
    return true;
}

double FrameSource::nodeMass(size_t b, int node) const {
    double m = 0;
    for (auto* mass : m_bodies[b].masses)
        if (size_t(node) < mass->nodalMasses().size()) m += mass->nodalMasses()[node];
    return m;
}

/// The field at the body's surface points: the displacement magnitude (mm), or the average over the
/// elements around a node of an element field (von Mises in kPa, J).
void FrameSource::nodeField(const Body& b, std::vector<double>& out) const {
    out.assign(b.nodes.size(), 0.0);
    if (m_field == Field::Displacement || b.visual) {
        for (size_t i = 0; i < b.nodes.size(); ++i) out[i] = 1e3 * ((*b.points)[b.nodes[i]] - b.rest[i]).norm();
        return;
    }
    const char* name = m_field == Field::VonMises ? "vonMises" : "J";
    const double scale = m_field == Field::VonMises ? 1e-3 : 1.0;
    std::vector<double> sum(b.state->size(), 0.0);
    std::vector<int> count(b.state->size(), 0);
    std::vector<core::CellField> cells;
    for (auto* ff : b.elementFields) {
        cells.clear();
        ff->cellData(*b.state, cells);
        auto f = std::find_if(cells.begin(), cells.end(), [&](const core::CellField& c) { return c.name == name && c.components == 1; });
        if (f == cells.end()) continue;
        size_t e = 0;
        auto add = [&](const auto& elements) {
            for (auto& el : elements) {
                for (int n : el) sum[n] += f->values[e], ++count[n];
                ++e;
            }
        };
        if (ff->tetrahedra()) add(*ff->tetrahedra());
        if (ff->hexahedra()) add(*ff->hexahedra());
    }
    for (size_t i = 0; i < b.nodes.size(); ++i) {
        const int n = b.nodes[i];
        out[i] = count[n] ? scale * sum[n] / count[n] : std::numeric_limits<double>::quiet_NaN();
    }
}

void FrameSource::capture(Frame& out, double t, long step) const {
    out.time = t;
    out.step = step;
    out.field = m_field;
    out.bodies.resize(m_bodies.size());
    for (size_t k = 0; k < m_bodies.size(); ++k) {
        const Body& b = m_bodies[k];
        BodyFrame& f = out.bodies[k];
        if (f.triangles.empty()) {
            f.name = b.name;
            f.triangles = b.triangles;
            f.stateNodes = b.nodes;
            f.constrained = b.constrained;
        }
        f.points.resize(b.nodes.size());
        for (size_t i = 0; i < b.nodes.size(); ++i) f.points[i] = (*b.points)[b.nodes[i]];
        if (m_field == Field::None) f.field.clear();
        else nodeField(b, f.field);
    }
    out.tools.resize(m_tools.size());
    for (size_t k = 0; k < m_tools.size(); ++k) {
        ToolFrame& t = out.tools[k];
        const core::Pose pose = m_tools[k]->pose();
        t.name = m_tools[k]->name();
        t.triangles = m_toolTriangles[k];
        t.points.resize(m_toolPoints[k].size());
        for (size_t i = 0; i < t.points.size(); ++i) t.points[i] = pose.position + pose.orientation * m_toolPoints[k][i];
        t.force = m_tools[k]->force();
        t.pose = pose;
    }
}

} // namespace fascia::view
