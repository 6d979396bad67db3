#include "Errors.h"

namespace fascia::python {

namespace {
const char* classFor(core::ErrorKind k) {
    switch (k) {
    case core::ErrorKind::Input: return "SceneError";
    case core::ErrorKind::Simulation: return "SimulationError";
    case core::ErrorKind::Output: return "OutputError";
    default: return "FasciaError";
    }
}

py::dict located(const core::Error& e) {
    py::dict d;
    d["file"] = e.loc().file.empty() ? py::object(py::none()) : py::object(py::str(e.loc().file));
    d["line"] = e.loc().line > 0 ? py::object(py::int_(e.loc().line)) : py::object(py::none());
    d["message"] = e.message();
    py::list notes;
    for (auto& n : e.notes()) notes.append(n);
    d["notes"] = notes;
    return d;
}
} // namespace

py::object exceptionFor(const core::Error& e, const std::string& cls, const py::dict& extra) {
    py::module_ errors = py::module_::import("fascia._errors");
    py::dict kw = located(e);
    py::list all;  // every error the load found (core::Error::more), the first included
    all.append(errors.attr("ErrorRecord")(**located(e)));
    for (auto& m : e.more()) all.append(errors.attr("ErrorRecord")(**located(m)));
    kw["errors"] = all;
    for (auto item : extra) kw[item.first] = item.second;
    return errors.attr(cls.empty() ? classFor(e.kind()) : cls.c_str())(std::string(e.what()), **kw);
}

void raise(const py::object& exc) {
    PyErr_SetObject(reinterpret_cast<PyObject*>(Py_TYPE(exc.ptr())), exc.ptr());
    throw py::error_already_set();
}

void raise(const std::string& cls, const std::string& text, const py::dict& extra) {
    py::module_ errors = py::module_::import("fascia._errors");
    raise(errors.attr(cls.c_str())(text, **extra));
}

void registerErrorTranslator() {
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const core::Error& e) {
            py::object exc = exceptionFor(e);
            PyErr_SetObject(reinterpret_cast<PyObject*>(Py_TYPE(exc.ptr())), exc.ptr());
        }
    });
}

} // namespace fascia::python
