#pragma once
#include "fascia/sim/Mechanics.h"

namespace fascia::mechanics {

/// Positions, rest positions, velocities, forces and reaction forces of one body's nodes.
/// Initialised from `position` (inline or linked, e.g. "@loader.positions") or, when unset, from
/// the mesh source (MeshLoader, GridMesh) in its context.
class MechanicalObject : public core::BaseMechanicalState {
public:
    void init() override;

    core::Param<Positions> m_position{this, core::ParamSpec("position").unit("m").help("rest positions (3 numbers per node), or a link such as \"@loader.positions\"; default: the mesh source in the context")};
    core::Param<Positions> m_velocity{this, core::ParamSpec("velocity").unit("m/s").help("initial velocities, one per node (default zero)")};
    core::Param<Vec3> m_initialVelocity{this, core::ParamSpec("initialVelocity").unit("m/s").help("initial velocity of every node (ignored when velocity is given)"), Vec3::Zero()};
};

} // namespace fascia::mechanics
