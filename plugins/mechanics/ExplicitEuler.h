#pragma once
#include "Integrator.h"

namespace fascia::mechanics {

/// Forward (explicit) Euler, HEML eq. (31): x(t+dt) = x + dt v; v(t+dt) = v + dt (f/m - alpha v).
/// Less stable than SemiImplicitEuler; offered for comparison.
class ExplicitEuler : public DampedIntegrator {
public:
    void step(core::MechanicalGroup& g, double t, double dt) override;
};

} // namespace fascia::mechanics
