#include "PrescribedDisplacement.h"

namespace fascia::mechanics {

void PrescribedDisplacement::init() {
    using C = core::Curve;
    if (m_curve.isSet())
        for (const core::BaseParam* p : {static_cast<const core::BaseParam*>(&m_shape), static_cast<const core::BaseParam*>(&m_rampTime),
                                         static_cast<const core::BaseParam*>(&m_startTime)})
            if (p->isSet())
                fail(*p, "give curve or shape, rampTime and startTime, not both (the curve holds the shape and its times)");
    const std::string& k = m_shape.get();
    const double s = m_startTime.get(), T = m_rampTime.get();
    if (k == "step") C::make({s, 0.0, s, 1.0}, C::Interpolation::Linear, C::After::Hold, m_shapeCurve);
    else
        C::make({s, 0.0, s + T, 1.0}, k == "smooth" ? C::Interpolation::Smooth : C::Interpolation::Linear,
                k == "ramp" ? C::After::Extend : C::After::Hold, m_shapeCurve);
    AxisConstraint::init();  // projects the state at t = 0
}

double PrescribedDisplacement::shape(double t) const {
    return m_curve.isSet() ? m_curve.value(t) : m_shapeCurve.value(t);
}

double PrescribedDisplacement::shapeRate(double t) const {
    return m_curve.isSet() ? m_curve.rate(t) : m_shapeCurve.rate(t);
}

} // namespace fascia::mechanics
