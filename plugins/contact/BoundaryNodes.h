#pragma once
/// The boundary nodes of a volume mesh: the nodes of the element faces that belong to one element
/// only (triangles of tetrahedra, quadrilaterals of hexahedra).
#include "fascia/base/Types.h"

namespace fascia::contact {

/// Sorted boundary node indices of the mesh's tetrahedra and hexahedra; empty when it has none.
IndexList boundaryNodes(const MeshData& mesh);

} // namespace fascia::contact
