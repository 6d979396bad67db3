#pragma once
#include "Integrator.h"

namespace fascia::mechanics {

/// Forward (explicit) Euler, HEML eq. (31): x(t+dt) = x + dt v; v(t+dt) = v + dt (f/m - alpha v).
/// Less stable than SemiImplicitEuler; offered for comparison.
///
/// Stability: on an oscillator of frequency omega (x'' + alpha x' + omega^2 x = 0) one step has the
/// characteristic polynomial z^2 - (2 - alpha dt) z + (1 - alpha dt + omega^2 dt^2), whose roots
/// lie inside the unit circle iff alpha dt - omega^2 dt^2 > 0 and 4 - 2 alpha dt + omega^2 dt^2 > 0
/// (the Jury conditions). Without damping no dt is stable: every vibration grows. With damping the
/// limit over all modes 0 <= omega <= omega_max is dt < min(2 / alpha, alpha / omega_max^2) (the first
/// from the slow modes, the second from the fastest), far below central difference's 2 / omega_max
/// for light damping.
class ExplicitEuler : public DampedIntegrator {
public:
    void step(core::MechanicalGroup& g, double t, double dt) override;
    /// min(2 / alpha, alpha / omega_max^2) with omega_max = 2 / critical; 0 (no stable step) without
    /// damping.
    double stableTimeStep(double critical, std::string& why) const override;
};

} // namespace fascia::mechanics
