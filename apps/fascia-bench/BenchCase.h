#pragma once
// What fascia-bench times: one case (a force field on a mesh, with its options), shared by main.cpp
// and the suites kept in their own files (ContactSuite.cpp).
#include "fascia/sim/Simulation.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace bench {

struct Case {
    std::string forcefield = "HEML", material = "CompressibleNeoHookean", mesh, element = "tetrahedra6";
    int cube = 0, steps = 200, threads = 2, repeat = 5;
    bool viscous = false, determinism = false;
    std::string bodyExtra;  ///< more components in the body's node (XML), e.g. a tool
    std::string label;      ///< printed as "case" when set (what the extra components are)
    int settle = 0;         ///< steps run after the initial deformation, before the warm-up
};

/// Builds a case as the timing does (deformed, at half the critical step, settled).
using BuildCase = std::function<std::unique_ptr<fascia::core::Simulation>(const Case&)>;
/// Times cases side by side (one line of a suite).
using RunCases = std::function<void(const std::vector<Case>&)>;

/// --suite contact (ContactSuite.cpp): the cost of a rigid tool's contact on the abdomen-size mesh.
void runContactSuite(const Case& base, const std::string& organMesh, const BuildCase& build, const RunCases& run);

} // namespace bench
