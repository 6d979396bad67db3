#pragma once
/// One parallel region per step (docs/design.md, section 1, "the threaded step"; docs/performance.md,
/// issue 17). A force field that implements ThreadedForces splits its addForce into stages (a node pass,
/// element blocks, the ordered sum of its block buffers); an integrator whose update is node by node
/// runs its step through stepThreaded, which runs, in one parallel region:
///
///   1. the initial forces (external + m g) and every threaded force field's node pass, by chunks;
///   2. the other force fields (serially, by whichever thread takes that task first) and every
///      threaded force field's blocks, all from one shared counter;
///   3. per chunk of state nodes: the block buffers summed in block order, force field by force field,
///      then the integrator's update of the chunk and the finite check's sums (the constrained chunks
///      wait for the constraints: 3b below).
///
/// Every phase hands its tasks out from a shared atomic counter (dynamic: a thread that is descheduled
/// leaves its share to the others) and each task's result depends on the task only, never on the
/// thread that ran it, so the step is bitwise the same for any thread count and any schedule
/// (docs/design.md, principle 5). A barrier separates the phases, because each reads what the
/// previous one wrote anywhere (u for the blocks, every block's buffer for the sums).
#include "fascia/sim/Mechanics.h"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <exception>
#include <vector>

namespace fascia::core {

/// A force field's addForce in stages (implemented by HEML and TLED): what the group's threaded step
/// runs inside its one region, and what runThreadedForces runs for addForce itself.
class ThreadedForces {
public:
    virtual ~ThreadedForces() = default;
    /// Serially, before any other stage: checks, the viscous history's clock and coefficients; the
    /// state whose positions the next stages read. May throw.
    virtual void beginForces(BaseMechanicalState& state, double t) = 0;
    /// Nodes of the pass before the blocks (in the force field's own numbering); 0 when it has none.
    virtual long prepareNodes() const { return 0; }
    /// That pass over its nodes [lo, hi) (TLED: u = x - X; HEML: positions in internal order).
    virtual void prepareRange(long lo, long hi) {}
    /// Its element blocks (fixed by the mesh, never by the thread count).
    virtual long forceBlocks() const = 0;
    /// Block b into its own node buffer, after every prepare range. Any thread; must not throw.
    virtual void runForceBlock(long b) = 0;
    /// f (3 doubles per state node) += its forces at the state nodes [lo, hi), summed per node in block
    /// order, after every block; clears what the next evaluation needs cleared. Any thread, disjoint ranges.
    virtual void sumForceRange(double* f, long lo, long hi) = 0;
};

/// A test hook called before each element block of the threaded stages with the OpenMP thread number
/// and the block's index in the step (a test delays one thread with it); null (the default): none.
using TaskHook = void (*)(int thread, long task);
void setTaskHook(TaskHook hook);
TaskHook taskHook();

/// Whether stepThreaded runs (default true; FASCIA_THREADED_STEP=0 in the environment turns it off, as
/// does setThreadedStep(false)): off, every integrator takes its sequential path (computeForces, then
/// its update), which gives the same bits. For tests and benchmarks of the two paths.
void setThreadedStep(bool on);
bool threadedStepEnabled();
/// Whether the threads own ranges of each phase's tasks (TaskCounter; default true): false with
/// FASCIA_HANDOUT=shared in the environment or setOwnedRanges(false). The same bits either way.
void setOwnedRanges(bool on);
bool ownedRanges();

namespace detail {
/// Runs fn on the calling thread in a team of its own (an orphaned "omp for" inside it binds to that
/// team, not to the enclosing region), keeping the first exception for the caller to rethrow.
template <class Fn>
inline void runAlone(std::exception_ptr& error, Fn&& fn) {
#pragma omp parallel num_threads(1)
    {
        try {
            fn();
        } catch (...) {
            error = std::current_exception();
        }
    }
}

/// Tasks 0 .. total - 1 of one phase, handed out dynamically. Each of the T threads of the team owns the
/// range [t total / T, (t + 1) total / T) and takes its tasks in order from a counter of its own; when its
/// range is done it takes from the other ranges (work stealing). On a quiet machine each thread so runs
/// the same blocks and node chunks step after step (their data stay in its core's caches), and a thread
/// that is descheduled leaves its range to the others. With ownedRanges() false (FASCIA_HANDOUT=shared in
/// the environment) every thread takes from one shared counter instead (an experiment of issue 17).
struct TaskCounter {
    static constexpr int kMaxRanges = 64;
    struct alignas(64) Slot {
        std::atomic<long> next{0};
    };
    Slot slots[kMaxRanges];
    long take(long total) {
        const int T = std::min(omp_get_num_threads(), kMaxRanges);
        if (T == 1 || !ownedRanges()) return slots[0].next.fetch_add(1, std::memory_order_relaxed);
        const int t = omp_get_thread_num() % T;
        for (int k = 0; k < T; ++k) {
            const int r = (t + k) % T;
            const long begin = total * r / T, end = total * (r + 1) / T;
            if (slots[r].next.load(std::memory_order_relaxed) >= end - begin) continue;
            const long i = begin + slots[r].next.fetch_add(1, std::memory_order_relaxed);
            if (i < end) return i;
        }
        return total;
    }
};

/// Maps a flat task index to (force field k, its local task) through the prefix sums `start`.
inline size_t ownerOf(const std::vector<long>& start, long task) {
    size_t k = 0;
    while (k + 1 < start.size() && task >= start[k + 1]) ++k;
    return k;
}

inline void callHook(long task) {
    if (TaskHook h = taskHook()) h(omp_get_thread_num(), task);
}

/// The phases 1 and 2 of the threaded stages (see the top of this file) for the force fields ffs:
/// their node passes, then their blocks; `init(lo, hi)` adds state-node chunks to phase 1 (the group's
/// initial forces; none when nInit is 0) and `alone()` runs as the first task of phase 2 (the force
/// fields that are not threaded). Ends with a barrier. Call inside a parallel region, on every thread.
template <class Init, class Alone>
void runPrepareAndBlocks(const std::vector<ThreadedForces*>& ffs, long nInit,
                         Init&& init, bool haveAlone, Alone&& alone, TaskCounter& c1, TaskCounter& c2,
                         std::exception_ptr& error) {
    const long initChunks = (nInit + kNodeChunk - 1) / kNodeChunk;
    std::vector<long> prep{initChunks}, blocks{haveAlone ? 1L : 0L};
    for (ThreadedForces* ff : ffs) {
        prep.push_back(prep.back() + (ff->prepareNodes() + kNodeChunk - 1) / kNodeChunk);
        blocks.push_back(blocks.back() + ff->forceBlocks());
    }
    for (long k = c1.take(prep.back()); k < prep.back(); k = c1.take(prep.back())) {
        if (k < initChunks) {
            init(k * kNodeChunk, std::min(nInit, (k + 1) * kNodeChunk));
            continue;
        }
        const size_t f = ownerOf(prep, k);  // prep[f] .. prep[f + 1] are the chunks of ffs[f]
        const long c = k - prep[f], n = ffs[f]->prepareNodes();
        ffs[f]->prepareRange(c * kNodeChunk, std::min(n, (c + 1) * kNodeChunk));
    }
    if (prep.back() > 0) {  // (the same on every thread)
#pragma omp barrier
    }
    for (long k = c2.take(blocks.back()); k < blocks.back(); k = c2.take(blocks.back())) {
        if (haveAlone && k == 0) {
            runAlone(error, alone);
            continue;
        }
        const size_t f = ownerOf(blocks, k);
        callHook(k);
        ffs[f]->runForceBlock(k - blocks[f]);
    }
#pragma omp barrier
}
} // namespace detail

/// addForce of a ThreadedForces force field, after its beginForces: its stages in one parallel region
/// (phases 1, 2 and the sum into f over the state's nNodes nodes). Bitwise the same for any thread count.
inline void runThreadedForces(ThreadedForces& ff, double* f, long nNodes) {
    const std::vector<ThreadedForces*> ffs{&ff};
    detail::TaskCounter c1, c2, c3;
    std::exception_ptr error;
    const bool parallel = ff.forceBlocks() > 1;
#pragma omp parallel if (parallel)
    {
        detail::runPrepareAndBlocks(
            ffs, 0, [](long, long) {}, false, [] {}, c1, c2, error);
        const long chunks = (nNodes + kNodeChunk - 1) / kNodeChunk;
        for (long c = c3.take(chunks); c < chunks; c = c3.take(chunks)) ff.sumForceRange(f, c * kNodeChunk, std::min(nNodes, (c + 1) * kNodeChunk));
    }
}

/// The group's step in one parallel region: the forces of every force field at time t (the threaded
/// ones through their stages, the others serially inside the region), the constraints' projection and
/// the reactions as computeForces does them, and update(lo, hi) on every chunk of state nodes, which
/// must update x and v of nodes [lo, hi) from their own x, v, f and 1/m alone. Also computes the sums
/// of checkStep for every chunk the constraints do not touch (g.chunkReady). Returns false, having done
/// nothing, when no force field of the group is threaded or the threaded step is off: the caller then
/// takes its sequential path (computeForces, then the update), which gives the same bits as this one
/// when the threaded force fields come after the others in the group (else the sums of f run in another
/// order: deterministic still, but not the sequential path's bits).
template <class Update>
bool stepThreaded(MechanicalGroup& g, double t, Update&& update) {
    if (!threadedStepEnabled()) return false;
    std::vector<ThreadedForces*> ffs;
    std::vector<BaseForceField*> others;
    for (BaseForceField* ff : g.forceFields) {
        if (auto* tf = dynamic_cast<ThreadedForces*>(ff)) ffs.push_back(tf);
        else others.push_back(ff);
    }
    if (ffs.empty()) return false;
    BaseMechanicalState& s = *g.state;
    const long n = static_cast<long>(s.size());
    for (ThreadedForces* ff : ffs) ff->beginForces(s, t);
    const long chunks = (n + kNodeChunk - 1) / kNodeChunk;
    g.prepareReactions();
    // chunks holding a constrained node are updated after the constraints (phase 3b); a constraint
    // that lists no nodes (a rigid tool: the nodes it touches depend on the state) may touch any
    // chunk, so then every chunk waits for the constraints
    bool anyNode = false;
    for (const BaseConstraint* c : g.constraints) anyNode = anyNode || c->constrainedNodes().empty();
    g.chunkReady.assign(size_t(chunks), anyNode ? 0 : 1);
    for (int i : g.reactionNodes)
        if (i >= 0 && i < n) g.chunkReady[size_t(i / kNodeChunk)] = 0;
    g.chunkSums.assign(2 * size_t(chunks), 0.0);
    const MechanicalGroup::ForceStart init = g.forceStart(t);
    double* fp = flat(s.f());
    long blocks = 0;
    for (ThreadedForces* ff : ffs) blocks += ff->forceBlocks();
    detail::TaskCounter c1, c2, c3, c4;
    std::exception_ptr error;
    // the team: all threads, or one when the measured steps say so (a loaded core: TeamChoice)
    const bool parallel = blocks > 1 || n > kParallelNodes;
    const bool adapt = parallel && adaptiveTeamEnabled() && omp_get_max_threads() > 1;
    const int team = adapt ? g.team.choose() : 1;
    const double start = adapt ? omp_get_wtime() : 0.0;
#pragma omp parallel if (parallel && team == 1)
    {
        detail::runPrepareAndBlocks(
            ffs, n, [&](long lo, long hi) { g.initialForces(init, lo, hi); }, !others.empty(),
            [&] {
                for (BaseForceField* ff : others) {
                    ScopedTimer timer(ff->timer());
                    ff->addForce(s, s.f(), t);
                }
            },
            c1, c2, error);
        for (long c = c3.take(chunks); c < chunks; c = c3.take(chunks)) {
            const long lo = c * kNodeChunk, hi = std::min(n, (c + 1) * kNodeChunk);
            for (ThreadedForces* ff : ffs) ff->sumForceRange(fp, lo, hi);
            if (!g.chunkReady[size_t(c)] || error) continue;
            update(lo, hi);
            g.checkChunk(c, lo, hi);
        }
        if (!g.constraints.empty()) {
#pragma omp barrier
#pragma omp single
            if (!error) detail::runAlone(error, [&] { g.applyConstraints(); });
            // (the implicit barrier of single)
            for (long c = c4.take(chunks); c < chunks; c = c4.take(chunks))
                if (!g.chunkReady[size_t(c)] && !error) update(c * kNodeChunk, std::min(n, (c + 1) * kNodeChunk));
        }
    }
    if (adapt) g.team.record(team, omp_get_wtime() - start);
    if (error) std::rethrow_exception(error);
    return true;
}

} // namespace fascia::core
