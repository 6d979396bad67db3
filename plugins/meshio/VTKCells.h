#pragma once
/// What the legacy .vtk reader (our own parser) and the .vtu reader (through VTK) share: VTK cell
/// type numbers, their names, and how a cell becomes a mesh element. Names no VTK type, so that it
/// compiles without VTK. Private to the readers.
#include "MeshBuilder.h"

#include <string>

namespace fascia::meshio::detail {

/// VTK cell type numbers (vtkCellType.h of VTK 9; the legacy file format writes these numbers).
enum VtkCellType : int {
    kVtkTriangle = 5,
    kVtkTetra = 10,
    kVtkVoxel = 11,
    kVtkHexahedron = 12,
};

/// The name a skipped cell type is counted under in ReadReport::skipped ("line", "quadrangle",
/// "10-node tetrahedron", ... or "VTK cell type N" for a number without a name).
std::string vtkCellName(int type);

/// Number of points a kept cell type has (4, 8, 8, 3); 0 for the types that are skipped.
int vtkKeptCellSize(int type);

/// Adds cell `index` of the file (VTK type `type`, nodes[0..n) already checked against the point
/// count) to b: a tetrahedron (10) with 4 points, a hexahedron (12) or voxel (11, reordered to
/// hexahedron order) with 8, a triangle (5) with 3; any other cell is counted as skipped under
/// vtkCellName(type). line > 0 is where the cell is in an ASCII file, byte >= 0 where it is in a
/// BINARY one (for validation errors). The cell's nodes join physical group `group` (0: none).
void addVtkCell(MeshBuilder& b, long long index, int type, const int* nodes, size_t n, int group, int line,
                long long byte = -1);

/// A cell array of the file (tuples * components values, in cell order) into b.mesh.cellArrays,
/// restricted to the kept volume cells (the tetrahedra, then the hexahedra, by b.origin's cell
/// numbers): only arrays with 1 or 3 components are kept, as MeshReaders.h says.
void addVtkCellArray(MeshBuilder& b, const std::string& name, int components, const double* values);

} // namespace fascia::meshio::detail
