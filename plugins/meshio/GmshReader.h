#pragma once
/// Gmsh .msh reader: ASCII versions 1 (legacy $NOD/$ELM), 2.x and 4.1; binary files are refused.
/// Private to the readers (readMesh in MeshReaders.h is the entry point).
#include "MeshBuilder.h"

#include <string>

namespace fascia::meshio::detail {

/// Reads the Gmsh mesh at path into b: nodes, tetrahedra, hexahedra and triangles with their physical
/// groups and $PhysicalNames; other element kinds are counted in b.report->skipped.
void readGmsh(const std::string& path, MeshBuilder& b);

} // namespace fascia::meshio::detail
