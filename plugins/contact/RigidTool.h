#pragma once
/// What every rigid tool shares: the body it touches, its pose over time, kinematic contact with
/// the body's surface nodes, Coulomb friction, and the force and torque the body exerts on it.
/// A shape (PlaneTool, SphereTool, CapsuleTool, SurfaceTool) gives only its signed distance.
#include "ToolMotion.h"
#include "fascia/sim/Tool.h"

#include <vector>

namespace fascia::contact {

/// Contact by kinematic projection (docs/design.md, section 4.5), on the boundary nodes of the
/// body's mesh (all its nodes when the mesh has no elements):
/// - forces (projectForces, at every force evaluation): at a node touching the tool (signed
///   distance at most a tolerance), the force component pushing into the tool is removed; that
///   removed force is the normal contact force N n on the node (n the tool's outward normal). With
///   friction, a node at rest on the tool (relative to it) keeps sticking while the tangential force
///   is at most staticFriction N (the tangential force is removed too); otherwise the kinetic force
///   kineticFriction N opposes its sliding (or the tangential force, from rest).
/// - positions (projectPositions, after the integrator's update): a node inside the tool goes to
///   the closest point of its surface at the new pose; the force that gives this correction over the
///   step, m dx / dt^2 (as central difference would), is added to the node's contact force (the
///   impulse of a node that reached the tool during the step: without it the force of a node
///   touching a curved tool every other step would flicker between zero and twice its value);
/// - velocities (projectVelocities): the velocity into the tool, relative to the tool's own motion
///   at that point, is removed; a sticking node takes the tool's tangential velocity, and a sliding
///   one that the friction would turn back stops (relative to the tool).
/// The contact forces are recorded as the reactions of the body's nodes (BaseMechanicalState
/// reaction()); the tool's force is minus their sum, its torque their moment about the pose's
/// position. Every loop runs over the surface nodes in order: the same result for any thread count.
class RigidTool : public core::BaseTool {
public:
    RigidTool();
    void init() override;
    void beginStep(double t, double dt) override { m_stepped = true; }
    void projectPositions(core::BaseMechanicalState& s, double t) override;
    void projectVelocities(core::BaseMechanicalState& s, double t) override;
    void projectForces(core::BaseMechanicalState& s) override;

    /// Between steps it carries: the last two poses and their times, the pose setPose gave (state of
    /// the embedding program, not a function of time), the per-node contact forces, stick/slide
    /// states and sliding directions of the last force evaluation, and the force and torque.
    void saveState(core::StateWriter& out) const override;
    void restoreState(core::StateReader& in) override;

    void setPose(const core::Pose& pose) override;
    core::Pose pose() const override { return m_pose; }
    Vec3 force() const override { return m_force; }
    Vec3 torque() const override { return m_torque; }
    core::BaseMechanicalState* body() const override { return m_body; }

    /// The contact force on each node of the body at the last force evaluation (N; zero off contact).
    const Positions& contactForces() const { return m_contact; }
    /// The body's nodes the tool can touch (its mesh's boundary nodes), in increasing order.
    const IndexList& surfaceNodes() const { return m_surface; }
    /// The number of nodes in contact at the last force evaluation.
    size_t contactCount() const { return m_active.size(); }

    /// Signed distance (m) of a point given in the tool's own frame to the tool's surface: negative
    /// inside; `normal` gets the unit outward normal at the closest surface point (tool frame).
    virtual double signedDistance(const Vec3& local, Vec3& normal) const = 0;
    /// A box in the tool's frame that holds every point of the tool within `margin` of its surface
    /// or inside it (the broad phase); an unbounded tool (a plane) returns false.
    virtual bool localBounds(double margin, Vec3& lo, Vec3& hi) const = 0;
    /// The tool's size (m), for the contact tolerance.
    virtual double size() const = 0;
    /// Whether signedDistance is dear enough to keep each node's last answer (a surface tool's is):
    /// a step asks it for a node up to three times at the same tool-frame point (projectPositions,
    /// projectVelocities, the next projectForces).
    virtual bool memoizeDistance() const { return false; }

    core::Link<core::BaseMechanicalState> m_bodyLink{this, core::ParamSpec("body").help("the MechanicalObject of the body the tool touches (default: the one in its context)")};
    ToolMotion m_motion{this};
    core::Param<double> m_staticFriction{this, core::ParamSpec("staticFriction").min(0).help("Coulomb static friction coefficient: a node sticks while its tangential force is at most this times its normal force (0: frictionless)"), 0.0};
    core::Param<double> m_kineticFriction{this, core::ParamSpec("kineticFriction").min(0).help("Coulomb kinetic friction coefficient, at most staticFriction (default: staticFriction)"), 0.0};

protected:
    /// Called by the shape's init() after its own checks.
    void initContact();

private:
    /// Node i at world point x -> tool frame at the current pose, and the world normal of the
    /// result. With memoizeDistance(), node i's last answer when its tool-frame point is bitwise the
    /// same (signedDistance being a function of the point alone: bitwise its own answer).
    double distanceWorld(size_t i, const Vec3& x, Vec3& normalWorld);
    /// The nodes to test this step: the surface nodes in the pose's broad-phase box, in order.
    void candidates(const core::BaseMechanicalState& s, std::vector<int>& out) const;
    /// The summed nodal masses of the body's group (null before the simulation assembled it).
    const std::vector<double>* groupMass() const;
    /// The tool's velocity at world point x over the last step (rigid motion from m_prevPose).
    Vec3 toolVelocity(const Vec3& x) const;

    core::BaseMechanicalState* m_body = nullptr;
    IndexList m_surface;
    core::Pose m_pose, m_prevPose;       ///< the pose of the last projection and the one before it
    double m_poseTime = 0, m_prevTime = 0;  ///< their times
    core::Pose m_set;                    ///< the pose setPose gave
    bool m_hasSet = false;               ///< setPose was called: it replaces the scene's motion
    bool m_stepped = false;              ///< a step has begun
    double m_tolerance = 0, m_muS = 0, m_muK = 0;
    Vec3 m_force = Vec3::Zero(), m_torque = Vec3::Zero();
    Positions m_contact;                 ///< contact force per body node
    std::vector<int> m_active;           ///< nodes with a contact force, in order
    std::vector<signed char> m_slip;     ///< per node: 1 sticking, 2 sliding (at the last force evaluation)
    Positions m_slipDir;                 ///< per node: the sliding direction (world, unit)
    Positions m_anchor;                  ///< per sticking node: its point in the tool's frame at the step's start
    std::vector<int> m_scratch;
    /// Per body node (with memoizeDistance()): its last tool-frame query point and the answer. One
    /// slot a node, so that a parallel loop over nodes could use it without locks.
    struct DistanceMemo {
        Vec3 local, normal;
        double distance;
        bool valid;
    };
    std::vector<DistanceMemo> m_memo;
};

} // namespace fascia::contact
