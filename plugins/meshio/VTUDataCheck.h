#pragma once
/// Checks of a .vtu's cell arrays made before VTK reads them, after the header check
/// (VTUHeaderCheck.h): VTK 9.1 trusts their values. Decodes the arrays it checks (base64, and
/// compressed blocks with VTK's own compressor). Private to the readers; needs VTK.
#include "VTUHeaderCheck.h"

#include <string>

namespace fascia::meshio::detail {

/// Fails with an error at the byte of the problem ("file: byte N: error: ...") when, in a Piece, one
/// of its numeric arrays does not read as VTK 9.1 reads it, which then dereferences a null array in
/// vtkXMLDataReader::ReadPieceData (a point or cell data array) or leaks the cell types array
/// (vtkXMLUnstructuredGridReader::ReadPieceData returns without freeing it):
/// - base64 text that holds fewer bytes than its header announces (decoded as VTK does: 4
///   characters at a time, all of them base64);
/// - a compressed block that does not expand to the bytes its header announces (decompressed with
///   VTK's own compressor);
/// - ascii text with something other than numbers of the array's type (whole numbers within its
///   range; decimal numbers for a float type: no nan, inf or hexadecimal, which VTK's istream does
///   not read).
/// Or when its cell offsets are not whole numbers that never decrease from 0, up to at most the
/// values its connectivity array holds (VTK 9.1 allocates the connectivity the last offset
/// announces: 2^58 entries for a file of 1.3 kB).
/// All found by fuzz_vtu (docs/robustness.md; tests/fuzz/regressions/vtu).
void checkVtuData(const std::string& path, const VtuLayout& layout);

} // namespace fascia::meshio::detail
