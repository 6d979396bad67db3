#pragma once
/// _fascia.Core: one simulation as the Python class fascia.Simulation (fascia/_simulation.py) drives
/// it. Steps run with the GIL released (a Python thread, a viewer or a device reader, runs beside
/// them); errors become fascia exceptions; node arrays are views (Views.h).
#include "Holder.h"

#include <pybind11/numpy.h>

namespace fascia::python {

class Core {
public:
    /// Builds and initialises a scene tree (Scene.h); sceneFile "" for a scene built in Python.
    Core(const py::tuple& tree, const std::string& sceneFile, const std::string& outputDir, double dt);
    /// Hands the controllers the Python simulation (a weak reference) and calls their on_init.
    void attach(py::object simWeak);

    void run(long steps);
    void runUntil(double T);
    /// Runs up to `steps` steps toward T (all of them when T is reached first): a slice of run_until
    /// for a progress bar. Returns the steps taken.
    long stepToward(double T, long steps);
    void close();

    core::Simulation& sim() const;
    py::array view(const std::string& state, const std::string& array);
    py::dict toolState(const std::string& name);
    void setToolPose(const std::string& name, py::object position, py::object orientation);
    void setToolVelocity(const std::string& name, py::object velocity, py::object angular);
    py::tuple surface(const std::string& name);
    py::dict cellData(const std::string& forceField);
    py::list componentList() const;
    const std::shared_ptr<Holder>& holder() const { return m_h; }

private:
    /// Runs f (steps) with the GIL released; a failure becomes its Python exception.
    template <class F> void stepping(F&& f);
    [[noreturn]] void raiseStepError(const core::Error& e);
    void moveTools();
    std::shared_ptr<Holder> m_h;
};

void bindCore(py::module_& m);

} // namespace fascia::python
