#include "MechanicalObject.h"
#include "fascia/scene/Node.h"

namespace fascia::mechanics {

void MechanicalObject::init() {
    Positions rest;
    if (m_position.isSet()) {
        rest = m_position.get();
    } else if (auto* topo = node()->findInContext<core::BaseTopology>()) {
        rest = topo->meshData().points;
    } else {
        fail("no positions: set position=\"...\" (or link it, e.g. \"@loader.positions\"), or put a MeshLoader or "
             "GridMesh in the same node");
    }
    if (rest.empty()) fail(m_position, "has no nodes");
    m_x0 = std::move(rest);
    resize(m_x0.size());
    if (m_velocity.isSet()) {
        if (m_velocity.get().size() != m_x0.size())
            fail(m_velocity, "velocity has " + std::to_string(m_velocity.get().size()) + " entries for " +
                                 std::to_string(m_x0.size()) + " nodes");
        m_v = m_velocity.get();
    } else {
        m_v.assign(m_x0.size(), m_initialVelocity.get());
    }
}

} // namespace fascia::mechanics
