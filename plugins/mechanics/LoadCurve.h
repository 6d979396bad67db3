#pragma once
#include "fascia/sim/LoadCurve.h"

namespace fascia::mechanics {

/// A load curve declared once and linked by the loads it scales (curve="@name"): tabulated points
/// (t_k, c_k), interpolated linearly or smoothly (the 3-4-5 polynomial), the first value held before
/// the first point, the last held after the last point or the last segment continued. The formulas:
/// fascia/sim/LoadCurve.h. A linear ramp over T is points="0 0  T 1", a smooth step the same with
/// interpolation="smooth", a step at t0 points="t0 0  t0 1" (two points at one time are a jump).
class LoadCurve : public core::BaseLoadCurve {
public:
    void init() override;
    const core::Curve& curve() const override { return m_curve; }

    core::Param<NumberList> m_points{this, core::ParamSpec("points").required().help("times and values \"t1 c1 t2 c2 ...\" (s, -), times non-decreasing; two points at one time make a jump")};
    core::Param<std::string> m_interpolation{this, core::ParamSpec("interpolation").choices({"linear", "smooth"}).help("between points: linear, or smooth (c_k + (c_k+1 - c_k) s(r), s(r) = r^3 (10 - 15 r + 6 r^2), zero slope at every point)"), "linear"};
    core::Param<std::string> m_after{this, core::ParamSpec("after").choices({"hold", "extend"}).help("after the last point: hold its value, or extend the last segment (linear interpolation only)"), "hold"};

private:
    core::Curve m_curve;
};

} // namespace fascia::mechanics
