#pragma once
#include "Integrator.h"

#include <vector>

namespace fascia::mechanics {

/// Semi-implicit (symplectic) Euler, HEML eq. (32): v(t+dt) = v + dt (f/m - alpha v);
/// x(t+dt) = x + dt v(t+dt).
/// With halfStepStart (the default) the very first velocity update uses dt/2: the velocities are
/// then staggered by half a step and the scheme is the leapfrog (Stormer-Verlet) method, second
/// order in positions, so a constant acceleration gives u = a t^2/2 to round-off. Without it, the
/// paper's eq. (32) from rest, first order (u = a t (t + dt)/2 under constant acceleration).
/// Note that with halfStepStart the velocities the state holds (and exporters write) are the
/// leapfrog's mid-step velocities v(t - dt/2), as in every staggered scheme.
class SemiImplicitEuler : public DampedIntegrator {
public:
    void step(core::MechanicalGroup& g, double t, double dt) override;

    core::Param<bool> m_halfStepStart{this, core::ParamSpec("halfStepStart").help("first velocity update over dt/2 (leapfrog start: second-order positions; velocities are then mid-step values)"), true};

private:
    std::vector<const core::BaseMechanicalState*> m_started;
};

} // namespace fascia::mechanics
