// fascia-bench: the cases of a suite line timed side by side in rounds (Bench.h, runCases), with
// single-step statistics, the bytes of the data layout and an optional competing process.
#include "Bench.h"
#include "Contend.h"
#include "ReferenceKernel.h"
#include "Statistics.h"

#include "fascia/sim/LayoutBytes.h"
#include "fascia/sim/StepTeam.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace fascia::bench {

using namespace fascia::core;
namespace fs = std::filesystem;

namespace {

/// Steps shorter than this are timed in groups (the clock's cost and resolution stay below 1 %).
constexpr double kShortestTimedMs = 0.01;

/// One case ready to time: its steps, its force evaluation alone, and what it computes on.
struct Timed {
    std::function<void()> step;
    std::function<void()> forces;  ///< empty: not timed alone
    std::function<void()> finish;  ///< after each timed sample: waits for the steps a device queued (empty: none)
    size_t elements = 0, nodes = 0;
    LayoutBytes bytes;
    int group = 1;                 ///< steps per timed sample
};

/// What the rounds measured of one case.
struct Times {
    std::vector<double> window;  ///< per repeat, ms per step over the timed window
    std::vector<double> steps;   ///< per sample (a step, or a group of `group` steps), ms per step
    std::vector<double> forces;  ///< per repeat, ms per force evaluation alone
    long takeovers = 0;          ///< blocks the step team's caller took over in the timed steps
};

/// The objects a Timed refers to.
struct Owned {
    std::unique_ptr<Simulation> sim;
    std::unique_ptr<ReferenceTLED> ref;
    Positions f;
    std::vector<double> fRef;
};

double since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

/// The reference kernel on the mesh, masses, fixed nodes, time step and deformed state of c's scene.
std::unique_ptr<ReferenceTLED> referenceFor(const Case& c, double& dt) {
    auto sim = build(c, c.threads);
    auto* ff = dynamic_cast<BaseForceField*>(sim->find("ff"));
    const MechanicalGroup& g = sim->groups().at(0);
    if (!ff || !ff->tetrahedra() || ff->tetrahedra()->empty() || (ff->hexahedra() && !ff->hexahedra()->empty()))
        throw std::runtime_error("--reference needs a mesh of tetrahedra");
    IndexList fixed;
    for (const BaseConstraint* k : g.constraints) fixed.insert(fixed.end(), k->constrainedNodes().begin(), k->constrainedNodes().end());
    std::vector<double> mass = g.mass;
    if (mass.empty() && !g.masses.empty()) mass = g.masses[0]->nodalMasses();
    const double mu = kYoung / (2 * (1 + kPoisson)), kappa = kYoung / (3 * (1 - 2 * kPoisson));  // NeoHookean's
    auto ref = std::make_unique<ReferenceTLED>(*ff->tetrahedra(), g.state->x0(), mu, kappa, mass, fixed, c.threads);
    ref->setState(g.state->x());
    dt = sim->dt();
    return ref;
}

Timed prepare(const Case& c, Owned& o) {
    Timed t;
    if (c.reference) {
        double dt = 0;
        o.ref = referenceFor(c, dt);
        ReferenceTLED* r = o.ref.get();
        t.step = [r, dt] { r->step(dt); };
        t.forces = [r, &o] { r->forces(o.fRef); };
        t.elements = r->elementCount();
        t.nodes = r->nodeCount();
        t.bytes = r->layoutBytes();
    } else {
        o.sim = build(c, c.threads);
        Simulation* s = o.sim.get();
        BaseStepBackend* device = s->groups().at(0).backend;
        auto* ff = dynamic_cast<BaseForceField*>(s->find("ff"));
        auto& st = s->state("state");
        o.f.assign(st.size(), Vec3::Zero());
        t.step = [s] { s->step(); };
        // (at the simulation's time: TLED's viscous history then recomputes the same step each
        // call; HEML's would recompute the open step's states at the current positions and so
        // change the trajectory: not timed alone with viscosity)
        if (ff && !device && !(c.viscous && c.forcefield == "HEML")) t.forces = [ff, s, &st, &o] { ff->addForce(st, o.f, s->time()); };
        t.elements = ff ? ff->elementCount() : 0;
        t.nodes = st.size();
        if (auto* lr = dynamic_cast<const LayoutReport*>(device ? static_cast<Component*>(device) : ff)) t.bytes = lr->layoutBytes();
        if (device) t.finish = [device] { device->wait(); };
        s->run(0);  // initialised and started
    }
    // warm-up, which also chooses the group of steps a sample times
    omp_set_num_threads(c.threads);
    const auto t0 = std::chrono::steady_clock::now();
    for (int k = 0; k < 5; ++k) t.step();
    if (t.finish) t.finish();
    const double per = since(t0) / 5;
    t.group = per >= kShortestTimedMs ? 1 : int(std::ceil(kShortestTimedMs / std::max(per, 1e-6)));
    // a device runs the steps the host queued: one sample is the whole window, with one wait at its end
    if (t.finish) t.group = c.steps;
    return t;
}

/// The repeats in rounds, each round timing every case once, the order alternating between rounds
/// (no case always runs first), each repeat step by step (or by groups of steps), then the force
/// evaluation alone.
std::vector<Times> timeRounds(const std::vector<Case>& cs, std::vector<Timed>& ts) {
    const size_t nc = cs.size();
    std::vector<Times> out(nc);
    for (int r = 0; r < cs[0].repeat; ++r)
        for (size_t j = 0; j < nc; ++j) {
            const size_t i = r % 2 == 0 ? j : nc - 1 - j;
            Timed& t = ts[i];
            omp_set_num_threads(cs[i].threads);
            const long taken = teamTakeovers();
            const auto w0 = std::chrono::steady_clock::now();
            for (int done = 0; done < cs[i].steps;) {
                const int m = std::min(t.group, cs[i].steps - done);
                const auto t0 = std::chrono::steady_clock::now();
                for (int k = 0; k < m; ++k) t.step();
                if (t.finish) t.finish();
                out[i].steps.push_back(since(t0) / m);
                done += m;
            }
            out[i].window.push_back(since(w0) / cs[i].steps);
            out[i].takeovers += teamTakeovers() - taken;
            if (!t.forces) continue;
            const auto f0 = std::chrono::steady_clock::now();
            for (int k = 0; k < cs[i].steps; ++k) t.forces();
            out[i].forces.push_back(since(f0) / cs[i].steps);
        }
    return out;
}

/// The median over the rounds of case i's time divided by case 0's in the same round.
double ratioToFirst(const std::vector<double>& a, const std::vector<double>& first) {
    std::vector<double> r;
    for (size_t k = 0; k < a.size() && k < first.size(); ++k) r.push_back(a[k] / first[k]);
    return median(r);
}

/// 1- and c.threads-thread runs of 50 steps from the same state give bitwise the same positions.
bool bitwiseAcrossThreads(const Case& c) {
    auto a = build(c, 1), b = build(c, c.threads);
    omp_set_num_threads(1);  // the force fields read the thread count when they run
    a->run(50);
    omp_set_num_threads(c.threads);
    b->run(50);
    auto& xa = a->state("state").x();
    auto& xb = b->state("state").x();
    for (size_t k = 0; k < xa.size(); ++k)
        if (!(xa[k].array() == xb[k].array()).all()) return false;
    return true;
}

std::string fmt(const char* f, double v) {
    char buf[96];
    std::snprintf(buf, sizeof buf, f, v);
    return buf;
}

/// The JSON object of case i.
void printCase(const std::vector<Case>& cs, const std::vector<Timed>& ts, const std::vector<Times>& tm, size_t i,
               const Contender& contender, int bitwise) {
    const Case& c = cs[i];
    const Timed& t = ts[i];
    const Times& m = tm[i];
    const double med = median(m.window), E = double(std::max<size_t>(1, t.elements));
    const auto [fastest, slowest] = std::minmax_element(m.window.begin(), m.window.end());
    const StepStats st = stepStats(m.steps);
    const std::string name = c.reference ? "reference" : c.forcefield;
    const std::string mesh = c.mesh.empty() ? "cube" + std::to_string(c.cube) + "-" + c.element : fs::path(c.mesh).filename().string();
    std::string s = "{\"forcefield\": \"" + name + "\", \"material\": \"" + c.material + "\"" + (c.viscous ? ", \"viscoelastic\": true" : "") +
                    (c.label.empty() ? "" : ", \"case\": \"" + c.label + "\"") +
                    ", \"mesh\": \"" + mesh + "\", \"elements\": " + std::to_string(t.elements) + ", \"nodes\": " + std::to_string(t.nodes) +
                    ", \"threads\": " + std::to_string(c.threads) + ", \"precision\": \"" +
                    (c.reference ? std::string("double") : c.precision) + "\"" +
                    (c.nodeBuffers.empty() || c.reference || c.forcefield != "TLED" ? "" : ", \"node_buffers\": \"" + c.nodeBuffers + "\"") +
                    (c.device.empty() ? "" : ", \"device\": \"" + c.device + "\"") + (c.block > 0 ? ", \"block\": " + std::to_string(c.block) : "") +
                    (c.forceOrder.empty() ? "" : ", \"force_order\": \"" + c.forceOrder + "\"") + ", \"steps\": " + std::to_string(c.steps);
    s += fmt(", \"ms_per_step\": %.5f", med) + fmt(", \"ms_min\": %.5f", *fastest) + fmt(", \"ms_max\": %.5f", *slowest);
    s += fmt(", \"median_step_ms\": %.5f", st.median) + fmt(", \"p90_step_ms\": %.5f", st.p90) + fmt(", \"p99_step_ms\": %.5f", st.p99);
    if (t.group > 1) s += ", \"step_group\": " + std::to_string(t.group);
    if (c.threads > 1) s += ", \"takeovers\": " + std::to_string(m.takeovers);
    s += fmt(", \"ns_per_element_step\": %.4f", t.elements ? med * 1e6 / E : 0.0);
    s += fmt(", \"steps_per_s\": %.0f", 1e3 / med) + fmt(", \"element_steps_per_s\": %.4g", t.elements ? E * 1e3 / med : 0.0);
    const double perElement = double(ts[0].elements) / E;
    if (i > 0) {
        // per element: the step-time ratio scaled by the element counts
        const double rq = ratioToFirst(m.window, tm[0].window);
        s += fmt(", \"step_time_vs_first\": %.4f", rq) + fmt(", \"per_element_vs_first\": %.4f", rq * perElement);
    }
    if (t.elements && !m.forces.empty()) {
        s += fmt(", \"forcefield_ns_per_element\": %.3f", median(m.forces) * 1e6 / E);
        if (i > 0 && !tm[0].forces.empty())
            s += fmt(", \"forcefield_per_element_vs_first\": %.4f", ratioToFirst(m.forces, tm[0].forces) * perElement);
    }
    if (t.elements && t.bytes.total() > 0) {
        // bytes from the layout (core::LayoutBytes), and the rate they imply at the measured times
        s += fmt(", \"bytes_per_element_step\": %.1f", double(t.bytes.total()) / E) +
             fmt(", \"element_data_bytes_per_element\": %.1f", double(t.bytes.elementData) / E) +
             fmt(", \"node_bytes_per_element\": %.1f", double(t.bytes.nodeRows) / E) +
             fmt(", \"buffer_bytes_per_element\": %.1f", double(t.bytes.buffers) / E);
        if (!m.forces.empty()) s += fmt(", \"forcefield_gb_per_s\": %.2f", double(t.bytes.total()) / (median(m.forces) * 1e6));
        s += fmt(", \"step_gb_per_s\": %.2f", double(t.bytes.total()) / (med * 1e6));
    }
    if (bitwise >= 0)
        s += ", \"bitwise_identical_1_vs_" + std::to_string(c.threads) + "_threads\": " + (bitwise ? "true" : "false");
    if (c.contend) s += ", \"contend\": true, \"contend_core\": " + std::to_string(contender.core()) + fmt(", \"contend_cpu_s\": %.3f", contender.cpuSeconds());
    std::printf("%s}\n", s.c_str());
}

} // namespace

/// Times the cases side by side: every case is built and warmed up first, then the repeats run in
/// rounds (each round times every case once), so that a slow spell of a noisy machine hits all of
/// them alike. Beside its own median, each case after the first reports the median over the rounds
/// of its time divided by the first case's time in the same round (docs/performance.md, lesson 9).
/// With contend (the first case's), a competing process spins on one core from the warm-up to the
/// end of the determinism runs (Contend.h).
void runCases(const std::vector<Case>& cs) {
    std::vector<Owned> owned(cs.size());
    std::vector<Timed> ts;
    for (size_t i = 0; i < cs.size(); ++i) ts.push_back(prepare(cs[i], owned[i]));
    Contender contender(cs[0].contend);
    for (size_t i = 0; i < cs.size(); ++i) {  // warm again, now beside the competitor
        const int warm = ts[i].finish ? 100 : 2 * ts[i].group;  // (a device's group is its whole window)
        for (int k = 0; k < warm; ++k) ts[i].step();
        if (ts[i].finish) ts[i].finish();
    }
    const std::vector<Times> tm = timeRounds(cs, ts);
    std::vector<int> bitwise(cs.size(), -1);  // -1: not asked
    for (size_t i = 0; i < cs.size(); ++i)
        if (cs[i].determinism && !cs[i].reference) bitwise[i] = bitwiseAcrossThreads(cs[i]) ? 1 : 0;
    contender.stop();
    for (size_t i = 0; i < cs.size(); ++i) printCase(cs, ts, tm, i, contender, bitwise[i]);
    std::fflush(stdout);
}

} // namespace fascia::bench
