#pragma once
/// fascia-bench --contend: a competing busy process during the timing, so that one core is held by
/// a neighbour as a surgical simulator's render and haptic threads hold one (docs/performance.md, "Method", --contend). A forked
/// child spins, pinned to the last core this process may run on (where sched_setaffinity allows),
/// and dies with the bench whatever happens: stop() and the destructor kill and reap it, SIGINT,
/// SIGTERM and SIGHUP kill it before the bench dies of them, and the kernel kills it when the bench
/// dies any other way (PR_SET_PDEATHSIG).
#include <sys/types.h>

namespace fascia::bench {

class Contender {
public:
    /// Starts the competitor when on (otherwise does nothing).
    explicit Contender(bool on);
    ~Contender();
    Contender(const Contender&) = delete;
    Contender& operator=(const Contender&) = delete;
    /// Kills and reaps the competitor (once; later calls do nothing).
    void stop();
    bool running() const { return m_pid > 0; }
    /// The child's process id (0 when none was started), the core it is pinned to (-1: not pinned)
    /// and, after stop(), the CPU seconds it used.
    pid_t pid() const { return m_started; }
    int core() const { return m_core; }
    double cpuSeconds() const { return m_cpu; }

private:
    pid_t m_pid = 0, m_started = 0;
    int m_core = -1;
    double m_cpu = 0;
};

} // namespace fascia::bench
