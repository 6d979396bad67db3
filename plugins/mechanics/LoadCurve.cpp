#include "LoadCurve.h"

namespace fascia::mechanics {

void LoadCurve::init() {
    using C = core::Curve;
    const std::string problem =
        C::make(m_points.get(), m_interpolation.get() == "smooth" ? C::Interpolation::Smooth : C::Interpolation::Linear,
                m_after.get() == "extend" ? C::After::Extend : C::After::Hold, m_curve);
    if (!problem.empty()) fail(m_points, "points: " + problem);
}

} // namespace fascia::mechanics
