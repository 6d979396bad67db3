#pragma once
/// The checks every mesh goes through after reading (see validateMesh in MeshReaders.h), with
/// errors located where the reader found each node and element. Private to the readers.
#include "MeshBuilder.h"

namespace fascia::meshio::detail {

/// Checks mesh, flips inverted elements when opt.fixOrientation, and fills empty group vectors
/// with 0; the first problem is an input error located through `origin`.
void validate(MeshData& mesh, const ElementOrigin& origin, const ReadOptions& opt, ReadReport& report);

} // namespace fascia::meshio::detail
