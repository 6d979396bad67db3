// The data check VTK 9.1 needs before it reads a .vtp's cells (checkVtpOffsets, VtpLayout.h): the
// last offset of each section, read as VTK reads it (ascii numbers, base64, compressed blocks
// expanded with VTK's own compressors). VTK then allocates the connectivity that offset announces
// (2^58 entries for a .vtu of 1.3 kB: plugins/meshio/VTUDataCheck.h) and checks the offsets
// increase only afterwards, so the last one is all that must be bounded here.
#include "VtpLayout.h"
#include "fascia/base/Error.h"

#include <vtkDataCompressor.h>
#include <vtkLZ4DataCompressor.h>
#include <vtkLZMADataCompressor.h>
#include <vtkSmartPointer.h>
#include <vtkZLibDataCompressor.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace fascia::surface::detail {

namespace {

[[noreturn]] void failAt(const std::string& path, long long at, const std::string& message) {
    core::throwInputError(core::SourceLoc{path, 0, at}, message);
}

vtkSmartPointer<vtkDataCompressor> compressor(const std::string& name) {
    if (name == "vtkZLibDataCompressor") return vtkSmartPointer<vtkZLibDataCompressor>::New();
    if (name == "vtkLZ4DataCompressor") return vtkSmartPointer<vtkLZ4DataCompressor>::New();
    return vtkSmartPointer<vtkLZMADataCompressor>::New();  // the scan let no other name pass
}

/// The stored bytes [from, from + n) of the data at `at` (base64 text decoded strictly, as VTK
/// does); fails when the file holds fewer.
std::string stored(const std::string& text, const VtpArray& a, size_t at, unsigned long long from, unsigned long long n,
                   const std::string& path) {
    std::string bytes = a.base64 ? decodeBase64(text, at, a.end, size_t(from + n), true) : text.substr(std::min(at, a.end), size_t(from + n));
    if (bytes.size() < from + n)
        failAt(path, (long long)a.tag, "DataArray '" + a.name + "' holds fewer bytes than its header announces: " +
                                           (a.base64 ? "its base64 text is corrupt" : "the file is truncated"));
    return bytes.substr(size_t(from));
}

/// The bytes of value k of a binary or appended array.
std::string valueBytes(const std::string& text, const VtpLayout& l, const VtpArray& a, unsigned long long k, const std::string& path) {
    const unsigned long long w = l.header64 ? 8 : 4, tb = unsigned(a.typeBytes), byte = k * tb;
    auto word = [&](const std::string& b, size_t i) {
        unsigned long long v = 0;
        for (size_t j = 0; j < w; ++j) v = (v << 8) | (unsigned char)b[size_t(i * w + (l.bigEndian ? j : w - 1 - j))];
        return v;
    };
    if (!l.compressed) return stored(text, a, a.data, w + byte, tb, path);  // the size word, then the values, in one stream
    // the header (blocks, block size, last block size, each block's compressed size), then the blocks;
    // base64 encodes the two apart
    const unsigned long long blocks = word(stored(text, a, a.data, 0, w, path), 0);
    const std::string h = stored(text, a, a.data, 0, (3 + blocks) * w, path);
    const unsigned long long blockSize = word(h, 1), last = word(h, 2), b = byte / blockSize;
    const size_t blockData = a.base64 ? size_t(a.data + (h.size() + 2) / 3 * 4) : size_t(a.data + h.size());
    unsigned long long before = 0;
    for (unsigned long long i = 0; i < b; ++i) before += word(h, size_t(3 + i));
    const unsigned long long size = (b + 1 == blocks && last != 0) ? last : blockSize;
    const std::string packed = stored(text, a, blockData, before, word(h, size_t(3 + b)), path);
    std::string plain(size_t(size), '\0');
    const size_t got = compressor(l.compressor)->Uncompress(reinterpret_cast<const unsigned char*>(packed.data()), packed.size(),
                                                            reinterpret_cast<unsigned char*>(&plain[0]), plain.size());
    if (got != size)
        failAt(path, (long long)a.tag, "compressed block " + std::to_string(b) + " of DataArray '" + a.name + "' does not expand to the " +
                                           std::to_string(size) + " bytes its header announces: the data is corrupt");
    return plain.substr(size_t(byte - b * blockSize), size_t(tb));
}

/// A value of the array's type from its bytes in the file's byte order (long double: a 64-bit
/// offset keeps its digits for the message).
long double decode(const std::string& bytes, const VtpArray& a, bool bigEndian) {
    std::uint64_t u = 0;
    const size_t n = bytes.size();
    for (size_t j = 0; j < n; ++j) u = (u << 8) | (unsigned char)bytes[bigEndian ? j : n - 1 - j];
    if (a.type == "Float32") {
        float f;
        const std::uint32_t u32 = std::uint32_t(u);
        std::memcpy(&f, &u32, 4);
        return f;
    }
    if (a.type == "Float64") {
        double d;
        std::memcpy(&d, &u, 8);
        return d;
    }
    if (a.type[0] == 'U') return (long double)u;
    const std::uint64_t sign = std::uint64_t(1) << (8 * n - 1);
    return (u & sign) ? -(long double)((~u + 1) & (sign | (sign - 1))) : (long double)u;  // two's complement of the type's width
}

/// Number k of an ascii array, or a located error when it is none (VTK reads whole numbers of an
/// integer type, and decimal numbers of a float one).
long double asciiValue(const std::string& text, const VtpLayout& l, const VtpArray& a, unsigned long long k, const std::string& path) {
    const long long at = VtpValueBytes(text, l, a).at(k);
    size_t e = size_t(at);
    while (e < a.end && !std::isspace((unsigned char)text[e])) ++e;
    const char *b = text.data() + at, *end = text.data() + e;
    long double v = 0;
    std::from_chars_result r{b, std::errc::invalid_argument};
    if (a.type[0] == 'F') {
        double d = 0;
        r = std::from_chars(b, end, d);
        v = d;
    } else if (a.type[0] == 'U') {
        unsigned long long u = 0;
        r = std::from_chars(b, end, u);
        v = (long double)u;
    } else {
        long long i = 0;
        r = std::from_chars(b, end, i);
        v = (long double)i;
    }
    if (r.ec != std::errc() || r.ptr != end) {
        std::string shown = text.substr(size_t(at), std::min<size_t>(e - size_t(at), 40));
        for (char& ch : shown) ch = ch >= ' ' && ch < 127 ? ch : '?';  // the file may be anything
        failAt(path, at, "DataArray '" + a.name + "' holds '" + shown + "', not a number of its type " + a.type);
    }
    return v;
}

} // namespace

void checkVtpOffsets(const std::string& text, const VtpLayout& l, const std::string& path) {
    for (int k = 0; k < kSections; ++k) {
        const VtpLayout::Cells& c = l.cells[size_t(k)];
        if (c.count == 0) continue;
        const VtpArray& o = c.offsets;
        const unsigned long long lastCell = c.count - 1;
        const long double v = o.format == "ascii" ? asciiValue(text, l, o, lastCell, path) : decode(valueBytes(text, l, o, lastCell, path), o, l.bigEndian);
        const long long at = VtpValueBytes(text, l, o).at(lastCell);
        const std::string cell = "cell " + std::to_string(lastCell) + " of <" + kVtpSectionNames[k] + ">";
        if (!(v >= 0) || v != std::floor(v))
            failAt(path, at, cell + " (the last) has the offset " + std::to_string(v) + ": offsets are whole numbers from 0 up");
        if (v > (long double)c.connectivity.values)
            failAt(path, at, cell + " (the last) ends at offset " + std::to_string((unsigned long long)std::min(v, 1.8e19L)) +
                                 ", past the " + std::to_string(c.connectivity.values) + " values of its connectivity array: the file is corrupt");
    }
}

} // namespace fascia::surface::detail
