#pragma once
#include "AxisConstraint.h"
#include "fascia/sim/LoadCurve.h"

namespace fascia::mechanics {

/// Nodes follow x(t) = X + d * s(t) along the masked axes, where d is `displacement` and s a load
/// curve (`curve`, fascia/sim/LoadCurve.h) or, without one, the load shape: ramp (t/T), rampHold
/// (min(t/T, 1)), smooth (3-4-5 polynomial 10r^3 - 15r^4 + 6r^5, r = min(t/T, 1)) or step (1), with
/// time counted from startTime (before it s = 0). The shapes are load curves too: ramp is
/// "linear s 0 s+T 1 extend", rampHold "linear s 0 s+T 1", smooth "smooth s 0 s+T 1",
/// step "step s" (s = startTime).
/// Records the reaction force on its nodes like FixedConstraint.
class PrescribedDisplacement : public AxisConstraint {
public:
    void init() override;

    /// The load shape s(t) and its time derivative.
    double shape(double t) const;
    double shapeRate(double t) const;
    bool prescribesMotion() const override { return true; }

    core::Param<Vec3> m_displacement{this, core::ParamSpec("displacement").unit("m").required().help("displacement vector d reached when the shape is 1")};
    core::Param<std::string> m_shape{this, core::ParamSpec("shape").choices({"ramp", "rampHold", "smooth", "step"}).help("load shape s(t)"), "rampHold"};
    core::Param<double> m_rampTime{this, core::ParamSpec("rampTime").unit("s").above(0).help("duration T of the ramp (ramp, rampHold, smooth)"), 1.0};
    core::Param<double> m_startTime{this, core::ParamSpec("startTime").unit("s").min(0).help("time at which the load starts"), 0.0};
    core::CurveParam m_curve{this, core::curveSpec("curve", "the displacement, u(t) = c(t) d (instead of shape, rampTime and startTime)")};

protected:
    Vec3 offset(double t) const override { return shape(t) * m_displacement.get(); }
    Vec3 rate(double t) const override { return shapeRate(t) * m_displacement.get(); }

private:
    core::Curve m_shapeCurve;  ///< shape, rampTime and startTime as a curve
};

} // namespace fascia::mechanics
