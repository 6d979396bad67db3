#pragma once
/// The threads of the threaded step (ThreadedStep.h; docs/performance.md, lesson 17: a loaded core).
///
/// An OpenMP parallel region ends when every thread of its team has arrived, and its barriers wait
/// for every thread too: when another process holds the core of one of them (a render or haptic
/// thread beside the simulation), the step waits until the scheduler gives that thread its core
/// back, several milliseconds for a step of a tenth of one. The step team never waits for a thread
/// to arrive or to leave. The caller posts a job of phases, each a list of tasks; the caller and
/// whichever workers are running take the tasks of the open phase from shared counters (each thread
/// owns a range of them and takes from the others' when its own is done); the caller waits at the
/// end of a phase only for the tasks that were taken and not yet done, runs what must run alone
/// (TeamJob::between), and opens the next phase. A worker that comes late takes what is left; one
/// that does not come at all leaves its share to the others. A worker only touches the job through
/// a task it took, and the caller does not return before that task is done (or taken over, below).
/// Results stay bitwise the same for any thread count and schedule as long as each task's result
/// depends on the task only (docs/design.md, principle 5).
///
/// What an arrival-free team cannot avoid by itself is a worker preempted while it holds a task: the
/// caller would wait for that task until the scheduler gives the worker its core back (milliseconds).
/// Two remedies:
/// - a worker gives its core up itself (sched_yield) at a task boundary after 1 ms of CPU time in one
///   stretch, before the scheduler's slice ends in the middle of a task; with no other thread waiting
///   for the core the yield returns at once;
/// - tasks that can be run twice (TeamJob::rerunnable: they write nothing shared until they claim
///   their result, claimTask) are taken over: when the caller has nothing left to take and a task has
///   run 4 times as long as the phase's finished tasks took on average (and at least 50 us), the
///   caller runs it again itself. Whichever run claims first writes the result; the other one, when
///   its thread gets its core back, finds its claim refused and drops what it computed. Both runs
///   compute the same bits, so the result does not depend on which one won.
/// A run that lost its claim may still be executing after runTeamJob returned (its thread is off its
/// core): it writes only its thread's own scratch, and it may read data the next step is rewriting
/// (what it computes from them is dropped). The team keeps the job itself alive until then;
/// whatever else such a run reads must not be freed or moved before waitForLateTasks() returns: the
/// force fields call it in their init and destructor, Node in its destructor, a state in its resize.
///
/// The workers (threads - 1 of them, started on first use and kept) spin for 2 ms after their last
/// task (the next step comes soon: 300 us cost the abdomen scene 10-30 % on a quiet machine, its
/// workers fell asleep between steps) and then sleep until a job comes: a simulation that runs on one
/// thread (TeamChoice) leaves them asleep, off the other cores.

#include <memory>
#include <string>
#include <vector>

namespace fascia::core {

/// A job of the step team: phases 0 .. phases() - 1, run one after the other, each of tasks(p)
/// independent tasks.
class TeamJob {
public:
    virtual ~TeamJob() = default;
    virtual int phases() const = 0;
    /// The tasks of phase p, asked for when the phase opens (after between(p - 1)).
    virtual long tasks(int phase) const = 0;
    /// Task k of phase p, on thread `thread` (0: the caller). Any thread; must not throw.
    virtual void run(int phase, long k, int thread) = 0;
    /// On the caller alone, after every task of phase p and before the next phase opens.
    virtual void between(int phase) { (void)phase; }
    /// Whether task k of phase p may be run twice at once (see the top of this file): it writes
    /// only its thread's own scratch until claimTask() says true, and then its shared results.
    virtual bool rerunnable(int phase, long k) const {
        (void)phase, (void)k;
        return false;
    }
};

/// Inside a task of the step team: whether this run may write the task's shared results (true for
/// exactly one run of each task; false for a run that another one has overtaken). Outside a team
/// task (the sequential path, an OpenMP loop): true. Call it at most once per run, after computing.
bool claimTask();

/// Returns when no thread runs a task that lost its claim any more (they come back when their
/// threads get their cores back: milliseconds at most). For whatever such a task reads, before it
/// is freed or reallocated.
void waitForLateTasks();

/// Tasks the caller has taken over so far in this process (for tests and benchmarks).
long teamTakeovers();

/// The cores the step team's workers run on: worker t (1 .. threads - 1) on cores[(t - 1) % size],
/// from its next task on; empty (the default): wherever the process may run. For an embedding
/// program that places its threads itself: under a competing thread, two threads run 0.78 times one
/// when the step's caller has a core of its own and 1.2 times when it shares one
/// (docs/performance.md, lesson 18), and the kernel chooses unless told. Pin the simulation thread
/// yourself and give the workers the cores you share with your render or haptic threads.
/// FASCIA_WORKER_CORES="1,3" in the environment sets it at start. Throws std::invalid_argument
/// naming a core this machine does not have.
void setWorkerCores(const std::vector<int>& cores);
std::vector<int> workerCores();
/// Parses a core list ("1", "1,3"): the list, or std::invalid_argument saying what is wrong.
std::vector<int> parseCoreList(const std::string& text);
/// Times a worker could not be pinned to its core (sched_setaffinity refused: a cpuset without it).
long workerPinFailures();

/// Runs job on the calling thread and on up to threads - 1 workers, as above; returns when every
/// task of every phase is done. threads <= 1: on the caller alone, in order. The team keeps the job
/// alive while a run that lost its claim may still be inside it (its thread off its core).
void runTeamJob(const std::shared_ptr<TeamJob>& job, int threads);

/// Whether the threads own ranges of each phase's tasks (default true): false with
/// FASCIA_HANDOUT=shared in the environment or setOwnedRanges(false), and every thread takes from one
/// shared counter instead. The same bits either way.
void setOwnedRanges(bool on);
bool ownedRanges();

} // namespace fascia::core
