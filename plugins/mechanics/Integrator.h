#pragma once
#include "fascia/sim/Mechanics.h"

namespace fascia::mechanics {

/// Shared parameters of the explicit integrators: mass-proportional (Rayleigh) damping,
/// m x'' + alpha m x' + f_int = f_ext.
class DampedIntegrator : public core::BaseIntegrator {
public:
    core::Param<double> m_damping{this, core::ParamSpec("damping").unit("1/s").min(0).help("mass-proportional Rayleigh damping alpha: damping force -alpha m v"), 0.0};
};

} // namespace fascia::mechanics
