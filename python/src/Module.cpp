// _fascia: the compiled half of the Python module fascia (docs/python.md).
#include "Core.h"
#include "Errors.h"
#include "PyController.h"
#include "Scene.h"
#include "Views.h"

#include "fascia/base/Component.h"
#include "fascia/sim/StepTeam.h"

#include <omp.h>

namespace py = pybind11;
using namespace fascia;

PYBIND11_MODULE(_fascia, m) {
    m.doc() = "Fascia's core, for the Python package fascia (docs/python.md)";
    python::registerErrorTranslator();
    python::bindScene(m);
    python::bindViews(m);
    python::bindController(m);
    python::bindCore(m);
    m.def("set_threads", [](int n) {
        if (n < 1) python::raise("SceneError", "threads must be at least 1, not " + std::to_string(n));
        omp_set_num_threads(n);
    }, "OpenMP threads of the steps (results do not depend on it).");
    m.def("threads", [] { return omp_get_max_threads(); });
    m.def("set_timers", &core::setTimersEnabled, "Per-component timers on or off (off by default).");
}
