#pragma once
/// The pose of a rigid tool over time: fixed, along a load curve, or through keyframes; the pose an
/// embedding program sets (BaseTool::setPose) replaces them.
#include "fascia/sim/LoadCurve.h"
#include "fascia/sim/Tool.h"

namespace fascia::contact {

/// The pose parameters every tool declares, and the pose they give at a time t.
///   fixed:      position, orientation
///   curve:      position + c(t) displacement (positionCurve, a load curve), orientation fixed
///   keyframes:  keyTimes t_k (increasing), keyPositions (3 per key), keyOrientations (4 per key,
///               w x y z, optional): positions linear between keys, orientations by slerp, the first
///               key held before it and the last after it.
class ToolMotion {
public:
    explicit ToolMotion(core::Component* owner);
    /// Checks the parameters (located errors at the attribute at fault) and prepares the keys.
    void init(const core::Component& owner);
    /// The scene's pose at time t.
    core::Pose at(double t) const;

    core::Param<Vec3> position;
    core::Param<NumberList> orientation;
    core::Param<Vec3> displacement;
    core::CurveParam positionCurve;
    core::Param<NumberList> keyTimes;
    core::Param<NumberList> keyPositions;
    core::Param<NumberList> keyOrientations;

private:
    std::vector<core::Pose> m_keys;
    Eigen::Quaterniond m_orientation = Eigen::Quaterniond::Identity();
};

/// The unit quaternion of 4 numbers w x y z, or a located error at the parameter.
Eigen::Quaterniond readQuaternion(const core::Component& owner, const core::BaseParam& p, const double* wxyz);

} // namespace fascia::contact
