#pragma once
/// TetGen reader: name.node (the points) and name.ele (the tetrahedra, with an optional region
/// attribute). Private to the readers (readMesh in MeshReaders.h is the entry point).
#include "MeshBuilder.h"

#include <string>

namespace fascia::meshio::detail {

/// Reads the TetGen mesh named by `given` (its .node or its .ele file; the other one is looked for
/// beside it, with an extension of the same case) into b.
void readTetGen(const std::string& given, MeshBuilder& b);

/// Fails (at line 0 of `given`) unless both files of the TetGen mesh named by `given` exist and can
/// be read (checkReadable).
void checkTetGenFiles(const std::string& given);

} // namespace fascia::meshio::detail
