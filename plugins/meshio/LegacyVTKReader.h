#pragma once
/// Legacy VTK reader (.vtk), our own parser: VTK's legacy reader is not built for hostile input (it
/// overflows buffers when CELLS counts lie and allocates what a header announces), so it is not
/// used. Needs no VTK: it is built with and without FASCIA_WITH_VTK. Private to the readers
/// (readMesh in MeshReaders.h is the entry point).
#include "MeshBuilder.h"

#include <string>

namespace fascia::meshio::detail {

/// Reads the legacy VTK unstructured grid at path into b. Supported: file versions 1.0 to 4.2 (CELLS
/// as "n i0 i1 ..." per cell) and 5.x (CELLS with OFFSETS and CONNECTIVITY), ASCII and BINARY
/// (big-endian), sections POINTS, CELLS, CELL_TYPES, CELL_DATA (SCALARS, VECTORS, NORMALS,
/// TENSORS, TEXTURE_COORDINATES, COLOR_SCALARS, GLOBAL_IDS, PEDIGREE_IDS, LOOKUP_TABLE and FIELD
/// arrays), and POINT_DATA, FIELD and METADATA blocks, which are read and ignored. Kept cells,
/// groups and cell arrays as readMesh documents. Every count is checked against the bytes left in
/// the file before anything is allocated; every error is located at its line (ASCII) or byte
/// offset (BINARY: "file: byte N: error: ...").
void readLegacyVtk(const std::string& path, MeshBuilder& b);

} // namespace fascia::meshio::detail
