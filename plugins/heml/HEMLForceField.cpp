// HEMLForceField: set-up (init), the staged forces, the viscous history's state IO, the energy, the
// stable time step and the cell data. The precomputation is in HEMLElements.cpp, the element loop
// in HEMLKernel.h (instantiated in HEMLKernelDouble.cpp, HEMLKernelFloat.cpp).
#include "fascia/heml/HEMLForceField.h"
#include "HEMLData.h"

#include "fascia/base/StateIO.h"
#include "fascia/elements/EdgeForm.h"
#include "fascia/elements/Errors.h"
#include "fascia/elements/FibreField.h"
#include "fascia/elements/Geometry.h"
#include "fascia/elements/Tensor3.h"
#include "fascia/materials/RelaxationSplit.h"
#include "fascia/scene/Node.h"
#include "fascia/viscoelastic/ViscoelasticProny.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace fascia::heml {

using materials::BaseMaterial;
using elements::edgeA;
using elements::edgeB;
using elements::traceDk;

namespace {

// one block with the loop of its material (or the mass-spring loop)
template <bool Forces, bool Visco>
double runOne(Impl& d, size_t b, const BlockRun& x) {
    const Impl::Loops& f = d.loops[d.massSpring ? 0 : size_t(d.blocks[b].material)];
    return (Forces ? (Visco ? f.forcesVisco : f.forces) : f.energy)(d, b, x);
}

} // namespace

HEMLForceField::HEMLForceField() = default;
HEMLForceField::~HEMLForceField() { core::waitForLateTasks(); }  // (a block's late run may still read m_impl)

// ---------------------------------------------------------------------------------------------
// set-up

std::vector<core::Component*> HEMLForceField::dependencies() const {
    std::vector<core::Component*> deps;
    if (!node()) return deps;
    if (auto* s = node()->findInContext<core::BaseMechanicalState>()) deps.push_back(s);
    elements::addTetMeshDependencies(*this, m_mesh, m_tetrahedra, deps);
    if (!m_stiffness.isSet()) {
        if (auto* m = elements::defaultMaterial(*this, m_material, m_groupMaterials)) deps.push_back(m);
        for (auto* m : elements::listedMaterials(*this, m_groupMaterials)) deps.push_back(m);
    }
    if (auto* v = node()->findLocal<viscoelastic::ViscoelasticProny>()) deps.push_back(v);
    return deps;
}

void HEMLForceField::init() {
    core::waitForLateTasks();
    m_impl = std::make_unique<Impl>();
    Impl& d = *m_impl;
    d.J0 = m_J0.get();
    d.mixed = m_precision.get() == "mixed";

    // topology and rest positions (the element layer's one rule)
    elements::TetMesh tm = elements::resolveTetMesh(*this, m_mesh, m_tetrahedra);
    m_tets = std::move(tm.tets);
    const MeshData* mesh = tm.mesh;
    const Positions& rest = tm.rest;

    // materials
    d.massSpring = m_stiffness.isSet();
    // (the materials per element are kept only until the blocks hold them: 8 bytes an element at the
    // peak: docs/performance.md, "Peak memory, HEML")
    std::vector<BaseMaterial*> elementMaterial(m_tets.size(), nullptr);
    if (d.massSpring) {
        if (m_material.get() || m_groupMaterials.isSet())
            fail(m_stiffness, "'stiffness' selects the mass-spring mode, which uses no material: remove 'material'/'groupMaterials' or 'stiffness'");
    } else {
        // per mesh group, else the default material (the element layer's one rule)
        elementMaterial = elements::assignMaterials(*this, m_groupMaterials,
                                                      elements::defaultMaterial(*this, m_material, m_groupMaterials), mesh,
                                                      m_tets.size(), 0)
                                .tetrahedra;
    }

    // fibre directions per element (input order; empty when no material reads them)
    m_dirA.clear();
    m_dirB.clear();
    if (!d.massSpring) {
        const std::vector<const BaseMaterial*> cells(elementMaterial.begin(), elementMaterial.end());
        elements::FibreField a = elements::resolveFibres(*this, 0, m_fibreArray, mesh, cells, m_tets.size());
        elements::FibreField b = elements::resolveFibres(*this, 1, m_fibreArray2, mesh, cells, m_tets.size());
        if (a.used) m_dirA = std::move(a.dir);
        if (b.used) m_dirB = std::move(b.dir);
    }

    // viscoelasticity
    m_visco = node() ? node()->findLocal<viscoelastic::ViscoelasticProny>() : nullptr;
    if (node())
        if (const auto all = node()->findAllLocal<viscoelastic::ViscoelasticProny>(); all.size() > 1)
            all[1]->fail("a second ViscoelasticProny beside HEMLForceField '" + name() + "': HEML relaxes one series (its terms on the part `apply` names)",
                         {"put all the terms in one ViscoelasticProny (TLEDForceField takes one series per part)"});
    if (m_visco && d.massSpring) fail(m_stiffness, "ViscoelasticProny is not supported in mass-spring mode");
    // each part that relaxes must be stress-free at rest, or a body at rest creeps (RelaxationSplit.h)
    if (m_visco && !d.massSpring) {
        std::vector<const BaseMaterial*> seen;
        for (const BaseMaterial* m : elementMaterial) {
            if (std::find(seen.begin(), seen.end(), m) != seen.end()) continue;
            seen.push_back(m);
            const std::string err = materials::relaxationRestError(materials::relaxationSplit(*m, d.J0),
                                                                   m_visco->relaxesIsochoric(), m_visco->relaxesVolumetric(),
                                                                   m->className() + " '" + m->name() + "'");
            if (!err.empty()) m_visco->failApply(err);
        }
    }

    m_rest = rest;
    precompute(rest, elementMaterial);
}

void HEMLForceField::checkState(const core::BaseMechanicalState& state) const {
    if (!m_impl) fail("used before init()");
    if (state.size() != m_impl->nNodes)
        elements::runtimeError(*this, "the state '" + state.name() + "' has " + std::to_string(state.size()) +
                                          " nodes but the force field was set up for " + std::to_string(m_impl->nNodes));
}

// ---------------------------------------------------------------------------------------------
// forces

bool HEMLForceField::worstElement(const core::BaseMechanicalState& state, core::ElementReport& out) const {
    return elements::worstElement(m_tets, {}, m_rest, state.x(), out);
}

void HEMLForceField::saveState(core::StateWriter& out) const {
    if (!m_impl || m_impl->nTerms == 0) return;
    const Impl& d = *m_impl;
    out.put("arrays", long(d.Yprev.size()));
    for (size_t k = 0; k < d.Yprev.size(); ++k) {
        out.put("Yprev", d.Yprev[k].data(), d.Yprev[k].size());
        out.put("Ycur", d.Ycur[k].data(), d.Ycur[k].size());
    }
    d.clock.save(out);
}

void HEMLForceField::restoreState(core::StateReader& in) {
    if (!m_impl || m_impl->nTerms == 0) return;
    Impl& d = *m_impl;
    const long n = in.getLong("arrays");
    if (n != long(d.Yprev.size()))
        in.fail("[" + path() + "] the checkpoint has " + std::to_string(n) + " viscous state arrays, this force field " +
                std::to_string(d.Yprev.size()));
    for (size_t k = 0; k < d.Yprev.size(); ++k) {
        in.getInto("Yprev", d.Yprev[k].data(), d.Yprev[k].size());
        in.getInto("Ycur", d.Ycur[k].data(), d.Ycur[k].size());
    }
    d.clock.restore(in);
}

void HEMLForceField::adoptHistory(const std::vector<double>& Yt, const std::vector<double>& Yh, const viscoelastic::HistoryClock& clock) {
    Impl& d = *m_impl;
    const size_t n = d.nElements, terms = static_cast<size_t>(d.nTerms);
    if (Yt.size() != 6 * terms * n || !Yh.empty())
        elements::runtimeError(*this, "a step backend handed back " + std::to_string(Yt.size() + Yh.size()) + " Prony states for its " +
                                          std::to_string(terms) + " terms and " + std::to_string(n) + " tetrahedra");
    for (size_t t = 0; t < terms; ++t)
        for (size_t q = 0; q < 6; ++q)
            for (size_t e = 0; e < n; ++e) d.Ycur[t * 6 + q][static_cast<size_t>(d.slotOf[e])] = Yt[(6 * t + q) * n + e];
    d.Yprev = d.Ycur;
    d.clock = clock;
}

long HEMLForceField::forceNodes(const core::BaseMechanicalState& state, const Positions& f) const {
    checkState(state);
    if (f.size() != state.size()) elements::runtimeError(*this, "force array of the wrong size");
    return static_cast<long>(m_impl->nNodes);
}

void HEMLForceField::beginForces(core::BaseMechanicalState& state, double t) {
    checkState(state);
    Impl& d = *m_impl;
    if (d.nTerms > 0) {
        // a new time advances the history, over the time elapsed since the last evaluation
        // (viscoelastic/HistoryClock.h)
        if (!m_visco->hasCoefficients())
            elements::runtimeError(*this, "ViscoelasticProny '" + m_visco->name() + "' has no time step yet");
        if (d.clock.beginEvaluation(t, m_visco->dt())) std::swap(d.Yprev, d.Ycur);
        viscoelastic::stepCoefficients(*m_visco, d.clock.elapsed(), m_visco->dt(), d.A, d.B);
    }
    d.evalX = core::flat(state.x());
}

void HEMLForceField::addForceRaw(const double* x, double* fout) {
    Impl& d = *m_impl;
    if (d.nTerms > 0) {
        if (!m_visco->hasCoefficients())
            elements::runtimeError(*this, "ViscoelasticProny '" + m_visco->name() + "' has no time step yet");
        if (d.A.empty()) {
            d.A = m_visco->A();
            d.B = m_visco->B();
        }
    }
    // one job of the step team: positions in internal order, the element blocks (each into its own
    // node rows), then per node the sum of its rows in block order (deterministic for any thread count)
    d.evalX = x;
    core::runThreadedForces(*this, fout, static_cast<long>(d.nNodes));
}

long HEMLForceField::prepareNodes() const { return m_impl->rows.directGather() ? 0 : static_cast<long>(m_impl->nNodes); }

void HEMLForceField::prepareRange(long lo, long hi) { m_impl->rows.positionsRange(m_impl->evalX, lo, hi); }

// (not when the blocks read the state's positions in place, below about 21,800 nodes: a program may
// reassign the state's x between steps, and a late run would read the freed array)
bool HEMLForceField::rerunnableBlocks() const { return m_impl->nTerms == 0 && !m_impl->rows.directGather(); }

void HEMLForceField::runForceBlock(long bl, int thread) {
    // the forces into the thread's own rows, the buffer and the energy written only by the run that
    // claims the block (a block taken over runs twice: core/StepTeam.h); the viscous states are
    // written in place (Ycur), so viscous blocks are not rerunnable (nor those of small meshes:
    // rerunnableBlocks)
    Impl& d = *m_impl;
    const size_t b = static_cast<size_t>(bl);
    const BlockRun run{d.rows.positionsBase(d.evalX), d.scratch.positions(thread), d.scratch.forces(thread, d.rows.rowCount(b))};
    const double energy = d.nTerms > 0 ? runOne<true, true>(d, b, run) : runOne<true, false>(d, b, run);
    if (!core::claimTask()) return;  // another run of the block came first
    d.rows.commit(b, run.forces);
    d.blockEnergy[b] = energy;
}

void HEMLForceField::sumForceRange(double* f, long lo, long hi) { m_impl->rows.sumRange(f, lo, hi); }

double HEMLForceField::potentialEnergy(const core::BaseMechanicalState& state) const {
    checkState(state);
    Impl& d = *m_impl;
    const double* x = state.x().data()->data();
    const size_t nb = d.blocks.size();
#pragma omp parallel if (nb > 1)
    {
        // (the thread's own position rows: the step team's may still be in use by a late run)
        simd::DVec rows(4 * d.rows.maxRows());
        const BlockRun run{d.rows.positionsIn(x), rows.data(), nullptr};
#pragma omp for schedule(dynamic, 1)
        for (size_t b = 0; b < nb; ++b) d.blockEnergy[b] = runOne<false, false>(d, b, run);
    }
    double E = 0.0;
    for (double e : d.blockEnergy) E += e;
    return E;
}

// ---------------------------------------------------------------------------------------------
// time step, cell data, accessors

double HEMLForceField::stableTimeStep(const core::BaseMechanicalState& state) const {
    const double inf = std::numeric_limits<double>::infinity();
    if (!m_impl || !node()) return inf;
    const Impl& d = *m_impl;
    auto* mass = node()->findInContext<core::BaseMass>();
    if (!mass) return inf;
    if (d.massSpring) {
        const auto& m = mass->nodalMasses();
        if (m.size() != d.nNodes) return inf;
        // omega^2 <= max_i sum_j k_ij (1/m_i + 1/m_j) (Gershgorin on M^-1/2 K M^-1/2, unique edges)
        std::map<std::pair<int, int>, bool> edges;
        for (const auto& t : m_tets)
            for (int k = 0; k < 6; ++k) {
                const int a = t[edgeA(k)], b = t[edgeB(k)];
                edges[{std::min(a, b), std::max(a, b)}] = true;
            }
        std::vector<double> rate(d.nNodes, 0.0);
        const double k = m_stiffness.get();
        for (const auto& e : edges) {
            const int a = e.first.first, b = e.first.second;
            if (m[a] <= 0 || m[b] <= 0) continue;
            const double s = k * (1.0 / m[a] + 1.0 / m[b]);
            rate[a] += s;
            rate[b] += s;
        }
        const double w2 = *std::max_element(rate.begin(), rate.end());
        return w2 > 0 ? 2.0 / std::sqrt(w2) : inf;
    }
    // the density, else the total mass over the mesh volume (the element layer's one rule)
    const double V = d.totalVolume;
    // (the altitudes from the rest shape here, once: not kept per element, for the peak memory:
    // docs/performance.md, "Peak memory, HEML")
    const auto altitude = [&](size_t e) {
        const auto& t = m_tets[e];
        const Vec3 &p0 = m_rest[t[0]], &p1 = m_rest[t[1]], &p2 = m_rest[t[2]], &p3 = m_rest[t[3]];
        return elements::tetAltitude(p0, p1, p2, p3, std::abs(elements::edgeRest(p0, p1, p2, p3).det) / 6.0);  // (as precompute's volume)
    };
    return elements::stableTimeStep(m_tets.size(), altitude, [&](size_t e) { return materialOf(e); }, elements::densityFor(*mass, V));
}

namespace {

/// The viscous part of the second Piola-Kirchhoff stress of one element at deformation gradient F
/// (what the Prony histories subtract from the elastic S, for a stress output): the element loop's
/// relaxation (HEMLKernel.h, relax) written for one element with Eigen. R_k = Vol/2 tr(D_k V^-1 S_r V^-T),
/// S_r the relaxed part's S; gamma_i = A_i R + B_i Y_i (eq. (20)); back to a tensor by the inverse of
/// the map tr(D_k M) (HEMLKernel.h, traceDk) and S = V M V^T. (Out of line: inlined, it changes how
/// the compiler contracts cellData's own arithmetic into fused multiply-adds, and J and the von
/// Mises stress move in the last bit; tools/compare-builds.sh checks that they do not.)
[[gnu::noinline]] Mat3 viscousStress(const Impl& d, size_t slot, const Mat3& V, const Mat3& F, const materials::Invariants& in,
                   const materials::Response& r, double shift, const Vec3& a0, const Vec3& b0, const std::vector<DVec>& Y,
                   const double* A, const double* B) {
    const Mat3 I = Mat3::Identity(), C = F.transpose() * F, JCi = in.J * C.inverse();
    const double q = shift / std::max(d.J0, in.J);  // the rest split (materials/RelaxationSplit.h)
    Mat3 Sr = Mat3::Zero();
    if (d.relaxIso)
        Sr += 2.0 * (r.dI1 * I + r.dI2 * (in.I1 * I - C) + r.dI4 * a0 * a0.transpose() + r.dI6 * b0 * b0.transpose()) +
              (r.dJiso - q) * JCi;
    if (d.relaxVol) Sr += (r.dJvol + q) * JCi;
    const Mat3 Vi = V.inverse(), M = Vi * Sr * Vi.transpose();
    const double vol = d.volume(slot);
    double R[6];
    traceDk(M(0, 0), M(1, 1), M(2, 2), M(0, 1), M(1, 2), M(0, 2), R);
    double g[6] = {0, 0, 0, 0, 0, 0};
    for (int t = 0; t < d.nTerms; ++t)
        for (int k = 0; k < 6; ++k) g[k] += A[t] * 0.5 * vol * R[k] + B[t] * Y[size_t(t * 6 + k)][slot];
    // tr(D_k G) = g_k: G12 = -g_4 ..., G11 = g_1 - G12 - G13 ... (traceDk inverted), G = 2/Vol of it
    const double G12 = -g[3], G23 = -g[4], G13 = -g[5];
    Mat3 G;
    G << g[0] - G12 - G13, G12, G13, G12, g[1] - G12 - G23, G23, G13, G23, g[2] - G13 - G23;
    return V * (2.0 / vol * G) * V.transpose();
}

} // namespace

void HEMLForceField::cellData(const core::BaseMechanicalState& state, std::vector<core::CellField>& out) const {
    checkState(state);
    const Impl& d = *m_impl;
    const size_t ne = m_tets.size();
    // the viscous history of the state at the scene's time (viscoelastic/HistoryClock.h): its
    // coefficients, and each material's rest shift
    const std::vector<DVec>* Y = nullptr;
    std::vector<double> A, B;
    std::map<const BaseMaterial*, double> shift;
    if (d.nTerms > 0 && m_visco->hasCoefficients()) {
        const viscoelastic::HistoryClock::Output o = d.clock.outputAt(node() ? node()->context().time : 0.0, m_visco->dt());
        Y = o.current ? &d.Ycur : &d.Yprev;
        if (!o.lastCoefficients) viscoelastic::stepCoefficients(*m_visco, o.elapsed, m_visco->dt(), A, B);
        else if (!d.A.empty()) A = d.A, B = d.B;
        else A = m_visco->A(), B = m_visco->B();
        for (size_t m = 0; m < d.materials.size(); ++m) shift[d.materials[m]] = d.restShift[m];
    }
    core::CellField J{"J", 1, "", std::vector<double>(ne)};
    core::CellField vm{"vonMises", 1, "Pa", std::vector<double>(ne)};
    const auto& x = state.x();
    const double J0 = m_J0.get();
    for (size_t e = 0; e < ne; ++e) {
        const auto& t = m_tets[e];
        Mat3 V, v;
        for (int k = 0; k < 3; ++k) {
            V.col(k) = m_rest[t[k + 1]] - m_rest[t[0]];
            v.col(k) = x[t[k + 1]] - x[t[0]];
        }
        const Mat3 F = v * V.inverse();
        const double Je = F.determinant();
        J.values[e] = Je;
        const BaseMaterial* m = materialOf(e);
        if (!m) continue;  // mass-spring: no stress
        const Mat3 Bm = F * F.transpose();
        materials::Invariants in;
        in.I1 = Bm.trace();
        in.I2 = 0.5 * (in.I1 * in.I1 - (Bm * Bm).trace());
        in.J = Je;
        Vec3 fa = Vec3::Zero(), fb = Vec3::Zero();
        if (!m_dirA.empty()) {
            fa = F * m_dirA[e];
            in.I4 = fa.squaredNorm();
        }
        if (!m_dirB.empty()) {
            fb = F * m_dirB[e];
            in.I6 = fb.squaredNorm();
        }
        materials::Response r;
        m->evaluate(&in, &r, 1, J0);
        // Kirchhoff stress tau = F S F^T = 2 [dI1 B + dI2 (I1 B - B^2) + dI4 Fa Fa^T + dI6 Fb Fb^T] + J dW/dJ I
        Mat3 tau = 2.0 * (r.dI1 * Bm + r.dI2 * (in.I1 * Bm - Bm * Bm) + r.dI4 * fa * fa.transpose() +
                          r.dI6 * fb * fb.transpose()) +
                   Je * (r.dJiso + r.dJvol) * Mat3::Identity();
        if (Y) {
            const Vec3 a0 = m_dirA.empty() ? Vec3::Zero() : m_dirA[e], b0 = m_dirB.empty() ? Vec3::Zero() : m_dirB[e];
            tau -= F * viscousStress(d, size_t(d.slotOf[e]), V, F, in, r, shift[m], a0, b0, *Y, A.data(), B.data()) * F.transpose();
        }
        const Mat3 sig = tau / std::max(Je, J0);
        vm.values[e] = elements::vonMises(elements::Sym33<double>{sig(0, 0), sig(1, 1), sig(2, 2), sig(0, 1), sig(1, 2), sig(0, 2)});
    }
    out.push_back(std::move(J));
    if (!m_impl->massSpring) out.push_back(std::move(vm));
}

size_t HEMLForceField::elementCount() const { return m_tets.size(); }
size_t HEMLForceField::blockCount() const { return m_impl ? m_impl->blocks.size() : 0; }
const materials::BaseMaterial* HEMLForceField::materialOf(size_t e) const {
    if (!m_impl || e >= m_impl->slotOf.size() || m_impl->massSpring) return nullptr;
    // the block of the element's slot (blocks in slot order) holds its material
    const Impl& d = *m_impl;
    const size_t slot = size_t(d.slotOf[e]);
    const auto b = std::upper_bound(d.blocks.begin(), d.blocks.end(), slot, [](size_t s, const Block& blk) { return s < blk.begin; }) - 1;
    return b->material >= 0 ? d.materials[size_t(b->material)] : nullptr;
}
bool HEMLForceField::usesFastPath() const {
    if (!m_impl || m_impl->massSpring) return true;
    for (const auto& f : m_impl->loops)
        if (!f.inlined) return false;
    return true;
}

} // namespace fascia::heml
