// fascia-run: runs a scene headless. See `fascia-run --help`.
#include "fascia/base/CommandLine.h"
#include "fascia/plugin/PluginManager.h"
#include "fascia/plugin/Registry.h"
#include "fascia/scene/Node.h"
#include "fascia/scene/SceneLoader.h"
#include "fascia/sim/Simulation.h"
#include "fascia/sim/StepTeam.h"

#include <omp.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstring>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace fascia::core;

namespace {

const char* kHelp = R"(fascia-run: run a Fascia scene headless

usage:
  fascia-run SCENE.xml [--steps N | --time T] [--dt DT] [--threads N] [--output DIR] [--quiet] [--timers]
             [--checkpoint FILE [--checkpoint-every N]] [--restart FILE] [--worker-cores LIST]
  fascia-run --list
  fascia-run --describe COMPONENT
  fascia-run --help

options:
  --steps N        run N steps
  --time T         run until T seconds of simulated time, exactly: steps of dt, the last
                   one shortened to end on T (ceil(T/dt) steps); a dt larger than T is an
                   error (default: the root node's endTime, or 100 steps when it has none)
  --dt DT          time step in seconds, overriding the scene's dt
  --threads N      OpenMP threads (default: all cores); results do not depend on it
  --worker-cores LIST  pin the step's worker threads to these cores (1 or 1,3; worker t on
                   the t-th of the list, round robin; default: where the kernel puts them):
                   with another busy thread on the machine, start fascia-run pinned (taskset
                   -c 0) and give the workers the core it shares (docs/performance.md, lesson 18)
  --output DIR     folder exporters and monitors write into (created; default: .)
  --snapshot FILE.png  a picture of the final state, relative to the output folder: the
                   bodies' surfaces coloured by displacement, with the tools (a PngSnapshot
                   added to the scene's root; plugin view, where the build has VTK). Without a
                   display it renders under its own Xvfb (Debian's xvfb); with neither, exit 1
  --quiet          no progress bar
  --timers         time each component and print the table at the end (inclusive: an
                   integrator's time contains the force fields and constraints it calls)
  --checkpoint FILE  write the whole state to FILE at the end of the run (also when
                   interrupted), and the last good state there when the run diverges
                   (written atomically: FILE.tmp, then renamed over FILE)
  --checkpoint-every N  also every N steps (of the step count, so that a restarted run keeps
                   the rhythm); needs --checkpoint
  --restart FILE   resume from a checkpoint of this scene (a changed parameter or mesh file
                   is an error): --steps N runs N more steps, --time T and endTime run up to
                   T; a dt other than the saved one (--dt, the scene's) applies from the
                   checkpoint on. Give the --output folder of the run that wrote it: exporters
                   continue its series (the .pvd lists the earlier files, CSVs are appended to)
  --list           print every registered component with its plugin and a description
  --describe NAME  print the parameters of a component (type, default, unit, range, help)

plugins: the built-in plugin folder is loaded automatically, then every folder of
FASCIA_PLUGIN_PATH (colon separated); a scene loads more with <RequiredPlugin name="..."/>.

output: a progress bar on a terminal (none when piped or with --quiet), then one summary line:
  fascia-run: N steps, T s simulated, W s wall, M ms/step, real-time factor R

exit codes:
  0  success
  2  invalid scene or input (the located error, file:line, on stderr), or a --restart
     checkpoint that is missing, corrupt or of another scene (file: error: ...)
  3  the simulation failed while running (NaN, or a kinetic energy growing without bound: the
     step, time, component and worst element named, a stable dt suggested; the last good state,
     before the failing step and any growth leading to it, is written as a checkpoint, to
     --checkpoint FILE or else OUTPUT/diverged.ckpt), or a static solver (DynamicRelaxation) did not converge in a load
     step (warned, files written)
  1  anything else (bad command line, a file that cannot be written, internal error)
  130  interrupted (Ctrl-C or SIGTERM): the run stops after the current step, files complete
)";

constexpr long kMaxSteps = 1000000000000L;
volatile std::sig_atomic_t g_interrupted = 0;
void onSignal(int) { g_interrupted = 1; }

/// A bad command line found after parsing it (CommandLine::fail's message): exits 1.
[[noreturn]] void usage(const std::string& msg) {
    std::cerr << "fascia-run: " << msg << "\n(see fascia-run --help)\n";
    std::exit(1);
}

int listComponents() {
    PluginManager::instance().loadDefaultPlugins();
    const auto& reg = Registry::instance();
    size_t w = 0;
    for (auto& [n, e] : reg.entries()) w = std::max(w, n.size());
    for (auto& [n, e] : reg.entries()) {
        std::string plugin = e.plugin.empty() ? "core" : e.plugin;
        // the first line of the description (further lines are details for --describe)
        const std::string first = e.description.substr(0, e.description.find('\n'));
        std::printf("%-*s  %-22s %s\n", int(w), n.c_str(), plugin.c_str(), first.c_str());
    }
    return 0;
}

int describe(const std::string& name) {
    PluginManager::instance().loadDefaultPlugins();
    try {
        std::cout << describeComponent(name);
    } catch (const Error& e) {
        std::cerr << "fascia-run: " << e.message() << "\n";
        return 2;
    }
    return 0;
}

void progress(long done, long total, double wall) {
    const int width = 40;
    const double f = total > 0 ? double(done) / double(total) : 1.0;
    const int filled = int(f * width);
    std::fprintf(stderr, "\r[%.*s%*s] %3d%%  step %ld/%ld  %.1f s", filled,
                 "########################################", width - filled, "", int(f * 100), done, total, wall);
    std::fflush(stderr);
}


/// The folder of a checkpoint file must exist and be writable before the run starts, and the file
/// must not be a folder (the rename over it would fail only at the end of the run).
void checkCheckpointFolder(const std::string& file) {
    struct stat st {};
    if (::stat(file.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
        throwOutputError({}, "--checkpoint '" + file + "' is a folder, not a file");
    const std::string::size_type slash = file.rfind('/');
    const std::string dir = slash == std::string::npos ? "." : slash == 0 ? "/" : file.substr(0, slash);
    if (access(dir.c_str(), W_OK | X_OK) != 0)
        throwOutputError({}, "--checkpoint '" + file + "': cannot write into the folder '" + dir + "': " + std::strerror(errno));
}

/// After a failed step: the state at its start, as a checkpoint; the line that says where it is.
void writeLastGood(Simulation& sim, const std::string& checkpoint) {
    const std::string path = !checkpoint.empty() ? checkpoint : sim.outputDir() + "/diverged.ckpt";
    try {
        const long step = sim.saveLastGoodState(path);
        if (step < 0) return;
        std::cerr << "fascia-run: the last good state (step " << step << ", t = " << sim.time() << " s) is in '" << path
                  << "': restart from it with --restart " << path << " (and a smaller dt)\n";
    } catch (const Error& e) {
        std::cerr << "fascia-run: the last good state could not be written: " << e.what() << "\n";
    }
}

/// The command line.
struct Options {
    std::string scene, output, describeName, checkpoint, restart, snapshot;
    long steps = -1, checkpointEvery = 0;
    double endTime = -1, dt = 0;
    int threads = 0;
    std::vector<int> workerCores;
    bool quiet = false, timers = false, list = false, help = false;
};

/// Parses the command line; a bad one exits 1 (usage). Stops at --help (help set).
Options parseArgs(int argc, char** argv) {
    Options o;
    CommandLine cl("fascia-run", argc, argv);
    while (cl.next()) {
        const std::string& a = cl.arg();
        if (cl.isHelp()) {
            o.help = true;
            return o;
        } else if (a == "--steps") {
            o.steps = cl.integer(0, kMaxSteps);
        } else if (a == "--time") {
            o.endTime = cl.positive();
        } else if (a == "--dt") {
            o.dt = cl.positive();
        } else if (a == "--threads") {
            o.threads = int(cl.integer(1, 1024));
        } else if (a == "--worker-cores") {
            const std::string v = cl.text("a list of cores, such as 1 or 1,3");
            try {
                o.workerCores = fascia::core::parseCoreList(v);
            } catch (const std::invalid_argument& e) {
                usage(std::string("--worker-cores: ") + e.what());
            }
        } else if (a == "--output") {
            o.output = cl.path("a folder");
        } else if (a == "--snapshot") {
            o.snapshot = cl.path("a .png file");
        } else if (a == "--quiet" || a == "-q") {
            o.quiet = true;
        } else if (a == "--timers") {
            o.timers = true;
        } else if (a == "--checkpoint") {
            o.checkpoint = cl.path("a file");
        } else if (a == "--checkpoint-every") {
            o.checkpointEvery = cl.integer(1, kMaxSteps);
        } else if (a == "--restart") {
            o.restart = cl.path("a checkpoint file");
        } else if (a == "--list") {
            o.list = true;
        } else if (a == "--describe") {
            o.describeName = cl.text("a component name");
        } else if (cl.isOption()) {
            cl.unknownOption();
        } else if (o.scene.empty()) {
            o.scene = a;
        } else {
            usage("one scene at a time ('" + o.scene + "' and '" + a + "')");
        }
    }
    if (o.steps >= 0 && o.endTime > 0) usage("give --steps or --time, not both");
    if (o.checkpointEvery > 0 && o.checkpoint.empty()) usage("--checkpoint-every needs --checkpoint FILE");
    return o;
}

/// The scene with a PngSnapshot of the final state added to its root (--snapshot); its name is
/// free in the root node ("snapshot", else "snapshot2" ...).
std::unique_ptr<Simulation> withSnapshot(const Options& o, const LoadOptions& opts) {
    ElementSpec spec = parseSceneFile(o.scene);
    PluginManager::instance().loadDefaultPlugins();
    if (!Registry::instance().find("PngSnapshot"))
        throwInputError({}, "--snapshot needs the PngSnapshot component (plugin view), which this build does not have",
                        {"build with VTK (FASCIA_WITH_VTK=ON, FASCIA_WITH_VIEWER=ON)"});
    std::string name = "snapshot";
    for (int k = 2;; ++k) {
        bool taken = false;
        for (auto& c : spec.children)
            for (auto& [key, value] : c.attributes) taken |= key == "name" && value == name;
        if (!taken) break;
        name = "snapshot" + std::to_string(k);
    }
    spec.children.push_back({"PngSnapshot", {"fascia-run --snapshot", 0}, {{"name", name}, {"filename", o.snapshot}}, {}});
    auto root = buildScene(spec);
    root->context().sceneFile = o.scene;
    auto sim = std::make_unique<Simulation>(std::move(root));
    sim->configure(opts);
    sim->init();
    return sim;
}

/// The closing lines: every file the components claimed that exists, with the component that wrote
/// it; a .pvd with the number of files of its series.
void printOutputs(Simulation& sim, const Options& o) {
    namespace fs = std::filesystem;
    std::error_code ec;
    std::vector<std::string> lines;
    for (auto& [path, who] : sim.root().context().outputs) {
        if (!fs::exists(path, ec)) continue;
        const std::string component = who.substr(0, who.find(" ("));
        const Component* c = sim.find(component);
        std::string line = "  " + path + "  (" + (c ? c->className() + " " + c->name() : component);
        if (fs::path(path).extension() == ".pvd") {
            std::ifstream in(path);
            long n = 0;
            for (std::string l; std::getline(in, l);) n += l.find("<DataSet") != std::string::npos;
            line += ", a ParaView series of " + std::to_string(n) + " files";
        }
        lines.push_back(line + ")");
    }
    if (lines.empty()) return;
    std::printf("fascia-run: outputs in %s:\n", (o.output.empty() ? std::string(".") : o.output).c_str());
    for (auto& l : lines) std::printf("%s\n", l.c_str());
}

/// Loads the scene (and the --restart checkpoint) and works out the run: the end time T (0 for a
/// run of a number of steps) and the number of steps, into o.steps. Writes nothing.
std::unique_ptr<Simulation> loadScene(Options& o, double& T) {
    LoadOptions opts;
    opts.outputDir = o.output;
    opts.dt = o.dt;
    if (!o.checkpoint.empty()) checkCheckpointFolder(o.checkpoint);
    std::unique_ptr<Simulation> sim = o.snapshot.empty() ? Simulation::fromFile(o.scene, opts) : withSnapshot(o, opts);
    if (!o.restart.empty()) sim->restore(o.restart);
    if (!(sim->dt() > 0))
        throwInputError({o.scene, sim->root().loc().line}, "no time step: set dt on the root node or pass --dt");
    // a run to an end time ends on it exactly: its last step is shortened (Simulation::stepToward)
    T = o.steps >= 0 ? 0.0 : o.endTime > 0 ? o.endTime : sim->root().endTime.get();
    if (o.steps >= 0) return sim;
    if (!o.restart.empty() && T > 0 && !(sim->stepsUntil(T) > 0))
        throwInputError({o.restart, 0}, "the checkpoint is at t = " + std::to_string(sim->time()) +
                                            " s, at or past the end time " + std::to_string(T) + " s: nothing to run",
                        {"give a later --time, or --steps N for N more steps"});
    if (T > 0 && o.restart.empty()) sim->checkEndTime(T);  // (a restarted run may have less than dt left)
    const double n = T > 0 ? std::ceil((T - sim->time()) / sim->dt() - 1e-9) : 100.0;
    if (!(n <= double(kMaxSteps))) {
        std::ostringstream msg;
        msg << "time " << T << " s at dt = " << sim->dt() << " s is more than 1e12 steps";
        throwInputError({o.scene, sim->root().loc().line}, msg.str());
    }
    o.steps = T > 0 ? sim->stepsUntil(T) : long(n);
    return sim;
}

/// What the stepping did: the steps done, the wall time, the step of the last periodic checkpoint.
struct RunResult {
    long done = 0, saved = -1;
    double wall = 0;
};

/// Starts the observers and runs the steps (toward T when T > 0), with the periodic checkpoints and
/// the progress bar, until done or interrupted.
RunResult runSteps(Simulation& sim, const Options& o, double T) {
    sim.start();  // the scene is valid: only now do the observers write the initial state
    std::signal(SIGINT, onSignal);
    std::signal(SIGTERM, onSignal);
    const bool bar = !o.quiet && isatty(STDERR_FILENO);
    const auto start = std::chrono::steady_clock::now();
    auto lastDraw = start;
    RunResult r;
    for (; r.done < o.steps && !g_interrupted; ++r.done) {
        if (T > 0) sim.stepToward(T);
        else sim.step();
        if (o.checkpointEvery > 0 && sim.stepCount() % o.checkpointEvery == 0) {
            sim.save(o.checkpoint);
            r.saved = sim.stepCount();
        }
        if (bar) {
            auto now = std::chrono::steady_clock::now();
            if (now - lastDraw > std::chrono::milliseconds(100) || r.done + 1 == o.steps) {
                progress(r.done + 1, o.steps, std::chrono::duration<double>(now - start).count());
                lastDraw = now;
            }
        }
    }
    r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (bar) std::fputc('\n', stderr);
    return r;
}

/// The end of the run: the end checkpoint, the final records, the summary line, the timers and the
/// static solvers' reports; returns the exit code (130 interrupted, 3 a static solve that failed).
int finishRun(Simulation& sim, const Options& o, const RunResult& r) {
    // the end checkpoint holds the state before finish() records the final state, as a run that
    // went on would have it
    if (!o.checkpoint.empty() && r.saved != sim.stepCount()) sim.save(o.checkpoint);
    sim.finish();
    const double simulated = sim.time();
    std::printf("fascia-run: %ld steps, %.6g s simulated, %.3f s wall, %.4f ms/step, real-time factor %.3g\n", r.done,
                simulated, r.wall, r.done ? 1e3 * r.wall / double(r.done) : 0.0, r.wall > 0 ? simulated / r.wall : 0.0);
    printOutputs(sim, o);
    if (const long refused = fascia::core::workerPinFailures())
        std::fprintf(stderr, "fascia-run: warning: a worker could not be pinned to its core %ld times (sched_setaffinity "
                             "refused: a cpuset without the core?); the workers ran where the kernel put them\n", refused);
    if (o.timers) {
        std::printf("%-40s %-22s %12s %10s\n", "component", "type", "seconds", "calls");
        for (auto& t : sim.timers())
            if (t.calls) std::printf("%-40s %-22s %12.6f %10ld\n", t.path.c_str(), t.type.c_str(), t.seconds, t.calls);
    }
    // what a static solver reports (once per integrator); one that did not converge exits 3
    std::vector<const BaseIntegrator*> integrators;
    bool failed = false;
    for (auto& g : sim.groups())
        if (std::find(integrators.begin(), integrators.end(), g.integrator) == integrators.end()) {
            integrators.push_back(g.integrator);
            if (const std::string line = g.integrator->runSummary(); !line.empty()) std::printf("%s\n", line.c_str());
            failed |= g.integrator->runFailed();
        }
    if (g_interrupted) {
        std::cerr << "fascia-run: interrupted after " << r.done << " steps (files written so far are complete)\n";
        return 130;
    }
    if (failed) {
        std::cerr << "fascia-run: the static solution did not converge in some load steps (see the warnings above)\n";
        return 3;
    }
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    Options o = parseArgs(argc, argv);
    if (o.help) {
        std::cout << kHelp;
        return 0;
    }
    std::unique_ptr<Simulation> sim;
    try {
        if (o.list) return listComponents();
        if (!o.describeName.empty()) return describe(o.describeName);
        if (o.scene.empty()) usage("no scene given");
        if (o.threads > 0) omp_set_num_threads(o.threads);
        if (!o.workerCores.empty()) fascia::core::setWorkerCores(o.workerCores);
        setTimersEnabled(o.timers);
        double T = 0;
        sim = loadScene(o, T);
        const RunResult r = runSteps(*sim, o, T);
        return finishRun(*sim, o, r);
    } catch (const Error& e) {
        std::cout.flush();
        // every error the load found (Error::more), then, when there are several, how many, as a compiler does
        std::string text = std::string(e.what()) + "\n";
        if (e.count() > 1)
            text += (o.scene.empty() ? std::string("fascia-run") : o.scene) + ": " + std::to_string(e.count()) + " errors\n";
        std::cerr << text;
        switch (e.kind()) {
        case ErrorKind::Input: return 2;
        case ErrorKind::Simulation:
            if (sim && sim->failedStep() > 0) writeLastGood(*sim, o.checkpoint);
            return 3;
        default: return 1;
        }
    } catch (const std::exception& e) {
        std::cerr << "fascia-run: internal error: " << e.what() << "\n";
        return 1;
    }
}
