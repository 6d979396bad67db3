#pragma once
/// VTK reader: legacy .vtk and XML .vtu unstructured grids, read with VTK's own readers. This header
/// names no VTK type: VTKReader.cpp is the only reader source that includes VTK, and a build without
/// VTK (FASCIA_WITH_VTK=OFF) compiles NoVTKReader.cpp instead, which refuses such files. Private to
/// the readers (readMesh in MeshReaders.h is the entry point).
#include "MeshBuilder.h"

#include <string>

namespace fascia::meshio::detail {

/// Reads the VTK unstructured grid at path (XML .vtu when xml, else legacy .vtk) into b: points,
/// tetrahedra, hexahedra (voxels turned into hexahedra) and triangles, groups from the int cell
/// array "gmsh:physical" or "CellEntityIds", and every 1- or 3-component cell array.
void readVtk(const std::string& path, bool xml, MeshBuilder& b);

} // namespace fascia::meshio::detail
