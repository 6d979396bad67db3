/// fascia-bench's instruments: the order statistics of single steps and the competitor of
/// --contend (started, pinned, killed and reaped; never outliving the bench, on SIGINT or SIGKILL).
#include "Contend.h"
#include "Statistics.h"

#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <fstream>
#include <string>
#include <thread>

using namespace fascia::bench;

namespace {

/// True while process pid runs (a zombie, killed and not yet reaped, counts as gone).
bool alive(pid_t pid) {
    std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
    std::string line;
    if (!std::getline(in, line)) return false;
    const size_t close = line.rfind(')');
    const char state = close + 2 < line.size() ? line[close + 2] : '?';
    return state != 'Z' && state != 'X';
}

/// Waits up to 5 s for pid to be gone.
bool goneWithin5s(pid_t pid) {
    for (int k = 0; k < 500; ++k) {
        if (!alive(pid)) return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
}

/// Forks a process that starts a competitor, reports its pid through a pipe and waits; returns the
/// process and the competitor's pid.
std::pair<pid_t, pid_t> forkBenchWithCompetitor() {
    int fd[2];
    REQUIRE(pipe(fd) == 0);
    const pid_t bench = fork();
    REQUIRE(bench >= 0);
    if (bench == 0) {
        Contender c(true);
        const pid_t p = c.pid();
        if (write(fd[1], &p, sizeof p) != sizeof p) _exit(1);
        for (;;) pause();
    }
    close(fd[1]);
    pid_t competitor = 0;
    REQUIRE(read(fd[0], &competitor, sizeof competitor) == sizeof competitor);
    close(fd[0]);
    return {bench, competitor};
}

} // namespace

TEST_CASE("quantile: the sample with floor(q n) below it, the median of single steps", "[bench]") {
    std::vector<double> v;
    for (int i = 100; i >= 1; --i) v.push_back(i);  // 1 .. 100, unsorted
    CHECK(quantile(v, 0.5) == 51);
    CHECK(quantile(v, 0.9) == 91);
    CHECK(quantile(v, 0.99) == 100);
    CHECK(quantile(v, 1.0) == 100);
    CHECK(quantile(v, 0.0) == 1);
    // a descheduled step moves the mean, not the median
    std::vector<double> steps(99, 1.0);
    steps.push_back(1000.0);
    const StepStats s = stepStats(steps);
    CHECK(s.median == 1.0);
    CHECK(s.p90 == 1.0);
    CHECK(s.p99 == 1000.0);
    CHECK(median({}) == 0.0);
    CHECK(median({3.0, 1.0}) == 3.0);  // the upper of the middle two
}

TEST_CASE("Contender: a pinned busy child while it lives, killed and reaped by stop", "[bench]") {
    Contender off(false);
    CHECK_FALSE(off.running());
    CHECK(off.pid() == 0);
    Contender c(true);
    REQUIRE(c.running());
    const pid_t pid = c.pid();
    CHECK(alive(pid));
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    if (c.core() >= 0) {
        // pinned to its core: the kernel reports the one CPU
        std::ifstream in("/proc/" + std::to_string(pid) + "/status");
        std::string line, allowed;
        while (std::getline(in, line))
            if (line.rfind("Cpus_allowed_list:", 0) == 0) allowed = line.substr(line.find_first_not_of(" \t", 18));
        CHECK(allowed == std::to_string(c.core()));
    }
    c.stop();
    CHECK_FALSE(c.running());
    CHECK_FALSE(alive(pid));
    CHECK(c.cpuSeconds() > 0.05);  // it spun (about 0.3 s, less on a loaded machine)
    c.stop();                      // a second stop does nothing
}

TEST_CASE("Contender: SIGINT to the bench kills the competitor before the bench dies", "[bench]") {
    const auto [bench, competitor] = forkBenchWithCompetitor();
    CHECK(alive(competitor));
    kill(bench, SIGINT);
    int status = 0;
    REQUIRE(waitpid(bench, &status, 0) == bench);
    CHECK(WIFSIGNALED(status));
    CHECK(WTERMSIG(status) == SIGINT);
    CHECK_FALSE(alive(competitor));  // reaped by the handler, before the bench died
}

TEST_CASE("Contender: a bench killed outright takes the competitor with it", "[bench]") {
    const auto [bench, competitor] = forkBenchWithCompetitor();
    CHECK(alive(competitor));
    kill(bench, SIGKILL);  // no handler runs: the kernel's parent-death signal does it
    int status = 0;
    REQUIRE(waitpid(bench, &status, 0) == bench);
    CHECK(goneWithin5s(competitor));
}
