#pragma once
/// The role of a rigid tool: a body of fixed shape whose pose a scene, a load curve or an embedding
/// program (a haptic loop) sets, and which reports the force the deformable body exerts on it.
/// The core knows no contact: a pose and a force are geometry. A tool acts on its body as a
/// constraint (a unilateral, state-dependent one), so it plays the BaseConstraint role too; the
/// contact plugin (plugins/contact) provides the shapes.
///
/// ```
/// auto sim = fascia::core::Simulation::fromFile("scenes/interaction/palpation.xml");
/// fascia::core::BaseTool& probe = sim->tool("probe");
/// for (;;) {                                   // a haptic loop
///     probe.setPose({devicePosition, deviceOrientation});  // takes effect at the next step
///     sim->step();
///     feedback = probe.force();                // the force the body exerts on the tool (N)
/// }
/// ```
#include "fascia/sim/Mechanics.h"

#include <Eigen/Geometry>

namespace fascia::core {

/// A rigid pose: the tool's reference point (its origin) and orientation in the world frame. A
/// point p of the tool's own frame is at position + orientation * p.
struct Pose {
    Vec3 position = Vec3::Zero();                                          ///< m
    Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();       ///< unit quaternion
};

/// A rigid tool touching one deformable body.
class BaseTool : public BaseConstraint {
public:
    /// Sets the pose from code (an embedding program): it takes effect at the next step and holds
    /// from then on, replacing the scene's fixed pose or keyframes. The orientation is normalised.
    virtual void setPose(const Pose& pose) = 0;
    /// The current pose: the one the last step ended with (before any step, the initial one, or the
    /// one set by setPose).
    virtual Pose pose() const = 0;
    /// The force (N) the body exerts on the tool at the last step, in the world frame: minus the sum
    /// of the contact forces on the body's nodes. Zero before any step.
    virtual Vec3 force() const = 0;
    /// The torque (N m) of those contact forces about the tool's reference point pose().position.
    virtual Vec3 torque() const = 0;
    /// The mechanical state the tool touches (null before init). The simulation puts the tool into
    /// that state's group, wherever the tool sits in the scene graph.
    virtual BaseMechanicalState* body() const = 0;
    /// A triangulation of the tool's surface in its own frame (outward triangles), for viewers and
    /// exporters; contact never uses it. An unbounded tool (a plane) is drawn as a square of
    /// half-side `extent` (m) about its origin. False when the tool has no shape to draw.
    virtual bool displayMesh(double extent, Positions& points, Triangles& triangles) const { return false; }
    /// A tool holds no fixed set of nodes: its contacts change with the state.
    const IndexList& constrainedNodes() const override { return m_noNodes; }

private:
    IndexList m_noNodes;
};

} // namespace fascia::core
