// Checks of a .vtu's announced sizes before VTK allocates them (see VTUHeaderCheck.h). The XML part
// is scanned for its VTKFile, Piece, Points/Cells/PointData/CellData and DataArray tags; the data
// headers are decoded where they are (inline base64, appended raw or base64).
#include "VTUHeaderCheck.h"
#include "fascia/surface/VtkXmlText.h"

#include "ReaderSupport.h"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace fascia::meshio::detail {
namespace {

/// Deflate (ZLib) expands at most 1032:1 and LZ4 at most 255:1; LZMA has no such bound in theory,
/// but a mesh block that expands more than this is no mesh.
constexpr unsigned long long kMaxExpansion = 1032;

class VtuChecker {
public:
    VtuChecker(const std::string& text, const std::string& path) : m_t(text), m_path(path) {}
    /// For vtuValueBytes: the file of a layout the check made (it passed, so nothing here fails).
    explicit VtuChecker(const VtuLayout& l)
        : m_t(l.text), m_path(kNoPath), m_header64(l.header64), m_compressed(l.compressed), m_bigEndian(l.bigEndian) {}
    /// For vtuBlocks: the same, failing with the file's name.
    VtuChecker(const VtuLayout& l, const std::string& path)
        : m_t(l.text), m_path(path), m_header64(l.header64), m_compressed(l.compressed), m_bigEndian(l.bigEndian) {}
    VtuLayout takeLayout() {
        m_layout.header64 = m_header64;
        m_layout.compressed = m_compressed;
        m_layout.bigEndian = m_bigEndian;
        m_layout.compressor = m_compressor;
        return std::move(m_layout);
    }

    void run() {
        const size_t appended = appendedTag();
        const std::string_view xml = std::string_view(m_t).substr(0, appended);
        if (appended != std::string::npos) appendedStart(appended);
        std::string context;
        for (size_t p = xml.find('<'); p != std::string_view::npos; p = xml.find('<', p + 1)) {
            const size_t e = xml.find('>', p);
            if (e == std::string_view::npos) break;
            const std::string_view tag = xml.substr(p + 1, e - p - 1);
            const std::string name(tag.substr(0, tag.find_first_of(" \t\r\n/>")));
            if (name == "VTKFile" || name == "Piece" || name == "DataArray") plainAttributes(tag, name, p);
            if (m_fileAt == std::string::npos && (name == "Piece" || name == "DataArray"))  // how is it stored?
                failAt(p, "a <" + name + "> before any <VTKFile> tag: a .vtu file starts with <VTKFile type=\"UnstructuredGrid\" ...>");
            if (name == "VTKFile") {
                // one root: its attributes say how every array is stored
                if (m_fileAt != std::string::npos)
                    failAt(p, "a second <VTKFile> tag (the first is at byte " + std::to_string(m_fileAt) + "): a .vtu has one root element");
                m_fileAt = p;
                fileAttributes(tag, p);
            } else if (name == "Piece") {
                pieceEnd();
                m_pieceAt = p;
                m_points = count(tag, "NumberOfPoints", p);
                m_cells = count(tag, "NumberOfCells", p);
                m_layout.pieces.push_back({p, m_points, m_cells, {}, {}, {}, {}, {}});
            } else if (name == "Points" || name == "Cells" || name == "PointData" || name == "CellData" ||
                       name == "FieldData") {
                context = name;
                m_names.clear();
            } else if (name == "/Points" || name == "/Cells" || name == "/PointData" || name == "/CellData" ||
                       name == "/FieldData") {
                context.clear();
            } else if (name == "DataArray") {
                dataArray(tag, context, p, e + 1);
            }
        }
        pieceEnd();
    }

private:
    /// The VTKFile tag's header type, compressor and byte order. VTK 9.1 makes no compressor for a
    /// class name it does not know and then decompresses with it (a null dereference in
    /// vtkXMLDataReader::ReadPieceData), so only the names it knows pass; the others likewise.
    void fileAttributes(std::string_view tag, size_t at) {
        const std::string header = attribute(tag, "header_type"), compressor = attribute(tag, "compressor"),
                          order = attribute(tag, "byte_order");
        if (!header.empty() && header != "UInt32" && header != "UInt64")
            failAt(at, "VTKFile has header_type " + quoted(header) + ": expected UInt32 or UInt64");
        if (!compressor.empty() && compressor != "vtkZLibDataCompressor" && compressor != "vtkLZ4DataCompressor" &&
            compressor != "vtkLZMADataCompressor")
            failAt(at, "VTKFile has compressor " + quoted(compressor) +
                           ": expected vtkZLibDataCompressor, vtkLZ4DataCompressor or vtkLZMADataCompressor");
        if (!order.empty() && order != "LittleEndian" && order != "BigEndian")
            failAt(at, "VTKFile has byte_order " + quoted(order) + ": expected LittleEndian or BigEndian");
        m_header64 = header == "UInt64";
        m_compressed = !compressor.empty();
        m_compressor = compressor;
        m_bigEndian = order == "BigEndian";
    }
    [[noreturn]] void failAt(size_t at, const std::string& message) const {
        failAtByte(m_path, (long long)at, message);
    }
    static bool space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
    /// The value of attribute `key` (after a space, "=" with optional spaces around it, in double
    /// quotes, as XML has it; plainAttributes refused single quotes and references).
    static std::string attribute(std::string_view tag, const char* key) {
        const std::string_view k(key);
        for (size_t p = tag.find(k); p != std::string_view::npos; p = tag.find(k, p + 1)) {
            if (p == 0 || !space(tag[p - 1])) continue;
            size_t q = p + k.size();
            while (q < tag.size() && space(tag[q])) ++q;
            if (q >= tag.size() || tag[q] != '=') continue;
            ++q;
            while (q < tag.size() && space(tag[q])) ++q;
            if (q >= tag.size() || tag[q] != '"') continue;
            const size_t e = tag.find('"', q + 1);
            return std::string(tag.substr(q + 1, e == std::string_view::npos ? std::string_view::npos : e - q - 1));
        }
        return {};
    }
    /// A tag whose attributes the check reads has them in double quotes and without references:
    /// XML allows single quotes and "&#111;", which the check would not see but VTK's parser would
    /// (Name="&#111;ffsets" is VTK's offsets array).
    void plainAttributes(std::string_view tag, const std::string& name, size_t at) const {
        bool quoted = false, single = false;
        for (size_t i = 0; i < tag.size(); ++i) {
            if (tag[i] == '"') quoted = !quoted;
            if (quoted || tag[i] != '=') continue;
            size_t j = i + 1;
            while (j < tag.size() && space(tag[j])) ++j;
            single = single || (j < tag.size() && tag[j] == '\'');
        }
        if (single || tag.find('&') != std::string_view::npos)
            failAt(at, "the <" + name + "> tag has an attribute in single quotes or an & in it: the check reads attributes in double quotes, without character references");
    }
    unsigned long long count(std::string_view tag, const char* key, size_t at) const {
        const std::string v = attribute(tag, key);
        unsigned long long n = 0;
        const auto [ptr, ec] = std::from_chars(v.data(), v.data() + v.size(), n);
        if (v.empty() || ec != std::errc() || ptr != v.data() + v.size())
            failAt(at, std::string("the Piece's ") + key + " " + quoted(v) + " is not a whole number >= 0");
        return n;
    }
    static int typeBytes(const std::string& type) {
        if (type == "Int8" || type == "UInt8") return 1;
        if (type == "Int16" || type == "UInt16") return 2;
        if (type == "Int32" || type == "UInt32" || type == "Float32") return 4;
        if (type == "Int64" || type == "UInt64" || type == "Float64") return 8;
        return 0;
    }
    /// A Piece with points needs a Points array, one with cells a cell types array.
    void pieceEnd() {
        if (m_points > 0 && !m_havePoints)
            failAt(m_pieceAt, "the Piece announces " + std::to_string(m_points) + " points but has no Points array: the file is incomplete or truncated");
        if (m_cells > 0 && !m_haveTypes)
            failAt(m_pieceAt, "the Piece announces " + std::to_string(m_cells) + " cells but has no cell types array: the file is incomplete or truncated");
        m_points = m_cells = 0;
        m_havePoints = m_haveTypes = false;
    }
    /// The byte of the <AppendedData> tag (npos: none). Its name alone: VTK 9.1 takes no
    /// <AppendedDataA> for it and then reads appended arrays through a null stream.
    size_t appendedTag() const {
        const size_t p = m_t.find("<AppendedData");  // VTK 9.1's parser stops at the first, whatever follows
        if (p == std::string::npos) return p;
        const size_t e = p + 13;
        if (!(e < m_t.size() && (space(m_t[e]) || m_t[e] == '>' || m_t[e] == '/')))
            failAt(p, "a tag named <AppendedData...> but not <AppendedData>: VTK 9.1 takes it for the appended data and finds none");
        return p;
    }
    void appendedStart(size_t tagAt) {
        // VTK 9.1 takes the data to start one character after the first non-space after the tag
        // (that character being the '_'): anything else there shifts every appended array
        const size_t tagEnd = m_t.find('>', tagAt);
        size_t u = tagEnd == std::string::npos ? m_t.size() : tagEnd + 1;
        while (u < m_t.size() && (m_t[u] == ' ' || m_t[u] == '\t' || m_t[u] == '\n' || m_t[u] == '\r')) ++u;
        if (u >= m_t.size() || m_t[u] != '_') failAt(tagAt, "<AppendedData> has no '_' right before its data");
        m_appended = u + 1;
        plainAttributes(std::string_view(m_t).substr(tagAt, tagEnd - tagAt), "AppendedData", tagAt);
        const std::string encoding = attribute(std::string_view(m_t).substr(tagAt, tagEnd - tagAt), "encoding");
        // VTK 9.1 has no data stream for another encoding and reads through a null one
        if (encoding != "raw" && encoding != "base64")
            failAt(tagAt, "<AppendedData> has the encoding " + quoted(encoding) + ": expected raw or base64");
        m_appendedBase64 = encoding == "base64";
    }

    /// Header words of the data at `at` (raw bytes, or base64 text when base64), n words of the
    /// header type; fails when they pass `end`.
    std::vector<unsigned long long> words(size_t at, size_t end, bool base64, size_t n, size_t where) const {
        const size_t w = m_header64 ? 8 : 4;
        std::string bytes;
        if (!base64) {
            if (at > end || n > (end - at) / w) failAt(where, "the data header passes the end of the file: it is truncated");
            bytes = m_t.substr(at, n * w);
        } else {
            bytes = decodeBase64(at, end, n * w, where);
        }
        std::vector<unsigned long long> out(n);
        for (size_t i = 0; i < n; ++i) {
            unsigned long long v = 0;
            for (size_t k = 0; k < w; ++k) {
                const auto byte = (unsigned char)bytes[i * w + (m_bigEndian ? k : w - 1 - k)];
                v = (v << 8) | byte;
            }
            out[i] = v;
        }
        return out;
    }
    std::string decodeBase64(size_t at, size_t end, size_t want, size_t where) const {
        std::string out = base64Bytes(at, end, want);
        if (out.size() < want) failAt(where, "the base64 data header is shorter than its " + std::to_string(want) + " bytes");
        return out;
    }
    /// Up to `want` bytes of the base64 text from `at` (whitespace skipped unless `strict`), up to
    /// `end`, padding or a character that is not base64. Strict, as VTK 9.1 decodes data (4
    /// characters at a time, every one base64).
    std::string base64Bytes(size_t at, size_t end, size_t want, bool strict = false) const {
        return surface::decodeBase64(m_t, at, end, want, strict);
    }

    /// Uncompressed bytes the data at `at` announces, checked against what is stored up to `end`.
    unsigned long long announcedBytes(size_t at, size_t end, bool base64, size_t where) const {
        const size_t w = m_header64 ? 8 : 4;
        const unsigned long long stored = base64 ? (end - at) / 4 * 3 : end - at;  // bytes the file holds there
        if (!m_compressed) {
            const unsigned long long n = words(at, end, base64, 1, where)[0];
            if (n > stored) failAt(where, "the data header announces " + std::to_string(n) + " bytes, but only " +
                                              std::to_string(stored) + " follow in the file: the header lies or the file is truncated");
            return n;
        }
        const auto h = words(at, end, base64, 3, where);
        const unsigned long long blocks = h[0], blockSize = h[1], last = h[2];
        if (blocks > stored / w) failAt(where, "the compressed data header announces " + std::to_string(blocks) +
                                                   " blocks, more than the file holds: the header is corrupt");
        if (blocks == 0) return 0;
        // VTK 9.1 divides by the block size, and takes the last block to hold at most one
        if (blockSize == 0 || last > blockSize)
            failAt(where, "the compressed data header gives a block size of " + std::to_string(blockSize) + " and a last block of " +
                              std::to_string(last) + " bytes: the header is corrupt");
        const auto sizes = words(at, end, base64, 3 + size_t(blocks), where);
        unsigned long long compressed = 0, total = 0;
        for (unsigned long long b = 0; b < blocks; ++b) {
            const unsigned long long c = sizes[size_t(3 + b)];
            const unsigned long long u = (b + 1 == blocks && last != 0) ? last : blockSize;
            if (c > stored) failAt(where, "compressed block " + std::to_string(b) + " announces " + std::to_string(c) +
                                              " bytes, more than the file holds: the header is corrupt");
            compressed += c;
            if (u > kMaxExpansion * c + 64)
                failAt(where, "compressed block " + std::to_string(b) + " announces " + std::to_string(u) +
                                  " bytes from " + std::to_string(c) + " compressed ones, more than any compressor "
                                  "expands: the header is corrupt");
            total += u;
        }
        if (compressed > stored) failAt(where, "the compressed blocks announce " + std::to_string(compressed) +
                                                   " bytes, but only " + std::to_string(stored) + " follow in the file");
        return total;
    }

    void dataArray(std::string_view tag, const std::string& context, size_t at, size_t bodyStart) {
        const std::string name = attribute(tag, "Name"), format = attribute(tag, "format");
        const std::string comps = attribute(tag, "NumberOfComponents");
        unsigned long long nc = 1;
        if (!comps.empty() && (std::from_chars(comps.data(), comps.data() + comps.size(), nc).ec != std::errc() || nc == 0))
            failAt(at, "DataArray " + quoted(name) + " has NumberOfComponents " + quoted(comps));
        // polyhedron cells: VTK 9.1 follows the counts in "faces" without bounds, and Fascia reads
        // tetrahedra and hexahedra only
        if (context == "Cells" && (name == "faces" || name == "faceoffsets" || name == "face_connectivity" ||
                                   name == "face_offsets" || name == "polyhedron_to_faces" || name == "polyhedron_offsets"))
            failAt(at, "DataArray " + quoted(name) + " describes polyhedron cells: Fascia reads tetrahedra and hexahedra");
        long long tuples = -1;  // unknown for connectivity
        if (context == "Points" || context == "PointData") tuples = (long long)m_points;
        else if (context == "CellData" || (context == "Cells" && (name == "types" || name == "offsets")))
            tuples = (long long)m_cells;
        // VTK 9.1 keeps one point or cell data array of a name, then reads every DataArray into the
        // arrays by position: a second of a name reads into a null one
        if ((context == "PointData" || context == "CellData") && !name.empty()) {
            if (std::find(m_names.begin(), m_names.end(), name) != m_names.end())
                failAt(at, "a second DataArray named " + quoted(name) + " in " + context + ": each of its arrays needs a name of its own");
            m_names.push_back(name);
        }
        if (context == "Points") m_havePoints = true;
        if (context == "Cells" && name == "types") m_haveTypes = true;
        const std::string type = attribute(tag, "type");
        const int tb = typeBytes(type);
        // VTK 9.1 makes no array for a type it does not know, then reads into it (a null dereference
        // in vtkXMLDataReader::ReadPieceData): refuse it here. String and Bit arrays too: Fascia
        // reads numbers only, and VTK 9.1 crashed reading a binary String array of cell data
        // (found by fuzz_vtu)
        if (tb == 0)
            failAt(at, "DataArray " + quoted(name) + " has the type " + quoted(type) +
                           ": expected Int8, UInt8, Int16, UInt16, Int32, UInt32, Int64, UInt64, Float32 or Float64 (Fascia reads numeric arrays only)");
        // without a format VTK 9.1 took an array for appended data and allocated what garbage in it
        // announced (640 GB): a DataArray says how it is stored
        if (format != "ascii" && format != "binary" && format != "appended")
            failAt(at, "DataArray " + quoted(name) + " has the format " + quoted(format) + ": expected ascii, binary or appended");
        VtuArrayLayout where{at, format, bodyStart, false, tb, type, name, 0};
        unsigned long long values = 0;
        bool known = true;
        if (format == "ascii" && tb > 0) {  // numbers only: a string array has its own layout
            const size_t close = m_t.find('<', bodyStart);
            values = asciiValues(bodyStart, close == std::string::npos ? m_t.size() : close);
        } else if (format == "binary" && tb > 0) {
            const size_t close = m_t.find('<', bodyStart);
            size_t s = bodyStart;
            while (s < m_t.size() && (m_t[s] == ' ' || m_t[s] == '\n' || m_t[s] == '\r' || m_t[s] == '\t')) ++s;
            where.data = s;
            where.base64 = true;
            values = announcedBytes(s, close == std::string::npos ? m_t.size() : close, true, at) / unsigned(tb);
        } else if (format == "appended" && tb > 0) {
            if (m_appended == 0) failAt(at, "DataArray " + quoted(name) + " is appended, but the file has no <AppendedData>");
            unsigned long long off = 0;
            const std::string o = attribute(tag, "offset");
            if (std::from_chars(o.data(), o.data() + o.size(), off).ec != std::errc() || off > m_t.size() - m_appended)
                failAt(at, "DataArray " + quoted(name) + " has the offset " + quoted(o) + ", past the end of the appended data");
            where.data = m_appended + size_t(off);
            where.base64 = m_appendedBase64;
            values = announcedBytes(where.data, m_t.size(), m_appendedBase64, at) / unsigned(tb);
        } else {
            known = false;  // not reached: the type and the format were checked above
        }
        where.values = values;
        if (!m_layout.pieces.empty() && known) {
            m_layout.pieces.back().arrays.push_back(where);
            // the first of a name, as VTK 9.1 takes it (FindDataArrayWithName)
            VtuLayout::Piece& piece = m_layout.pieces.back();
            if (context == "Cells" && name == "offsets" && piece.offsets.tag == 0) piece.offsets = where;
            if (context == "Points" && piece.points3.tag == 0) piece.points3 = where;
            if (context == "Cells" && name == "connectivity" && piece.connectivity.tag == 0) piece.connectivity = where;
            if (context == "Cells" && name == "types" && piece.types.tag == 0) piece.types = where;
        }
        if (known && tuples >= 0 && values != (unsigned long long)tuples * nc)
            failAt(at, "DataArray " + quoted(name) + " of " + context + " holds " + std::to_string(values) +
                           " values, but the Piece's " + (tuples == (long long)m_points && context.find("Point") == 0 ? "NumberOfPoints " : "NumberOfCells ") +
                           std::to_string(tuples) + " needs " + std::to_string((unsigned long long)tuples * nc) +
                           " (" + std::to_string(nc) + " per tuple): the counts lie or the file is truncated");
    }
    unsigned long long asciiValues(size_t b, size_t e) const {
        unsigned long long n = 0;
        bool in = false;
        for (size_t p = b; p < e; ++p) {
            const char c = m_t[p];
            const bool space = c == ' ' || c == '\n' || c == '\r' || c == '\t';
            if (!space && !in) ++n;
            in = !space;
        }
        return n;
    }

public:
    /// vtuValueBytes (VTUHeaderCheck.h).
    std::vector<long long> valueBytes(const VtuArrayLayout& a, const std::vector<unsigned long long>& indices) const;
    /// vtuBlocks (VTUHeaderCheck.h).
    std::vector<VtuBlock> blocks(const VtuArrayLayout& a) const;
    /// Where array a's data ends: the next tag for inline data, the end of the file for appended.
    size_t dataEnd(const VtuArrayLayout& a) const {
        const size_t close = a.format == "appended" ? std::string::npos : m_t.find('<', a.data);
        return close == std::string::npos ? m_t.size() : close;
    }
    /// A compressed array's header words (blocks, block size, last block size, then each block's
    /// compressed size; empty without blocks) and where its blocks start: in base64 the header and
    /// the blocks are encoded apart, the header's characters first.
    struct CompressedHeader {
        std::vector<unsigned long long> h;
        size_t blockData = 0;
    };
    CompressedHeader compressedHeader(const VtuArrayLayout& a, size_t end) const {
        const unsigned long long blocks = words(a.data, end, a.base64, 1, a.tag)[0];
        if (blocks == 0) return {};
        CompressedHeader c{words(a.data, end, a.base64, 3 + size_t(blocks), a.tag), 0};
        const unsigned long long headerBytes = (3 + blocks) * (m_header64 ? 8 : 4);
        c.blockData = a.base64 ? size_t(a.data + (headerBytes + 2) / 3 * 4) : size_t(a.data + headerBytes);
        return c;
    }

private:
    /// The character of base64 text from `at` (up to `end`) that starts the 4-character group
    /// holding decoded byte q, whitespace skipped; -1 past the end. Forward only: q never decreases
    /// between calls on one cursor.
    struct Base64Cursor {
        const std::string& t;
        size_t p, end;
        unsigned long long chars = 0;  ///< base64 characters before p
        long long at(unsigned long long q) {
            const unsigned long long want = q / 3 * 4;
            for (; p < end; ++p) {
                const char c = t[p];
                if (c == ' ' || c == '\n' || c == '\r' || c == '\t') continue;
                if (chars == want) return (long long)p;
                ++chars;
            }
            return -1;
        }
    };
    static inline const std::string kNoPath;

    const std::string& m_t;
    const std::string& m_path;
    VtuLayout m_layout;
    bool m_header64 = false, m_compressed = false, m_bigEndian = false, m_appendedBase64 = false;
    std::string m_compressor;
    unsigned long long m_points = 0, m_cells = 0;
    size_t m_appended = 0, m_pieceAt = 0, m_fileAt = std::string::npos;
    std::vector<std::string> m_names;  ///< the array names met in the current PointData or CellData
    bool m_havePoints = false, m_haveTypes = false;
};

} // namespace

std::vector<long long> VtuChecker::valueBytes(const VtuArrayLayout& a, const std::vector<unsigned long long>& indices) const {
    std::vector<long long> out(indices.size(), -1);
    if (a.tag == 0 || a.typeBytes <= 0) return out;
    const size_t end = dataEnd(a);
    size_t k = 0;
    if (a.format == "ascii") {  // the n-th number
        unsigned long long n = 0;
        bool in = false;
        for (size_t p = a.data; p < end && k < out.size(); ++p) {
            const char c = m_t[p];
            const bool space = c == ' ' || c == '\n' || c == '\r' || c == '\t';
            if (!space && !in) {
                for (; k < out.size() && indices[k] == n; ++k) out[k] = (long long)p;
                ++n;
            }
            in = !space;
        }
        return out;
    }
    const size_t w = m_header64 ? 8 : 4;
    const unsigned tb = unsigned(a.typeBytes);
    if (!m_compressed) {  // one header word, then the values
        Base64Cursor cursor{m_t, a.data, end};
        for (; k < out.size(); ++k) {
            const unsigned long long q = w + indices[k] * tb;
            if (!a.base64) out[k] = q < end - a.data ? (long long)(a.data + q) : -1;
            else out[k] = cursor.at(q);
        }
        return out;
    }
    const CompressedHeader ch = compressedHeader(a, end);
    if (ch.h.empty()) return out;
    const auto& h = ch.h;
    const unsigned long long blocks = h[0], blockSize = h[1];
    const size_t blockData = ch.blockData;
    Base64Cursor cursor{m_t, blockData, end};
    unsigned long long b = 0, before = 0;  // the block, and the compressed bytes before it
    for (; k < out.size(); ++k) {
        if (blockSize == 0) break;
        const unsigned long long want = indices[k] * tb / blockSize;
        for (; b < want && b < blocks; ++b) before += h[size_t(3 + b)];
        if (want >= blocks) break;
        if (!a.base64) out[k] = before < end - blockData ? (long long)(blockData + before) : -1;
        else out[k] = cursor.at(before);
    }
    return out;
}

std::vector<VtuBlock> VtuChecker::blocks(const VtuArrayLayout& a) const {
    std::vector<VtuBlock> out;
    if (a.tag == 0 || a.typeBytes <= 0 || a.format == "ascii") return out;
    const size_t end = dataEnd(a);
    const size_t w = m_header64 ? 8 : 4;
    // n bytes from `at`; the header check bounded n by what the file holds
    auto take = [&](size_t at, unsigned long long n) {
        std::string bytes = a.base64 ? base64Bytes(at, end, size_t(n), true) : m_t.substr(std::min(at, end), size_t(n));
        if (bytes.size() < n)
            failAt(at, "DataArray " + quoted(a.name) + " holds " + std::to_string(bytes.size()) + " of the " + std::to_string(n) +
                           " bytes its header announces: " + (a.base64 ? "its base64 text is corrupt" : "the file is truncated"));
        return bytes;
    };
    if (!m_compressed) {  // one header word, then the values, in one stream
        const unsigned long long n = words(a.data, end, a.base64, 1, a.tag)[0];
        out.push_back({a.data, take(a.data, w + n).substr(w), n});
        return out;
    }
    const CompressedHeader ch = compressedHeader(a, end);
    if (ch.h.empty()) return out;
    const auto& h = ch.h;
    const unsigned long long blocks = h[0], blockSize = h[1], last = h[2], headerBytes = (3 + blocks) * w;
    const size_t blockData = ch.blockData;
    // VTK decodes the base64 header 4 characters at a time too: no space in it
    if (a.base64 && base64Bytes(a.data, end, size_t(headerBytes), true).size() < headerBytes)
        failAt(a.data, "DataArray " + quoted(a.name) + " has its compressed data header broken by a space or a character that is not base64");
    unsigned long long compressed = 0;
    for (unsigned long long b = 0; b < blocks; ++b) compressed += h[size_t(3 + b)];
    const std::string all = take(blockData, compressed);
    Base64Cursor cursor{m_t, blockData, end};
    unsigned long long before = 0;
    for (unsigned long long b = 0; b < blocks; ++b) {
        const unsigned long long c = h[size_t(3 + b)];
        const long long at = a.base64 ? cursor.at(before) : (long long)(blockData + before);
        out.push_back({at < 0 ? blockData : size_t(at), all.substr(size_t(before), size_t(c)),
                       (b + 1 == blocks && last != 0) ? last : blockSize});
        before += c;
    }
    return out;
}

VtuLayout checkVtuHeaders(const std::string& path) {
    std::string text = readWholeFile(path, true);
    VtuLayout layout;
    {
        VtuChecker checker(text, path);
        checker.run();
        layout = checker.takeLayout();
    }
    layout.text = std::move(text);
    return layout;
}

std::vector<VtuBlock> vtuBlocks(const VtuLayout& layout, const VtuArrayLayout& a, const std::string& path) {
    return VtuChecker(layout, path).blocks(a);
}

std::vector<long long> vtuValueBytes(const VtuLayout& layout, const VtuArrayLayout& a, const std::vector<unsigned long long>& indices) {
    return VtuChecker(layout).valueBytes(a, indices);
}

} // namespace fascia::meshio::detail
