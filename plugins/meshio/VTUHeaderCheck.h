#pragma once
/// Checks of a .vtu file made before VTK reads it: VTK's XML reader allocates what the file
/// announces (a compressed-block header of 2.3 GB makes it crash), so the sizes are checked against
/// the file first. Needs no VTK. Private to the readers.
#include <string>
#include <vector>

namespace fascia::meshio::detail {

/// Where a DataArray of a .vtu is, as the header check found it.
struct VtuArrayLayout {
    size_t tag = 0;          ///< the byte of its "<DataArray" (0: no such array)
    std::string format;      ///< "ascii", "binary" (inline base64) or "appended"
    size_t data = 0;         ///< where its data starts: ascii, the byte after the tag; binary and
                             ///< appended, the first byte (base64: character) of its header
    bool base64 = false;     ///< the data is base64 text (format binary, or appended base64)
    int typeBytes = 0;       ///< bytes per value (0: a type the check does not know)
    std::string type;        ///< its type attribute (Int32, Float64, ...)
    std::string name;        ///< its Name attribute
    unsigned long long values = 0;  ///< the values it holds (components counted), as its data announces
};

/// What the header check learned of a .vtu's layout, for errors found after VTK read it: per
/// Piece, where it is, its counts, and its Points and connectivity arrays.
struct VtuLayout {
    struct Piece {
        size_t at = 0;  ///< the byte of "<Piece"
        unsigned long long points = 0, cells = 0;
        VtuArrayLayout points3, connectivity, offsets, types;  ///< the Points array (3 values per point), the cells' connectivity, offsets and types
        std::vector<VtuArrayLayout> arrays;  ///< every DataArray of the Piece of a known numeric type, in file order
    };
    std::vector<Piece> pieces;
    bool header64 = false, compressed = false, bigEndian = false;
    std::string compressor;  ///< the VTKFile's compressor class (empty: none)
    std::string text;  ///< the file
};

/// Fails with an error located at the byte offset of the problem ("file: byte N: error: ...") when
/// the .vtu at path announces more than it holds: a Piece's NumberOfPoints or NumberOfCells that its
/// Points, cell types, offsets, point or cell data arrays do not have (one tuple each, so a cell
/// type array shorter than the cells is an error), a binary or appended data header (UInt32 or
/// UInt64, compressed blocks included) whose sizes pass the end of the file or of its data, or
/// compressed blocks that would expand more than any of VTK's compressors can; a Piece with points
/// but no Points array, or with cells but no cell types array. Returns what it learned.
VtuLayout checkVtuHeaders(const std::string& path);

/// The stored data of a binary or appended array, decoded from base64 where it is base64: one block
/// of its values' bytes (size: the bytes its header announces) when the file is not compressed, else
/// each compressed block with the bytes it must expand to. Fails, located, when the base64 text
/// holds fewer bytes than announced. Empty for an ascii array, or one of a type the check does not
/// know. The reader decompresses a piece's cell types with it before VTK reads them: VTK 9.1 leaks
/// a types array it cannot read (vtkXMLUnstructuredGridReader::ReadPieceData returns without
/// freeing it; found by fuzz_vtu, docs/robustness.md).
struct VtuBlock {
    size_t at = 0;                 ///< the block's first byte (base64: character) in the file
    std::string bytes;             ///< its stored bytes (compressed, when the file is)
    unsigned long long size = 0;   ///< the bytes it holds uncompressed
};
std::vector<VtuBlock> vtuBlocks(const VtuLayout& layout, const VtuArrayLayout& a, const std::string& path);

/// The bytes in the file of values indices[0] <= indices[1] <= ... of array a (value k: the k-th
/// number of the array, components counted): in ascii data, the number's first character; in
/// uncompressed appended raw data, its first byte; in uncompressed base64 data, the 4-character
/// group holding its first byte; in compressed data, the first byte (base64: character) of the
/// compressed block holding it (a value inside a compressed block has no byte of its own). -1 for a
/// value the file does not hold or an array of a type the check does not know.
std::vector<long long> vtuValueBytes(const VtuLayout& layout, const VtuArrayLayout& a,
                                     const std::vector<unsigned long long>& indices);

} // namespace fascia::meshio::detail
