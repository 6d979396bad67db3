#include "DynamicRelaxation.h"
#include "Integrator.h"
#include "fascia/base/Error.h"
#include "fascia/base/Format.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace fascia::mechanics {

using core::formatNumber;

namespace {

double norm(const Positions& p) {
    double s = 0;
    for (const Vec3& v : p) s += v.squaredNorm();
    return std::sqrt(s);
}

/// Increments kept for the rate estimate (rho over the last kWindow iterations).
constexpr int kWindow = 20;

/// The report's residual: rn over the load norm (0 without a load), and that norm.
void setResidual(LoadStepReport& rep, double rn, double load) {
    rep.residual = load > 0 ? rn / load : 0.0;
    rep.load = load;
}

/// The report's rate rho (the geometric mean of the last kWindow ratios of the increments) and
/// estimated displacement error rho / (1 - rho) ||du|| / ||u|| (0 once ||du|| is at duFloor).
void estimateError(const std::vector<double>& incr, double duFloor, double u2, LoadStepReport& rep) {
    const size_t m = incr.size();
    const size_t w = std::min<size_t>(m - 1, kWindow);
    double rho = 1.0;
    if (w > 0 && incr[m - 1 - w] > 0) rho = std::pow(incr[m - 1] / incr[m - 1 - w], 1.0 / double(w));
    const double err = incr.back() <= duFloor ? 0.0 : rho < 1 ? rho / (1 - rho) * incr.back() : INFINITY;
    rep.rate = rho;
    rep.displacementError = u2 > 0 ? err / std::sqrt(u2) : err == 0 ? 0.0 : INFINITY;
}

} // namespace

long DynamicRelaxation::totalIterations() const {
    long n = 0;
    for (auto& r : m_reports) n += r.iterations;
    return n;
}

DynamicRelaxation::StateData& DynamicRelaxation::setUp(core::MechanicalGroup& g) {
    StateData& d = m_data[g.state];
    const size_t n = g.state->size();
    if (d.shape.size() == n) return d;
    // the fictitious mass takes the shape of the scene's mass (a volume-lumped mass), not its values
    double sum = 0;
    size_t massive = 0;
    for (size_t i = 0; i < n; ++i)
        if (i < g.mass.size() && g.mass[i] > 0) sum += g.mass[i], ++massive;
    d.shape.assign(n, 0.0);
    for (size_t i = 0; i < n; ++i)
        if (i < g.mass.size() && g.mass[i] > 0) d.shape[i] = g.mass[i] * double(massive) / sum;
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const Vec3& p : g.state->x0()) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    d.diag = n ? (hi - lo).norm() : 0.0;
    if (!(d.diag > 0)) d.diag = 1.0;
    d.lambdaShape = 0;
    return d;
}

void DynamicRelaxation::freeComponents(core::MechanicalGroup& g, StateData& d) const {
    // the constraints zero the force components they hold: project a vector of ones (a constraint
    // that lists no nodes, a contact whose nodes change with the state, holds no component for good)
    Positions& f = g.state->f();
    const size_t n = f.size();
    std::fill(f.begin(), f.end(), Vec3::Ones());
    for (auto* c : g.constraints)
        if (!c->constrainedNodes().empty()) c->projectForces(*g.state);
    d.free.assign(3 * n, 0.0);
    for (size_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k) d.free[3 * i + k] = (f[i][k] != 0.0 && d.shape[i] > 0) ? 1.0 : 0.0;
}

double DynamicRelaxation::residual(core::MechanicalGroup& g, const StateData& d, Positions& r) const {
    const Positions& f = g.state->f();
    r.resize(f.size());
    double s = 0;
    for (size_t i = 0; i < f.size(); ++i)
        for (int k = 0; k < 3; ++k) {
            r[i][k] = d.free[3 * i + k] * f[i][k];
            s += r[i][k] * r[i][k];
        }
    return std::sqrt(s);
}

double DynamicRelaxation::loadNorm(core::MechanicalGroup& g, StateData& d, double t) const {
    // external: body and external forces, and the force fields that are not element force fields
    // (ConstantForce, SurfacePressure ...), over every node; then the reactions of the constraints
    core::BaseMechanicalState& s = *g.state;
    const size_t n = s.size();
    d.scratch.assign(n, Vec3::Zero());
    const bool haveExt = s.externalForce().size() == n;
    const Vec3 gravity = (g.gravityCurve ? g.gravityCurve->value(t) : 1.0) * g.gravity;
    for (size_t i = 0; i < n; ++i) {
        if (haveExt) d.scratch[i] += s.externalForce()[i];
        if (i < g.mass.size()) d.scratch[i] += g.mass[i] * gravity;
    }
    for (auto* ff : g.forceFields)
        if (ff->elementCount() == 0) ff->addForce(s, d.scratch, t);
    return norm(d.scratch);
}

void DynamicRelaxation::scaleMass(StateData& d) const {
    // M = shape * lambda * safety / 4: the largest eigenvalue of M^-1 K becomes 4 / safety, below
    // central difference's limit 4 / h^2 for h = 1
    const size_t n = d.shape.size();
    d.invMass.assign(3 * n, 0.0);
    for (size_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k)
            if (d.free[3 * i + k] > 0) d.invMass[3 * i + k] = 4.0 / (d.shape[i] * d.lambdaShape * d.safety);
}

void DynamicRelaxation::estimateStiffness(core::MechanicalGroup& g, StateData& d, double t) {
    core::BaseMechanicalState& s = *g.state;
    Positions& x = s.x();
    const size_t n = x.size();
    d.start = x;
    g.computeForces(t);
    Positions f0 = s.f(), v(n, Vec3::Zero());
    // a fixed pseudo-random start (the same every run), on the free components
    unsigned long h = 12345;
    for (size_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k) {
            h = h * 6364136223846793005UL + 1442695040888963407UL;
            v[i][k] = d.free[3 * i + k] * (double((h >> 33) % 2001) / 1000.0 - 1.0);
        }
    const double eps = 1e-7 * d.diag;
    double lambda = 0;
    for (int it = 0; it < kPowerIterations; ++it) {
        double vmax = 0;
        for (auto& c : v) vmax = std::max(vmax, c.cwiseAbs().maxCoeff());
        if (!(vmax > 0)) break;
        for (size_t i = 0; i < n; ++i) x[i] = d.start[i] + (eps / vmax) * v[i];
        g.computeForces(t);
        double vkv = 0, den = 0;
        for (size_t i = 0; i < n; ++i) {
            const Vec3 vi = v[i] / vmax;
            Vec3 kv = (f0[i] - s.f()[i]) / eps;  // K v
            for (int k = 0; k < 3; ++k) kv[k] *= d.free[3 * i + k];
            vkv += vi.dot(kv);
            den += d.shape[i] * vi.squaredNorm();
            v[i] = d.shape[i] > 0 ? Vec3(kv / d.shape[i]) : Vec3::Zero();
        }
        if (den > 0) lambda = vkv / den;
    }
    x = d.start;
    if (!(lambda > 0) || !std::isfinite(lambda))
        core::throwSimulationError("[" + path() + "] step " + std::to_string(g.stepIndex) + ": the state '" +
                                   s.name() + "' shows no stiffness (estimated largest eigenvalue " + formatNumber(lambda, 3) +
                                   "): a static solution needs an elastic force field that holds every free node");
    d.lambdaShape = lambda;
    scaleMass(d);
}

void DynamicRelaxation::step(core::MechanicalGroup& g, double t, double dt) {
    const double T = t + dt;  // the load step's loads are those at the end of the step
    StateData& d = setUp(g);
    g.projectState(T);
    freeComponents(g, d);
    if (d.lambdaShape > 0)
        scaleMass(d);  // the free set may have changed
    else
        estimateStiffness(g, d, T);
    LoadStepReport rep = relax(g, d, T);
    rep.state = g.state->path();
    rep.loadStep = g.stepIndex;
    rep.time = T;
    // a static solution: at rest (prescribed nodes get their prescribed velocities)
    std::fill(g.state->v().begin(), g.state->v().end(), Vec3::Zero());
    g.projectState(T);
    if (m_printSteps.get())
        std::printf("DynamicRelaxation '%s': load step %ld (t = %.6g s): %ld iterations, residual %.3g, rate %.4g%s\n",
                    name().c_str(), rep.loadStep, rep.time, rep.iterations, rep.residual, rep.rate,
                    rep.converged ? "" : ", not converged");
    if (!rep.converged)
        warn("load step " + std::to_string(rep.loadStep) + " (t = " + formatNumber(T, 3) + " s) did not converge in " +
             std::to_string(rep.iterations) + " iterations: residual " + formatNumber(rep.residual, 3) + " (tolerance " +
             formatNumber(m_tolerance.get(), 3) + "), rate " + formatNumber(rep.rate, 3) + ", estimated displacement error " +
             formatNumber(rep.displacementError, 3) + " (tolerance " + formatNumber(m_displacementTolerance.get(), 3) +
             "); raise maxIterations, or check that the constraints hold the body (a free body has no static solution)");
    m_reports.push_back(rep);
}

DynamicRelaxation::Criteria DynamicRelaxation::criteria(const StateData& d) const {
    Criteria cr;
    cr.tol = m_tolerance.get();
    cr.dtol = m_displacementTolerance.get();
    // a residual at round-off: the force that a displacement of 1e-15 of the body's size (some 5
    // rounding errors of the positions) gives in the stiffest mode; below it nothing can improve
    double shapeNorm = 0;
    for (double m : d.shape) shapeNorm += m * m;
    cr.floor = 1e-15 * d.lambdaShape * d.diag * std::sqrt(shapeNorm);
    // increments at the rounding of the positions (1e-15 of the body's size per component): the
    // iteration cannot resolve the solution more finely, and the rate it shows is noise
    double freeCount = 0;
    for (double f : d.free) freeCount += f;
    cr.duFloor = 1e-15 * d.diag * std::sqrt(freeCount);
    return cr;
}

void DynamicRelaxation::updatePositions(StateData& d, Positions& x, double c) {
    const double alpha = 2.0 / (2.0 + c), beta = (2.0 - c) / (2.0 + c);
    for (size_t i = 0; i < x.size(); ++i)
        for (int k = 0; k < 3; ++k) {
            const double xi = x[i][k];
            x[i][k] = xi + beta * (xi - d.prev[i][k]) + alpha * d.invMass[3 * i + k] * d.r[i][k];
            d.prev[i][k] = xi;
        }
}

DynamicRelaxation::Increment DynamicRelaxation::increment(const core::BaseMechanicalState& s, const StateData& d,
                                                          const Positions& rNew) {
    // Rayleigh quotient of the increment: du . K du / du . M du, K du ~ -(r(n+1) - r(n))
    Increment in;
    const Positions& x = s.x();
    for (size_t i = 0; i < x.size(); ++i) {
        const Vec3 du = x[i] - d.prev[i];
        in.kq -= du.dot(rNew[i] - d.r[i]);
        in.du2 += du.squaredNorm();
        for (int k = 0; k < 3; ++k)
            if (d.invMass[3 * i + k] > 0) in.mq += du[k] * du[k] / d.invMass[3 * i + k];
        in.u2 += (x[i] - s.x0()[i]).squaredNorm();
    }
    return in;
}

bool DynamicRelaxation::adapt(StateData& d, const Increment& du, const Criteria& cr, double& c) const {
    const double q = du.mq > 0 ? du.kq / du.mq : 0.0;
    if (du.mq > 0 && std::isfinite(du.kq)) c = 2.0 * std::sqrt(std::clamp(q, 1e-16, 1.0));
    if (!(q > 4.0 / d.safety && std::isfinite(q) && du.du2 > 1e4 * cr.duFloor * cr.duFloor)) return false;
    // an increment stiffer than the largest eigenvalue estimated: the body stiffened as it
    // deformed (a Rayleigh quotient never exceeds the largest eigenvalue); make the mass heavier
    // so that this mode sits at the estimate again, with 20 % to spare
    d.lambdaShape *= 1.2 * q * d.safety / 4.0;
    scaleMass(d);
    return true;
}

void DynamicRelaxation::restart(core::MechanicalGroup& g, StateData& d, double t, int& restarts) {
    if (++restarts > 4 || !std::isfinite(d.lambdaShape))
        core::throwSimulationError("[" + path() + "] step " + std::to_string(g.stepIndex) +
                                   ": dynamic relaxation diverges even with a 16 times heavier fictitious mass");
    Positions& x = g.state->x();
    x = d.start;
    d.prev = x;
    d.safety *= 2.0;
    scaleMass(d);
    g.computeForces(t);
    residual(g, d, d.r);
}

bool DynamicRelaxation::converged(core::MechanicalGroup& g, StateData& d, double t, const Criteria& cr, double rn,
                                  double& ext, LoadStepReport& rep) const {
    setResidual(rep, rn, ext + norm(g.state->reaction()));
    if (!cr.forceMet(rn, rep.load)) return false;
    ext = loadNorm(g, d, t);  // the loads may follow the body (a pressure): measure them now
    setResidual(rep, rn, ext + norm(g.state->reaction()));
    return cr.forceMet(rn, rep.load) && rep.displacementError <= cr.dtol;
}

LoadStepReport DynamicRelaxation::relax(core::MechanicalGroup& g, StateData& d, double t) {
    core::BaseMechanicalState& s = *g.state;
    Positions& x = s.x();
    const Criteria cr = criteria(d);
    const long maxIt = m_maxIterations.get();
    LoadStepReport rep;
    d.start = x;
    d.prev = x;
    g.computeForces(t);
    double rn = residual(g, d, d.r);
    double ext = loadNorm(g, d, t);
    const double rn0 = rn;
    setResidual(rep, rn, ext + norm(s.reaction()));
    if (cr.forceMet(rn, rep.load)) {  // already in equilibrium (a load held)
        rep.converged = true;
        return rep;
    }
    bool unilateral = false;  // a constraint without a fixed node list (a contact) acts on the iterates
    for (auto* c : g.constraints) unilateral = unilateral || c->constrainedNodes().empty();
    std::vector<double> incr;  // ||du|| of the iterations
    Positions rNew(x.size());
    int restarts = 0;
    int stalled = 0;
    double c = d.c;
    for (long it = 1; it <= maxIt; ++it) {
        updatePositions(d, x, c);
        // the constraints' positions again: the held components are where they were, and a contact
        // (a tool) puts the nodes that moved into it back onto its surface
        if (unilateral) g.projectState(t);
        g.computeForces(t);
        rn = residual(g, d, rNew);
        const Increment du = increment(s, d, rNew);
        d.r.swap(rNew);
        if (adapt(d, du, cr, c)) incr.clear();
        if (!std::isfinite(rn) || rn > 1e8 * std::max({rn0, rep.load, cr.floor})) {
            // unstable: the stiffness grew beyond the estimate; start the step again with a heavier mass
            restart(g, d, t, restarts);
            incr.clear();
            c = 0;
            continue;
        }
        incr.push_back(std::sqrt(du.du2));
        // no component moved: the updates are below the rounding of the positions and nothing changes
        stalled = du.du2 == 0 ? stalled + 1 : 0;
        rep.iterations = it;
        estimateError(incr, cr.duFloor, du.u2, rep);
        if (converged(g, d, t, cr, rn, ext, rep)) {
            rep.converged = true;
            break;
        }
        if (stalled >= 3) break;  // reported as not converged, at the residual reached
    }
    d.c = c;
    return rep;
}

void DynamicRelaxation::saveState(core::StateWriter& out) const {
    out.put("states", long(m_data.size()));
    for (const auto& [state, d] : m_data) {
        out.put("state", state->path());
        out.put("shape", d.shape);
        out.put("lambdaShape", d.lambdaShape);
        out.put("safety", d.safety);
        out.put("c", d.c);
        out.put("diag", d.diag);
    }
    out.put("reports", long(m_reports.size()));
    for (const LoadStepReport& r : m_reports) {
        out.put("state", r.state);
        out.put("loadStep", r.loadStep);
        const double v[6] = {r.time, double(r.iterations), r.residual, r.load, r.rate, r.displacementError};
        out.put("values", v, 6);
        out.put("converged", r.converged);
    }
}

void DynamicRelaxation::restoreState(core::StateReader& in) {
    m_data.clear();
    const long n = in.getLong("states");
    for (long k = 0; k < n; ++k) {
        const auto& s = savedState(*this, in, in.getText("state"));
        StateData& d = m_data[&s];
        d.shape.resize(s.size());
        in.getInto("shape", d.shape.data(), d.shape.size());
        d.lambdaShape = in.getDouble("lambdaShape");
        d.safety = in.getDouble("safety");
        d.c = in.getDouble("c");
        d.diag = in.getDouble("diag");
    }
    m_reports.clear();
    const long reports = in.getLong("reports");
    for (long k = 0; k < reports; ++k) {
        LoadStepReport r;
        r.state = in.getText("state");
        r.loadStep = in.getLong("loadStep");
        double v[6];
        in.getInto("values", v, 6);
        r.time = v[0], r.iterations = long(v[1]), r.residual = v[2], r.load = v[3], r.rate = v[4], r.displacementError = v[5];
        r.converged = in.getBool("converged");
        m_reports.push_back(r);
    }
}

std::string DynamicRelaxation::runSummary() const {
    if (m_reports.empty()) return {};
    long failed = 0, most = 0, mostStep = 0;
    double worst = 0;
    for (auto& r : m_reports) {
        failed += r.converged ? 0 : 1;
        if (r.iterations > most) most = r.iterations, mostStep = r.loadStep;
        worst = std::max(worst, r.residual);
    }
    std::ostringstream os;
    os << "DynamicRelaxation '" << name() << "': " << m_reports.size() << " load steps, " << totalIterations()
       << " iterations (most: " << most << " at step " << mostStep << "), largest residual " << formatNumber(worst, 3) << ", ";
    if (failed)
        os << failed << " load step(s) did not converge";
    else
        os << "all converged";
    return os.str();
}

double DynamicRelaxation::stableTimeStep(double, std::string&) const { return std::numeric_limits<double>::infinity(); }

bool DynamicRelaxation::runFailed() const {
    for (auto& r : m_reports)
        if (!r.converged) return true;
    return false;
}

} // namespace fascia::mechanics
