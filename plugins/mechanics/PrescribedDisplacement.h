#pragma once
#include "NodeSelection.h"

namespace fascia::mechanics {

/// Nodes follow x(t) = X + d * s(t) along the masked axes, where d is `displacement` and s the
/// load shape: ramp (t/T), rampHold (min(t/T, 1)), smooth (3-4-5 polynomial 10r^3 - 15r^4 + 6r^5,
/// r = min(t/T, 1)) or step (1). Time counts from startTime; before it s = 0.
/// Records the reaction force on its nodes like FixedConstraint.
class PrescribedDisplacement : public core::BaseConstraint {
public:
    void init() override;
    void projectPositions(core::BaseMechanicalState& s, double t) override;
    void projectVelocities(core::BaseMechanicalState& s, double t) override;
    void projectForces(core::BaseMechanicalState& s) override;
    const IndexList& constrainedNodes() const override { return m_nodes; }
    std::array<bool, 3> constrainedAxes() const override { return m_mask; }

    /// The load shape s(t) and its time derivative.
    double shape(double t) const;
    double shapeRate(double t) const;

    NodeSelection m_select{this};
    core::Param<Vec3> m_displacement{this, core::ParamSpec("displacement").unit("m").required().help("displacement vector d reached when the shape is 1")};
    core::Param<std::string> m_shape{this, core::ParamSpec("shape").choices({"ramp", "rampHold", "smooth", "step"}).help("load shape s(t)"), "rampHold"};
    core::Param<double> m_rampTime{this, core::ParamSpec("rampTime").unit("s").above(0).help("duration T of the ramp (ramp, rampHold, smooth)"), 1.0};
    core::Param<double> m_startTime{this, core::ParamSpec("startTime").unit("s").min(0).help("time at which the load starts"), 0.0};
    core::Param<IndexList> m_directions{this, axisMaskSpec("directions", "prescribed axes \"x y z\" as 0/1 flags; the other axes are free"), IndexList{1, 1, 1}};

private:
    IndexList m_nodes;
    std::array<bool, 3> m_mask{true, true, true};
    int m_kind = 1;
};

} // namespace fascia::mechanics
