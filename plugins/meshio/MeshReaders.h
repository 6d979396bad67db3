#pragma once
/// Volume-mesh readers: Gmsh (.msh ASCII 1, 2.2, 4.1), VTK (.vtk legacy, .vtu XML) and TetGen
/// (.node/.ele). Pure functions: no scene component here (the MeshLoader component wraps them).
/// One reader per format (GmshReader, LegacyVTKReader, VTKReader, TetGenReader); this header is
/// their only public face. Legacy .vtk files are parsed by our own reader (no VTK needed); a build
/// without VTK (FASCIA_WITH_VTK=OFF) refuses .vtu files with a located error ("this build has no
/// VTK support: ...").
///
/// Every problem with the input throws fascia::core::Error (ErrorKind::Input) located at the line of
/// the mesh file where it is ("file:line: error: ..."; in a BINARY legacy .vtk file and in the
/// headers of a .vtu at its byte offset: "file: byte N: error: ..."), or at line 0 ("file: error:
/// ...") when no place in the file is at fault: a file that cannot be read as a mesh (checkMeshFile),
/// or a mesh without volume elements, a .vtu that VTK itself refuses or whose cells name missing points.
#include "fascia/base/Types.h"

#include <array>
#include <map>
#include <string>

namespace fascia::meshio {

struct ReadOptions {
    /// Flip inverted elements (negative signed volume) instead of failing; each flip is counted in
    /// ReadReport::flippedElements.
    bool fixOrientation = false;
};

struct ReadReport {
    int flippedElements = 0;  ///< inverted elements flipped because of ReadOptions::fixOrientation
    std::string format;       ///< e.g. "Gmsh 2.2 ASCII", "Gmsh 1 (legacy)", "VTK XML", "TetGen"
    /// Elements of the file that were not kept, by kind ("line", "point", "quadrangle", "prism",
    /// "10-node tetrahedron", ...) -> count. Only tetrahedra and hexahedra (volume elements) and
    /// triangles are kept.
    std::map<std::string, int> skipped;
};

/// Reads a volume mesh; the reader is picked by the extension (case-insensitive):
///   .msh        Gmsh ASCII, versions 1 (legacy $NOD/$ELM), 2.x and 4.1 (binary is refused)
///   .vtk        VTK legacy unstructured grid, ASCII or BINARY, file versions 1.0-4.2 and 5.1
///   .vtu        VTK XML unstructured grid
///   .node/.ele  TetGen: either name may be given, the other one is looked for beside it
/// Node ids of the file (any numbering, e.g. 1-based or with gaps) are mapped to 0-based indices in
/// file order. Kept elements: tetrahedra, hexahedra (Gmsh/VTK node order; VTK voxels are turned into
/// hexahedra) and triangles; all other kinds are skipped and counted in report->skipped.
///
/// Physical groups: tetrahedronGroup/hexahedronGroup/triangleGroup always have one tag per element
/// (0: none). Sources: Gmsh physical tags; VTK int cell array "gmsh:physical" or "CellEntityIds";
/// TetGen region attribute (first element attribute, when it is a whole number). groupNames comes
/// from $PhysicalNames. nodeGroups holds, for every physical group (of any element kind, points and
/// lines included), the sorted unique node indices of its elements under "physical:<tag>", and also
/// under its name when it has one.
///
/// cellArrays (VTK files only): every cell data array with 1 or 3 components, restricted to the
/// volume cells, flattened in element order: all tetrahedra first (in `tetrahedra` order), then all
/// hexahedra; an array with k components has k * (tets + hexes) values.
///
/// The mesh is then checked with validateMesh().
fascia::MeshData readMesh(const std::string& path, const ReadOptions& opt = {}, ReadReport* report = nullptr);

/// The checks readMesh makes before it reads: fails (an input error at line 0 of path) when path has
/// no known extension, does not exist, is no regular file (a folder, FIFO or device is refused from
/// its type, without opening it), is larger than core::kMaxMeshFileBytes or cannot be opened; for
/// TetGen, when either of the two files fails so. MeshLoader locates these at its filename.
void checkMeshFile(const std::string& path);

/// Checks a mesh and throws an input error located in `file` on the first problem: no volume
/// elements, an element naming a node that does not exist, a non-finite coordinate, a degenerate
/// element (|volume| <= 1e-12 * (longest edge)^3), an inverted element (negative signed volume;
/// flipped and counted in report->flippedElements when opt.fixOrientation: a tetrahedron's last two
/// nodes are swapped, a hexahedron's bottom and top faces are exchanged). Group vectors that are
/// empty are filled with 0 (one per element). Used by readMesh and by generated meshes.
void validateMesh(fascia::MeshData& mesh, const std::string& file, const ReadOptions& opt, ReadReport* report);

/// det[b-a, c-a, d-a] / 6: positive when (a, b, c) turn counter-clockwise seen from d.
double tetrahedronSignedVolume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// Signed volume of the trilinear 8-node hexahedron (VTK/Gmsh node order: 0-1-2-3 the bottom face
/// counter-clockwise seen from above, 4-5-6-7 the top face above them); exact also for warped
/// (non-planar) faces. Positive for a well-ordered element.
double hexahedronVolume(const std::array<Vec3, 8>& corners);
double hexahedronVolume(const Positions& points, const std::array<int, 8>& hex);

/// Sum of the signed volumes of all tetrahedra and hexahedra.
double totalVolume(const fascia::MeshData& mesh);

} // namespace fascia::meshio
