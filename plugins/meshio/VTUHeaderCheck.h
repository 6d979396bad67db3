#pragma once
/// Checks of a .vtu file made before VTK reads it: VTK's XML reader allocates what the file
/// announces (a compressed-block header of 2.3 GB makes it crash), so the sizes are checked against
/// the file first. Needs no VTK. Private to the readers.
#include <string>

namespace fascia::meshio::detail {

/// Fails with an error located at the byte offset of the problem ("file: byte N: error: ...") when
/// the .vtu at path announces more than it holds: a Piece's NumberOfPoints or NumberOfCells that its
/// Points, cell types, offsets, point or cell data arrays do not have (one tuple each, so a cell
/// type array shorter than the cells is an error), a binary or appended data header (UInt32 or
/// UInt64, compressed blocks included) whose sizes pass the end of the file or of its data, or
/// compressed blocks that would expand more than any of VTK's compressors can; a Piece with points
/// but no Points array, or with cells but no cell types array.
void checkVtuHeaders(const std::string& path);

} // namespace fascia::meshio::detail
