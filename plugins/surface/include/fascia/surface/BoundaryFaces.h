#pragma once
/// The boundary of a volume mesh: the faces that only one element has.
#include "fascia/base/Types.h"

#include <functional>

namespace fascia::surface {

/// The faces of the tetrahedra and hexahedra of `mesh` that only one element has, as triangles
/// turned away from that element (normal (b - a) x (c - a) pointing out of the body): a
/// tetrahedron's face as it is, a hexahedron's quadrilateral face split in two along its diagonal
/// from its first node. Ordered by the face's sorted node list (a triangle before a quadrilateral
/// that starts with the same nodes), so the result does not depend on the element order.
/// `onSurface`, when given, says which nodes can be on the boundary: faces with another node are
/// skipped without being counted (a generated grid knows its boundary nodes, so the work grows
/// with the surface, not the volume).
Triangles boundaryTriangles(const MeshData& mesh, const std::function<bool(int)>& onSurface = {});

} // namespace fascia::surface
