/// fascia.test.probe: TestProbe, a component the fascia-run tests (tests/apps/TestFasciaRun.cpp)
/// put in a scene to see from inside the run what the command line did:
/// - threadsFile: at init, writes the OpenMP thread count the run got ("maxThreads N" and
///   "teamSize N", the size of a parallel region);
/// - pauseAtStep: at the start of that step, writes readyFile and waits until a signal is
///   delivered, so that a test can send SIGINT or SIGTERM at a known step, without sleeping.
#include "fascia/plugin/Plugin.h"
#include "fascia/plugin/Registry.h"
#include "fascia/sim/Mechanics.h"

#include <omp.h>

#include <atomic>
#include <csignal>
#include <ctime>
#include <fstream>

namespace fascia::test {

class TestProbe : public core::BaseObserver {
public:
    core::Param<FilePath> m_threadsFile{this, core::ParamSpec("threadsFile").help("file to write the OpenMP thread counts into")};
    core::Param<int> m_pauseAtStep{this, core::ParamSpec("pauseAtStep").min(0).help("step (1-based) to wait for a signal at; 0: never"), 0};
    core::Param<FilePath> m_readyFile{this, core::ParamSpec("readyFile").help("file written when the probe starts waiting")};

    void init() override {
        if (m_pauseAtStep.get() > 0 && m_readyFile.get().resolved.empty()) fail(m_pauseAtStep, "pauseAtStep needs readyFile");
        if (m_threadsFile.get().resolved.empty()) return;
        int team = 0;
#pragma omp parallel
        {
#pragma omp single
            team = omp_get_num_threads();
        }
        std::ofstream(m_threadsFile.get().resolved) << "maxThreads " << omp_get_max_threads() << "\nteamSize " << team << "\n";
    }
    void beginStep(double, double) override {
        if (++m_steps != m_pauseAtStep.get()) return;
        // the signal may be delivered to any thread of the process (VTK's TBB workers, OpenMP's):
        // a handler of ours, chained before fascia-run's, raises a flag that this thread waits for,
        // whichever thread runs it. Installed before the ready file, so no signal is missed; the
        // poll interval decides nothing (the wait ends when the flag is up).
        s_seen = 0;
        struct sigaction ours {}, oldInt {}, oldTerm {};
        ours.sa_handler = &TestProbe::onSignal;
        sigemptyset(&ours.sa_mask);
        sigaction(SIGINT, nullptr, &oldInt);
        sigaction(SIGTERM, nullptr, &oldTerm);
        s_chainInt = oldInt.sa_handler;
        s_chainTerm = oldTerm.sa_handler;
        sigaction(SIGINT, &ours, nullptr);
        sigaction(SIGTERM, &ours, nullptr);
        std::ofstream(m_readyFile.get().resolved) << m_steps << "\n";
        while (!s_seen) {
            const timespec ms{0, 1000000};
            nanosleep(&ms, nullptr);
        }
        sigaction(SIGINT, &oldInt, nullptr);
        sigaction(SIGTERM, &oldTerm, nullptr);
    }
    void observe(double, long) override {}

private:
    static void onSignal(int sig) {
        using Handler = void (*)(int);
        const Handler chained = sig == SIGINT ? s_chainInt : s_chainTerm;
        if (chained != SIG_DFL && chained != SIG_IGN && chained) chained(sig);  // fascia-run's: it stops the run
        s_seen = 1;
    }
    static inline std::atomic<int> s_seen{0};  // lock-free: safe in a handler and across threads
    static inline void (*s_chainInt)(int) = nullptr;
    static inline void (*s_chainTerm)(int) = nullptr;
    int m_steps = 0;
};

static void registerAll(core::Registry& r) {
    r.add<TestProbe>("TestProbe", "reports OpenMP threads and waits for a signal at a chosen step (fascia-run tests)");
}

} // namespace fascia::test

FASCIA_PLUGIN("fascia.test.probe", "0.0.1", "a probe for the fascia-run tests", fascia::test::registerAll)
