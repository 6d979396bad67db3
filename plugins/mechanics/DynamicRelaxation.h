#pragma once
#include "fascia/sim/Mechanics.h"

#include <algorithm>
#include <map>
#include <string>
#include <vector>

namespace fascia::mechanics {

/// What one static load step of DynamicRelaxation did.
struct LoadStepReport {
    std::string state;              ///< path of the mechanical state
    long loadStep = 0;              ///< the simulation step (1-based)
    double time = 0;                ///< time the loads were evaluated at (s): the end of the step
    long iterations = 0;            ///< dynamic relaxation iterations (force evaluations after the first)
    double residual = 0;            ///< free-node force residual / (external + reaction force norm)
    double load = 0;                ///< that external + reaction force norm (N), at the last iteration
    double rate = 0;                ///< estimated convergence rate rho (ratio of successive increments)
    double displacementError = 0;   ///< rho / (1 - rho) ||du|| / ||u||: estimated distance to the solution
    bool converged = false;
};

/// Static solver: adaptive dynamic relaxation after Joldes, Wittek and Miller (2009), "Computation
/// of intra-operative brain shift using dynamic relaxation", Computer Methods in Applied Mechanics
/// and Engineering 198, 3313-3320. Chosen in the scene instead of an integrator; every simulation
/// step is one static load step, the loads being evaluated at the step's end time t + dt, from the
/// previous step's solution.
///
/// Each load step iterates explicit central differences on a fictitious mass M with a fixed
/// fictitious step h = 1 (the paper's eq. for the damped central-difference update):
///   u(n+1) = u(n) + beta (u(n) - u(n-1)) + alpha M^-1 r(n),
///   alpha = 2 h^2 / (2 + c h),  beta = (2 - c h) / (2 + c h),
/// r the free-node force residual (external + internal forces after the constraints).
/// - The fictitious mass is the shape of the scene's mass distribution (its values do not matter)
///   scaled so that h = 1 is stable: the largest eigenvalue of M^-1 K is estimated by a power
///   iteration on force differences, K v ~ (f(x) - f(x + eps v)) / eps, and M is chosen so that it
///   becomes 4 / kMassSafety (central difference is stable up to 4 / h^2).
/// - The damping is c = 2 omega_min, omega_min^2 the lowest eigenvalue of M^-1 K, estimated at every
///   iteration by the Rayleigh quotient of the increments, du . K du / du . M du with
///   K du ~ -(r(n+1) - r(n)) (the paper's estimate of the lowest mode, which dominates the late
///   iterations). No damping is given by the user.
/// - It stops when both hold: ||r|| <= tolerance (||external|| + ||reaction||) (or below the
///   round-off floor, the force a displacement of 1e-15 of the body's size gives), and the estimated
///   distance to the solution rho / (1 - rho) ||du|| <= displacementTolerance ||u||, rho the
///   convergence rate (the geometric mean of ||du(n)|| / ||du(n-1)|| over the last 20 iterations),
///   or ||du|| at the rounding of the positions (1e-15 of the body's size per component).
/// - The solution does not depend on the declared mass; gravity loads (m g) do.
/// - With a ViscoelasticProny the force fields advance their viscous history once per load step:
///   every iteration of a step evaluates forces at the same time t + dt, from the history committed
///   at the previous step (HEML and TLED recompute the new history from the committed one at each
///   evaluation of a step), and the last evaluation is at the converged solution.
/// - A constraint that lists no nodes (a rigid tool's contact, plugins/contact) is unilateral: it holds
///   no component for good, and with one in the group every iteration projects the constraints'
///   positions again (docs/design.md, section 4.5).
/// A load step that does not converge within maxIterations is a located warning naming the step,
/// the residual and the rate; the run goes on, and runFailed() makes fascia-run exit 3.
class DynamicRelaxation : public core::BaseIntegrator {
public:
    void step(core::MechanicalGroup& g, double t, double dt) override;
    std::string runSummary() const override;
    bool runFailed() const override;
    /// Infinity: dt is a load step, not an integration step (the iterations take their own fictitious
    /// masses and step, so any dt is stable), and the scene's dt is not warned as above the force
    /// fields' critical step.
    double stableTimeStep(double critical, std::string& why) const override;
    /// Per state what carries over between load steps (the fictitious mass shape and its scale, the
    /// safety factor, the damping of the last iteration), and the reports of the load steps so far.
    void saveState(core::StateWriter& out) const override;
    void restoreState(core::StateReader& in) override;

    /// One report per load step and state, in order.
    const std::vector<LoadStepReport>& reports() const { return m_reports; }
    /// Total iterations over every load step.
    long totalIterations() const;

    core::Param<double> m_tolerance{this, core::ParamSpec("tolerance").above(0).below(1).help("force criterion: free-node residual norm / (external + reaction force norm) below this"), 1e-6};
    core::Param<double> m_displacementTolerance{this, core::ParamSpec("displacementTolerance").above(0).below(1).help("displacement criterion: estimated distance to the solution, rho/(1 - rho) ||du||, / ||u|| below this"), 1e-6};
    core::Param<int> m_maxIterations{this, core::ParamSpec("maxIterations").min(1).help("iterations per load step before it is reported as not converged (a warning; fascia-run exits 3)"), 100000};
    core::Param<bool> m_printSteps{this, core::ParamSpec("printSteps").help("print one line per load step (iterations, residual, rate) on standard output"), false};

    /// Safety factor on the estimated largest eigenvalue of M^-1 K (the power iteration approaches it
    /// from below).
    static constexpr double kMassSafety = 1.25;
    /// Power iterations for that estimate.
    static constexpr int kPowerIterations = 40;

private:
    /// What a state keeps between load steps.
    struct StateData {
        std::vector<double> shape;   ///< fictitious mass shape per node (scene mass / its mean)
        std::vector<double> invMass; ///< 1 / fictitious mass per component, 0 where held or massless
        std::vector<double> free;    ///< 1 for a free component, 0 for a held one or a massless node
        double lambdaShape = 0;      ///< largest eigenvalue of diag(shape)^-1 K (power iteration)
        double safety = kMassSafety;
        double c = 0;                ///< damping of the last iteration (the next load step starts with it)
        double diag = 0;             ///< rest bounding-box diagonal (m)
        Positions start, prev, r, scratch;
    };
    StateData& setUp(core::MechanicalGroup& g);
    void freeComponents(core::MechanicalGroup& g, StateData& d) const;
    void estimateStiffness(core::MechanicalGroup& g, StateData& d, double t);
    void scaleMass(StateData& d) const;
    /// Masked copy of the state's forces into r; returns ||r||.
    double residual(core::MechanicalGroup& g, const StateData& d, Positions& r) const;
    /// ||external forces|| + ||reactions||: the norm the residual is measured against.
    double loadNorm(core::MechanicalGroup& g, StateData& d, double t) const;
    LoadStepReport relax(core::MechanicalGroup& g, StateData& d, double t);
    /// What relax measures its iterations against: the tolerances and the round-off floors.
    struct Criteria {
        double tol = 0, dtol = 0;
        double floor = 0;    ///< the residual at round-off (the force field's answer to a 1e-15 displacement)
        double duFloor = 0;  ///< the increment norm at the rounding of the positions
        bool forceMet(double r, double load) const { return r <= std::max(tol * load, floor); }
    };
    Criteria criteria(const StateData& d) const;
    /// One damped central-difference update of the positions (d.prev takes the old ones).
    static void updatePositions(StateData& d, Positions& x, double c);
    /// An iteration's increment du = x - d.prev: its Rayleigh quotient terms du . K du (K du from
    /// the residuals d.r, rNew) and du . M du, ||du||^2 and ||u||^2.
    struct Increment {
        double kq = 0, mq = 0, du2 = 0, u2 = 0;
    };
    static Increment increment(const core::BaseMechanicalState& s, const StateData& d, const Positions& rNew);
    /// The damping c = 2 omega_min from the increment's Rayleigh quotient q, and a heavier mass when q
    /// is above the largest eigenvalue estimated (the body stiffened); true then (the rate starts again).
    bool adapt(StateData& d, const Increment& du, const Criteria& cr, double& c) const;
    /// The load step again from its start with a heavier fictitious mass; fails after 4 restarts.
    void restart(core::MechanicalGroup& g, StateData& d, double t, int& restarts);
    /// The report's residual after an iteration (the loads measured again once the force criterion
    /// holds: they may follow the body); true when both criteria hold.
    bool converged(core::MechanicalGroup& g, StateData& d, double t, const Criteria& cr, double rn, double& ext,
                   LoadStepReport& rep) const;

    std::map<const core::BaseMechanicalState*, StateData> m_data;
    std::vector<LoadStepReport> m_reports;
};

} // namespace fascia::mechanics
