#pragma once
/// Fascia's errors as Python exceptions (the classes live in fascia/_errors.py): a located input
/// error becomes fascia.SceneError with file, line, message and notes; a failed step
/// fascia.SimulationError with the step, the time and the worst element; an output that cannot be
/// written fascia.OutputError. Nothing aborts the interpreter.
#include "fascia/base/Error.h"

#include <pybind11/pybind11.h>

#include <string>

namespace fascia::python {

namespace py = pybind11;

/// The Python exception object for e, of class `cls` (a name in fascia._errors; empty: chosen by
/// e's kind), with e's location and `extra` as attributes.
py::object exceptionFor(const core::Error& e, const std::string& cls = {}, const py::dict& extra = {});
/// Sets exc as the current Python exception and throws error_already_set (pybind11 re-raises it).
[[noreturn]] void raise(const py::object& exc);
/// A new error of class cls with the text `text` (no location), raised at once.
[[noreturn]] void raise(const std::string& cls, const std::string& text, const py::dict& extra = {});
/// Installs the translator: any core::Error that leaves a binding becomes its Python exception.
void registerErrorTranslator();

} // namespace fascia::python
