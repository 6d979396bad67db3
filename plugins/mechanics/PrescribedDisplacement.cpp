#include "PrescribedDisplacement.h"

#include <algorithm>

namespace fascia::mechanics {

void PrescribedDisplacement::init() {
    const std::string& k = m_shape.get();
    m_kind = k == "ramp" ? 0 : k == "rampHold" ? 1 : k == "smooth" ? 2 : 3;
    AxisConstraint::init();  // projects the state at t = 0
}

double PrescribedDisplacement::shape(double t) const {
    const double tau = t - m_startTime.get();
    if (tau <= 0) return 0;
    const double r = tau / m_rampTime.get();
    switch (m_kind) {
    case 0: return r;
    case 1: return std::min(r, 1.0);
    case 2: {
        const double q = std::min(r, 1.0);
        return q * q * q * (10 - 15 * q + 6 * q * q);
    }
    default: return 1;
    }
}

double PrescribedDisplacement::shapeRate(double t) const {
    const double tau = t - m_startTime.get();
    if (tau <= 0) return 0;
    const double T = m_rampTime.get(), r = tau / T;
    switch (m_kind) {
    case 0: return 1 / T;
    case 1: return r < 1 ? 1 / T : 0;
    case 2: return r < 1 ? 30 * r * r * (1 - r) * (1 - r) / T : 0;
    default: return 0;
    }
}

} // namespace fascia::mechanics
