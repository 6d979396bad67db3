#pragma once
/// The .vtp (VTK XML PolyData) surface reader behind readSurface (fascia/surface/TriangleSurface.h).
/// This header names no VTK type: VtpReader.cpp reads with VTK, and a build without VTK
/// (FASCIA_WITH_VTK=OFF) compiles NoVtpReader.cpp instead, which refuses .vtp files. Private to
/// the surface library.
#include "fascia/surface/TriangleSurface.h"

#include <string>

namespace fascia::surface::detail {

/// Reads the .vtp whose bytes are `bytes` (the file s.file) into s: its points, and as triangles
/// its polygons (each a fan around its first point, as OBJ faces) and triangle strips; vertices
/// and lines are ignored. s.origin holds the byte of each triangle's cell in the file.
void readVtp(const std::string& bytes, TriangleSurface& s);

} // namespace fascia::surface::detail
