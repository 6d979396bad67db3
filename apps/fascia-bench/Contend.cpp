// The --contend competitor (Contend.h): a forked child that spins on one core.
#include "Contend.h"

#include <sched.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <stdexcept>

namespace fascia::bench {

namespace {

/// The running competitor, for the signal handler (one at a time).
volatile sig_atomic_t g_child = 0;
const int kSignals[] = {SIGINT, SIGTERM, SIGHUP};
struct sigaction g_previous[3];

/// Kills and reaps the competitor, then dies of the signal as the bench would have without us.
void onSignal(int sig) {
    const pid_t child = g_child;
    if (child > 0) {
        kill(child, SIGKILL);
        waitpid(child, nullptr, 0);
        g_child = 0;
    }
    signal(sig, SIG_DFL);
    raise(sig);
}

/// The last core of the set this process may run on (-1 when unknown).
int lastCore() {
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof set, &set) != 0) return -1;
    for (int c = CPU_SETSIZE - 1; c >= 0; --c)
        if (CPU_ISSET(c, &set)) return c;
    return -1;
}

/// Pins process pid to core; false when not allowed.
bool pin(pid_t pid, int core) {
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(core, &set);
    return sched_setaffinity(pid, sizeof set, &set) == 0;
}

[[noreturn]] void spin(pid_t parent) {
    // dies with the bench, even when it is killed with SIGKILL (and if it died before this line)
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(0);
    volatile unsigned long x = 0;
    for (;;) {
        for (int i = 0; i < (1 << 24); ++i) x = x + 1;
        if (getppid() != parent) _exit(0);
    }
}

} // namespace

Contender::Contender(bool on) {
    if (!on) return;
    if (g_child != 0) throw std::runtime_error("--contend: a competitor is already running");
    m_core = lastCore();
    const pid_t parent = getpid();
    std::fflush(nullptr);  // nothing buffered twice
    const pid_t pid = fork();
    if (pid < 0) throw std::runtime_error("--contend: fork failed");
    if (pid == 0) spin(parent);
    m_pid = m_started = pid;
    // pinned from here, so that core() says what the kernel did
    if (m_core >= 0 && !pin(pid, m_core)) m_core = -1;
    g_child = pid;
    struct sigaction sa = {};
    sa.sa_handler = onSignal;
    sigemptyset(&sa.sa_mask);
    for (int i = 0; i < 3; ++i) sigaction(kSignals[i], &sa, &g_previous[i]);
}

Contender::~Contender() { stop(); }

void Contender::stop() {
    if (m_pid <= 0) return;
    for (int i = 0; i < 3; ++i) sigaction(kSignals[i], &g_previous[i], nullptr);
    kill(m_pid, SIGKILL);
    struct rusage ru = {};
    while (wait4(m_pid, nullptr, 0, &ru) < 0 && errno == EINTR) {}
    m_cpu = double(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) + 1e-6 * double(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
    g_child = 0;
    m_pid = 0;
}

} // namespace fascia::bench
