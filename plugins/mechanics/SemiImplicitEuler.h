#pragma once
#include "Integrator.h"

#include <utility>
#include <vector>

namespace fascia::mechanics {

/// Semi-implicit (symplectic) Euler, HEML eq. (32): v(t+dt) = v + dt (f/m - alpha v);
/// x(t+dt) = x + dt v(t+dt).
/// With halfStepStart (the default) the very first velocity update uses dt/2: the velocities are
/// then staggered by half a step and the scheme is the leapfrog (Stormer-Verlet) method, second
/// order in positions, so a constant acceleration gives u = a t^2/2 to round-off. Without it, the
/// paper's eq. (32) from rest, first order (u = a t (t + dt)/2 under constant acceleration).
/// Note that with halfStepStart the velocities the state holds (and exporters write) are the
/// leapfrog's mid-step velocities v(t - dt/2), as in every staggered scheme. After a change of dt the
/// first kick spans (dt_old + dt)/2, from v(t - dt_old/2) to v(t + dt/2).
///
/// Stability: on an oscillator of frequency omega with damping alpha one step has the characteristic
/// polynomial z^2 - (2 - alpha dt - omega^2 dt^2) z + (1 - alpha dt), stable (Jury conditions) iff
/// alpha dt < 2 and 4 - 2 alpha dt - omega^2 dt^2 > 0, i.e. dt < 4 / (alpha + sqrt(alpha^2 + 4 omega^2)):
/// 2 / omega without damping (central difference's limit), smaller with it.
class SemiImplicitEuler : public DampedIntegrator, public core::ExplicitScheme {
public:
    void step(core::MechanicalGroup& g, double t, double dt) override;
    /// Its update, damping and start, for a step backend (fascia/sim/StepTerms.h).
    Terms schemeTerms() const override { return {Update::SemiImplicitEuler, m_damping.get(), m_halfStepStart.get()}; }
    /// 4 / (alpha + sqrt(alpha^2 + 4 omega_max^2)) with omega_max = 2 / critical; critical itself
    /// without damping.
    double stableTimeStep(double critical, std::string& why) const override;
    /// The states stepped so far and the dt of their last step (the staggered velocities' half step).
    void saveState(core::StateWriter& out) const override;
    void restoreState(core::StateReader& in) override;

    core::Param<bool> m_halfStepStart{this, core::ParamSpec("halfStepStart").help("first velocity update over dt/2 (leapfrog start: second-order positions; velocities are then mid-step values)"), true};

private:
    /// the states stepped so far, with the dt of their last step
    std::vector<std::pair<const core::BaseMechanicalState*, double>> m_lastDt;
};

} // namespace fascia::mechanics
