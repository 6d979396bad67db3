#pragma once
#include "NodeSelection.h"

namespace fascia::mechanics {

/// Holds nodes at their rest positions, in all directions or along a per-axis mask (rollers,
/// symmetry planes). Records the reaction force (the force the support exerts) on each node.
class FixedConstraint : public core::BaseConstraint {
public:
    void init() override;
    void projectPositions(core::BaseMechanicalState& s, double t) override;
    void projectVelocities(core::BaseMechanicalState& s, double t) override;
    void projectForces(core::BaseMechanicalState& s) override;
    const IndexList& constrainedNodes() const override { return m_nodes; }
    std::array<bool, 3> constrainedAxes() const override { return m_mask; }

    NodeSelection m_select{this};
    core::Param<IndexList> m_directions{this, axisMaskSpec("directions", "constrained axes \"x y z\" as 0/1 flags: \"1 1 1\" fixes, \"0 0 1\" is a roller free in x and y"), IndexList{1, 1, 1}};

private:
    IndexList m_nodes;
    std::array<bool, 3> m_mask{true, true, true};
};

} // namespace fascia::mechanics
