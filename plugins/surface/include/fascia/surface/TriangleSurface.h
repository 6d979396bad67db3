#pragma once
/// Triangle surfaces read from STL (ASCII and binary), Wavefront OBJ and VTK XML PolyData (.vtp,
/// the format Fascia writes surfaces in; with VTK only) files, and the check that
/// such a surface is closed, edge-manifold and consistently oriented (what a rigid surface tool or a
/// signed distance needs). Pure functions: no scene component here. The library (fascia_surface) is
/// shared, so that leaf plugins can link it (meshio for visual surfaces, contact for surface tools;
/// docs/design.md, section 2).
///
/// Every problem with the input is a fascia::core::Error (ErrorKind::Input) located where it is:
/// "file:line: error: ..." in a text file, "file: byte N: error: ..." in a binary STL or a .vtp
/// file, or at line 0 for the file as a whole.
#include "fascia/base/Error.h"
#include "fascia/base/Types.h"

#include <string>
#include <vector>

namespace fascia::surface {

/// An indexed triangle surface with, for each triangle, where it is in its file.
struct TriangleSurface {
    Positions points;       ///< vertices (file units)
    Triangles triangles;    ///< 0-based vertex indices, in file order (OBJ polygons split into fans)
    std::string file;       ///< the file it was read from ("" when built in code)
    std::string format;     ///< "STL ASCII", "STL binary", "OBJ" or "VTK XML PolyData"
    /// Per triangle: the line it is on (text files) or the byte offset of its record (binary STL)
    /// or of its cell's first point (.vtp; the connectivity array's tag when it is compressed).
    std::vector<long long> origin;
    bool byteOffsets = false;  ///< origin holds byte offsets (binary STL, .vtp) rather than lines
};

/// Reads a triangle surface; the format is picked by the extension (case-insensitive):
///   .stl  ASCII ("solid ... facet normal ... outer loop, 3 vertex lines ... endsolid") or binary
///         (80-byte header, uint32 count, 50 bytes per triangle); binary when the file size is
///         84 + 50 count, whatever the header says (binary files that begin with "solid" exist).
///         Vertices with equal coordinates are merged into one (STL repeats them per triangle).
///   .obj  "v x y z [w]" and "f i j k ..." lines (indices 1-based, negative ones relative to the
///         last vertex read, "i/t/n" forms accepted); a polygon of n vertices becomes a fan of
///         n - 2 triangles (v0, v(k), v(k+1)); normals, texture coordinates, groups, materials,
///         smoothing groups and lines are ignored; any other keyword is a located error.
///   .vtp  VTK XML PolyData of one Piece (ascii, binary or appended data, compressed or not),
///         read with VTK after its headers were checked against the file
///         (plugins/surface/VtpLayout.h): its points (not merged), its polygons as fans like OBJ
///         faces, and its triangle strips (the degenerate triangles that join strips dropped);
///         vertices, lines and the point and cell data are ignored. VTK's own complaints become
///         the error's message. A build without VTK refuses .vtp files (located, saying so).
/// Refused (located): an unknown extension, an empty file or one without triangles, a truncated or
/// oversized binary file (its count is checked against the file size before anything is
/// allocated), a malformed number, a non-finite coordinate, a face naming a vertex that does not
/// exist, a triangle that uses one vertex twice; in a .vtp also what is not VTK XML PolyData, a
/// header that announces more than the file holds, a polygon of fewer than 3 points.
TriangleSurface readSurface(const std::string& path);

/// What is wrong with a surface, edge by edge. An undirected edge is "open" when one triangle
/// has it, "non-manifold" when three or more have it, and "misoriented" when its two triangles
/// run along it in the same direction (a consistently oriented closed surface runs each edge once
/// each way).
struct SurfaceReport {
    long long openEdges = 0, nonManifoldEdges = 0, misorientedEdges = 0;
    long long firstBadTriangle = -1;  ///< a triangle at the first bad edge found (-1: none)
    int firstBadA = -1, firstBadB = -1;  ///< that edge's vertices
    double volume = 0;  ///< enclosed signed volume (positive when the triangles face outwards)
    bool closed() const { return openEdges == 0 && nonManifoldEdges == 0 && misorientedEdges == 0; }
};

/// Inspects every edge (sorted, so the report is the same for any order of work).
SurfaceReport inspectSurface(const Positions& points, const Triangles& triangles);

/// Throws a located input error (at the line or byte of the triangle of the first bad edge, in
/// the surface's file) unless the surface is closed, edge-manifold and consistently oriented;
/// `who` says what needs it, e.g. "SurfaceTool 'probe'". A closed surface that faces inwards
/// (negative enclosed volume) is turned outwards in place; returns true when it was.
bool requireClosedSurface(TriangleSurface& surface, const std::string& who);

/// The enclosed signed volume of a closed surface: the sum over triangles of a . (b x c) / 6
/// (divergence theorem); positive when the triangles turn counter-clockwise seen from outside.
double enclosedVolume(const Positions& points, const Triangles& triangles);

/// Where triangle `tri` of the surface is: its file and line (text), or its file and byte offset
/// (binary STL, .vtp: "file: byte N: error: ...").
core::SourceLoc triangleLocation(const TriangleSurface& surface, size_t tri);

} // namespace fascia::surface
