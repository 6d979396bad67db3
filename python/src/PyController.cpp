#include "PyController.h"
#include "Errors.h"
#include "Views.h"

#include "fascia/plugin/Registry.h"

#include <map>

namespace fascia::python {

namespace {
/// Objects handed over by Python scenes, by id, until their PythonController takes them at init.
std::map<int, py::object>& handOver() {
    static auto* table = new std::map<int, py::object>();  // (never destroyed: it holds Python objects)
    return *table;
}
int g_nextId = 1;
} // namespace

PyController::PyController() = default;

PyController::~PyController() {
    if (m_holder) {
        auto& c = m_holder->controllers;
        c.erase(std::remove(c.begin(), c.end(), this), c.end());
    }
}

void PyController::init() {
    py::gil_scoped_acquire gil;
    if (m_objectId.get() > 0) {
        auto it = handOver().find(m_objectId.get());
        if (it == handOver().end()) fail(m_objectId, "no Python object was handed over with id " + std::to_string(m_objectId.get()));
        m_object = it->second;
        handOver().erase(it);
    } else if (!m_controller.get().empty()) {
        try {
            m_object = py::module_::import("fascia._controller").attr("instantiate")(m_controller.get(), m_args.get(), loc().file);
        } catch (py::error_already_set& e) {
            fail(m_controller, "cannot make the controller: " + std::string(e.what()));
        }
    } else {
        fail("give controller=\"module.Class\" (or, from Python, add the controller object itself)");
    }
    auto hook = [&](const char* n) { return py::hasattr(m_object, n) ? m_object.attr(n) : py::object(); };
    m_begin = hook("on_step_begin");
    m_end = hook("on_step_end");
    if (!m_begin && !m_end && !py::hasattr(m_object, "on_init"))
        fail("the controller object (" + std::string(py::str(py::type::of(m_object).attr("__name__"))) +
             ") has none of on_init, on_step_begin, on_step_end");
}

void PyController::attach(Holder* h, py::object simWeak) {
    m_holder = h;
    m_simWeak = std::move(simWeak);
    h->controllers.push_back(this);
}

void PyController::callInit() {
    if (py::hasattr(m_object, "on_init")) call("on_init", nullptr);
}

void PyController::call(const char* hook, const double* t) {
    py::gil_scoped_acquire gil;
    std::string what;
    try {
        py::object sim = m_simWeak ? m_simWeak() : py::none();
        py::object f = m_object.attr(hook);
        py::object r = t ? f(sim, *t) : f(sim);
        if (!r.is_none()) {
            what = std::string(hook) + " returned " + std::string(py::repr(r)) + "; a controller hook returns None";
            m_holder->pending = py::module_::import("fascia._errors").attr("ControllerError")(what);
        } else if (m_holder) {
            checkWritten(*m_holder);
        }
    } catch (py::error_already_set& e) {
        what = std::string(hook) + " raised " + std::string(py::str(e.type().attr("__name__"))) + ": " +
               std::string(py::str(e.value()));
        e.restore();
        PyObject *type, *value, *trace;
        PyErr_Fetch(&type, &value, &trace);
        PyErr_NormalizeException(&type, &value, &trace);
        if (trace) PyException_SetTraceback(value, trace);
        if (m_holder) m_holder->pending = py::reinterpret_steal<py::object>(value);
        Py_XDECREF(type);
        Py_XDECREF(trace);
    }
    if (!what.empty())
        throw core::Error(core::ErrorKind::Simulation, loc(), className() + " '" + name() + "': " + what);
}

void PyController::beginStep(double t, double) {
    if (m_begin) call("on_step_begin", &t);  // (the GIL is taken in call: no Python object before it)
}

void PyController::observe(double t, long step) {
    if (step > 0 && m_end) call("on_step_end", &t);
}

void bindController(py::module_& m) {
    auto& reg = core::Registry::instance();
    if (!reg.find("PythonController")) {
        reg.setCurrentPlugin("fascia.python", "the Python module fascia");
        reg.add<PyController>("PythonController",
                              "a Python object whose on_step_begin / on_step_end run every step (a scene loaded from Python)");
        reg.setCurrentPlugin("", "");
    }
    m.def("hand_over", [](py::object obj) {
        const int id = g_nextId++;
        handOver()[id] = std::move(obj);
        return id;
    }, "Keeps a controller object for the PythonController of that id (fascia.Node.add does it).");
    m.def("drop_hand_over", [](int id) { handOver().erase(id); });
}

} // namespace fascia::python
