#include "Core.h"
#include "Errors.h"
#include "PyController.h"
#include "Scene.h"
#include "Views.h"

#include "fascia/plugin/PluginManager.h"

#include <pybind11/stl.h>

#include <Eigen/Geometry>

namespace fascia::python {

Holder::~Holder() {
    // the controllers hold Python objects: the simulation goes with the GIL held (Python drops it)
    sim.reset();
}

namespace {
Vec3 vec3(const py::object& o, const char* what) {
    auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(o);
    if (!a || a.ndim() != 1 || a.shape(0) != 3)
        raise("SceneError", std::string(what) + " must be 3 numbers, not " + std::string(py::repr(o)));
    return {a.at(0), a.at(1), a.at(2)};
}
py::array_t<double> toArray(const Vec3& v) { return py::array_t<double>(3, v.data()); }
} // namespace

Core::Core(const py::tuple& tree, const std::string& sceneFile, const std::string& outputDir, double dt)
    : m_h(std::make_shared<Holder>()) {
    core::PluginManager::instance().loadDefaultPlugins();
    auto root = core::buildScene(specFromTree(tree));
    if (!sceneFile.empty()) root->context().sceneFile = sceneFile;
    m_h->sim = std::make_unique<core::Simulation>(std::move(root));
    core::LoadOptions o;
    o.outputDir = outputDir;
    o.dt = dt;
    m_h->sim->configure(o);
    m_h->sim->init();
    m_h->closedWhy = "the simulation was closed";
}

void Core::attach(py::object simWeak) {
    m_h->sim->root().visit([&](const core::Node& n) {
        for (auto* c : n.findAllLocal<PyController>()) c->attach(m_h.get(), simWeak);
    });
    for (auto* c : std::vector<PyController*>(m_h->controllers)) c->callInit();
}

core::Simulation& Core::sim() const {
    if (m_h->closed) raise("SimulationError", m_h->closedWhy);
    return *m_h->sim;
}

void Core::raiseStepError(const core::Error& e) {
    if (m_h->pending && !m_h->pending.is_none()) {
        py::object cause = m_h->pending;
        m_h->pending = py::none();
        py::object exc = exceptionFor(e, "ControllerError");
        if (!py::isinstance(cause, py::module_::import("fascia._errors").attr("ControllerError")))
            PyException_SetCause(exc.ptr(), cause.release().ptr());  // (steals the reference)
        raise(exc);
    }
    py::dict extra;
    if (e.kind() == core::ErrorKind::Simulation) {
        core::Simulation& s = *m_h->sim;
        extra["step"] = s.failedStep() > 0 ? s.failedStep() : s.stepCount() + 1;
        extra["time"] = s.time();
        core::ElementReport worst;
        bool found = false;
        std::string where;
        for (const auto& g : s.groups())
            for (auto* ff : g.forceFields) {
                core::ElementReport r;
                if (ff->worstElement(*g.state, r) && (!found || core::worseElement(r, worst))) {
                    worst = r;
                    found = true;
                    where = ff->path();
                }
            }
        if (found) {
            py::dict w;
            w["force_field"] = where;
            w["index"] = worst.index;
            w["J"] = worst.J;
            w["centroid"] = toArray(worst.centroid);
            extra["worst_element"] = w;
        } else {
            extra["worst_element"] = py::none();
        }
    }
    raise(exceptionFor(e, "", extra));
}

template <class F> void Core::stepping(F&& f) {
    core::Simulation& s = sim();
    checkWritten(*m_h);
    try {
        py::gil_scoped_release nogil;
        f(s);
    } catch (const core::Error& e) {
        raiseStepError(e);
    }
    s.fetchState();
}

void Core::moveTools() {
    if (m_h->moving.empty()) return;
    const double dt = m_h->sim->dt();
    for (auto& m : m_h->moving) {
        core::Pose p = m.tool->pose();
        p.position += dt * m.velocity;
        const double angle = dt * m.angularVelocity.norm();
        if (angle > 0) p.orientation = Eigen::AngleAxisd(angle, m.angularVelocity.normalized()) * p.orientation;
        m.tool->setPose(p);
    }
}

void Core::run(long steps) {
    stepping([&](core::Simulation& s) {
        s.start();
        for (long i = 0; i < steps; ++i) {
            moveTools();
            s.step();
        }
    });
}

void Core::runUntil(double T) {
    while (stepToward(T, 1L << 40) > 0) {
    }
}

long Core::stepToward(double T, long steps) {
    long done = 0;
    stepping([&](core::Simulation& s) {
        if (!std::isfinite(T)) core::throwInputError({}, "end time " + std::to_string(T) + " s is not a finite number");
        if (done == 0 && s.time() == 0) s.checkEndTime(T);
        s.start();
        for (; done < steps && s.stepsUntil(T) > 0; ++done) {
            moveTools();
            s.stepToward(T);
        }
    });
    return done;
}

void Core::close() {
    if (m_h->closed) return;
    m_h->closed = true;
    m_h->sim->finish();  // the observers' final records and cleanup; the memory stays for the views
}

py::array Core::view(const std::string& stateName, const std::string& array) {
    core::BaseMechanicalState& st = sim().state(stateName);
    const std::string label = "state '" + stateName + "'." + array;
    if (array == "x") return nodeView(m_h, st.x(), label, true);
    if (array == "v") return nodeView(m_h, st.v(), label, true);
    if (array == "external_force") return nodeView(m_h, st.externalForce(), label, true);
    if (array == "f") return nodeView(m_h, st.f(), label, false);
    if (array == "x0") return nodeView(m_h, st.x0(), label, false);
    if (array == "reaction") return nodeView(m_h, st.reaction(), label, false);
    raise("SceneError", "no array '" + array + "' (x, v, f, x0, reaction, external_force)");
}

py::dict Core::toolState(const std::string& name) {
    core::BaseTool& t = sim().tool(name);
    const core::Pose p = t.pose();
    py::dict d;
    d["position"] = toArray(p.position);
    d["orientation"] = py::array_t<double>(4, std::array<double, 4>{p.orientation.w(), p.orientation.x(),
                                                                   p.orientation.y(), p.orientation.z()}.data());
    d["force"] = toArray(t.force());
    d["torque"] = toArray(t.torque());
    for (auto& m : m_h->moving)
        if (m.tool == &t) {
            d["velocity"] = toArray(m.velocity);
            d["angular_velocity"] = toArray(m.angularVelocity);
        }
    return d;
}

void Core::setToolPose(const std::string& name, py::object position, py::object orientation) {
    core::BaseTool& t = sim().tool(name);
    core::Pose p = t.pose();
    if (!position.is_none()) p.position = vec3(position, "a tool's position");
    if (!orientation.is_none()) {
        auto q = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(orientation);
        if (!q || q.ndim() != 1 || q.shape(0) != 4 || !(std::abs(q.at(0)) + std::abs(q.at(1)) + std::abs(q.at(2)) + std::abs(q.at(3)) > 0))
            raise("SceneError", "a tool's orientation is a quaternion (w, x, y, z), not " + std::string(py::repr(orientation)));
        p.orientation = Eigen::Quaterniond(q.at(0), q.at(1), q.at(2), q.at(3));
    }
    if (!p.position.allFinite() || !p.orientation.coeffs().allFinite())
        raise("SceneError", "a tool's pose must be finite");
    t.setPose(p);
}

void Core::setToolVelocity(const std::string& name, py::object velocity, py::object angular) {
    core::BaseTool& t = sim().tool(name);
    MovingTool* m = nullptr;
    for (auto& x : m_h->moving) m = x.tool == &t ? &x : m;
    if (!m) m = &m_h->moving.emplace_back(MovingTool{&t});
    if (!velocity.is_none()) m->velocity = vec3(velocity, "a tool's velocity");
    if (!angular.is_none()) m->angularVelocity = vec3(angular, "a tool's angular velocity");
    if (!m->velocity.allFinite() || !m->angularVelocity.allFinite()) raise("SceneError", "a tool's velocity must be finite");
}

py::tuple Core::surface(const std::string& name) {
    core::SurfaceView s = sim().surface(name);
    auto& points = const_cast<Positions&>(*s.points);
    py::array tri(py::dtype::of<int>(), {py::ssize_t(s.triangles->size()), py::ssize_t(3)},
                  s.triangles->empty() ? nullptr : s.triangles->data()->data());  // (a copy)
    return py::make_tuple(nodeView(m_h, points, "surface '" + name + "'.points", false), tri);
}

py::dict Core::cellData(const std::string& path) {
    auto* ff = dynamic_cast<core::BaseForceField*>(sim().find(path));
    if (!ff) raise("SceneError", "no force field '" + path + "' in the scene");
    core::BaseMechanicalState* st = nullptr;
    for (const auto& g : m_h->sim->groups())
        for (auto* f : g.forceFields) st = f == ff ? g.state : st;
    if (!st) raise("SceneError", "force field '" + path + "' acts on no state");
    std::vector<core::CellField> fields;
    ff->cellData(*st, fields);
    py::dict d;
    for (auto& f : fields) {
        const auto n = py::ssize_t(f.values.size() / size_t(f.components));
        py::array a = f.components == 1 ? py::array(py::dtype::of<double>(), {n}, f.values.data())
                                        : py::array(py::dtype::of<double>(), {n, py::ssize_t(f.components)}, f.values.data());
        d[py::str(f.name)] = a;
    }
    return d;
}

py::list Core::componentList() const {
    py::list out;
    sim().root().visit([&](const core::Node& n) {
        out.append(py::make_tuple(n.path(), "Node"));
        for (auto& c : n.components()) out.append(py::make_tuple(c->path(), c->className()));
    });
    return out;
}

void bindCore(py::module_& m) {
    py::class_<Core>(m, "Core", "One simulation (use fascia.Simulation).")
        .def(py::init<const py::tuple&, const std::string&, const std::string&, double>(), py::arg("tree"),
             py::arg("scene_file") = "", py::arg("output_dir") = "", py::arg("dt") = 0.0)
        .def("attach", &Core::attach)
        .def("run", &Core::run)
        .def("run_until", &Core::runUntil)
        .def("step_toward", &Core::stepToward)
        .def("close", &Core::close)
        .def_property_readonly("closed", [](const Core& c) { return c.holder()->closed; })
        .def_property_readonly("time", [](const Core& c) { return c.sim().time(); })
        .def_property_readonly("step_count", [](const Core& c) { return c.sim().stepCount(); })
        .def_property("dt", [](const Core& c) { return c.sim().dt(); }, [](Core& c, double dt) { c.sim().setDt(dt); })
        .def_property_readonly("critical_dt", [](const Core& c) { return c.sim().criticalTimeStep(); })
        .def_property_readonly("output_dir", [](const Core& c) { return c.sim().outputDir(); })
        .def_property_readonly("failed_step", [](const Core& c) { return c.sim().failedStep(); })
        .def("steps_until", [](const Core& c, double T) { return c.sim().stepsUntil(T); })
        .def("start", [](Core& c) { c.sim().start(); })
        .def("save", [](Core& c, const std::string& p) { c.sim().save(p); })
        .def("restore", [](Core& c, const std::string& p) { c.sim().restore(p); })
        .def("save_last_good_state", [](Core& c, const std::string& p) { return c.sim().saveLastGoodState(p); })
        .def("set_snapshot_every", [](Core& c, long n) { c.sim().setSnapshotEvery(n); })
        .def("timers", [](const Core& c) {
            py::list out;
            for (auto& t : c.sim().timers()) out.append(py::make_tuple(t.path, t.type, t.seconds, t.calls));
            return out;
        })
        .def("view", &Core::view)
        .def("state_size", [](Core& c, const std::string& s) { return c.sim().state(s).size(); })
        .def("tool", &Core::toolState)
        .def("set_tool_pose", &Core::setToolPose, py::arg("name"), py::arg("position") = py::none(),
             py::arg("orientation") = py::none())
        .def("set_tool_velocity", &Core::setToolVelocity, py::arg("name"), py::arg("velocity") = py::none(),
             py::arg("angular_velocity") = py::none())
        .def("surface", &Core::surface)
        .def("cell_data", &Core::cellData)
        .def("components", &Core::componentList)
        .def("elements", [](Core& c, const std::string& path) {
            auto* ff = dynamic_cast<core::BaseForceField*>(c.sim().find(path));
            if (!ff) raise("SceneError", "no force field '" + path + "' in the scene");
            auto cells = [](const auto* v, py::ssize_t k) {
                const py::ssize_t n = v ? py::ssize_t(v->size()) : 0;
                return py::array(py::dtype::of<int>(), {n, k}, n ? v->data()->data() : nullptr);  // (copies)
            };
            return py::make_tuple(cells(ff->tetrahedra(), 4), cells(ff->hexahedra(), 8));
        })
        .def("param", [](const Core& c, const std::string& path, const std::string& name) {
            core::Base* b = c.sim().find(path);
            if (!b && (path.empty() || path == "/" || path == c.sim().root().path())) b = &c.sim().root();
            if (!b) b = c.sim().root().resolveNode(path);
            if (!b) raise("SceneError", "no component or node '" + path + "'");
            core::BaseParam* p = b->findParam(name);
            if (!p) raise("SceneError", "'" + path + "' has no parameter '" + name + "'");
            return p->valueText();
        });
}

} // namespace fascia::python
