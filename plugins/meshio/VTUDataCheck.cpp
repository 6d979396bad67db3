// The cell arrays of a .vtu checked before VTK reads them (see VTUDataCheck.h).
#include "VTUDataCheck.h"

#include "ReaderSupport.h"

#include <vtkDataCompressor.h>
#include <vtkLZ4DataCompressor.h>
#include <vtkLZMADataCompressor.h>
#include <vtkSmartPointer.h>
#include <vtkZLibDataCompressor.h>

#include <charconv>
#include <cstdint>
#include <vector>

namespace fascia::meshio::detail {
namespace {

vtkSmartPointer<vtkDataCompressor> compressorFor(const VtuLayout& l) {
    if (l.compressor == "vtkZLibDataCompressor") return vtkSmartPointer<vtkZLibDataCompressor>::New();
    if (l.compressor == "vtkLZ4DataCompressor") return vtkSmartPointer<vtkLZ4DataCompressor>::New();
    return vtkSmartPointer<vtkLZMADataCompressor>::New();  // the header check lets no other through
}

/// The bytes of a binary or appended array's values, decompressed where the file is compressed;
/// each block must expand to the bytes its header announces (`what` names the array in the error).
std::string valueData(const std::string& path, const VtuLayout& l, const VtuArrayLayout& a, const std::string& what) {
    const std::vector<VtuBlock> blocks = vtuBlocks(l, a, path);
    if (!l.compressed) return blocks.empty() ? std::string() : blocks[0].bytes;
    vtkSmartPointer<vtkDataCompressor> z = compressorFor(l);
    std::string out;
    for (size_t k = 0; k < blocks.size(); ++k) {
        const VtuBlock& b = blocks[k];
        const size_t first = out.size();
        out.resize(first + size_t(b.size));
        const size_t got = b.size == 0 ? 0 :
            z->Uncompress(reinterpret_cast<const unsigned char*>(b.bytes.data()), b.bytes.size(),
                          reinterpret_cast<unsigned char*>(&out[first]), size_t(b.size));
        if (got != b.size)
            failAtByte(path, (long long)b.at, "compressed block " + std::to_string(k) + " of the " + what + " array does not expand to the " +
                                                  std::to_string(b.size) + " bytes its header announces: the data is corrupt");
    }
    return out;
}

/// Value k of an integer array's bytes (the type's size and the file's byte order); false for a
/// type that is not an integer.
bool integerAt(const std::string& bytes, const VtuArrayLayout& a, bool bigEndian, size_t k, long long& v) {
    const size_t w = size_t(a.typeBytes);
    if (a.type.rfind("Float", 0) == 0 || w == 0 || (k + 1) * w > bytes.size()) return false;
    unsigned long long u = 0;
    for (size_t i = 0; i < w; ++i) u = (u << 8) | (unsigned char)bytes[k * w + (bigEndian ? i : w - 1 - i)];
    const bool isSigned = a.type[0] == 'I';
    if (isSigned && w < 8 && (u >> (8 * w - 1)) != 0) u |= ~0ull << (8 * w);  // sign-extend
    if (!isSigned && u > (unsigned long long)INT64_MAX) return false;
    v = (long long)u;
    return true;
}

/// The whole numbers of an ascii array's text; false (and `bad` at the token) when one is not.
bool asciiIntegers(const std::string& t, size_t from, std::vector<long long>& out, size_t& bad) {
    const size_t close = t.find('<', from), end = close == std::string::npos ? t.size() : close;
    auto space = [](char c) { return c == ' ' || c == '\n' || c == '\r' || c == '\t'; };
    for (size_t p = from; p < end;) {
        if (space(t[p])) {
            ++p;
            continue;
        }
        size_t q = p;
        while (q < end && !space(t[q])) ++q;
        const size_t s = t[p] == '+' ? p + 1 : p;
        long long v = 0;
        const auto [ptr, ec] = std::from_chars(t.data() + s, t.data() + q, v);
        if (ec != std::errc() || ptr != t.data() + q || q == s) {
            bad = p;
            return false;
        }
        out.push_back(v);
        p = q;
    }
    return true;
}

/// A Piece's offsets: whole numbers from >= 0, never decreasing, the last at most `limit`.
void checkOffsets(const std::string& path, const VtuLayout& l, const VtuArrayLayout& a, unsigned long long limit) {
    if (a.tag == 0 || a.typeBytes <= 0) return;
    std::vector<long long> v;
    if (a.format == "ascii") {
        size_t bad = 0;
        if (!asciiIntegers(l.text, a.data, v, bad))
            failAtByte(path, (long long)bad, "the cell offsets array holds " + detail::quoted(l.text.substr(bad, 20)) + ", not a whole number");
    } else {
        const std::string bytes = valueData(path, l, a, "cell offsets");
        const size_t n = bytes.size() / size_t(a.typeBytes);
        v.resize(n);
        for (size_t k = 0; k < n; ++k)
            if (!integerAt(bytes, a, l.bigEndian, k, v[k]))
                failAtByte(path, (long long)a.tag, "the cell offsets array has the type " + detail::quoted(a.type) + " or a value past 2^63: expected whole numbers");
    }
    long long last = 0;
    for (size_t k = 0; k < v.size(); ++k) {
        const bool wrong = v[k] < last || (unsigned long long)v[k] > limit;
        if (!wrong) {
            last = v[k];
            continue;
        }
        const long long at = vtuValueBytes(l, a, {k})[0];
        failAtByte(path, at >= 0 ? at : (long long)a.tag,
                   "cell " + std::to_string(k + 1) + "'s offset " + std::to_string(v[k]) +
                       (v[k] < last ? " is below the one before it (" + std::to_string(last) + "): offsets never decrease"
                                    : " passes the " + std::to_string(limit) + " values of the connectivity array") +
                       ": the file is corrupt");
    }
}

} // namespace

void checkVtuData(const std::string& path, const VtuLayout& l) {
    for (const VtuLayout::Piece& p : l.pieces) {
        // every array's base64 text decodes and every compressed block decompresses, or fails
        for (const VtuArrayLayout& a : p.arrays)
            if (l.compressed || a.base64) valueData(path, l, a, a.tag == p.types.tag ? "cell types" : detail::quoted(a.name));
        if (p.connectivity.tag != 0 && p.connectivity.typeBytes > 0) checkOffsets(path, l, p.offsets, p.connectivity.values);
    }
}

} // namespace fascia::meshio::detail
