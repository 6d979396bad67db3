#pragma once
/// fascia-bench's cases (BenchCase.cpp: the scene of a case) and their timing side by side
/// (Timing.cpp). main.cpp parses the command line and holds the suites.
#include "fascia/sim/Simulation.h"

#include <memory>
#include <string>
#include <vector>

namespace fascia::bench {

/// The material of every case: E = 3 kPa, nu = 0.45 where it applies (the reference kernel's mu and
/// kappa come from these two).
constexpr double kYoung = 3000, kPoisson = 0.45;

struct Case {
    std::string forcefield = "HEML", material = "CompressibleNeoHookean", mesh, element = "tetrahedra6";
    std::string precision = "double";  ///< the force field's precision parameter (double or mixed); on a device, CudaStep's (double or float)
    int block = 0;                     ///< CudaStep's blockSize (0: its default)
    std::string forceOrder;            ///< CudaStep's forceOrder (element, node; empty: its default)
    std::string device;                ///< "cuda": the whole step on the GPU (a CudaStep in the root node); "emulate": its CPU emulation; empty: the CPU
    std::string nodeBuffers;           ///< TLED's nodeBuffers parameter (auto, range, compact; empty: its default)
    int cube = 0, steps = 200, threads = 2, repeat = 5;
    bool viscous = false, determinism = false;
    bool reference = false;  ///< the reference kernel (ReferenceKernel.h) on the case's mesh, not a force field
    bool contend = false;    ///< a competing busy process during the timing (Contend.h)
    std::string bodyExtra;   ///< more components in the body's node (XML), e.g. a tool
    std::string label;       ///< printed as "case" when set (what the extra components are)
    int settle = 0;          ///< steps run after the initial deformation, before the warm-up
};

/// c with force field ff and the neo-Hookean material it is compared with: HEML's compressible
/// neo-Hookean (eq. (26)), TLED's neo-Hookean (scaling suite, and the tled suite's organ line)
Case sideBySide(const Case& c, const std::string& ff);
/// The reference kernel on c's mesh with c's threads (TLED's neo-Hookean in double).
Case referenceCase(const Case& c);
/// name found in ., scenes/meshes or the source tree's scenes/meshes (else name itself).
std::string findMesh(const std::string& name);
/// The scene of a case: its mesh, lumped mass, material, force field, semi-implicit Euler, the base fixed.
std::string sceneXml(const Case& c);
/// The case's scene on `threads` OpenMP threads, at half the critical time step, deformed by two
/// smooth waves (every element works).
std::unique_ptr<core::Simulation> build(const Case& c, int threads);
/// Times the cases side by side in rounds and prints one JSON object per case (Timing.cpp).
void runCases(const std::vector<Case>& cs);
inline void runCase(const Case& c) { runCases({c}); }
/// --suite contact (ContactSuite.cpp): the cost of a rigid tool's contact on the abdomen-size mesh,
/// from base's steps, repeats and threads.
void runContactSuite(const Case& base);

} // namespace fascia::bench
