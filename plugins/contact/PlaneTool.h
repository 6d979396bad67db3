#pragma once
#include "RigidTool.h"

namespace fascia::contact {

/// A rigid half-space (a plate, a table): the body stays on the side its normal points to. In the
/// tool's frame the plane passes through the origin (the pose's position) with normal `normal`;
/// the signed distance of a point l is normal . l.
class PlaneTool : public RigidTool {
public:
    void init() override;
    double signedDistance(const Vec3& local, Vec3& normal) const override;
    bool localBounds(double, Vec3&, Vec3&) const override { return false; }
    double size() const override { return 0; }
    /// A square of half-side extent about the pose's position.
    bool displayMesh(double extent, Positions& points, Triangles& triangles) const override;

    core::Param<Vec3> m_normal{this, core::ParamSpec("normal").help("the plane's normal in the tool's frame, pointing to the body's side (normalised)"), Vec3(0, 0, 1)};

private:
    Vec3 m_n = Vec3(0, 0, 1);
};

} // namespace fascia::contact
