#include "fascia/sim/StepTeam.h"

#include <atomic>
#include <chrono>
#include <algorithm>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <sched.h>
#include <unistd.h>
#include <time.h>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace fascia::core {

namespace {

bool ownedDefault() {
    const char* e = std::getenv("FASCIA_HANDOUT");
    return !(e && std::string(e) == "shared");
}
std::atomic<bool> g_owned{ownedDefault()};

/// A worker's time on its core since it last lost it: it gives the core up (sched_yield) at a task
/// boundary after kRun of CPU time in one stretch, before the scheduler preempts it in the middle
/// of a task that the caller would then wait for (docs/design.md, section 1, "the threaded step": a competing process on its core).
class RunClock {
public:
    void beforeTask() {
        const double wall = now(CLOCK_MONOTONIC), cpu = now(CLOCK_THREAD_CPUTIME_ID);
        // off the core since the mark (wall time ran ahead of CPU time): a new stretch
        if ((wall - m_wall) - (cpu - m_cpu) > 2e-4) mark(wall, cpu);
        if (cpu - m_cpu < kRun) return;
        sched_yield();
        mark(now(CLOCK_MONOTONIC), now(CLOCK_THREAD_CPUTIME_ID));
    }

private:
    static constexpr double kRun = 1e-3;
    static double now(clockid_t c) {
        timespec t;
        clock_gettime(c, &t);
        return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
    }
    void mark(double wall, double cpu) {
        m_wall = wall;
        m_cpu = cpu;
    }
    double m_wall = 0, m_cpu = 0;
};

inline void relax() {
#if defined(__x86_64__) || defined(__i386__)
    _mm_pause();
#endif
}

std::int64_t nowNs() {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// A task's state (the low byte of its slot's word; the phase's tag in the high 32 bits): taken and
/// running, run again by the caller, claimed by one of its runs. A word with another phase's tag is
/// a task nobody has taken.
enum TaskState : std::uint64_t { kRunning = 1, kTakenOver = 2, kClaimed = 3 };

struct alignas(16) TaskSlot {
    std::atomic<std::uint64_t> word{0};
    std::atomic<std::int64_t> start{0};  ///< when its first run began (ns)
};

/// The task the calling thread runs, for claimTask (none outside the team's tasks).
struct CurrentTask {
    std::atomic<std::uint64_t>* word = nullptr;
    std::uint64_t tag = 0;
    bool claimed = false;
};
thread_local CurrentTask t_task;

std::atomic<long> g_takeovers{0};

/// A phase's tag from its even epoch: 32 bits, as the range counters and task slots hold it in
/// their high halves (it wraps after 2^32 phases, where a 64-bit compare would never match again).
inline std::uint64_t tagOf(std::uint64_t epoch) { return (epoch >> 1) & 0xffffffffu; }
std::atomic<long> g_pinFailures{0};

/// The workers' cores (setWorkerCores): the list and its generation, which a worker compares with
/// the one it applied before each phase it joins.
struct CoreList {
    std::mutex mutex;
    std::vector<int> cores;
    std::atomic<unsigned> generation{0};
};
CoreList& coreList() {
    static CoreList* c = [] {
        auto* l = new CoreList;  // (never destroyed, as the team)
        if (const char* e = std::getenv("FASCIA_WORKER_CORES"); e && *e) {
            try {
                l->cores = parseCoreList(e);
                l->generation = 1;
            } catch (const std::invalid_argument& err) {
                std::fprintf(stderr, "fascia: FASCIA_WORKER_CORES ignored: %s\n", err.what());
            }
        }
        return l;
    }();
    return *c;
}

/// A worker's pinning: applies the core list when its generation changed (worker t of the team).
class WorkerPin {
public:
    WorkerPin() { m_saved = sched_getaffinity(0, sizeof m_original, &m_original) == 0; }
    void update(int t) {
        CoreList& l = coreList();
        const unsigned g = l.generation.load(std::memory_order_acquire);
        if (g == m_applied) return;
        m_applied = g;
        cpu_set_t set;
        {
            std::lock_guard<std::mutex> lock(l.mutex);
            if (l.cores.empty()) {
                if (!m_saved) return;
                set = m_original;
            } else {
                CPU_ZERO(&set);
                CPU_SET(l.cores[size_t(t - 1) % l.cores.size()], &set);
            }
        }
        if (sched_setaffinity(0, sizeof set, &set) != 0) g_pinFailures.fetch_add(1, std::memory_order_relaxed);
    }

private:
    cpu_set_t m_original;
    bool m_saved = false;
    unsigned m_applied = 0;
};

constexpr int kMaxThreads = 64;
/// How long an idle worker spins for the next phase before it sleeps (a step of a small mesh
/// comes every few tenths of a millisecond).
constexpr auto kSpin = std::chrono::microseconds(2000);

/// The team's state. The open phase is published as a seqlock (epoch odd while the caller writes
/// it, even when it holds); each range counter holds the phase's tag (epoch / 2) in its high 32
/// bits and the next task of its range in the low 32, so a take from a phase that has since been
/// replaced fails on the tag.
class Team {
public:
    void run(const std::shared_ptr<TeamJob>& held, int threads) {
        TeamJob& job = *held;
        threads = std::min(threads, kMaxThreads);
        startWorkers(threads - 1);
        releaseRetired();
        for (int p = 0; p < job.phases(); ++p) {
            const long n = job.tasks(p);
            const int ranges = ownedRanges() ? threads : 1;
            const std::uint64_t tag = open(&job, p, n, threads, ranges);
            work(job, p, n, ranges, 0, tag);
            while (m_done.load(std::memory_order_acquire) < n)
                if (!takeOver(job, p, n, tag)) relax();
            job.between(p);
        }
        // (the last phase stays published, exhausted: a worker that reads it takes nothing); a run
        // that lost its claim may still be inside the job: kept until no worker is in a task
        if (m_inTask.load(std::memory_order_seq_cst) > 0) {
            std::lock_guard<std::mutex> lock(m_retiredMutex);
            m_retiredJobs.push_back(held);
        }
    }

private:
    struct alignas(64) Counter {
        std::atomic<std::uint64_t> word{0};
    };

    /// Publishes phase p of job: n tasks in `ranges` ranges for `threads` threads. Returns the phase's tag.
    std::uint64_t open(TeamJob* job, int p, long n, int threads, int ranges) {
        const std::uint64_t e = m_epoch.load(std::memory_order_relaxed);
        m_epoch.store(e + 1, std::memory_order_relaxed);
        std::atomic_thread_fence(std::memory_order_release);
        m_job.store(job, std::memory_order_relaxed);
        m_phase.store(p, std::memory_order_relaxed);
        m_total.store(n, std::memory_order_relaxed);
        m_threads.store(threads, std::memory_order_relaxed);
        m_ranges.store(ranges, std::memory_order_relaxed);
        m_done.store(0, std::memory_order_relaxed);
        m_timed.store(0, std::memory_order_relaxed);
        m_busyNs.store(0, std::memory_order_relaxed);
        m_lastScan = 0;
        if (n > m_capacity) growSlots(n);
        const std::uint64_t tag = tagOf(e + 2);
        for (int r = 0; r < ranges; ++r) m_counters[r].word.store(tag << 32, std::memory_order_relaxed);
        m_epoch.store(e + 2, std::memory_order_seq_cst);  // (seq_cst: against m_sleeping, see sleep)
        if (m_sleeping.load(std::memory_order_seq_cst) > 0) {
            std::lock_guard<std::mutex> lock(m_mutex);
            m_wake.notify_all();
        }
        return tag;
    }

    /// Takes a task of the phase tagged `tag` (n tasks in T ranges, as published with it) for thread
    /// t: its own range first, then the others' in turn; -1 when none is left (or the phase was
    /// replaced).
    long take(std::uint64_t tag, long n, int T, int t) {
        for (int i = 0; i < T; ++i) {
            const int r = (t + i) % T;
            const long begin = n * r / T, size = n * (r + 1) / T - begin;
            std::uint64_t w = m_counters[r].word.load(std::memory_order_relaxed);
            for (;;) {
                if ((w >> 32) != tag) return -1;
                const long k = static_cast<long>(w & 0xffffffffu);
                if (k >= size) break;
                if (m_counters[r].word.compare_exchange_weak(w, w + 1, std::memory_order_acq_rel, std::memory_order_relaxed))
                    return begin + k;
            }
        }
        return -1;
    }

    /// Thread t runs tasks of the phase until none is left (a worker: clock, its RunClock).
    void work(TeamJob& job, int p, long n, int ranges, int t, std::uint64_t tag, RunClock* clock = nullptr) {
        TaskSlot* slots = m_slots.load(std::memory_order_acquire);
        for (;;) {
            if (clock) clock->beforeTask();
            if (clock) m_inTask.fetch_add(1, std::memory_order_seq_cst);
            const long k = take(tag, n, ranges, t);
            if (k >= 0) {
                TaskSlot& s = slots[k];
                const std::int64_t start = nowNs();
                s.start.store(start, std::memory_order_relaxed);
                s.word.store(tag << 32 | kRunning, std::memory_order_release);
                if (runTask(job, p, k, t, s, tag)) {
                    m_busyNs.fetch_add(nowNs() - start, std::memory_order_relaxed);
                    m_timed.fetch_add(1, std::memory_order_relaxed);
                    m_done.fetch_add(1, std::memory_order_release);
                }
            }
            // (a run that lost its claim touches nothing of the job from here on)
            if (clock) m_inTask.fetch_sub(1, std::memory_order_seq_cst);
            if (k < 0) break;
        }
    }

    /// Runs task k of phase p on thread t; true when this run's result is the task's (claimTask).
    static bool runTask(TeamJob& job, int p, long k, int t, TaskSlot& s, std::uint64_t tag) {
        struct Current {  // (reset however the task ends)
            Current(TaskSlot& s, std::uint64_t tag) { t_task = CurrentTask{&s.word, tag, false}; }
            ~Current() { t_task = CurrentTask{}; }
        } current(s, tag);
        job.run(p, k, t);
        return t_task.claimed || claimTask();  // (a task that never asked claims here)
    }

    /// On the caller, with nothing left to take: runs again a rerunnable task of the phase that has
    /// run 4 times the phase's mean task time (at least 50 us); see StepTeam.h. False when none is due.
    bool takeOver(TeamJob& job, int p, long n, std::uint64_t tag) {
        const std::int64_t now = nowNs();
        if (now - m_lastScan < 20000) return false;  // (looks every 20 us)
        m_lastScan = now;
        const long timed = m_timed.load(std::memory_order_relaxed);
        if (timed == 0) return false;
        const std::int64_t limit = std::max<std::int64_t>(4 * m_busyNs.load(std::memory_order_relaxed) / timed, 50000);
        TaskSlot* slots = m_slots.load(std::memory_order_acquire);
        for (long k = 0; k < n; ++k) {
            std::uint64_t w = slots[k].word.load(std::memory_order_acquire);
            if (w != (tag << 32 | kRunning) || now - slots[k].start.load(std::memory_order_relaxed) < limit || !job.rerunnable(p, k))
                continue;
            if (!slots[k].word.compare_exchange_strong(w, tag << 32 | kTakenOver, std::memory_order_acq_rel)) continue;
            g_takeovers.fetch_add(1, std::memory_order_relaxed);
            if (runTask(job, p, k, 0, slots[k], tag)) m_done.fetch_add(1, std::memory_order_release);
            return true;
        }
        return false;
    }

    /// Room for n tasks' slots. The old slots stay allocated: a late run may still claim in them.
    void growSlots(long n) {
        long cap = std::max<long>(m_capacity, 1024);
        while (cap < n) cap *= 2;
        m_retired.emplace_back(new TaskSlot[size_t(cap)]);
        m_slots.store(m_retired.back().get(), std::memory_order_release);
        m_capacity = cap;
    }

    /// Frees the jobs kept for late runs once no worker is in a task.
    void releaseRetired() {
        std::vector<std::shared_ptr<TeamJob>> gone;
        {
            std::lock_guard<std::mutex> lock(m_retiredMutex);
            if (m_retiredJobs.empty() || m_inTask.load(std::memory_order_seq_cst) > 0) return;
            gone.swap(m_retiredJobs);
        }
    }

public:
    void waitForLate() {
        while (m_inTask.load(std::memory_order_seq_cst) > 0) std::this_thread::sleep_for(std::chrono::microseconds(50));
        releaseRetired();
    }

private:

    void startWorkers(int count) {
        // (only the caller of runTeamJob starts workers: the threaded step runs on one thread at a time)
        while (static_cast<int>(m_workers.size()) < count) {
            const int t = static_cast<int>(m_workers.size()) + 1;
            m_workers.emplace_back([this, t] { workerLoop(t); });
            m_workers.back().detach();
        }
    }

    void workerLoop(int t) {
        std::uint64_t seen = 0;
        RunClock clock;
        WorkerPin pin;
        auto idleSince = std::chrono::steady_clock::now();
        for (unsigned spins = 0;; ++spins) {
            const std::uint64_t e = m_epoch.load(std::memory_order_acquire);
            if ((e & 1) == 0 && e != seen) {
                TeamJob* job = m_job.load(std::memory_order_relaxed);
                const int p = m_phase.load(std::memory_order_relaxed), threads = m_threads.load(std::memory_order_relaxed),
                          ranges = m_ranges.load(std::memory_order_relaxed);
                const long n = m_total.load(std::memory_order_relaxed);
                std::atomic_thread_fence(std::memory_order_acquire);
                if (m_epoch.load(std::memory_order_relaxed) != e) continue;  // (being replaced: read again)
                pin.update(t);
                if (job && t < threads) work(*job, p, n, ranges, t, tagOf(e), &clock);
                seen = e;
                idleSince = std::chrono::steady_clock::now();
                continue;
            }
            relax();
            if ((spins & 255) != 0 || std::chrono::steady_clock::now() - idleSince < kSpin) continue;
            sleepWhile(e);
            idleSince = std::chrono::steady_clock::now();
        }
    }

    /// Sleeps until the epoch is no longer e (open() wakes the sleepers it sees).
    void sleepWhile(std::uint64_t e) {
        m_sleeping.fetch_add(1, std::memory_order_seq_cst);
        {
            std::unique_lock<std::mutex> lock(m_mutex);
            m_wake.wait(lock, [&] { return m_epoch.load(std::memory_order_seq_cst) != e; });
        }
        m_sleeping.fetch_sub(1, std::memory_order_seq_cst);
    }

    alignas(64) std::atomic<std::uint64_t> m_epoch{0};
    std::atomic<TeamJob*> m_job{nullptr};
    std::atomic<int> m_phase{0}, m_threads{1}, m_ranges{1};
    std::atomic<long> m_total{0};
    Counter m_counters[kMaxThreads];
    alignas(64) std::atomic<long> m_done{0};
    alignas(64) std::atomic<long> m_timed{0};        ///< tasks of the phase done by their first run
    std::atomic<std::int64_t> m_busyNs{0};           ///< their time together
    alignas(64) std::atomic<int> m_inTask{0};        ///< workers inside work()'s take and task
    std::int64_t m_lastScan = 0;                     ///< (the caller's)
    std::atomic<TaskSlot*> m_slots{nullptr};
    long m_capacity = 0;
    std::vector<std::unique_ptr<TaskSlot[]>> m_retired;  ///< every slot array (the last is m_slots)
    std::mutex m_retiredMutex;
    std::vector<std::shared_ptr<TeamJob>> m_retiredJobs;  ///< jobs a late run may still be inside
    alignas(64) std::atomic<int> m_sleeping{0};
    std::mutex m_mutex;
    std::condition_variable m_wake;
    std::vector<std::thread> m_workers;
};

Team& team() {
    // (never destroyed: its detached workers may still be asleep in it when the program ends)
    static Team* t = new Team;
    return *t;
}

} // namespace

void runTeamJob(const std::shared_ptr<TeamJob>& held, int threads) {
    TeamJob& job = *held;
    if (threads <= 1) {
        for (int p = 0; p < job.phases(); ++p) {
            const long n = job.tasks(p);
            for (long k = 0; k < n; ++k) job.run(p, k, 0);
            job.between(p);
        }
        return;
    }
    team().run(held, threads);
}

bool claimTask() {
    CurrentTask& c = t_task;
    if (!c.word || c.claimed) return true;
    std::uint64_t w = c.word->load(std::memory_order_acquire);
    for (;;) {
        if ((w >> 32) != c.tag || (w & 0xff) == kClaimed) return false;
        if (c.word->compare_exchange_weak(w, c.tag << 32 | kClaimed, std::memory_order_acq_rel, std::memory_order_acquire)) break;
    }
    c.claimed = true;
    return true;
}

void waitForLateTasks() { team().waitForLate(); }

long teamTakeovers() { return g_takeovers.load(std::memory_order_relaxed); }

std::vector<int> parseCoreList(const std::string& text) {
    const long have = sysconf(_SC_NPROCESSORS_CONF);
    std::vector<int> cores;
    size_t at = 0;
    for (;;) {
        const size_t comma = text.find(',', at);
        const std::string item = text.substr(at, comma == std::string::npos ? std::string::npos : comma - at);
        size_t used = 0;
        long c = -1;
        try {
            c = std::stol(item, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (item.empty() || used != item.size() || c < 0)
            throw std::invalid_argument("'" + text + "' is not a list of core numbers such as 1 or 1,3 (at '" + item + "')");
        if (c >= have || c >= CPU_SETSIZE)
            throw std::invalid_argument("core " + item + " of '" + text + "': this machine has cores 0 to " + std::to_string(have - 1));
        cores.push_back(int(c));
        if (comma == std::string::npos) return cores;
        at = comma + 1;
    }
}

void setWorkerCores(const std::vector<int>& cores) {
    const long have = sysconf(_SC_NPROCESSORS_CONF);
    for (int c : cores)
        if (c < 0 || c >= have || c >= CPU_SETSIZE)
            throw std::invalid_argument("setWorkerCores: core " + std::to_string(c) + ": this machine has cores 0 to " + std::to_string(have - 1));
    CoreList& l = coreList();
    std::lock_guard<std::mutex> lock(l.mutex);
    l.cores = cores;
    l.generation.fetch_add(1, std::memory_order_acq_rel);
}

std::vector<int> workerCores() {
    CoreList& l = coreList();
    std::lock_guard<std::mutex> lock(l.mutex);
    return l.cores;
}

long workerPinFailures() { return g_pinFailures.load(std::memory_order_relaxed); }

void setOwnedRanges(bool on) { g_owned.store(on); }
bool ownedRanges() { return g_owned.load(std::memory_order_relaxed); }

} // namespace fascia::core
