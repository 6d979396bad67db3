#pragma once
#include "RigidTool.h"

namespace fascia::contact {

/// A rigid capsule: a laparoscopic instrument's shaft with a rounded tip. The points within
/// `radius` of the segment from the tip centre (the pose's position, the tool's origin) to
/// length * axis (tool frame); the signed distance of a point is its distance to that segment
/// minus the radius.
class CapsuleTool : public RigidTool {
public:
    void init() override;
    double signedDistance(const Vec3& local, Vec3& normal) const override;
    bool localBounds(double margin, Vec3& lo, Vec3& hi) const override;
    double size() const override { return m_length.get() + 2 * m_radius.get(); }
    bool displayMesh(double extent, Positions& points, Triangles& triangles) const override;

    core::Param<double> m_radius{this, core::ParamSpec("radius").unit("m").above(0).required().help("radius of the shaft and of its rounded tip")};
    core::Param<double> m_length{this, core::ParamSpec("length").unit("m").min(0).required().help("length of the shaft's axis, from the tip centre back along axis")};
    core::Param<Vec3> m_axis{this, core::ParamSpec("axis").help("direction from the tip centre along the shaft, in the tool's frame (normalised)"), Vec3(0, 0, 1)};

private:
    Vec3 m_a = Vec3(0, 0, 1);
};

} // namespace fascia::contact
