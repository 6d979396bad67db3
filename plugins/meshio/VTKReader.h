#pragma once
/// VTK XML reader (.vtu unstructured grids), read with VTK's own reader after checkVtuHeaders has
/// checked the sizes the file announces. This header names no VTK type: VTKReader.cpp is the only
/// reader source that includes VTK, and a build without VTK (FASCIA_WITH_VTK=OFF) compiles
/// NoVTKReader.cpp instead, which refuses .vtu files. Legacy .vtk files have their own reader
/// (LegacyVTKReader.h), which needs no VTK. Private to the readers (readMesh in MeshReaders.h is
/// the entry point).
#include "MeshBuilder.h"

#include <string>

namespace fascia::meshio::detail {

/// Reads the VTK XML unstructured grid at path into b: points, tetrahedra, hexahedra (voxels turned
/// into hexahedra) and triangles, groups from the int cell array "gmsh:physical" or
/// "CellEntityIds", and every 1- or 3-component cell array.
void readVtu(const std::string& path, MeshBuilder& b);

} // namespace fascia::meshio::detail
