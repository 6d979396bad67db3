#pragma once
#include "NodeSelection.h"
#include "fascia/sim/StepTerms.h"

namespace fascia::mechanics {

/// What FixedConstraint and PrescribedDisplacement share: selected nodes follow x = X + offset(t)
/// and v = rate(t) along the masked axes, and their force along those axes is removed (the group
/// records it as the reaction): a core::AxisHold, which a step backend runs from its nodes and axes.
class AxisConstraint : public core::BaseConstraint, public core::AxisHold {
public:
    void init() override;
    void projectPositions(core::BaseMechanicalState& s, double t) override;
    void projectVelocities(core::BaseMechanicalState& s, double t) override;
    void projectForces(core::BaseMechanicalState& s) override;
    const IndexList& constrainedNodes() const override { return m_nodes; }
    std::array<bool, 3> constrainedAxes() const override { return m_mask; }

    NodeSelection m_select{this};
    core::Param<IndexList> m_directions{this, axisMaskSpec("directions", "held axes \"x y z\" as 0/1 flags: \"1 1 1\" all, \"0 0 1\" z only (a roller free in x and y); the other axes are free"), IndexList{1, 1, 1}};

protected:
    /// Displacement from the rest position and its rate at time t (zero for a fixed node).
    virtual Vec3 offset(double t) const { return Vec3::Zero(); }
    virtual Vec3 rate(double t) const { return Vec3::Zero(); }

    IndexList m_nodes;
    std::array<bool, 3> m_mask{true, true, true};
};

} // namespace fascia::mechanics
