#include "fascia/tled/TLEDForceField.h"

#include "TLEDData.h"

#include "fascia/base/Simd.h"
#include "fascia/base/StateIO.h"
#include "fascia/elements/Errors.h"
#include "fascia/elements/Geometry.h"
#include "fascia/elements/Tensor3.h"
#include "fascia/scene/Node.h"
#include "fascia/materials/RelaxationSplit.h"
#include "fascia/viscoelastic/ViscoelasticProny.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fascia::tled {

using materials::BaseMaterial;
using Impl = TLEDForceField::Impl;

namespace {
/// The mesh source in the context (MeshLoader, GridMesh ...: a core::BaseTopology).
core::BaseTopology* findMeshSource(const core::Component& self) {
    return self.node() ? self.node()->findInContext<core::BaseTopology>() : nullptr;
}
} // namespace

TLEDForceField::TLEDForceField() : m_impl(std::make_unique<Impl>()) {}
TLEDForceField::~TLEDForceField() { core::waitForLateTasks(); }  // (a block's late run may still read m_impl)
size_t TLEDForceField::blockCount() const { return m_impl->blocks.size(); }

// ------------------------------------------------------------------------------------------------
// set-up

std::vector<core::Component*> TLEDForceField::dependencies() const {
    std::vector<core::Component*> deps;
    if (!node()) return deps;
    if (auto* s = node()->findInContext<core::BaseMechanicalState>()) deps.push_back(s);
    if (auto* m = elements::defaultMaterial(*this, m_material, m_groupMaterials)) deps.push_back(m);
    for (auto* m : elements::listedMaterials(*this, m_groupMaterials)) deps.push_back(m);
    for (auto* p : node()->findAllLocal<viscoelastic::ViscoelasticProny>()) deps.push_back(p);
    if (!m_mesh.isSet() && !m_tetrahedra.isSet() && !m_hexahedra.isSet())
        if (auto* src = findMeshSource(*this)) deps.push_back(src);
    return deps;
}

void TLEDForceField::init() {
    core::waitForLateTasks();
    m_impl = std::make_unique<Impl>();
    Impl& im = *m_impl;
    im.J0 = m_J0.get();

    // elements
    const MeshData* mesh = nullptr;
    if (m_mesh.isSet()) {
        if (m_tetrahedra.isSet() || m_hexahedra.isSet())
            fail(m_mesh, "both mesh and tetrahedra/hexahedra are given: give the elements one way");
        mesh = &m_mesh.get();
    } else if (!m_tetrahedra.isSet() && !m_hexahedra.isSet()) {
        auto* src = findMeshSource(*this);
        if (!src)
            fail("no elements: set mesh=\"@loader.mesh\" (or tetrahedra/hexahedra), or put a mesh source "
                 "(MeshLoader, GridMesh) in the node or a parent");
        mesh = &src->meshData();
    }
    if (mesh) {
        m_tets = mesh->tetrahedra;
        m_hexes = mesh->hexahedra;
    } else {
        m_tets = m_tetrahedra.get();
        m_hexes = m_hexahedra.get();
    }
    const size_t nT = m_tets.size(), nH = m_hexes.size();
    if (nT + nH == 0) fail("the mesh has no tetrahedra and no hexahedra");
    im.nTetCells = nT;

    // state and rest positions
    auto* state = node() ? node()->findInContext<core::BaseMechanicalState>() : nullptr;
    if (!state) fail("no mechanical state (MechanicalObject) in its node or a parent");
    const Positions& X = state->x0();
    int maxNode = -1;
    for (auto& t : m_tets) for (int v : t) maxNode = std::max(maxNode, v);
    for (auto& h : m_hexes) for (int v : h) maxNode = std::max(maxNode, v);
    if (static_cast<size_t>(maxNode) >= X.size())
        fail("elements use node " + std::to_string(maxNode) + " but the state '" + state->name() + "' has " +
             std::to_string(X.size()) + " nodes");
    im.nodeCount = static_cast<size_t>(maxNode + 1);
    im.mixed = m_precision.get() == "mixed";

    precompute(mesh, X);

    // viscoelasticity
    bool isoTaken = false, volTaken = false;
    size_t stateBytes = 0;
    for (auto* p : node()->findAllLocal<viscoelastic::ViscoelasticProny>()) {
        ViscoSet vs;
        vs.prony = p;
        vs.iso = p->relaxesIsochoric();
        vs.vol = p->relaxesVolumetric();
        if ((vs.iso && isoTaken) || (vs.vol && volTaken))
            fail("two ViscoelasticProny components in its node relax the same part of the stress; give one series per "
                 "part (apply=\"isochoric\" and apply=\"volumetric\") or one with apply=\"both\"");
        isoTaken |= vs.iso;
        volTaken |= vs.vol;
        vs.terms = static_cast<int>(p->termCount());
        const size_t n = im.batches * static_cast<size_t>(vs.terms) * 6 * kBatch;
        vs.Yprev.assign(n, 0.0);
        vs.Ycur.assign(n, 0.0);
        stateBytes += 2 * n * sizeof(double);
        im.visco.push_back(std::move(vs));
    }
    // each part that relaxes must be stress-free at rest, or a body at rest creeps (RelaxationSplit.h)
    bool onePartAlone = false;
    for (const ViscoSet& vs : im.visco) onePartAlone |= vs.iso != vs.vol;
    for (auto& g : im.groups) {
        const materials::RelaxationSplit split = materials::relaxationSplit(*g.material, im.J0);
        for (const ViscoSet& vs : im.visco) {
            const std::string err = materials::relaxationRestError(split, vs.iso, vs.vol, g.material->className() + " '" +
                                                                                              g.material->name() + "'");
            if (!err.empty()) vs.prony->failApply(err);
        }
        g.restShift = onePartAlone ? split.shift : 0.0;
    }
    // states beyond a quarter of a typical L3 (32 MiB here) are written with streaming stores: they
    // are read once per step and would only evict the element data (docs/performance.md)
    const std::string& stream = m_streamStates.get();
    im.streamStates = stream == "on" || (stream == "auto" && stateBytes > (size_t(8) << 20));
    const double dt = node()->context().dt;
    if (dt > 0) dtChanged(dt);
}

void TLEDForceField::dtChanged(double dt) {
    Impl& im = *m_impl;
    im.dt = dt;
    // TLED eq. (30); once forces were evaluated, A and B stay those of the last evaluation (a stress
    // output reads them) until the next one computes them for the time it advances over
    if (!im.clock.evaluated())
        for (auto& vs : im.visco) vs.prony->coefficients(dt, vs.A, vs.B);
}

// ------------------------------------------------------------------------------------------------
// evaluation

namespace {

template <class Block>
void runBlock(const Impl& im, const Block& b, const KernelIO& io) {
    im.groups[static_cast<size_t>(b.group)].fn(im, b, io);
}

/// u = x - X for the internal nodes [lo, hi) the elements use, 4 per node in internal order (the 4th is padding).
void displacementRange(const Impl& im, const core::BaseMechanicalState& state, double* __restrict up, long lo, long hi) {
    const double* __restrict x = core::flat(state.x());
    const double* __restrict X = core::flat(state.x0());
    const int* __restrict node = im.nodeOf.empty() ? nullptr : im.nodeOf.data();
    for (long i = lo; i < hi; ++i) {
        const size_t p = 3 * static_cast<size_t>(node ? node[i] : i);
        up[4 * i] = x[p] - X[p];
        up[4 * i + 1] = x[p + 1] - X[p + 1];
        up[4 * i + 2] = x[p + 2] - X[p + 2];
        up[4 * i + 3] = 0.0;
    }
}

/// displacementRange over every node. An orphaned "omp for": shared by the threads of the enclosing
/// parallel region (every caller opens its own, so a caller inside a user's parallel region still gets all of u).
void displacements(const Impl& im, const core::BaseMechanicalState& state, std::vector<double>& u) {
    const long n = static_cast<long>(im.nodeCount);
    const long chunks = (n + core::kNodeChunk - 1) / core::kNodeChunk;
#pragma omp for schedule(static)
    for (long c = 0; c < chunks; ++c)
        displacementRange(im, state, u.data(), c * core::kNodeChunk, std::min(n, (c + 1) * core::kNodeChunk));
}

/// Runs every block on the state's current displacements; setup(io, block index) chooses the outputs
/// (energy, S, F) and the history. For the outputs other than the forces of a step.
template <class Block, class Setup>
void runBlocksOn(const Impl& im, const std::vector<Block>& blocks, const core::BaseMechanicalState& state, Setup&& setup) {
    std::vector<double> u(4 * im.nodeCount);
#pragma omp parallel if (im.nodeCount > 65536)
    displacements(im, state, u);
    const long nb = static_cast<long>(blocks.size());
#pragma omp parallel if (nb > 1)
    {
        std::vector<double> rows;  // compact rows: the block's u, its own copy (the force path's rows stay untouched)
#pragma omp for schedule(dynamic, 1)
        for (long bi = 0; bi < nb; ++bi) {
            const size_t b = static_cast<size_t>(bi);
            KernelIO io;
            io.u = u.data();
            if (im.compact) {
                rows.resize(4 * (im.rows.rowEnd(b) - im.rows.rowBegin(b)));
                im.rows.loadRows(b, u.data(), rows.data());
                io.u = rows.data();
            }
            setup(io, b);
            runBlock(im, blocks[b], io);
        }
    }
}

/// What a stress output at time t reads (viscoelastic/HistoryClock.h): the history and the
/// coefficients of each series, so that the stress is the one of the state at t.
struct OutputHistory {
    std::vector<double> A[2], B[2];
    const double* Y[2] = {nullptr, nullptr};
    OutputHistory(const Impl& im, double t) {
        const viscoelastic::HistoryClock::Output o = im.clock.outputAt(t, im.dt);
        for (size_t v = 0; v < im.visco.size(); ++v) {
            Y[v] = o.current ? im.visco[v].Ycur.data() : im.visco[v].Yprev.data();
            if (!o.lastCoefficients) viscoelastic::stepCoefficients(*im.visco[v].prony, o.elapsed, im.dt, A[v], B[v]);
        }
    }
    void setUp(KernelIO& io) const {
        for (size_t v = 0; v < 2; ++v) {
            io.Yhist[v] = Y[v];
            io.A[v] = A[v].empty() ? nullptr : A[v].data();
            io.B[v] = B[v].empty() ? nullptr : B[v].data();
        }
    }
};

} // namespace

long TLEDForceField::forceNodes(const core::BaseMechanicalState& state, const Positions& f) const {
    if (f.size() < m_impl->nodeCount)
        elements::runtimeError(*this, "its elements use " + std::to_string(m_impl->nodeCount) + " nodes but the force array has " +
                                          std::to_string(f.size()));
    return static_cast<long>(std::min(f.size(), state.size()));
}

void TLEDForceField::beginForces(core::BaseMechanicalState& state, double t) {
    Impl& im = *m_impl;
    if (state.size() < im.nodeCount)
        elements::runtimeError(*this, "its elements use " + std::to_string(im.nodeCount) + " nodes but the state '" +
                                          state.name() + "' has " + std::to_string(state.size()));
    // viscous history: a new time advances it, over the time elapsed since the last evaluation (the
    // last evaluation becomes the previous step; viscoelastic/HistoryClock.h)
    if (!im.visco.empty()) {
        if (!(im.dt > 0)) elements::runtimeError(*this, "viscoelastic stresses need a time step (dtChanged was not called)");
        if (im.clock.beginEvaluation(t, im.dt))
            for (auto& vs : im.visco) std::swap(vs.Yprev, vs.Ycur);
        for (auto& vs : im.visco) viscoelastic::stepCoefficients(*vs.prony, im.clock.elapsed(), im.dt, vs.A, vs.B);
    }
    im.u.resize(4 * im.nodeCount);
    im.evalState = &state;
}

long TLEDForceField::prepareNodes() const { return static_cast<long>(m_impl->nodeCount); }

void TLEDForceField::prepareRange(long lo, long hi) {
    displacementRange(*m_impl, *m_impl->evalState, m_impl->u.data(), lo, hi);
}

bool TLEDForceField::rerunnableBlocks() const { return m_impl->visco.empty(); }

void TLEDForceField::runForceBlock(long bi, int thread) {
    Impl& im = *m_impl;
    KernelIO io;
    const size_t b = static_cast<size_t>(bi);
    // the forces into the thread's own rows, the buffer written only by the run that claims the
    // block (a block taken over runs twice: core/StepTeam.h); the viscous states are written in
    // place (Ynew), so viscous blocks are not rerunnable
    if (im.compact) {
        double* u = im.scratch.positions(thread);
        im.rows.loadRows(b, im.u.data(), u);  // the block's rows of u
        io.u = u;
    } else {
        io.u = im.u.data();
        io.bufLo = im.buffers.lo(b);
    }
    io.buf = im.scratch.forces(thread, im.compact ? im.rows.rowCount(b) : im.buffers.rowCount(b));
    for (size_t v = 0; v < im.visco.size(); ++v) {
        io.Yhist[v] = im.visco[v].Yprev.data();
        io.Ynew[v] = im.visco[v].Ycur.data();
    }
    io.streamY = im.streamStates;
    runBlock(im, im.blocks[b], io);
    if (io.streamY) simd::streamFence();
    if (!core::claimTask()) return;  // another run of the block came first
    if (im.compact) im.rows.commit(b, io.buf);
    else im.buffers.commit(b, io.buf);
}

void TLEDForceField::sumForceRange(double* f, long lo, long hi) {
    // per node, in block order (bitwise the same for any thread count); the range layout clears its
    // buffers here, the compact one when a block loads its rows
    if (m_impl->compact) m_impl->rows.sumRange(f, lo, hi);
    else m_impl->buffers.sumRange(f, lo, hi);
}

bool TLEDForceField::worstElement(const core::BaseMechanicalState& state, core::ElementReport& out) const {
    return elements::worstElement(m_tets, m_hexes, state.x0(), state.x(), out);
}

void TLEDForceField::saveState(core::StateWriter& out) const {
    const Impl& im = *m_impl;
    if (im.visco.empty()) return;
    out.put("series", long(im.visco.size()));
    for (const ViscoSet& vs : im.visco) {
        out.put("Yprev", vs.Yprev.data(), vs.Yprev.size());
        out.put("Ycur", vs.Ycur.data(), vs.Ycur.size());
    }
    im.clock.save(out);
}

void TLEDForceField::restoreState(core::StateReader& in) {
    Impl& im = *m_impl;
    if (im.visco.empty()) return;
    const long n = in.getLong("series");
    if (n != long(im.visco.size()))
        in.fail("[" + path() + "] the checkpoint has " + std::to_string(n) + " Prony series, this force field " +
                std::to_string(im.visco.size()));
    for (ViscoSet& vs : im.visco) {
        in.getInto("Yprev", vs.Yprev.data(), vs.Yprev.size());
        in.getInto("Ycur", vs.Ycur.data(), vs.Ycur.size());
    }
    im.clock.restore(in);
}

void TLEDForceField::adoptHistory(const std::vector<double>& Yt, const std::vector<double>& Yh, const viscoelastic::HistoryClock& clock) {
    Impl& im = *m_impl;
    size_t terms = 0;
    for (const ViscoSet& vs : im.visco) terms += static_cast<size_t>(vs.terms);
    if (Yt.size() != 6 * terms * im.tet.size() || Yh.size() != 6 * terms * im.hex.size())
        elements::runtimeError(*this, "a step backend handed back " + std::to_string(Yt.size() + Yh.size()) + " Prony states for its " +
                                          std::to_string(terms) + " terms and " + std::to_string(im.tet.size() + im.hex.size()) + " elements");
    size_t k0 = 0;  // the first term of the series among all
    for (ViscoSet& vs : im.visco) {
        const size_t nt = static_cast<size_t>(vs.terms);
        for (const Block& b : im.blocks) {
            const bool tets = b.kind == 0;
            const std::vector<int>& orig = tets ? im.tet.orig : im.hex.orig;
            const std::vector<double>& Y = tets ? Yt : Yh;
            const size_t n = tets ? im.tet.size() : im.hex.size();
            for (size_t i = b.begin; i < b.end; ++i) {
                // (the batch slot of internal element i: TLEDKernel.h; term t, component c at ((m terms + t) 6 + c) kBatch + lane)
                const size_t m = b.batchBase + (i - b.begin) / kBatch, lane = (i - b.begin) % kBatch, e = static_cast<size_t>(orig[i]);
                for (size_t t = 0; t < nt; ++t)
                    for (size_t c = 0; c < 6; ++c) vs.Ycur[((m * nt + t) * 6 + c) * kBatch + lane] = Y[(6 * (k0 + t) + c) * n + e];
            }
        }
        vs.Yprev = vs.Ycur;
        k0 += nt;
    }
    im.clock = clock;
}

size_t TLEDForceField::bufferRows() const { return m_impl->compact ? m_impl->rows.rows() : m_impl->buffers.rows(); }
bool TLEDForceField::compactBuffers() const { return m_impl->compact; }
bool TLEDForceField::usesFastPath() const {
    for (const auto& g : m_impl->groups)
        if (!g.law) return false;
    return true;
}

double TLEDForceField::potentialEnergy(const core::BaseMechanicalState& state) const {
    const Impl& im = *m_impl;
    if (state.size() < im.nodeCount) return std::numeric_limits<double>::quiet_NaN();
    std::vector<double> e(im.blocks.size(), 0.0);
    runBlocksOn(im, im.blocks, state, [&](KernelIO& io, size_t bi) {
        io.energy = &e[bi];
        // the energy is the elastic one (the kernel skips the viscous stresses without forces or
        // stress output); the committed history, should it read one
        for (size_t v = 0; v < im.visco.size(); ++v) io.Yhist[v] = im.visco[v].Yprev.data();
    });
    double sum = 0;
    for (double v : e) sum += v;
    return sum;
}

void TLEDForceField::stresses(const core::BaseMechanicalState& state, double t, std::vector<double>& S) const {
    const Impl& im = *m_impl;
    S.assign(6 * elementCount(), 0.0);
    if (state.size() < im.nodeCount) return;
    const OutputHistory h(im, t);
    runBlocksOn(im, im.blocks, state, [&](KernelIO& io, size_t) {
        io.S = S.data();
        h.setUp(io);
    });
}

void TLEDForceField::cellData(const core::BaseMechanicalState& state, std::vector<core::CellField>& out) const {
    const Impl& im = *m_impl;
    const size_t n = elementCount();
    if (state.size() < im.nodeCount) return;
    // the stress of the state at the scene's time (the one an observer writes)
    const OutputHistory h(im, node() ? node()->context().time : 0.0);
    std::vector<double> S(6 * n, 0.0), F(9 * n, 0.0);
    runBlocksOn(im, im.blocks, state, [&](KernelIO& io, size_t) {
        io.S = S.data();
        io.F = F.data();
        h.setUp(io);
    });
    core::CellField fS{"S", 6, "Pa", S};
    core::CellField fSig{"cauchyStress", 6, "Pa", std::vector<double>(6 * n)};
    core::CellField fVM{"vonMises", 1, "Pa", std::vector<double>(n)};
    core::CellField fJ{"J", 1, "", std::vector<double>(n)};
    for (size_t e = 0; e < n; ++e) {
        const double* Fe = &F[9 * e];
        const double* Se = &S[6 * e];
        const elements::Mat33<double> Fm{Fe[0], Fe[1], Fe[2], Fe[3], Fe[4], Fe[5], Fe[6], Fe[7], Fe[8]};
        const double J = elements::det(Fm);
        const elements::Sym33<double> sig = elements::cauchyStress(Fm, {Se[0], Se[1], Se[2], Se[3], Se[4], Se[5]}, J);
        double* o = &fSig.values[6 * e];
        o[0] = sig.xx; o[1] = sig.yy; o[2] = sig.zz; o[3] = sig.xy; o[4] = sig.yz; o[5] = sig.xz;
        fVM.values[e] = elements::vonMises(sig);
        fJ.values[e] = J;
    }
    out.push_back(std::move(fS));
    out.push_back(std::move(fSig));
    out.push_back(std::move(fVM));
    out.push_back(std::move(fJ));
}

double TLEDForceField::restVolume(size_t e) const {
    const Impl& im = *m_impl;
    if (e < im.nTetCells) {
        for (size_t i = 0; i < im.tet.size(); ++i)
            if (static_cast<size_t>(im.tet.orig[i]) == e) return im.tet.vol[i];
    } else {
        for (size_t i = 0; i < im.hex.size(); ++i)
            if (static_cast<size_t>(im.hex.orig[i]) == e - im.nTetCells) return im.hex.vol[i];
    }
    return 0;
}

double TLEDForceField::elementTimeStep(size_t e, double rho) const {
    const Impl& im = *m_impl;
    for (const Block& b : im.blocks) {
        const auto& grp = im.groups[static_cast<size_t>(b.group)];
        for (size_t i = b.begin; i < b.end; ++i) {
            const size_t cell = b.kind == 0 ? static_cast<size_t>(im.tet.orig[i]) : im.nTetCells + static_cast<size_t>(im.hex.orig[i]);
            if (cell == e) return (b.kind == 0 ? im.tet.length[i] : im.hex.length[i]) / grp.material->waveSpeed(rho);
        }
    }
    return std::numeric_limits<double>::infinity();
}

double TLEDForceField::stableTimeStep(const core::BaseMechanicalState&) const {
    const Impl& im = *m_impl;
    const core::BaseMass* mass = node() ? node()->findInContext<core::BaseMass>() : nullptr;
    if (!mass) return std::numeric_limits<double>::infinity();
    // the density, else the total mass over the mesh volume (the element layer's one rule)
    double volume = 0;
    for (double v : im.tet.vol) volume += v;
    for (double v : im.hex.vol) volume += v;
    const double rho = elements::densityFor(*mass, volume);
    // TLED section 7: dt_cr = min_e L_e / c_e, over the elements in internal order
    std::vector<std::pair<double, const BaseMaterial*>> cells;
    for (const Block& b : im.blocks)
        for (size_t i = b.begin; i < b.end; ++i)
            cells.emplace_back(b.kind == 0 ? im.tet.length[i] : im.hex.length[i], im.groups[static_cast<size_t>(b.group)].material);
    return elements::stableTimeStep(
        cells.size(), [&](size_t e) { return cells[e].first; }, [&](size_t e) { return cells[e].second; }, rho);
}

} // namespace fascia::tled
