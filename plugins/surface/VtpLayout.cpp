// Scanning a .vtp's tags and data headers before VTK reads it: VtpLayout.h. The XML part (up to
// <AppendedData>) is scanned tag by tag, as VTK's parser sees it (comments, processing instructions
// and CDATA skipped, '>' inside quotes kept in the tag); each DataArray's data header is decoded
// where it is (inline base64, appended raw or base64) and checked against what the file holds.
#include "VtpLayout.h"
#include "fascia/base/Error.h"

#include <charconv>
#include <cstring>
#include <string_view>
#include <utility>

namespace fascia::surface::detail {

const char* const kVtpSectionNames[kSections] = {"Verts", "Lines", "Strips", "Polys"};

namespace {

/// Deflate expands at most 1032:1 and LZ4 255:1; LZMA has no such bound in theory, but a surface
/// whose data expands more than this is no surface.
constexpr unsigned long long kMaxExpansion = 1032;

/// The Piece's attribute that counts the cells of each section.
const char* const kCountKeys[kSections] = {"NumberOfVerts", "NumberOfLines", "NumberOfStrips", "NumberOfPolys"};

bool space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

/// Text of the file in a message: at most 40 characters, a byte that is not printable ASCII shown
/// as '?' (the file may be anything).
std::string quoted(std::string_view s) {
    std::string out = "'";
    for (const char c : s.substr(0, 40)) out += c >= ' ' && c < 127 ? c : '?';
    if (s.size() > 40) out += "...";
    return out + "'";
}

int typeBytes(const std::string& type) {
    if (type == "Int8" || type == "UInt8") return 1;
    if (type == "Int16" || type == "UInt16") return 2;
    if (type == "Int32" || type == "UInt32" || type == "Float32") return 4;
    if (type == "Int64" || type == "UInt64" || type == "Float64") return 8;
    return 0;
}

/// Whether `tag` (the text between '<' and '>') has attribute `key`, and its value: after a space,
/// the key, '=' with optional spaces around it, in double quotes.
bool attribute(std::string_view tag, std::string_view key, std::string& value) {
    for (size_t p = tag.find(key); p != std::string_view::npos; p = tag.find(key, p + 1)) {
        if (p == 0 || !space(tag[p - 1])) continue;
        size_t q = p + key.size();
        while (q < tag.size() && space(tag[q])) ++q;
        if (q >= tag.size() || tag[q] != '=') continue;
        for (++q; q < tag.size() && space(tag[q]);) ++q;
        if (q >= tag.size() || tag[q] != '"') continue;
        const size_t e = tag.find('"', q + 1);
        value = std::string(tag.substr(q + 1, e == std::string_view::npos ? std::string_view::npos : e - q - 1));
        return true;
    }
    value.clear();
    return false;
}

class Scanner {
public:
    Scanner(const std::string& text, const std::string& path) : m_t(text), m_path(path) {}
    VtpLayout run();

private:
    [[noreturn]] void failAt(size_t at, const std::string& message) const {
        core::throwInputError(core::SourceLoc{m_path, 0, (long long)at}, message);
    }
    void start();
    void appendedData(size_t at);
    void element(size_t at, std::string_view tag, size_t bodyStart, bool selfClosing);
    void fileTag(size_t at, std::string_view tag);
    void pieceTag(size_t at, std::string_view tag);
    void plainAttributes(size_t at, std::string_view tag, const std::string& name) const;
    unsigned long long number(size_t at, std::string_view tag, const char* key, const char* what) const;
    void dataArray(size_t at, std::string_view tag, size_t bodyStart, bool selfClosing);
    void checkCount(const VtpArray& a, unsigned long long tuples, const std::string& what) const;
    std::vector<unsigned long long> words(size_t at, size_t end, bool base64, size_t n, size_t where) const;
    unsigned long long announcedBytes(size_t at, size_t end, bool base64, size_t where) const;
    void finish() const;

    const std::string& m_t;
    const std::string& m_path;
    VtpLayout m_l;
    size_t m_fileAt = std::string::npos, m_xmlEnd = std::string::npos, m_appended = 0;
    bool m_appendedBase64 = false;
    int m_pieces = 0;
    std::string m_context;         ///< the section the scan is in: Points, PointData, Polys, ... ("": none)
    unsigned m_sectionsSeen = 0;   ///< the cell sections met in the Piece (a bit each)
};

/// Refuses what is no XML at all, before looking for tags.
void Scanner::start() {
    size_t first = 0;
    if (m_t.compare(0, 3, "\xEF\xBB\xBF") == 0) first = 3;  // a UTF-8 byte order mark
    while (first < m_t.size() && space(m_t[first])) ++first;
    if (first >= m_t.size() || m_t[first] != '<')
        failAt(first, "not an XML file: a .vtp (VTK XML PolyData) file starts with <?xml ...?> or <VTKFile type=\"PolyData\" ...>; "
                      "it starts with " + quoted(m_t.substr(first, 16)));
}

VtpLayout Scanner::run() {
    start();
    m_xmlEnd = m_t.find("<AppendedData");  // VTK's parser stops at the first, whatever follows it
    if (m_xmlEnd != std::string::npos) appendedData(m_xmlEnd);
    const std::string_view xml = std::string_view(m_t).substr(0, m_xmlEnd);
    for (size_t p = xml.find('<'); p != std::string_view::npos; p = xml.find('<', p + 1)) {
        // what VTK's parser takes for no element
        for (const auto& [open, close] : {std::pair{"<!--", "-->"}, {"<![CDATA[", "]]>"}, {"<?", "?>"}, {"<!", ">"}}) {
            if (xml.compare(p, std::strlen(open), open) != 0) continue;
            const size_t e = xml.find(close, p);
            if (e == std::string_view::npos) failAt(p, "an unterminated " + std::string(open) + " in the XML: the file is truncated or corrupt");
            p = e;
            break;
        }
        if (xml[p] != '<') continue;
        size_t e = p + 1;  // the '>' that ends the tag, outside quotes
        for (char q = 0; e < xml.size() && (q || xml[e] != '>'); ++e)
            if (xml[e] == '"' || xml[e] == '\'') q = q == xml[e] ? 0 : q ? q : xml[e];
        if (e >= xml.size()) failAt(p, "a tag without its '>': the file is truncated or corrupt");
        const bool selfClosing = xml[e - 1] == '/';
        element(p, xml.substr(p + 1, e - p - 1 - (selfClosing ? 1 : 0)), e + 1, selfClosing);
        p = e;
    }
    finish();
    m_l.compressed = !m_l.compressor.empty();
    return m_l;
}

/// VTK 9.1 takes the data to start one byte after the first non-space after the tag (which must be
/// the '_'), has no stream for an encoding other than raw and base64 and reads through a null one,
/// and takes <AppendedDataX> for the appended data too.
void Scanner::appendedData(size_t at) {
    const size_t after = at + 13;
    if (!(after < m_t.size() && (space(m_t[after]) || m_t[after] == '>' || m_t[after] == '/')))
        failAt(at, "a tag named <AppendedData...> but not <AppendedData>: VTK takes it for the appended data and finds none");
    const size_t e = m_t.find('>', at);
    if (e == std::string::npos) failAt(at, "<AppendedData> has no '>': the file is truncated");
    const std::string_view tag = std::string_view(m_t).substr(at + 1, e - at - 1);
    plainAttributes(at, tag, "AppendedData");
    std::string encoding;
    attribute(tag, "encoding", encoding);
    if (encoding != "raw" && encoding != "base64")
        failAt(at, "<AppendedData> has the encoding " + quoted(encoding) + ": expected raw or base64");
    m_appendedBase64 = encoding == "base64";
    size_t u = e + 1;
    while (u < m_t.size() && space(m_t[u])) ++u;
    if (u >= m_t.size() || m_t[u] != '_') failAt(at, "<AppendedData> has no '_' right before its data");
    m_appended = u + 1;
}

/// A tag whose attributes the scan reads has them in double quotes without references: XML also
/// allows single quotes and "&#111;", which VTK's parser would read and the scan would not.
void Scanner::plainAttributes(size_t at, std::string_view tag, const std::string& name) const {
    bool inQuotes = false;
    for (size_t i = 0; i < tag.size(); ++i) {
        if (tag[i] == '"') inQuotes = !inQuotes;
        if (!inQuotes && tag[i] == '\'') failAt(at, "the <" + name + "> tag has an attribute in single quotes: write them in double quotes");
    }
    if (tag.find('&') != std::string_view::npos)
        failAt(at, "the <" + name + "> tag has an & (a character reference) in it: write its attributes without them");
}

unsigned long long Scanner::number(size_t at, std::string_view tag, const char* key, const char* what) const {
    std::string v;
    if (!attribute(tag, key, v)) return 0;  // VTK takes a missing count for 0
    unsigned long long n = 0;
    const auto [ptr, ec] = std::from_chars(v.data(), v.data() + v.size(), n);
    if (v.empty() || ec != std::errc() || ptr != v.data() + v.size())
        failAt(at, std::string("the ") + what + "'s " + key + " " + quoted(v) + " is not a whole number >= 0");
    return n;
}

void Scanner::element(size_t at, std::string_view tag, size_t bodyStart, bool selfClosing) {
    const std::string name(tag.substr(0, tag.find_first_of(" \t\r\n")));
    const bool array = name == "DataArray" || name == "Array";  // VTK reads both
    if (m_fileAt == std::string::npos && name != "VTKFile")
        failAt(at, "the first element is <" + name.substr(0, 40) + ">, not <VTKFile>: not a VTK XML file (a .vtp surface starts with "
                   "<VTKFile type=\"PolyData\" ...>)");
    if (name == "VTKFile") return fileTag(at, tag);
    if (name == "Piece") return pieceTag(at, tag);
    if (array) return dataArray(at, tag, bodyStart, selfClosing);
    static const char* const sections[] = {"Points", "PointData", "CellData", "FieldData", "Verts", "Lines", "Strips", "Polys"};
    for (const char* s : sections) {
        if (name == s && !selfClosing) {
            m_context = s;
            for (int k = 0; k < kSections; ++k) {
                if (name != kVtpSectionNames[k]) continue;
                // VTK keeps one of them: which one a file with two means is not clear
                if (m_sectionsSeen & (1u << k)) failAt(at, "a second <" + name + "> in the Piece: a Piece has one");
                m_sectionsSeen |= 1u << k;
            }
        }
        if (name == std::string("/") + s) m_context.clear();
    }
}

/// The root: type PolyData, and how every array is stored. VTK 9.1 makes no compressor for a
/// class it does not know and then decompresses with it (a null dereference).
void Scanner::fileTag(size_t at, std::string_view tag) {
    if (m_fileAt != std::string::npos)
        failAt(at, "a second <VTKFile> tag (the first is at byte " + std::to_string(m_fileAt) + "): a .vtp has one root element");
    m_fileAt = at;
    plainAttributes(at, tag, "VTKFile");
    std::string type, header, order;
    attribute(tag, "type", type);
    if (type != "PolyData")
        failAt(at, "not VTK XML PolyData: the VTKFile's type is " + quoted(type) + (type == "UnstructuredGrid" ? " (a .vtu mesh?)" : "") +
                       "; a .vtp surface starts with <VTKFile type=\"PolyData\" ...>");
    attribute(tag, "header_type", header);
    attribute(tag, "compressor", m_l.compressor);
    attribute(tag, "byte_order", order);
    if (!header.empty() && header != "UInt32" && header != "UInt64")
        failAt(at, "VTKFile has header_type " + quoted(header) + ": expected UInt32 or UInt64");
    if (!m_l.compressor.empty() && m_l.compressor != "vtkZLibDataCompressor" && m_l.compressor != "vtkLZ4DataCompressor" &&
        m_l.compressor != "vtkLZMADataCompressor")
        failAt(at, "VTKFile has compressor " + quoted(m_l.compressor) +
                       ": expected vtkZLibDataCompressor, vtkLZ4DataCompressor or vtkLZMADataCompressor");
    if (!order.empty() && order != "LittleEndian" && order != "BigEndian")
        failAt(at, "VTKFile has byte_order " + quoted(order) + ": expected LittleEndian or BigEndian");
    m_l.header64 = header == "UInt64";
    m_l.bigEndian = order == "BigEndian";
}

void Scanner::pieceTag(size_t at, std::string_view tag) {
    // Fascia writes one Piece; a file of several (parallel output) is joined by VTK with shifted
    // point numbers, which would make the errors' places hard to tell
    if (++m_pieces > 1) failAt(at, "a second <Piece>: Fascia reads a .vtp of one Piece (merge the pieces, e.g. in ParaView)");
    plainAttributes(at, tag, "Piece");
    m_l.piece = at;
    m_l.points = number(at, tag, "NumberOfPoints", "Piece");
    for (int k = 0; k < kSections; ++k) m_l.cells[size_t(k)].count = number(at, tag, kCountKeys[k], "Piece");
}

void Scanner::dataArray(size_t at, std::string_view tag, size_t bodyStart, bool selfClosing) {
    plainAttributes(at, tag, "DataArray");
    VtpArray a;
    a.tag = at;
    attribute(tag, "Name", a.name);
    attribute(tag, "type", a.type);
    attribute(tag, "format", a.format);
    std::string text;
    if (attribute(tag, "NumberOfComponents", text)) {
        const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), a.components);
        if (text.empty() || ec != std::errc() || ptr != text.data() + text.size() || a.components == 0 || a.components > 2147483647ULL)
            failAt(at, "DataArray " + quoted(a.name) + " has NumberOfComponents " + quoted(text) + ": expected a whole number from 1");
    }
    // VTK 9.1 makes no array for a type it does not know and then reads into it; text and bit
    // arrays have layouts of their own, and a surface needs numbers only
    a.typeBytes = typeBytes(a.type);
    if (a.typeBytes == 0)
        failAt(at, "DataArray " + quoted(a.name) + " has the type " + quoted(a.type) +
                       ": expected Int8, UInt8, Int16, UInt16, Int32, UInt32, Int64, UInt64, Float32 or Float64 (Fascia reads numeric arrays only)");
    // without a format VTK 9.1 takes an array for appended data and allocates what is there
    if (a.format != "ascii" && a.format != "binary" && a.format != "appended")
        failAt(at, "DataArray " + quoted(a.name) + " has the format " + quoted(a.format) + ": expected ascii, binary or appended");
    const size_t next = selfClosing ? bodyStart : std::min(m_t.find('<', bodyStart), m_xmlEnd);
    if (a.format == "ascii") {
        a.data = bodyStart;
        a.end = next == std::string::npos ? m_t.size() : next;
        for (size_t p = a.data; p < a.end; ++p)
            if (!space(m_t[p]) && (p == a.data || space(m_t[p - 1]))) ++a.values;
    } else if (a.format == "binary") {
        a.base64 = true;
        a.data = bodyStart;
        a.end = next == std::string::npos ? m_t.size() : next;
        while (a.data < a.end && space(m_t[a.data])) ++a.data;
        if (a.data < a.end) a.values = announcedBytes(a.data, a.end, true, at) / unsigned(a.typeBytes);
    } else {
        if (m_appended == 0) failAt(at, "DataArray " + quoted(a.name) + " is appended, but the file has no <AppendedData>");
        unsigned long long offset = 0;
        attribute(tag, "offset", text);
        const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), offset);
        if (text.empty() || ec != std::errc() || ptr != text.data() + text.size() || offset > m_t.size() - m_appended)
            failAt(at, "DataArray " + quoted(a.name) + " has the offset " + quoted(text) + ", past the end of the appended data");
        a.base64 = m_appendedBase64;
        a.data = m_appended + size_t(offset);
        a.end = m_t.size();
        a.values = announcedBytes(a.data, a.end, a.base64, at) / unsigned(a.typeBytes);
    }

    // what it is, and the values it must hold
    unsigned long long cells = 0;
    for (const auto& c : m_l.cells) cells += c.count;
    if (m_context == "Points" && m_l.points3.tag == 0) {
        if (a.components != 3) failAt(at, "the Points array has " + std::to_string(a.components) + " components: expected 3 (x y z)");
        checkCount(a, m_l.points, "NumberOfPoints");
        m_l.points3 = a;
    } else if (m_context == "PointData") {
        checkCount(a, m_l.points, "NumberOfPoints");
    } else if (m_context == "CellData") {
        checkCount(a, cells, "the Piece's cell count (verts, lines, strips and polys)");
    } else if (m_context == "FieldData") {
        if (attribute(tag, "NumberOfTuples", text)) checkCount(a, number(at, tag, "NumberOfTuples", "DataArray"), "its NumberOfTuples");
    }
    for (int k = 0; k < kSections; ++k) {
        if (m_context != kVtpSectionNames[k]) continue;
        VtpLayout::Cells& c = m_l.cells[size_t(k)];
        // the first of a name, as VTK takes it
        if (a.name == "offsets" && c.offsets.tag == 0) {
            checkCount(a, c.count, kCountKeys[k]);
            c.offsets = a;
        }
        if (a.name == "connectivity" && c.connectivity.tag == 0) c.connectivity = a;
    }
}

/// The values an array must hold: one tuple of its components for each of `tuples`.
void Scanner::checkCount(const VtpArray& a, unsigned long long tuples, const std::string& what) const {
    const bool overflow = tuples > 0 && a.components > ~0ULL / tuples;
    if (!overflow && a.values == tuples * a.components) return;
    failAt(a.tag, "DataArray " + quoted(a.name) + " of <" + m_context + "> holds " + std::to_string(a.values) + " values, but " + what + " " +
                      std::to_string(tuples) + " needs " + (overflow ? "more" : std::to_string(tuples * a.components)) + " (" +
                      std::to_string(a.components) + " per tuple): the counts lie or the file is truncated");
}

/// n header words (of the header type) of the data at `at`: raw bytes, or base64 text; fails when
/// they pass `end`.
std::vector<unsigned long long> Scanner::words(size_t at, size_t end, bool base64, size_t n, size_t where) const {
    const size_t w = m_l.header64 ? 8 : 4;
    std::string bytes;
    if (!base64) {
        if (at > end || n > (end - at) / w) failAt(where, "the data header passes the end of the file: the file is truncated");
        bytes = m_t.substr(at, n * w);
    } else {
        bytes = decodeBase64(m_t, at, end, n * w, false);
        if (bytes.size() < n * w) failAt(where, "the base64 data header is shorter than its " + std::to_string(n * w) + " bytes: the file is truncated");
    }
    std::vector<unsigned long long> out(n);
    for (size_t i = 0; i < n; ++i)
        for (size_t k = 0; k < w; ++k) out[i] = (out[i] << 8) | (unsigned char)bytes[i * w + (m_l.bigEndian ? k : w - 1 - k)];
    return out;
}

/// The uncompressed bytes the data at `at` announces, checked against what the file holds up to
/// `end`: without compression one word, the size; with it, the blocks, their size, the last one's
/// size and each one's compressed size.
unsigned long long Scanner::announcedBytes(size_t at, size_t end, bool base64, size_t where) const {
    const size_t w = m_l.header64 ? 8 : 4;
    const unsigned long long stored = base64 ? (end - at) / 4 * 3 : end - at;  // at most this many bytes there
    if (m_l.compressor.empty()) {
        const unsigned long long n = words(at, end, base64, 1, where)[0];
        if (n > stored)
            failAt(where, "the data header announces " + std::to_string(n) + " bytes, but only " + std::to_string(stored) +
                              " follow in the file: the header lies or the file is truncated");
        return n;
    }
    const unsigned long long blocks = words(at, end, base64, 1, where)[0];
    if (blocks > stored / w)
        failAt(where, "the compressed data header announces " + std::to_string(blocks) + " blocks, more than the file holds: the header is corrupt");
    if (blocks == 0) return 0;
    const auto h = words(at, end, base64, 3 + size_t(blocks), where);
    const unsigned long long blockSize = h[1], last = h[2];
    // VTK 9.1 divides by the block size, and takes the last block to hold at most one
    if (blockSize == 0 || last > blockSize)
        failAt(where, "the compressed data header gives a block size of " + std::to_string(blockSize) + " and a last block of " +
                          std::to_string(last) + " bytes: the header is corrupt");
    unsigned long long compressed = 0, total = 0;
    for (unsigned long long b = 0; b < blocks; ++b) {
        const unsigned long long c = h[size_t(3 + b)], u = (b + 1 == blocks && last != 0) ? last : blockSize;
        if (c > stored || u > kMaxExpansion * c + 64)
            failAt(where, "compressed block " + std::to_string(b) + " announces " + std::to_string(u) + " bytes from " + std::to_string(c) +
                              " compressed ones" + (c > stored ? ", more than the file holds" : ", more than any compressor expands") +
                              ": the header is corrupt");
        compressed += c;
        total += u;
    }
    if (compressed > stored)
        failAt(where, "the compressed blocks announce " + std::to_string(compressed) + " bytes, but only " + std::to_string(stored) +
                          " follow in the file: the header lies or the file is truncated");
    return total;
}

/// What VTK needs to find in the Piece; a file without one is empty.
void Scanner::finish() const {
    if (m_fileAt == std::string::npos)
        failAt(0, "no <VTKFile> tag: not a VTK XML file; a .vtp surface starts with <VTKFile type=\"PolyData\" ...>");
    if (m_pieces == 0) failAt(m_fileAt, "the file has no <Piece>: it holds no surface (is it complete?)");
    if (m_l.points > 0 && m_l.points3.tag == 0)
        failAt(m_l.piece, "the Piece announces " + std::to_string(m_l.points) + " points but has no Points array: the file is incomplete");
    for (int k = 0; k < kSections; ++k) {
        const VtpLayout::Cells& c = m_l.cells[size_t(k)];
        if (c.count == 0) continue;  // VTK reads no array of an empty section
        for (const VtpArray* a : {&c.offsets, &c.connectivity})
            if (a->tag == 0)
                failAt(m_l.piece, "the Piece announces " + std::string(kCountKeys[k]) + "=\"" + std::to_string(c.count) + "\" but its <" +
                                      kVtpSectionNames[k] + "> has no " + (a == &c.offsets ? "offsets" : "connectivity") +
                                      " array: the file is incomplete");
    }
}

} // namespace


VtpLayout scanVtp(const std::string& text, const std::string& path) { return Scanner(text, path).run(); }

VtpValueBytes::VtpValueBytes(const std::string& text, const VtpLayout& layout, const VtpArray& array)
    : m_array(array), m_compressed(layout.compressed), m_word(layout.header64 ? 8 : 4) {
    if (array.format != "ascii") return;
    for (size_t p = array.data; p < array.end; ++p)
        if (!space(text[p]) && (p == array.data || space(text[p - 1]))) m_ascii.push_back(p);
}

long long VtpValueBytes::at(unsigned long long value) const {
    const VtpArray& a = m_array;
    if (a.format == "ascii") return value < m_ascii.size() ? (long long)m_ascii[size_t(value)] : (long long)a.tag;
    if (m_compressed || a.typeBytes <= 0) return (long long)a.tag;
    const unsigned long long byte = m_word + value * unsigned(a.typeBytes);  // in the decoded data, after the size word
    const unsigned long long p = a.base64 ? a.data + byte / 3 * 4 : a.data + byte;  // base64 written without spaces, as VTK does
    return p < a.end ? (long long)p : (long long)a.tag;
}

} // namespace fascia::surface::detail
