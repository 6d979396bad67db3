#include "ConstantForce.h"
#include "fascia/base/StateIO.h"

namespace fascia::mechanics {

void ConstantForce::init() {
    auto& s = contextState(*this);
    m_nodes = m_select.resolve(*this, s);
    if (m_force.isSet() == m_totalForce.isSet())
        fail(m_force.isSet() ? "give force or totalForce, not both" : "give force (per node) or totalForce");
    if (m_nodes.empty()) fail("selects no node");
    m_perNode = m_force.isSet() ? m_force.get() : Vec3(m_totalForce.get() / double(m_nodes.size()));
    m_scale = m_curve.value(0.0);
}

void ConstantForce::addForce(core::BaseMechanicalState&, Positions& f, double t) {
    m_scale = m_curve.value(t);
    const Vec3 fi = m_scale * m_perNode;
    for (int i : m_nodes) f[i] += fi;
}

void ConstantForce::unscaledLoad(IndexList& nodes, Positions& forces) const {
    nodes = m_nodes;
    forces.assign(m_nodes.size(), m_perNode);
}

void ConstantForce::saveState(core::StateWriter& out) const { out.put("scale", m_scale); }
void ConstantForce::restoreState(core::StateReader& in) { m_scale = in.getDouble("scale"); }

double ConstantForce::potentialEnergy(const core::BaseMechanicalState& s) const {
    double e = 0;
    for (int i : m_nodes) e -= m_scale * m_perNode.dot(s.x()[i] - s.x0()[i]);
    return e;
}

} // namespace fascia::mechanics
