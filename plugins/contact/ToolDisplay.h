#pragma once
/// Triangulations of the analytic tool shapes, for BaseTool::displayMesh (viewers, exporters).
#include "fascia/base/Types.h"

namespace fascia::contact {

/// A closed capsule in its own frame: the points within `radius` of the segment from the origin to
/// length * axis (a sphere for length 0), as `rings` latitude rings of `segments` vertices plus two
/// poles; outward triangles. axis must be a unit vector.
void capsuleMesh(double radius, double length, const Vec3& axis, int rings, int segments, Positions& points,
                 Triangles& triangles);

/// A square of half-side `extent` about the origin, normal to the unit `normal` (two triangles
/// facing it).
void squareMesh(const Vec3& normal, double extent, Positions& points, Triangles& triangles);

} // namespace fascia::contact
