#pragma once
/// One job of the step team per step (docs/design.md, section 1, "the threaded step";
/// docs/performance.md, lesson 17). A force field that implements ThreadedForces splits its addForce
/// into stages (a node pass, element blocks, the ordered sum of its block buffers); an integrator
/// whose update is node by node runs its step through stepThreaded, which runs, as the phases of one
/// job of the step team (fascia/sim/StepTeam.h):
///
///   0. the initial forces (external + m g) and every threaded force field's node pass, by chunks;
///   1. the other force fields (serially, by whichever thread takes that task first) and every
///      threaded force field's blocks;
///   2. per chunk of state nodes: the block buffers summed in block order, force field by force field,
///      then the integrator's update of the chunk and the finite check's sums; then, with
///      constraints, the constraints alone (TeamJob::between), and
///   3. the update of the chunks that hold a constrained node.
///
/// Every phase hands its tasks out dynamically (each thread its own range first, then the others':
/// a thread that is descheduled leaves its share to the others, and the caller waits only for the
/// tasks that were taken, never for a thread), and each task's result depends on the task only,
/// never on the thread that ran it, so the step is bitwise the same for any thread count and any
/// schedule (docs/design.md, principle 5). A phase opens when the previous one is done, because each
/// reads what the previous one wrote anywhere (u for the blocks, every block's buffer for the sums).
#include "fascia/sim/Mechanics.h"
#include "fascia/sim/StepTeam.h"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <exception>
#include <memory>
#include <type_traits>
#include <utility>
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
    /// Block b into its own node buffer, after every prepare range, on the step team's thread
    /// `thread` (0 .. 63, for per-thread scratch). Any thread; must not throw.
    virtual void runForceBlock(long b, int thread) = 0;
    /// Whether a block may run twice at once (the step team's takeover of a block whose thread lost
    /// its core, fascia/sim/StepTeam.h): true when runForceBlock computes into its thread's scratch
    /// and writes its buffer only when core::claimTask() says so. Default false.
    virtual bool rerunnableBlocks() const { return false; }
    /// f (3 doubles per state node) += its forces at the state nodes [lo, hi), summed per node in block
    /// order, after every block; clears what the next evaluation needs cleared. Any thread, disjoint ranges.
    virtual void sumForceRange(double* f, long lo, long hi) = 0;
};

/// A test hook called before each element block of the threaded stages with the step team's thread
/// number and the block's index in the step (a test delays one thread with it); null (the default): none.
using TaskHook = void (*)(int thread, long task);
void setTaskHook(TaskHook hook);
TaskHook taskHook();

/// Whether stepThreaded runs (default true; FASCIA_THREADED_STEP=0 in the environment turns it off, as
/// does setThreadedStep(false)): off, every integrator takes its sequential path (computeForces, then
/// its update), which gives the same bits. For tests and benchmarks of the two paths.
void setThreadedStep(bool on);
bool threadedStepEnabled();

namespace detail {
/// Runs fn on the calling thread in an OpenMP team of its own (an orphaned "omp for" inside it binds
/// to that team), keeping the first exception for the caller to rethrow.
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

/// Maps a flat task index to (force field k, its local task) through the prefix sums `start`.
inline size_t ownerOf(const std::vector<long>& start, long task) {
    size_t k = 0;
    while (k + 1 < start.size() && task >= start[k + 1]) ++k;
    return k;
}

/// The phases 0 and 1 of the threaded stages (see the top of this file) for the force fields ffs:
/// phase 0 the chunks of `nInit` state nodes of the initial forces (init(lo, hi); none when nInit is
/// 0), then every force field's node pass by chunks; phase 1 `alone()` as its first task when
/// haveAlone (the force fields that are not threaded), then every force field's blocks.
struct ForceStages {
    std::vector<ThreadedForces*> ffs;
    long initChunks = 0, nInit = 0;
    bool haveAlone = false;
    std::vector<long> prep, blocks;  ///< prefix sums of the tasks of phases 0 and 1

    ForceStages(std::vector<ThreadedForces*> f, long nInitNodes, bool alone)
        : ffs(std::move(f)), initChunks((nInitNodes + kNodeChunk - 1) / kNodeChunk), nInit(nInitNodes), haveAlone(alone) {
        prep.push_back(initChunks);
        blocks.push_back(haveAlone ? 1L : 0L);
        for (ThreadedForces* ff : ffs) {
            prep.push_back(prep.back() + (ff->prepareNodes() + kNodeChunk - 1) / kNodeChunk);
            blocks.push_back(blocks.back() + ff->forceBlocks());
        }
    }
    /// Task k of phase 0.
    template <class Init>
    void prepare(long k, Init&& init) const {
        if (k < initChunks) {
            init(k * kNodeChunk, std::min(nInit, (k + 1) * kNodeChunk));
            return;
        }
        const size_t f = ownerOf(prep, k);  // prep[f] .. prep[f + 1] are the chunks of ffs[f]
        const long c = k - prep[f], n = ffs[f]->prepareNodes();
        ffs[f]->prepareRange(c * kNodeChunk, std::min(n, (c + 1) * kNodeChunk));
    }
    /// Task k of phase 1 on thread `thread`.
    template <class Alone>
    void block(long k, int thread, std::exception_ptr& error, Alone&& alone) const {
        if (haveAlone && k == 0) {
            runAlone(error, alone);
            return;
        }
        const size_t f = ownerOf(blocks, k);
        if (TaskHook h = taskHook()) h(thread, k);
        ffs[f]->runForceBlock(k - blocks[f], thread);
        // (nothing of this job may be touched from here: a run that lost its claim may come back
        // after the job is gone, StepTeam.h)
    }
    /// Whether task k of phase 1 may run twice (TeamJob::rerunnable).
    bool rerunnable(long k) const { return !(haveAlone && k == 0) && ffs[ownerOf(blocks, k)]->rerunnableBlocks(); }
};

/// addForce's stages as a team job: the node passes, the blocks, the sum into f over nNodes nodes.
class ForcesJob final : public TeamJob {
public:
    ForcesJob(ThreadedForces& ff, double* f, long nNodes) : m_stages({&ff}, 0, false), m_f(f), m_n(nNodes) {}
    int phases() const override { return 3; }
    long tasks(int p) const override {
        return p == 0 ? m_stages.prep.back() : p == 1 ? m_stages.blocks.back() : (m_n + kNodeChunk - 1) / kNodeChunk;
    }
    void run(int p, long k, int thread) override {
        if (p == 0) m_stages.prepare(k, [](long, long) {});
        else if (p == 1) m_stages.block(k, thread, m_error, [] {});
        else m_stages.ffs[0]->sumForceRange(m_f, k * kNodeChunk, std::min(m_n, (k + 1) * kNodeChunk));
    }
    bool rerunnable(int p, long k) const override { return p == 1 && m_stages.rerunnable(k); }

private:
    ForceStages m_stages;
    double* m_f;
    long m_n;
    std::exception_ptr m_error;
};
} // namespace detail

/// addForce of a ThreadedForces force field, after its beginForces: its stages as one job of the step
/// team (StepTeam.h) on the OpenMP threads (omp_get_max_threads()). Bitwise the same for any thread count.
inline void runThreadedForces(ThreadedForces& ff, double* f, long nNodes) {
    runTeamJob(std::make_shared<detail::ForcesJob>(ff, f, nNodes), ff.forceBlocks() > 1 ? omp_get_max_threads() : 1);
}

namespace detail {
/// The group's step as a team job (stepThreaded): phases 0 and 1 of ForceStages, 2 the sums and the
/// update of the chunks no constraint touches, then (with constraints) the constraints alone and
/// phase 3, the update of the other chunks.
template <class Update>
class StepJob final : public TeamJob {
public:
    StepJob(MechanicalGroup& g, double t, std::vector<ThreadedForces*> ffs, std::vector<BaseForceField*> others, Update& update)
        : m_g(g), m_t(t), m_stages(std::move(ffs), static_cast<long>(g.state->size()), !others.empty()), m_others(std::move(others)),
          m_update(update), m_n(static_cast<long>(g.state->size())), m_init(g.forceStart(t)), m_f(flat(g.state->f())) {}
    int phases() const override { return m_g.constraints.empty() ? 3 : 4; }
    long tasks(int p) const override {
        return p == 0 ? m_stages.prep.back() : p == 1 ? m_stages.blocks.back() : (m_n + kNodeChunk - 1) / kNodeChunk;
    }
    void run(int p, long k, int thread) override {
        if (p == 0) {
            m_stages.prepare(k, [&](long lo, long hi) { m_g.initialForces(m_init, lo, hi); });
        } else if (p == 1) {
            m_stages.block(k, thread, m_error, [&] {
                for (BaseForceField* ff : m_others) {
                    ScopedTimer timer(ff->timer());
                    ff->addForce(*m_g.state, m_g.state->f(), m_t);
                }
            });
        } else if (p == 2) {
            const long lo = k * kNodeChunk, hi = std::min(m_n, (k + 1) * kNodeChunk);
            for (ThreadedForces* ff : m_stages.ffs) ff->sumForceRange(m_f, lo, hi);
            if (!m_g.chunkReady[size_t(k)] || m_error) return;
            m_update(lo, hi);
            m_g.checkChunk(k, lo, hi);
        } else if (!m_g.chunkReady[size_t(k)] && !m_error) {
            m_update(k * kNodeChunk, std::min(m_n, (k + 1) * kNodeChunk));
        }
    }
    void between(int p) override {
        if (p == 2 && !m_g.constraints.empty() && !m_error) runAlone(m_error, [&] { m_g.applyConstraints(); });
    }
    bool rerunnable(int p, long k) const override { return p == 1 && m_stages.rerunnable(k); }
    std::exception_ptr& error() { return m_error; }

private:
    MechanicalGroup& m_g;
    double m_t;
    ForceStages m_stages;
    std::vector<BaseForceField*> m_others;
    Update& m_update;
    long m_n;
    MechanicalGroup::ForceStart m_init;
    double* m_f;
    std::exception_ptr m_error;
};
} // namespace detail

/// The group's step as one job of the step team: the forces of every force field at time t (the
/// threaded ones through their stages, the others serially as one task), the constraints' projection
/// and the reactions as computeForces does them, and update(lo, hi) on every chunk of state nodes,
/// which must update x and v of nodes [lo, hi) from their own x, v, f and 1/m alone. Also computes the
/// sums of checkStep for every chunk the constraints do not touch (g.chunkReady). Returns false,
/// having done nothing, when no force field of the group is threaded or the threaded step is off: the
/// caller then takes its sequential path (computeForces, then the update), which gives the same bits
/// as this one when the threaded force fields come after the others in the group (else the sums of f
/// run in another order: deterministic still, but not the sequential path's bits).
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
    // chunks holding a constrained node are updated after the constraints (phase 3); a constraint
    // that lists no nodes (a rigid tool: the nodes it touches depend on the state) may touch any
    // chunk, so then every chunk waits for the constraints
    bool anyNode = false;
    for (const BaseConstraint* c : g.constraints) anyNode = anyNode || c->constrainedNodes().empty();
    g.chunkReady.assign(size_t(chunks), anyNode ? 0 : 1);
    for (int i : g.reactionNodes)
        if (i >= 0 && i < n) g.chunkReady[size_t(i / kNodeChunk)] = 0;
    g.chunkSums.assign(2 * size_t(chunks), 0.0);
    long blocks = 0;
    for (ThreadedForces* ff : ffs) blocks += ff->forceBlocks();
    // (shared: the team keeps it while a block's late run may be inside it, StepTeam.h)
    auto job = std::make_shared<detail::StepJob<std::remove_reference_t<Update>>>(g, t, std::move(ffs), std::move(others), update);
    // the team: all threads, or one when the measured steps say so (a loaded core: TeamChoice)
    const bool parallel = blocks > 1 || n > kParallelNodes;
    const bool adapt = parallel && adaptiveTeamEnabled() && omp_get_max_threads() > 1;
    const int team = adapt ? g.team.choose() : 1;
    const double start = adapt ? omp_get_wtime() : 0.0;
    runTeamJob(job, parallel && team == 1 ? omp_get_max_threads() : 1);
    if (adapt) g.team.record(team, omp_get_wtime() - start);
    if (job->error()) std::rethrow_exception(job->error());
    return true;
}

} // namespace fascia::core
