// fascia-bench: times full explicit steps (forces, integration, constraints) of a force field on a
// mesh and prints one JSON object per case. See `fascia-bench --help`.
#include "Bench.h"

#include "fascia/base/CommandLine.h"
#include "fascia/base/InputFile.h"

#include <algorithm>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

using namespace fascia::core;
using namespace fascia::bench;
namespace fs = std::filesystem;

namespace {

const char* kHelp = R"(fascia-bench: time full explicit steps of a force field

usage:
  fascia-bench [--forcefield HEML|TLED] [--material NAME] [--mesh FILE | --cube N]
               [--element tetrahedra6|tetrahedra5|hexahedra] [--steps N] [--threads T] [--repeat R]
               [--viscous] [--precision double|mixed] [--node-buffers auto|range|compact]
               [--determinism] [--reference] [--contend] [--device cpu|cuda] [--cuda-block B]
               [--cuda-forces element|node]
  fascia-bench --suite [NAME] [--steps N] [--repeat R] [--reference] [--contend] [--cubes LIST]
  fascia-bench --overhead N [--steps N] [--repeat R]
  fascia-bench --load SCENE.xml [--repeat R]
  fascia-bench [case options] --scene

  --forcefield    HEML (default) or TLED
  --material      a material component: CompressibleNeoHookean (default), StVenantKirchhoff,
                  NeoHookean, TransverselyIsotropic, ... (E = 3 kPa, nu = 0.45 where it applies)
  --mesh FILE     a mesh file (Gmsh, VTK, TetGen)
  --cube N        a generated unit cube of N x N x N cells (6 tetrahedra per cell by default)
  --steps N       timed steps per repeat (default 200)
  --threads T     OpenMP threads (default 2)
  --repeat R      timed repeats; the median is reported with min and max (default 5)
  --viscous       add a one-term ViscoelasticProny to the force field's node
  --precision P   the force field's precision: double (default) or mixed (element data and loop
                  in float, nodes and sums in double)
  --node-buffers L  TLED's block force buffers: auto (default), range (each block's node range)
                  or compact (one row per node of the block); with --suite, every TLED case
  --device D      cpu (default) or cuda: the whole step on a CUDA GPU (a CudaStep in the root
                  node; TLED or HEML; --precision is then double or float; emulate: the same through
                  CudaStep's CPU emulation, one thread, to check the bench's path). The host queues the
                  steps; each timed window ends with one wait for the device, and no state comes
                  back (no snapshot: Simulation::setSnapshotEvery(0)). Steps are timed by whole
                  windows (median_step_ms is a window's mean); bytes_per_element_step counts the
                  device step's arrays (CudaStep::layoutBytes)
  --cuda-block B  threads per block of the device's launches (CudaStep blockSize; default 256)
  --cuda-forces O where the device's element kernels write their corner forces (CudaStep
                  forceOrder): element (default) or node (node order: the gather reads one run)
  --determinism   also run with 1 thread and report whether positions are bitwise identical
  --reference     time the reference kernel first on the same mesh, with the same threads: a plain
                  TLED neo-Hookean step in double (apps/fascia-bench/ReferenceKernel.h), the
                  yardstick of docs/performance.md's targets; the ratios *_vs_first are then to it
  --contend       during the timing, a competing busy process spins on one core (the last one
                  this process may use, pinned where allowed), as a render or haptic thread would;
                  it is killed after the timing and the --determinism runs (and with the bench,
                  on any exit or signal)
  --suite [heml|tled|scaling|large|buffers|contact|gpu]
                  the standard sets of docs/performance.md: heml (default: HEML compressible
                  neo-Hookean and Saint Venant-Kirchhoff on the 4.4k and 21k organ meshes and a
                  2M-tetrahedron cube, 1 and 2 threads), tled (TLED neo-Hookean, transversely
                  isotropic and one Prony term on 20k and 200k tetrahedra, hexahedra against
                  tetrahedra; TLED beside HEML on the 21k organ mesh), scaling (HEML and TLED from
                  20k to 200k tetrahedra), large (the table of docs/performance.md's "Method":
                  per size, the reference kernel on 2 threads, then TLED and HEML in double and
                  mixed on 2 threads, in double on 1, each line quiet and then with --contend's competitor; 20k, 197k, 750k and 2.06M
                  tetrahedra; the 2M line holds seven copies of the mesh: several GB), contact
                  (HEML and TLED on the 21k organ mesh without a tool, with a capsule pressed into
                  it and moving every step, and with the same capsule as a 10k-triangle
                  SurfaceTool), buffers (TLED's two layouts of the block
                  buffers, range and compact, in double and mixed on 2 threads, on the large
                  suite's cubes), gpu (docs/performance.md, "The step on a GPU": the 21k organ
                  mesh on the CPU (TLED, 2 threads) first, then on the GPU, TLED and HEML, in float and
                  double; at 2M tetrahedra, per precision, TLED neo-Hookean first, then
                  transversely isotropic, one Prony term, hexahedra and HEML neo-Hookean;
                  TLED neo-Hookean tetrahedra in float and double at the sizes of --cubes,
                  default 150: 20.25M)
  --cubes LIST    the large suite's sizes as cube cells per side, e.g. 15,32 (default 15,32,50,70)
  --overhead N    per-step cost of the framework: a one-node scene with N trivial components
                  (ConstantForce) against the same scene with none
  --load SCENE    time to parse, build and initialise a scene (ms), median of the repeats
  --scene         print the case's scene (XML) instead of timing it, e.g. for fascia-run under
                  /usr/bin/time -v (tools/peak-memory.sh: peak memory per element)

The cases of one suite line (the tled suite's four cases per size, the scaling suite's HEML and
TLED per size) run side by side: built first, then timed in rounds, one repeat of each per round;
step_time_vs_first and per_element_vs_first are medians over the rounds of the ratio to the first
case of the line, robust to a noisy machine.

Each case prints one JSON object: forcefield, material, mesh, elements, nodes, threads, precision,
steps, ms_per_step (median), ms_min, ms_max, ns_per_element_step, and forcefield_ns_per_element:
the force field's addForce alone, timed in the same rounds (its element loop and its own node
passes, without the integrator, the other force terms and the checks of a step), with
forcefield_per_element_vs_first beside the step ratios.

Beside the mean over the timed window (ms_per_step), each step is timed on its own and the
samples of all repeats give median_step_ms, p90_step_ms and p99_step_ms; the two differ widely when
a thread is descheduled. Steps under 10 us are timed in groups (step_group steps a sample, each
sample divided by its count). bytes_per_element_step is what one force evaluation moves, counted
from the force field's arrays after init (core::LayoutReport: element data, node rows, block
buffers, also given apart per element), with forcefield_gb_per_s and step_gb_per_s the rates it
implies at the measured times. With --contend: "contend": true, contend_core (-1: not pinned) and
contend_cpu_s, the CPU time the competitor got. With more than one thread, takeovers: the blocks the
step's caller ran again in the timed steps because their thread had lost its core (fascia/sim/StepTeam.h).
)";

void runOverhead(int components, int steps, int repeat) {
    auto scene = [](int n) {
        std::ostringstream s;
        s << "<Node name=\"root\" dt=\"1e-3\">\n  <SemiImplicitEuler/>\n"
          << "  <MechanicalObject name=\"state\" position=\"0 0 0\"/>\n  <LumpedMass totalMass=\"1\"/>\n";
        for (int i = 0; i < n; ++i) s << "  <ConstantForce indices=\"0\" force=\"0 0 1e-9\"/>\n";
        s << "</Node>\n";
        return s.str();
    };
    std::vector<double> base, with;
    auto a = Simulation::fromString(scene(0), "<bench>");
    auto b = Simulation::fromString(scene(components), "<bench>");
    a->run(100);
    b->run(100);
    for (int r = 0; r < repeat; ++r) {
        for (auto* pair : {&base, &with}) {
            Simulation& sim = pair == &base ? *a : *b;
            const auto t0 = std::chrono::steady_clock::now();
            sim.run(steps);
            pair->push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count() / steps);
        }
    }
    std::sort(base.begin(), base.end());
    std::sort(with.begin(), with.end());
    const double mb = base[base.size() / 2], mw = with[with.size() / 2];
    std::printf("{\"case\": \"overhead\", \"components\": %d, \"steps\": %d, \"us_per_step_without\": %.4f, "
                "\"us_per_step_with\": %.4f, \"ns_per_component_step\": %.2f}\n",
                components, steps, mb, mw, (mw - mb) * 1e3 / components);
}

void runLoad(const std::string& scene, int repeat) {
    std::vector<double> ms;
    size_t nodes = 0, elements = 0;
    for (int r = 0; r < repeat; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        LoadOptions opts;
        opts.outputDir = (fs::temp_directory_path() / "fascia-bench-load").string();  // exporters write there
        auto sim = Simulation::fromFile(scene, opts);
        ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
        nodes = 0;
        elements = 0;
        for (auto& g : sim->groups()) {
            nodes += g.state->size();
            for (auto* ff : g.forceFields) elements += ff->elementCount();
        }
    }
    std::sort(ms.begin(), ms.end());
    std::printf("{\"case\": \"load\", \"scene\": \"%s\", \"nodes\": %zu, \"elements\": %zu, \"load_ms\": %.2f, "
                "\"load_ms_min\": %.2f, \"load_ms_max\": %.2f}\n",
                scene.c_str(), nodes, elements, ms[ms.size() / 2], ms.front(), ms.back());
}

/// Options that shape a suite rather than a case.
struct SuiteOptions {
    bool reference = false;          ///< the reference kernel first on every line
    std::vector<int> cubes;          ///< --cubes: the sizes of the large suite (empty: all)
};

/// The line's cases, with the reference kernel first when asked for (the ratios are then to it).
void runLine(std::vector<Case> line, const SuiteOptions& o) {
    if (o.reference && !line.empty() && !line[0].reference) line.insert(line.begin(), referenceCase(line[0]));
    runCases(line);
}

void suiteTled(const Case& c, const SuiteOptions& o) {
    // the paper's cost claims side by side in one run: fibres, viscosity, hexahedra
    for (int cube : {15, 32}) {  // 20,250 and 196,608 tetrahedra
        std::vector<Case> group;
        for (auto [mat, visc] : {std::pair{"NeoHookean", false}, std::pair{"TransverselyIsotropic", false},
                                 std::pair{"NeoHookean", true}}) {
            Case s = c;
            s.forcefield = "TLED";
            s.material = mat;
            s.viscous = visc;
            s.cube = cube;
            s.steps = cube > 20 ? std::min(c.steps, 100) : c.steps;
            group.push_back(s);
        }
        Case h = group[0];  // hexahedra with as many nodes
        h.element = "hexahedra";
        group.push_back(h);
        runLine(group, o);
    }
    // a Gmsh organ mesh, numbered as the mesher wrote it: TLED beside HEML (as in the scaling suite)
    std::vector<Case> organ;
    for (const char* ff : {"TLED", "HEML"}) {
        Case s = sideBySide(c, ff);
        s.mesh = findMesh("organ_21436.msh");
        s.cube = 0;
        organ.push_back(s);
    }
    runLine(organ, o);
}

void suiteScaling(const Case& c, const SuiteOptions& o) {
    for (int cube : {15, 20, 26, 32}) {  // 20k, 48k, 105k, 197k tetrahedra
        std::vector<Case> group;
        for (const char* ff : {"HEML", "TLED"}) {
            Case s = sideBySide(c, ff);
            s.cube = cube;
            s.steps = cube > 20 ? std::min(c.steps, 100) : c.steps;
            s.determinism = cube == 15;
            group.push_back(s);
        }
        runLine(group, o);
    }
}

/// The large-mesh table (docs/performance.md, "Method", --suite large): per size, the reference
/// kernel (2 threads) first, then TLED and HEML in double on 2 threads and on 1, each line quiet and then beside a competing process (with
/// --contend: only beside it).
void suiteLarge(const Case& c, const SuiteOptions& o) {
    const std::vector<int> all = {15, 32, 50, 70};  // 20,250, 196,608, 750,000 and 2,058,000 tetrahedra
    for (int cube : o.cubes.empty() ? all : o.cubes) {
        for (bool contend : {false, true}) {
            if (c.contend && !contend) continue;
            std::vector<Case> line;
            Case base = c;
            base.cube = cube;
            base.mesh.clear();
            base.element = "tetrahedra6";
            base.threads = 2;
            base.contend = contend;
            base.steps = cube <= 15 ? c.steps : std::min(c.steps, cube <= 32 ? 100 : cube <= 50 ? 40 : 20);
            if (cube > 32) base.repeat = std::min(c.repeat, 3);
            line.push_back(referenceCase(base));
            for (int threads : {2, 1})
                for (const char* precision : {"double", "mixed"})
                    for (const char* ff : {"TLED", "HEML"}) {
                        if (threads == 1 && std::string(precision) == "mixed") continue;
                        Case s = sideBySide(base, ff);
                        s.threads = threads;
                        s.precision = precision;
                        line.push_back(s);
                    }
            runCases(line);
        }
    }
}

/// TLED's two layouts of the block buffers (nodeBuffers) side by side: per size, range then compact,
/// in double and in mixed, 2 threads, on the large suite's cubes.
void suiteBuffers(const Case& c, const SuiteOptions& o) {
    const std::vector<int> all = {15, 32, 50, 70};
    for (int cube : o.cubes.empty() ? all : o.cubes) {
        std::vector<Case> line;
        for (const char* precision : {"double", "mixed"})
            for (const char* layout : {"range", "compact"}) {
                Case s = sideBySide(c, "TLED");
                s.mesh.clear();
                s.cube = cube;
                s.element = "tetrahedra6";
                s.threads = 2;
                s.precision = precision;
                s.nodeBuffers = layout;
                s.steps = cube <= 15 ? c.steps : std::min(c.steps, cube <= 32 ? 100 : cube <= 50 ? 40 : 20);
                if (cube > 32) s.repeat = std::min(c.repeat, 3);
                line.push_back(s);
            }
        runCases(line);
    }
}

void suiteHeml(const Case& c, const SuiteOptions& o) {
    for (const char* mat : {"CompressibleNeoHookean", "StVenantKirchhoff"})
        for (const std::string mesh : {"organ_4430.msh", "organ_21436.msh", "cube70"})
            for (int threads : {1, 2}) {
                Case s = c;
                s.material = mat;
                s.threads = threads;
                if (mesh == "cube70") {
                    s.mesh.clear();
                    s.cube = 70;  // 70^3 * 6 = 2.06M tetrahedra
                    s.steps = std::min(c.steps, 20);
                    s.repeat = std::min(c.repeat, 3);
                } else {
                    s.mesh = findMesh(mesh);
                }
                runLine({s}, o);
            }
}

/// The figures of docs/performance.md, "The step on a GPU", the quick ones first: the 21k organ mesh
/// on the CPU (TLED, 2 threads) and then on the GPU, TLED and HEML, in float and double; at 2M
/// tetrahedra, per precision, TLED neo-Hookean first, then transversely isotropic, one Prony term,
/// hexahedra and HEML neo-Hookean (ratios from the same rounds); then TLED neo-Hookean tetrahedra at
/// the sizes of --cubes (default 150: 20.25M elements), float then double.
void suiteGpu(const Case& c, const SuiteOptions& o) {
    // a line the device cannot run is said on stderr, and the next line runs (GPU time is scarce)
    const auto line = [](const std::vector<Case>& cs) {
        try {
            runCases(cs);
        } catch (const Error& e) {
            std::cerr << "fascia-bench: a line of the gpu suite failed: " << e.what() << "\n";
        }
    };
    std::vector<Case> organ;
    Case cpu = sideBySide(c, "TLED");
    cpu.mesh = findMesh("organ_21436.msh");
    cpu.cube = 0;
    cpu.threads = 2;
    cpu.steps = 2000;
    cpu.repeat = std::min(c.repeat, 5);
    organ.push_back(cpu);
    for (const char* ff : {"TLED", "HEML"})
        for (const char* precision : {"float", "double"}) {
            Case s = cpu;
            s.forcefield = ff;
            s.device = "cuda";
            s.precision = precision;
            s.steps = 20000;
            organ.push_back(s);
        }
    line(organ);
    Case base = sideBySide(c, "TLED");
    base.device = "cuda";
    base.mesh.clear();
    base.element = "tetrahedra6";
    base.repeat = std::min(c.repeat, 5);
    for (const char* precision : {"float", "double"}) {
        std::vector<Case> cases;  // (70: 2.06M tetrahedra)
        for (auto [mat, visc] : {std::pair{"NeoHookean", false}, std::pair{"TransverselyIsotropic", false}, std::pair{"NeoHookean", true}}) {
            Case s = base;
            s.precision = precision;
            s.material = mat;
            s.viscous = visc;
            s.cube = 70;
            s.steps = 500;
            cases.push_back(s);
        }
        Case h = cases[0];  // hexahedra: 126^3 = 2.0M
        h.element = "hexahedra";
        h.cube = 126;
        cases.push_back(h);
        Case e = cases[0];  // HEML's edge form on the same tetrahedra
        e.forcefield = "HEML";
        cases.push_back(e);
        Case o = cases[0];  // the corner forces in node order (the same bits; a choice of speed)
        o.forceOrder = "node";
        cases.push_back(o);
        line(cases);
    }
    for (int cube : o.cubes.empty() ? std::vector<int>{150} : o.cubes)  // 6 cube^3 tetrahedra
        for (const char* precision : {"float", "double"}) {
            Case s = base;
            s.precision = precision;
            s.cube = cube;
            s.steps = cube <= 70 ? 500 : 200;
            line({s});
        }
}

/// The suite called name; 1 (with a message) when there is none.
int runSuite(const std::string& name, const Case& c, const SuiteOptions& o) {
    if (name == "tled") suiteTled(c, o);
    else if (name == "scaling") suiteScaling(c, o);
    else if (name == "large") suiteLarge(c, o);
    else if (name == "heml") suiteHeml(c, o);
    else if (name == "buffers") suiteBuffers(c, o);
    else if (name == "contact") runContactSuite(c);
    else if (name == "gpu") suiteGpu(c, o);
    else {
        std::cerr << "fascia-bench: unknown suite '" << name << "' (heml, tled, scaling, large, buffers, contact or gpu)\n";
        return 1;
    }
    return 0;
}

/// Sizes of a cube (--cube, --cubes): GridMesh makes at most 5e7 cells (plugins/meshio/GridMesh.cpp).
constexpr long kMaxCube = 368;
/// A case's peak memory per cube cell: about 400 bytes per tetrahedron (the peak resident set per
/// element of tools/peak-memory.sh at 2M tetrahedra, docs/performance.md: 233 to 368), six to a
/// cell; a cell of hexahedra, with as many nodes, is counted as much.
constexpr double kBytesPerCubeCell = 6 * 400;
/// Per timed step of a case: its sample, the vector's growth and the quantiles' copy (Statistics.h);
/// a line's cases hold theirs side by side.
constexpr double kBytesPerSample = 24;
/// The cases of a suite line, at most: the large suite's reference kernel and six force field cases.
constexpr int kMaxCasesPerLine = 7;
/// Per trivial component of --overhead: its XML line, its element, the component and its parameters
/// (3.8 kB measured: the peak resident set of --overhead 40000 over that of --overhead 1), doubled.
constexpr double kBytesPerComponent = 8192;

/// What the command line asks for: a case (its options in c), a suite, --overhead, --load or --scene.
struct Options {
    Case c;
    bool suite = false, printScene = false;
    std::string suiteName = "heml", load;
    int overhead = 0;
    SuiteOptions suiteOptions;
};

/// --cubes: a comma-separated list of cube sizes.
std::vector<int> parseCubes(CommandLine& cl) {
    const std::string v = cl.text();
    std::vector<int> out;
    std::stringstream in(v);
    for (std::string item; std::getline(in, item, ',');) {
        char* end = nullptr;
        const long n = item.empty() ? 0 : std::strtol(item.c_str(), &end, 10);
        if (item.empty() || *end || n < 1 || n > kMaxCube)
            cl.fail("--cubes needs a list of integers in [1, " + std::to_string(kMaxCube) + "] such as 15,32, not '" + v + "'");
        out.push_back(int(n));
    }
    return out;
}

/// Parses the command line; --help prints the help and exits 0, a bad command line exits 1.
Options parseArgs(int argc, char** argv) {
    Options o;
    Case& c = o.c;
    CommandLine cl("fascia-bench", argc, argv);
    auto count = [&] { return int(cl.integer(1, INT_MAX)); };
    while (cl.next()) {
        if (cl.isHelp()) {
            std::cout << kHelp;
            std::exit(0);
        } else if (cl.is("--forcefield")) c.forcefield = cl.text();
        else if (cl.is("--material")) c.material = cl.text();
        else if (cl.is("--mesh")) c.mesh = cl.path();
        else if (cl.is("--cube")) c.cube = int(cl.integer(1, kMaxCube));
        else if (cl.is("--element")) c.element = cl.text();
        else if (cl.is("--steps")) c.steps = count();
        else if (cl.is("--threads")) c.threads = int(cl.integer(1, 1024));
        else if (cl.is("--repeat")) c.repeat = count();
        else if (cl.is("--viscous")) c.viscous = true;
        else if (cl.is("--precision")) c.precision = cl.text();
        else if (cl.is("--node-buffers")) c.nodeBuffers = cl.text();
        else if (cl.is("--determinism")) c.determinism = true;
        else if (cl.is("--contend")) c.contend = true;
        else if (cl.is("--device")) c.device = cl.text();
        else if (cl.is("--cuda-block")) c.block = int(cl.integer(32, 1024));  // CudaStep's blockSize range
        else if (cl.is("--cuda-forces")) c.forceOrder = cl.text();
        else if (cl.is("--scene")) o.printScene = true;
        else if (cl.is("--reference")) o.suiteOptions.reference = true;
        else if (cl.is("--cubes")) o.suiteOptions.cubes = parseCubes(cl);
        else if (cl.is("--suite")) {
            o.suite = true;
            if (const std::string name = cl.optionalValue(); !name.empty()) o.suiteName = name;
        } else if (cl.is("--overhead")) o.overhead = count();
        else if (cl.is("--load")) o.load = cl.path();
        else if (cl.isOption()) cl.unknownOption();
        else cl.fail("unexpected argument '" + cl.arg() + "' (a mesh is --mesh FILE, a scene --load SCENE.xml)");
    }
    return o;
}

/// Refuses what would not fit in memory before anything is built: the cube's cells (a case and
/// its reference or 1-thread copy; the large and buffers suites hold a line's cases side by side),
/// the timed steps' samples, --overhead's components. Exits 1.
void checkMemory(const Options& o) {
    const auto cubeFits = [](const char* option, long cube, int copies) {
        const double cells = double(cube) * double(cube) * double(cube), perCube = kBytesPerCubeCell * copies;
        requireMemory("fascia-bench", option + (" " + std::to_string(cube)), cells, perCube, "cube cells",
                      "at most " + (option + (" " + countText(std::cbrt(memoryBudgetBytes() / perCube)))));
    };
    if (!o.suite && o.load.empty() && o.overhead == 0 && o.c.mesh.empty() && o.c.cube > 0) cubeFits("--cube", o.c.cube, 2);
    const int copies = o.suiteName == "large" ? kMaxCasesPerLine : o.suiteName == "buffers" ? 4 : 1;
    for (int cube : o.suiteOptions.cubes) cubeFits("--cubes", cube, o.suite ? copies : 1);
    const double perStep = kBytesPerSample * kMaxCasesPerLine;
    requireMemory("fascia-bench", "--steps " + std::to_string(o.c.steps) + " --repeat " + std::to_string(o.c.repeat),
                  double(o.c.steps) * o.c.repeat, perStep, "timed steps",
                  "--steps times --repeat at most " + countText(memoryBudgetBytes() / perStep));
    if (o.overhead > 0) requireMemory("fascia-bench", "--overhead " + std::to_string(o.overhead), o.overhead, kBytesPerComponent, "components");
}

/// The choices that do not go together or name nothing; 1 (with a message) for a bad one, else 0.
int checkChoices(Options& o) {
    Case& c = o.c;
    if (c.forcefield != "HEML" && c.forcefield != "TLED") {
        std::cerr << "fascia-bench: --forcefield is HEML or TLED\n";
        return 1;
    }
    if (c.device == "cpu") c.device.clear();
    if (!c.device.empty() && c.device != "cuda" && c.device != "emulate") {
        std::cerr << "fascia-bench: --device is cpu, cuda or emulate\n";
        return 1;
    }
    if (c.device.empty() ? c.precision != "double" && c.precision != "mixed" : c.precision != "double" && c.precision != "float") {
        std::cerr << "fascia-bench: --precision is double or mixed" << (c.device.empty() ? "" : " on the CPU, double or float on --device cuda") << "\n";
        return 1;
    }
    if ((c.block > 0 || !c.forceOrder.empty()) && c.device.empty()) {
        std::cerr << "fascia-bench: --cuda-block and --cuda-forces need --device cuda (or emulate)\n";
        return 1;
    }
    if (!c.forceOrder.empty() && c.forceOrder != "element" && c.forceOrder != "node") {
        std::cerr << "fascia-bench: --cuda-forces is element or node\n";
        return 1;
    }
    if (!c.device.empty() && (o.suiteOptions.reference || c.contend)) {
        std::cerr << "fascia-bench: --device " << c.device << " runs without --reference or --contend\n";
        return 1;
    }
    if (!c.nodeBuffers.empty() && c.nodeBuffers != "auto" && c.nodeBuffers != "range" && c.nodeBuffers != "compact") {
        std::cerr << "fascia-bench: --node-buffers is auto, range or compact\n";
        return 1;
    }
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    Options o = parseArgs(argc, argv);
    Case& c = o.c;
    if (const int rc = checkChoices(o)) return rc;
    checkMemory(o);
    try {
        if (!c.mesh.empty()) requireRegularFile(c.mesh, "mesh file", kMaxMeshFileBytes, {c.mesh, 0});
        if (o.overhead > 0) {
            runOverhead(o.overhead, c.steps, c.repeat);
            return 0;
        }
        if (!o.load.empty()) {
            runLoad(o.load, c.repeat);
            return 0;
        }
        if (!o.suite) {
            if (c.mesh.empty() && c.cube == 0) c.cube = 16;
            if (o.printScene) {
                std::cout << sceneXml(c);
                return 0;
            }
            runLine({c}, o.suiteOptions);
            return 0;
        }
        return runSuite(o.suiteName, c, o.suiteOptions);
    } catch (const Error& e) {
        std::cerr << e.what() << "\n";
        return e.kind() == ErrorKind::Input ? 2 : e.kind() == ErrorKind::Simulation ? 3 : 1;
    } catch (const std::exception& e) {
        std::cerr << "fascia-bench: " << e.what() << "\n";
        return 1;
    }
}
