#pragma once
#include "RigidTool.h"

namespace fascia::contact {

/// A rigid sphere (an indenter, a probe's ball) of radius R centred on the pose's position: the
/// signed distance of a point l of the tool's frame is |l| - R.
class SphereTool : public RigidTool {
public:
    double signedDistance(const Vec3& local, Vec3& normal) const override;
    bool localBounds(double margin, Vec3& lo, Vec3& hi) const override;
    double size() const override { return 2 * m_radius.get(); }
    bool displayMesh(double extent, Positions& points, Triangles& triangles) const override;

    core::Param<double> m_radius{this, core::ParamSpec("radius").unit("m").above(0).required().help("radius of the sphere")};
};

} // namespace fascia::contact
