#pragma once
/// What a .vtp (VTK XML PolyData) file holds and where, found by scanning its XML tags and data
/// headers before VTK reads it. VTK 9.1's XML reader allocates whatever a file announces and
/// trusts its headers (a compressed block header of 2.3 GB crashes it, an unknown compressor or
/// array type is a null dereference: plugins/meshio/VTUHeaderCheck.h tells the same of .vtu
/// files), so the sizes are checked against the file first. Private to the surface library; needs
/// no VTK (the data checks that decompress are in VtpData.cpp).
#include "fascia/surface/VtkXmlText.h"

#include <array>
#include <string>
#include <vector>

namespace fascia::surface::detail {

/// One DataArray of the file.
struct VtpArray {
    size_t tag = 0;            ///< the byte of its "<DataArray" (0: the file has no such array)
    std::string name, type;    ///< its Name and type attributes
    std::string format;        ///< "ascii", "binary" (inline base64) or "appended"
    int typeBytes = 0;         ///< bytes per value
    unsigned long long components = 1;
    size_t data = 0;           ///< ascii: the byte after the tag; else the first byte (base64: character) of its data header
    size_t end = 0;            ///< where its data ends (the next tag; the end of the file for appended data)
    bool base64 = false;       ///< the data is base64 text
    unsigned long long values = 0;  ///< the numbers it holds, components counted (as its header announces)
};

/// The cell sections of a Piece, in VTK's order.
enum VtpSection { kVerts, kLines, kStrips, kPolys, kSections };
extern const char* const kVtpSectionNames[kSections];  ///< "Verts", "Lines", "Strips", "Polys"

/// The one Piece of a .vtp and how its data is stored.
struct VtpLayout {
    size_t piece = 0;               ///< the byte of "<Piece"
    unsigned long long points = 0;  ///< NumberOfPoints
    VtpArray points3;               ///< the Points array (3 components)
    struct Cells {
        unsigned long long count = 0;     ///< NumberOfVerts, ... NumberOfPolys
        VtpArray connectivity, offsets;   ///< the first array of each name in the section
    };
    std::array<Cells, kSections> cells;
    bool header64 = false, compressed = false, bigEndian = false;
    std::string compressor;  ///< the VTKFile's compressor attribute ("" when not compressed)
};

/// Scans the .vtp in `text` (the file `path`); fails with an error at the byte of the problem
/// ("path: byte N: error: ...") when it is not XML, not a VTKFile of type PolyData, has other than
/// one Piece, or announces more than it holds: a header_type, compressor or byte order VTK 9.1
/// does not know; an array of a type that is not numeric or without a format; binary or appended
/// data whose header (compressed blocks included) passes the end of the file or of its data, or
/// whose blocks would expand more than any compressor can; a Points array that does not hold 3
/// numbers per point, a section's offsets that do not hold one per cell, a section with cells but
/// without offsets or connectivity. Attributes are read in double quotes without character
/// references (a tag with others is refused: VTK's parser would see what the scan does not).
VtpLayout scanVtp(const std::string& text, const std::string& path);

/// Fails (located) when the data of the arrays VTK 9.1 trusts does not read as it reads it: the
/// last offset of every section with cells passes its connectivity array (VTK allocates that many
/// entries before reading them), or is no whole number; compressed blocks of those offsets that do
/// not expand to the bytes their header announces. Decompresses with VTK's compressors (VtpData.cpp).
void checkVtpOffsets(const std::string& text, const VtpLayout& layout, const std::string& path);

/// (fascia/surface/VtkXmlText.h, shared with meshio's .vtu reader)
using fascia::surface::decodeBase64;

/// The byte of each value of an array in the file, for errors found after VTK read it: in ascii
/// data the number's first character, in uncompressed raw data its first byte, in uncompressed
/// base64 data the 4-character group holding its first byte; in compressed data (no value has a
/// byte of its own there) the array's tag.
class VtpValueBytes {
public:
    VtpValueBytes(const std::string& text, const VtpLayout& layout, const VtpArray& array);
    long long at(unsigned long long value) const;

private:
    const VtpArray& m_array;
    bool m_compressed;
    unsigned m_word;
    std::vector<size_t> m_ascii;  ///< where each number of ascii data starts
};

} // namespace fascia::surface::detail
