#pragma once
/// What the Python objects of one simulation share: the simulation itself, kept alive as long as any
/// view of its memory is (a view never dangles), and what the bindings add around the steps.
#include "fascia/sim/Simulation.h"
#include "fascia/sim/Tool.h"

#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <vector>

namespace fascia::python {

namespace py = pybind11;

class PyController;

/// A node array a writeable view was handed out for: checked for NaN and infinity before each step.
struct Watched {
    const Positions* array;
    std::string label;  ///< "state 'organ'.x"
};

/// A tool moved by the bindings at a constant velocity: before each step its pose advances by dt.
struct MovingTool {
    core::BaseTool* tool;
    Vec3 velocity = Vec3::Zero(), angularVelocity = Vec3::Zero();
};

struct Holder {
    std::unique_ptr<core::Simulation> sim;
    bool closed = false;
    std::string closedWhy;  ///< why views and calls are refused ("the simulation was closed")
    std::vector<Watched> watched;
    std::vector<MovingTool> moving;
    std::vector<PyController*> controllers;
    /// The Python exception a controller raised in the step that failed (None when none).
    py::object pending;
    ~Holder();
};

} // namespace fascia::python
