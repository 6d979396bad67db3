#pragma once
#include "NodeSelection.h"
#include "fascia/sim/LoadCurve.h"
#include "fascia/sim/LoadTerms.h"

namespace fascia::mechanics {

/// A force on nodes: `force` on each node, or `totalForce` shared equally among them, scaled by
/// a load curve: F(t) = c(t) F (constant when no curve is given).
class ConstantForce : public core::BaseForceField, public core::NodalLoad {
public:
    void init() override;
    void addForce(core::BaseMechanicalState& s, Positions& f, double t) override;
    double potentialEnergy(const core::BaseMechanicalState& s) const override;
    /// The load factor of the last addForce (the energy's).
    void saveState(core::StateWriter& out) const override;
    void restoreState(core::StateReader& in) override;
    void unscaledLoad(IndexList& nodes, Positions& forces) const override;
    double loadFactor(double t) const override { return m_curve.value(t); }
    bool curved() const override { return m_curve.isSet(); }

    NodeSelection m_select{this};
    core::Param<Vec3> m_force{this, core::ParamSpec("force").unit("N").help("force applied to each selected node")};
    core::Param<Vec3> m_totalForce{this, core::ParamSpec("totalForce").unit("N").help("total force, shared equally by the selected nodes")};
    core::CurveParam m_curve{this, core::curveSpec("curve", "the force, F(t) = c(t) F")};

private:
    IndexList m_nodes;
    Vec3 m_perNode = Vec3::Zero();
    double m_scale = 1.0;  ///< c(t) at the last addForce (the energy's load)
};

} // namespace fascia::mechanics
