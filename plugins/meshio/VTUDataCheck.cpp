// The cell arrays of a .vtu checked before VTK reads them (see VTUDataCheck.h).
#include "VTUDataCheck.h"

#include "ReaderSupport.h"

#include <vtkDataCompressor.h>
#include <vtkLZ4DataCompressor.h>
#include <vtkLZMADataCompressor.h>
#include <vtkSmartPointer.h>
#include <vtkZLibDataCompressor.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <string_view>
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
/// Without `keep`, only the check: one block in memory at a time.
std::string valueData(const std::string& path, const VtuLayout& l, const VtuArrayLayout& a, const std::string& what, bool keep) {
    const std::vector<VtuBlock> blocks = vtuBlocks(l, a, path);
    if (!l.compressed) return blocks.empty() ? std::string() : blocks[0].bytes;
    vtkSmartPointer<vtkDataCompressor> z = compressorFor(l);
    std::string out;
    std::unique_ptr<unsigned char[]> scratch;  // without `keep`: not zero-filled, so untouched beyond what inflates
    size_t scratchSize = 0;
    for (size_t k = 0; k < blocks.size(); ++k) {
        const VtuBlock& b = blocks[k];
        unsigned char* to = nullptr;
        if (keep) {
            const size_t first = out.size();
            out.resize(first + size_t(b.size));
            to = reinterpret_cast<unsigned char*>(&out[first]);
        } else {
            if (scratchSize < b.size) {
                scratch.reset(new unsigned char[size_t(b.size)]);
                scratchSize = size_t(b.size);
            }
            to = scratch.get();
        }
        const size_t got = b.size == 0 ? 0 :
            z->Uncompress(reinterpret_cast<const unsigned char*>(b.bytes.data()), b.bytes.size(), to, size_t(b.size));
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

/// The numbers of an ascii array, each as VTK 9.1 reads it (an istream of the array's type, which
/// fails on anything else: VTK then dereferences a null array or leaks the cell types; found by
/// fuzz_vtu): whole numbers within the type's range for an integer type (into `out`), decimal
/// numbers for a float type (no nan, inf or hexadecimal).
void asciiNumbers(const std::string& path, const std::string& t, const VtuArrayLayout& a, std::vector<long long>* out) {
    const size_t close = t.find('<', a.data), end = close == std::string::npos ? t.size() : close;
    auto space = [](char c) { return c == ' ' || c == '\n' || c == '\r' || c == '\t'; };
    const bool real = a.type.rfind("Float", 0) == 0, isSigned = a.type[0] == 'I';
    const int bits = 8 * a.typeBytes;
    // VTK reads 8-bit values through a short
    const long long lo = bits == 8 ? -32768 : !isSigned ? 0 : bits >= 64 ? INT64_MIN : -(1ll << (bits - 1));
    const unsigned long long hi = bits == 8 ? 32767
                                  : bits >= 64 ? (isSigned ? (unsigned long long)INT64_MAX : UINT64_MAX)
                                               : (isSigned ? (1ull << (bits - 1)) - 1 : (1ull << bits) - 1);
    std::string token;
    for (size_t p = a.data; p < end;) {
        if (space(t[p])) {
            ++p;
            continue;
        }
        size_t q = p;
        while (q < end && !space(t[q])) ++q;
        const char *b = t.data() + p, *e = t.data() + q;
        bool ok = false;
        long long v = 0;
        if (real) {
            // strtod and strtof as the istream: an overflow to infinity fails, an underflow does not
            token.assign(b, e);
            char* stop = nullptr;
            const double d = bits == 32 ? double(std::strtof(token.c_str(), &stop)) : std::strtod(token.c_str(), &stop);
            ok = token.find_first_not_of("0123456789+-.eE") == std::string::npos && stop == token.c_str() + token.size() &&
                 !token.empty() && std::isfinite(d);
        } else if (*b == '-') {
            const auto r = std::from_chars(b, e, v);
            ok = r.ec == std::errc() && r.ptr == e && v >= lo;
        } else {
            unsigned long long u = 0;
            const char* from = b + (*b == '+');
            const auto r = std::from_chars(from, e, u);
            ok = r.ec == std::errc() && r.ptr == e && e > from && u <= hi;
            v = (long long)std::min<unsigned long long>(u, (unsigned long long)INT64_MAX);
        }
        if (!ok)
            failAtByte(path, (long long)p, "DataArray " + detail::quoted(a.name) + " holds " + detail::quoted(t.substr(p, std::min<size_t>(q - p, 40))) +
                                               (real ? ", not a decimal number" : ", not a whole number of its type " + a.type));
        if (out) out->push_back(v);
        p = q;
    }
}

/// A Piece's offsets: whole numbers from >= 0, never decreasing, the last at most `limit`.
void checkOffsets(const std::string& path, const VtuLayout& l, const VtuArrayLayout& a, unsigned long long limit) {
    if (a.tag == 0 || a.typeBytes <= 0) return;
    std::vector<long long> v;
    if (a.format == "ascii") {
        if (a.type.rfind("Float", 0) == 0)
            failAtByte(path, (long long)a.tag, "the cell offsets array has the type " + detail::quoted(a.type) + ": expected whole numbers");
        asciiNumbers(path, l.text, a, &v);
    } else {
        const std::string bytes = valueData(path, l, a, "cell offsets", true);
        const size_t n = bytes.size() / size_t(a.typeBytes);
        v.resize(n);
        for (size_t k = 0; k < n; ++k)
            if (!integerAt(bytes, a, l.bigEndian, k, v[k]))
                failAtByte(path, (long long)a.tag, "the cell offsets array has the type " + detail::quoted(a.type) + " or a value past 2^63: expected whole numbers");
    }
    long long last = 0;
    for (size_t k = 0; k < v.size(); ++k) {
        const bool wrong = v[k] < last || v[k] < 0 || (unsigned long long)v[k] > limit;
        if (!wrong) {
            last = v[k];
            continue;
        }
        const long long at = vtuValueBytes(l, a, {k})[0];
        failAtByte(path, at >= 0 ? at : (long long)a.tag,
                   "cell " + std::to_string(k + 1) + "'s offset " + std::to_string(v[k]) +
                       (v[k] < 0 ? std::string(" is negative")
                        : v[k] < last ? " is below the one before it (" + std::to_string(last) + "): offsets never decrease"
                                    : " passes the " + std::to_string(limit) + " values of the connectivity array") +
                       ": the file is corrupt");
    }
}

} // namespace

void checkVtuData(const std::string& path, const VtuLayout& l) {
    for (const VtuLayout::Piece& p : l.pieces) {
        // every array's base64 text decodes and every compressed block decompresses, or fails
        for (const VtuArrayLayout& a : p.arrays) {
            if (a.format == "ascii") asciiNumbers(path, l.text, a, nullptr);
            else if (l.compressed || a.base64) valueData(path, l, a, a.tag == p.types.tag ? "cell types" : detail::quoted(a.name), false);
        }
        if (p.connectivity.tag != 0 && p.connectivity.typeBytes > 0) checkOffsets(path, l, p.offsets, p.connectivity.values);
    }
}

} // namespace fascia::meshio::detail
