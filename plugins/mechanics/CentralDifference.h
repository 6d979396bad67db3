#pragma once
#include "Integrator.h"

#include <map>

namespace fascia::mechanics {

/// Central difference (TLED section 2, step 3 of its algorithm; the standard damped form), with
/// mass-proportional damping:
/// x(n+1) = [2 x(n) - (1 - alpha dt/2) x(n-1) + dt^2 f(n)/m] / (1 + alpha dt/2).
/// Consistent start: x(-1) = x(0) - dt v(0) + dt^2/2 (f(0)/m - alpha v(0)), so that a constant
/// acceleration gives u = a t^2/2 exactly. Velocities are the second-order backward difference.
/// Stability: on an oscillator of frequency omega the characteristic polynomial
/// (1 + alpha dt/2) z^2 - (2 - omega^2 dt^2) z + (1 - alpha dt/2) has its roots inside the unit circle
/// iff omega dt < 2, with any damping alpha >= 0 (Jury conditions): the force fields' critical step is
/// its limit (the BaseIntegrator default of stableTimeStep).
class CentralDifference : public DampedIntegrator, public core::ExplicitScheme {
public:
    void step(core::MechanicalGroup& g, double t, double dt) override;
    /// Its update and damping, for a step backend (fascia/sim/StepTerms.h).
    Terms schemeTerms() const override { return {Update::CentralDifference, m_damping.get(), true}; }
    /// Per state: x(n-1), the dt it is for and the steps taken since the (re)start.
    void saveState(core::StateWriter& out) const override;
    void restoreState(core::StateReader& in) override;

private:
    struct History {
        Positions prev;  ///< x(n-1)
        double dt = 0;
        long steps = 0;
    };
    std::map<core::BaseMechanicalState*, History> m_history;
};

} // namespace fascia::mechanics
