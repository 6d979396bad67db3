#pragma once
#include "NodeSelection.h"

namespace fascia::mechanics {

/// A constant force on nodes: `force` on each node, or `totalForce` shared equally among them.
class ConstantForce : public core::BaseForceField {
public:
    void init() override;
    void addForce(core::BaseMechanicalState& s, Positions& f, double t) override;
    double potentialEnergy(const core::BaseMechanicalState& s) const override;

    NodeSelection m_select{this};
    core::Param<Vec3> m_force{this, core::ParamSpec("force").unit("N").help("force applied to each selected node")};
    core::Param<Vec3> m_totalForce{this, core::ParamSpec("totalForce").unit("N").help("total force, shared equally by the selected nodes")};

private:
    IndexList m_nodes;
    Vec3 m_perNode = Vec3::Zero();
};

} // namespace fascia::mechanics
