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

#include <csignal>
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
        // block the signals first: one that arrives between the ready file and the wait stays
        // pending, and sigsuspend delivers it (no race, no timeout)
        sigset_t block, old;
        sigemptyset(&block);
        sigaddset(&block, SIGINT);
        sigaddset(&block, SIGTERM);
        sigprocmask(SIG_BLOCK, &block, &old);
        std::ofstream(m_readyFile.get().resolved) << m_steps << "\n";
        sigset_t wait = old;
        sigdelset(&wait, SIGINT);
        sigdelset(&wait, SIGTERM);
        sigsuspend(&wait);  // returns once fascia-run's handler has run
        sigprocmask(SIG_SETMASK, &old, nullptr);
    }
    void observe(double, long) override {}

private:
    int m_steps = 0;
};

static void registerAll(core::Registry& r) {
    r.add<TestProbe>("TestProbe", "reports OpenMP threads and waits for a signal at a chosen step (fascia-run tests)");
}

} // namespace fascia::test

FASCIA_PLUGIN("fascia.test.probe", "0.0.1", "a probe for the fascia-run tests", fascia::test::registerAll)
