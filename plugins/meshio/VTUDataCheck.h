#pragma once
/// Checks of a .vtu's cell arrays made before VTK reads them, after the header check
/// (VTUHeaderCheck.h): VTK 9.1 trusts their values. Decodes the arrays it checks (base64, and
/// compressed blocks with VTK's own compressor). Private to the readers; needs VTK.
#include "VTUHeaderCheck.h"

#include <string>

namespace fascia::meshio::detail {

/// Fails with an error at the byte of the problem ("file: byte N: error: ...") when, in a Piece:
/// - the base64 text of one of its arrays holds fewer bytes than its header announces (decoded as
///   VTK does: 4 characters at a time, all of them base64), or a compressed block of one of them
///   does not expand to the bytes its header announces
///   (VTK 9.1 then dereferences a null array in vtkXMLDataReader::ReadPieceData for a point or
///   cell data array, and leaks a cell types array it cannot read:
///   vtkXMLUnstructuredGridReader::ReadPieceData returns without freeing it), or an ascii types
///   array holds something other than whole numbers (the same leak);
/// - its cell offsets are not whole numbers that never decrease from 0, up to at most the values
///   its connectivity array holds (VTK 9.1 allocates the connectivity the last offset announces:
///   2^58 entries for a file of 1.3 kB). Compressed offsets are decompressed to be read.
/// Both found by fuzz_vtu (docs/robustness.md; tests/fuzz/regressions/vtu).
void checkVtuData(const std::string& path, const VtuLayout& layout);

} // namespace fascia::meshio::detail
