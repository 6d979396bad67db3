// A haptic loop on the public API: a scene steps in a simulation thread while a 1 kHz device loop on
// another thread drives a tool through a virtual coupling (fascia/haptics/VirtualCoupling.h) and
// records the force felt. The device is a generated trajectory: from the tool's initial position,
// down by `depth` along -z over the first 30 % of the run (a cosine ramp), then a circle of 10 mm
// radius in x-y at 1 Hz while pressed.
//
//   fascia-haptics-demo scenes/interaction/haptics.xml --seconds 5 --output force.csv
//
// Writes one CSV row per device tick (time, interval, force felt, device position, the number of
// tool states the simulation had published) and prints the summary: the device loop's rate and its
// interval's median and 99th percentile, the simulation's update rate and its real-time factor.
// The device loop runs at real-time priority (SCHED_FIFO, where the system permits it: root or
// CAP_SYS_NICE or an rtprio limit; else it says so in device_thread=) and spins the last `--spin`
// seconds before each tick (0.5 ms by default: an idle virtual CPU wakes late from a longer sleep),
// as haptic device loops do: the 99th-percentile interval went from 4.8-5.8 ms to 1.00 ms on a
// loaded two-core machine, and stays at 1.00 ms on a quiet one (docs/performance.md, "Haptics").
#include "fascia/base/CommandLine.h"
#include "fascia/base/Error.h"
#include "fascia/haptics/VirtualCoupling.h"
#include "fascia/sim/Simulation.h"
#include "fascia/sim/Tool.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <pthread.h>
#include <sched.h>
#include <iostream>
#include <string>
#include <thread>
#include <vector>

using fascia::Vec3;
using Clock = std::chrono::steady_clock;

namespace {

struct Options {
    std::string scene, tool = "probe", output = "haptics_force.csv";
    double seconds = 5, rate = 1000, stiffness = 1000, damping = 1, filterTime = 0.005, depth = 0.008;
    double spin = 0.0005;    ///< s: the device loop sleeps until this long before a tick, then spins to it
    bool realtime = true;    ///< ask for SCHED_FIFO for the device loop (falls back when not permitted)
};

const char* kHelp = R"(fascia-haptics-demo: a 1 kHz haptic device loop beside a simulation thread

usage:
  fascia-haptics-demo SCENE [--tool NAME] [--seconds S] [--rate HZ] [--stiffness N/m] [--damping Ns/m]
                      [--filter S] [--depth M] [--output FILE.csv] [--spin S] [--no-realtime]
  fascia-haptics-demo --help

  --tool NAME       the scene's tool the device drives (default probe)
  --seconds S       length of the run (default 5)
  --rate HZ         device ticks per second (default 1000)
  --stiffness N/m   the virtual coupling's spring (default 1000)
  --damping Ns/m    its damper (default 1)
  --filter S        the time constant of the force felt and of the tool's velocity (default 0.005)
  --depth M         how far the device presses along -z (default 0.008)
  --output FILE     one CSV row per device tick (default haptics_force.csv), written at the end
  --spin S          the device loop spins the last S seconds before each tick (default 0.0005, at most 1)
  --no-realtime     no SCHED_FIFO priority for the device loop

Prints the summary: device_ticks, device_rate_hz, the intervals' median and 99th percentile, the
simulation's update rate and real-time factors, the peak force. Exit codes: 0 success; 1 a bad
command line or an output that cannot be written; 2 a bad scene or tool; 3 the simulation failed
or a non-finite force was felt.
)";

/// Parses the command line; --help prints the help and exits 0, a bad command line exits 1.
Options parse(int argc, char** argv) {
    Options o;
    fascia::core::CommandLine cl("fascia-haptics-demo", argc, argv);
    while (cl.next()) {
        if (cl.isHelp()) {
            std::cout << kHelp;
            std::exit(0);
        } else if (cl.is("--tool")) o.tool = cl.text();
        else if (cl.is("--output")) o.output = cl.path();
        else if (cl.is("--seconds")) o.seconds = cl.number(0.001);
        else if (cl.is("--rate")) o.rate = cl.number(1);
        else if (cl.is("--stiffness")) o.stiffness = cl.number(1e-9);
        else if (cl.is("--damping")) o.damping = cl.number(0);
        else if (cl.is("--depth")) o.depth = cl.number(0);
        else if (cl.is("--filter")) o.filterTime = cl.number(0);
        else if (cl.is("--spin")) o.spin = cl.number(0, 1);  // (a clock duration of more would overflow)
        else if (cl.is("--no-realtime")) o.realtime = false;
        else if (cl.isOption()) cl.unknownOption();
        else if (o.scene.empty()) o.scene = cl.arg();
        else cl.fail("one scene at a time ('" + o.scene + "' and '" + cl.arg() + "')");
    }
    if (o.scene.empty()) cl.fail("no scene given");
    return o;
}

/// The device: position and velocity at time t of a run of `total` seconds from p0.
void trajectory(const Options& o, const Vec3& p0, double t, Vec3& x, Vec3& v) {
    const double press = 0.3 * o.seconds, pi = 3.14159265358979323846;
    if (t < press) {
        const double s = 0.5 * (1 - std::cos(pi * t / press));
        x = p0 - Vec3(0, 0, o.depth * s);
        v = Vec3(0, 0, -o.depth * 0.5 * pi / press * std::sin(pi * t / press));
        return;
    }
    // a circle of radius r entered smoothly: the radius grows over the first second of it
    const double u = t - press, r = 0.01 * std::min(1.0, u), dr = u < 1 ? 0.01 : 0.0, w = 2 * pi;
    x = p0 + Vec3(r * std::cos(w * u) - r, r * std::sin(w * u), -o.depth);
    v = Vec3(dr * (std::cos(w * u) - 1) - r * w * std::sin(w * u), dr * std::sin(w * u) + r * w * std::cos(w * u), 0);
}

struct Tick {
    double time, interval;  ///< s
    Vec3 force, device;
    std::uint64_t toolSequence;
};

struct SimStats {
    long steps = 0;
    double simulated = 0, busy = 0, wall = 0;  ///< s
    std::string error;
};

/// The simulation thread: steps as long as the device runs, never ahead of the wall clock, the tool
/// set each step to the coupling's proxy position for the latest device sample.
void simulate(fascia::core::Simulation& sim, fascia::core::BaseTool& tool, fascia::haptics::VirtualCoupling& coupling,
              double filterTime, const std::atomic<bool>& stop, std::atomic<bool>& failed, SimStats& stats) {
    try {
        const auto orientation = tool.pose().orientation;
        const auto start = Clock::now();
        const double t0 = sim.time();
        Vec3 previous = tool.pose().position, velocity = Vec3::Zero();
        while (!stop) {
            const fascia::haptics::CouplingSample d = coupling.device();
            const double wall = std::chrono::duration<double>(Clock::now() - start).count();
            if (d.sequence == 0 || sim.time() - t0 > wall) {  // real time at most
                std::this_thread::sleep_for(std::chrono::microseconds(50));
                continue;
            }
            tool.setPose({coupling.proxy(d.position, tool.force(), sim.dt()), orientation});
            const auto b = Clock::now();
            sim.step();
            stats.busy += std::chrono::duration<double>(Clock::now() - b).count();
            // the tool's velocity, smoothed over the coupling's filter time like its force
            const Vec3 x = tool.pose().position;
            velocity += sim.dt() / (filterTime + sim.dt()) * ((x - previous) / sim.dt() - velocity);
            coupling.publishTool(x, velocity, coupling.filteredContact());
            previous = x;
            ++stats.steps;
        }
        stats.simulated = sim.time() - t0;
        stats.wall = std::chrono::duration<double>(Clock::now() - start).count();
    } catch (const std::exception& e) {
        stats.error = e.what();
        failed = true;
    }
}

/// Gives the calling thread (the device loop) a real-time FIFO priority, as haptic device drivers do,
/// so that a busy machine (a render thread, a compiler) cannot hold it off its tick; the threads it
/// started before keep theirs. Returns the policy it runs under.
std::string raisePriority(bool wanted) {
    if (!wanted) return "normal (--no-realtime)";
    sched_param p{};
    p.sched_priority = std::max(1, sched_get_priority_max(SCHED_FIFO) / 2);
    const int rc = pthread_setschedparam(pthread_self(), SCHED_FIFO, &p);
    return rc == 0 ? "SCHED_FIFO " + std::to_string(p.sched_priority) : std::string("normal (SCHED_FIFO refused: ") + std::strerror(rc) + ")";
}

/// Waits for the tick at `when`: a sleep to `spin` before it (the kernel wakes a sleeper tens of
/// microseconds late, more on a busy machine), then a spin on the clock for the rest.
void waitUntil(Clock::time_point when, Clock::duration spin) {
    if (Clock::now() < when - spin) std::this_thread::sleep_until(when - spin);
    while (Clock::now() < when) {
    }
}

double percentile(std::vector<double> v, double p) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, size_t(p * double(v.size() - 1) + 0.5))];
}

} // namespace

int main(int argc, char** argv) {
    const Options o = parse(argc, argv);
    // a row per device tick is kept in memory (the device loop writes no file): refuse a run whose
    // rows would not fit before anything starts
    const double tickCount = std::max(1.0, std::round(o.seconds * o.rate));
    fascia::core::requireMemory("fascia-haptics-demo",
                                "--seconds " + fascia::core::CommandLine::realText(o.seconds) + " at --rate " +
                                    fascia::core::CommandLine::realText(o.rate),
                                tickCount, sizeof(Tick) + sizeof(double), "device ticks");
    std::unique_ptr<fascia::core::Simulation> sim;
    fascia::core::BaseTool* tool = nullptr;
    try {
        fascia::core::requireOutputFile(o.output);
    } catch (const fascia::core::Error& e) {
        std::cerr << e.what() << "\n";
        return 1;
    }
    try {
        sim = fascia::core::Simulation::fromFile(o.scene);
        tool = &sim->tool(o.tool);
        sim->start();
    } catch (const fascia::core::Error& e) {
        std::cerr << e.what() << "\n";
        return e.kind() == fascia::core::ErrorKind::Input ? 2 : 1;
    } catch (const std::exception& e) {
        std::cerr << "fascia-haptics-demo: " << e.what() << "\n";
        return 1;
    }
    fascia::haptics::VirtualCoupling coupling(o.stiffness, o.damping, o.filterTime);
    const Vec3 p0 = tool->pose().position;
    std::atomic<bool> stop{false}, failed{false};
    SimStats stats;
    std::thread simThread(simulate, std::ref(*sim), std::ref(*tool), std::ref(coupling), o.filterTime, std::cref(stop), std::ref(failed),
                          std::ref(stats));

    // the device loop: a tick every 1/rate s on the steady clock, on this thread at real-time priority
    const std::string policy = raisePriority(o.realtime);
    const auto spin = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(o.spin));
    const long ticks = long(tickCount);
    const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / o.rate));
    std::vector<Tick> log;
    log.reserve(size_t(ticks));
    const auto start = Clock::now();
    auto next = start, previous = start;
    for (long i = 0; i < ticks && !failed; ++i) {
        next += period;
        waitUntil(next, spin);
        const auto now = Clock::now();
        const double t = std::chrono::duration<double>(now - start).count();
        Vec3 x, v;
        trajectory(o, p0, t, x, v);
        coupling.publishDevice(x, v);
        std::uint64_t seq = 0;
        const Vec3 f = coupling.forceFelt(x, v, &seq);
        log.push_back({t, std::chrono::duration<double>(now - previous).count(), f, x, seq});
        previous = now;
    }
    const double duration = std::chrono::duration<double>(Clock::now() - start).count();
    stop = true;
    simThread.join();
    if (!stats.error.empty()) {
        std::cerr << "fascia-haptics-demo: the simulation failed: " << stats.error << "\n";
        return 3;
    }
    sim->finish();

    // written whole or not at all (FILE.tmp, renamed at the end)
    std::vector<double> intervals;
    bool finite = true;
    try {
        fascia::core::OutputFile file(o.output);
        std::ostream& csv = file.stream();
        csv.precision(9);
        csv << "time_s,interval_ms,force_x,force_y,force_z,device_x,device_y,device_z,tool_updates\n";
        for (const Tick& k : log) {
            csv << k.time << "," << 1e3 * k.interval << "," << k.force[0] << "," << k.force[1] << "," << k.force[2] << ","
                << k.device[0] << "," << k.device[1] << "," << k.device[2] << "," << k.toolSequence << "\n";
            intervals.push_back(1e3 * k.interval);
            finite = finite && k.force.allFinite();
        }
        file.commit();
    } catch (const fascia::core::Error& e) {
        std::cerr << e.what() << "\n";
        return 1;
    }
    const double under = double(std::count_if(intervals.begin(), intervals.end(), [](double ms) { return ms < 1.5; })) / double(intervals.size());
    double peak = 0;
    for (const Tick& k : log) peak = std::max(peak, k.force.norm());
    std::printf("device_thread=%s\n", policy.c_str());
    std::printf("device_ticks=%zu\ndevice_rate_hz=%.1f\ninterval_p50_ms=%.4f\ninterval_p99_ms=%.4f\nintervals_under_1.5ms=%.4f\n"
                "simulation_steps=%ld\nsimulation_update_rate_hz=%.1f\nsimulated_s=%.6f\nreal_time_factor=%.4f\n"
                "step_real_time_factor=%.4f\npeak_force_n=%.6g\n",
                log.size(), double(log.size()) / duration, percentile(intervals, 0.5), percentile(intervals, 0.99), under, stats.steps,
                double(stats.steps) / stats.wall, stats.simulated, stats.simulated / stats.wall,
                stats.busy > 0 ? stats.simulated / stats.busy : 0.0, peak);
    if (!finite) {
        std::cerr << "fascia-haptics-demo: a non-finite force was felt\n";
        return 3;
    }
    return 0;
}
