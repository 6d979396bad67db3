// STL (ASCII and binary) and OBJ surface readers, and the choice of reader by extension (.vtp in
// VtpReader.cpp): fascia/surface/TriangleSurface.h.
#include "fascia/surface/TriangleSurface.h"
#include "VtpReader.h"
#include "fascia/base/InputFile.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string_view>
#include <system_error>
#include <unordered_map>

namespace fascia::surface {

namespace {

[[noreturn]] void fail(const std::string& file, long long line, const std::string& message) {
    core::throwInputError(core::SourceLoc{file, int(std::min<long long>(line, 2147483647LL))}, message);
}
[[noreturn]] void failByte(const std::string& file, long long byte, const std::string& message) {
    core::throwInputError(core::SourceLoc{file, 0, byte}, message);
}

std::string quoted(std::string_view s) {
    std::string out = "'";
    out.append(s.substr(0, 40));
    if (s.size() > 40) out += "...";
    return out + "'";
}

/// The tokens of one line of a text file, with its number.
class Lines {
public:
    Lines(std::string_view text, const std::string& file) : m_p(text.data()), m_end(text.data() + text.size()), m_file(file) {}
    /// Moves to the next line; false at the end of the text.
    bool next() {
        if (m_p >= m_end) return false;
        const char* nl = static_cast<const char*>(std::memchr(m_p, '\n', size_t(m_end - m_p)));
        const char* e = nl ? nl : m_end;
        m_tokens.clear();
        for (const char* q = m_p; q < e;) {
            while (q < e && std::isspace((unsigned char)*q)) ++q;
            const char* s = q;
            while (q < e && !std::isspace((unsigned char)*q)) ++q;
            if (q > s) m_tokens.emplace_back(s, size_t(q - s));
        }
        m_p = nl ? nl + 1 : m_end;
        ++m_line;
        return true;
    }
    long long line() const { return m_line; }
    const std::vector<std::string_view>& tokens() const { return m_tokens; }
    double real(size_t i, const char* what) const {
        if (i >= m_tokens.size()) fail(m_file, m_line, std::string("the line ends before the ") + what);
        const std::string_view t = m_tokens[i];
        const char* b = t.data();
        const char* e = b + t.size();
        if (b < e && *b == '+') ++b;
        double v = 0;
        const auto [ptr, ec] = std::from_chars(b, e, v, std::chars_format::general);
        if (ec == std::errc::result_out_of_range) {
            v = std::strtod(std::string(t).c_str(), nullptr);  // underflow is harmless, overflow is not
            if (std::isinf(v)) fail(m_file, m_line, std::string("the ") + what + " " + quoted(t) + " is out of range");
            return v;
        }
        if (ec != std::errc() || ptr != e)
            fail(m_file, m_line, std::string("malformed number ") + quoted(t) + " for the " + what +
                                     ": expected a decimal number such as 0.25 or -1.5e-3");
        if (!std::isfinite(v)) fail(m_file, m_line, std::string("the ") + what + " is not a finite number");
        return v;
    }
    void expectCount(size_t n, const char* record) const {
        if (m_tokens.size() != n)
            fail(m_file, m_line, "a '" + std::string(record) + "' line has " + std::to_string(n) + " fields, this one has " +
                                     std::to_string(m_tokens.size()));
    }

private:
    const char* m_p;
    const char* m_end;
    const std::string& m_file;
    long long m_line = 0;
    std::vector<std::string_view> m_tokens;
};

bool keywordIs(std::string_view t, const char* k) {
    if (t.size() != std::strlen(k)) return false;
    for (size_t i = 0; i < t.size(); ++i)
        if (std::tolower((unsigned char)t[i]) != k[i]) return false;
    return true;
}

/// Merges vertices with equal coordinates (STL repeats each vertex in every triangle that has it).
class VertexMerger {
public:
    explicit VertexMerger(Positions& points) : m_points(points) {}
    int index(const Vec3& p) {
        Key k;
        for (int a = 0; a < 3; ++a) {
            const double c = p[a] == 0 ? 0.0 : p[a];  // -0 and +0 are one vertex
            std::memcpy(&k.bits[size_t(a)], &c, sizeof c);
        }
        const auto [it, fresh] = m_map.try_emplace(k, int(m_points.size()));
        if (fresh) m_points.push_back(p);
        return it->second;
    }

private:
    struct Key {
        std::array<std::uint64_t, 3> bits;
        bool operator==(const Key& o) const { return bits == o.bits; }
    };
    struct Hash {
        size_t operator()(const Key& k) const {
            std::uint64_t h = 0x9E3779B97F4A7C15ULL;
            for (auto b : k.bits) h = (h ^ b) * 0x100000001B3ULL + (h >> 29);
            return size_t(h);
        }
    };
    Positions& m_points;
    std::unordered_map<Key, int, Hash> m_map;
};

void addTriangle(TriangleSurface& s, std::array<int, 3> t, long long origin) {
    s.triangles.push_back(t);
    s.origin.push_back(origin);
}

/// A triangle using one vertex twice is no triangle (STL: two equal corners).
void checkDistinct(const TriangleSurface& s, const std::array<int, 3>& t, long long origin, const char* what) {
    if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) return;
    const std::string msg = std::string("the ") + what + " uses one vertex twice (vertices " + std::to_string(t[0] + 1) + " " +
                            std::to_string(t[1] + 1) + " " + std::to_string(t[2] + 1) + "): it has no area; remove it";
    if (s.byteOffsets) failByte(s.file, origin, msg);
    fail(s.file, origin, msg);
}

void readBinaryStl(const std::string& bytes, TriangleSurface& s) {
    s.format = "STL binary";
    s.byteOffsets = true;
    std::uint32_t count = 0;
    std::memcpy(&count, bytes.data() + 80, 4);  // little endian, as every STL writer
    if (count == 0) failByte(s.file, 80, "the binary STL file has no triangles (its count is 0)");
    VertexMerger merge(s.points);
    s.triangles.reserve(count);
    s.origin.reserve(count);
    for (std::uint32_t i = 0; i < count; ++i) {
        const size_t at = 84 + size_t(i) * 50;
        float v[12];  // normal, then 3 vertices
        std::memcpy(v, bytes.data() + at, sizeof v);
        std::array<int, 3> t;
        for (int c = 0; c < 3; ++c) {
            const Vec3 p(v[3 + 3 * c], v[4 + 3 * c], v[5 + 3 * c]);
            if (!p.allFinite())
                failByte(s.file, (long long)(at + 12 + 12 * size_t(c)),
                         "triangle " + std::to_string(i + 1) + " has a non-finite vertex coordinate");
            t[size_t(c)] = merge.index(p);
        }
        checkDistinct(s, t, (long long)at, ("triangle " + std::to_string(i + 1)).c_str());
        addTriangle(s, t, (long long)at);
    }
}

void readAsciiStl(const std::string& text, TriangleSurface& s) {
    s.format = "STL ASCII";
    Lines in(text, s.file);
    VertexMerger merge(s.points);
    enum class At { Outside, Solid, Facet, Loop, EndLoop } at = At::Outside;
    std::array<int, 3> tri{};
    int corners = 0;
    long long facetLine = 0;
    auto expect = [&](bool ok, const char* what) {
        if (!ok)
            fail(s.file, in.line(), "unexpected " + quoted(in.tokens()[0]) + ": expected " + what +
                                        " (an ASCII STL file is 'solid', then per triangle 'facet normal', 'outer loop', "
                                        "three 'vertex' lines, 'endloop', 'endfacet', then 'endsolid')");
    };
    while (in.next()) {
        const auto& tk = in.tokens();
        if (tk.empty()) continue;
        const std::string_view k = tk[0];
        switch (at) {
        case At::Outside:
            expect(keywordIs(k, "solid"), "'solid'");
            at = At::Solid;
            break;
        case At::Solid:
            if (keywordIs(k, "endsolid")) {
                at = At::Outside;
                break;
            }
            expect(keywordIs(k, "facet"), "'facet' or 'endsolid'");
            facetLine = in.line();
            at = At::Facet;
            break;
        case At::Facet:
            expect(keywordIs(k, "outer") && tk.size() == 2 && keywordIs(tk[1], "loop"), "'outer loop'");
            corners = 0;
            at = At::Loop;
            break;
        case At::Loop:
            if (keywordIs(k, "endloop")) {
                if (corners != 3)
                    fail(s.file, in.line(), "the facet of line " + std::to_string(facetLine) + " has " + std::to_string(corners) +
                                                " vertices; an STL facet has 3");
                at = At::EndLoop;
                break;
            }
            expect(keywordIs(k, "vertex"), "'vertex' or 'endloop'");
            in.expectCount(4, "vertex x y z");
            if (corners == 3) fail(s.file, in.line(), "a fourth vertex in the facet of line " + std::to_string(facetLine) + "; an STL facet has 3");
            tri[size_t(corners++)] = merge.index(Vec3(in.real(1, "x coordinate"), in.real(2, "y coordinate"), in.real(3, "z coordinate")));
            break;
        case At::EndLoop:
            expect(keywordIs(k, "endfacet"), "'endfacet'");
            checkDistinct(s, tri, facetLine, "facet");
            addTriangle(s, tri, facetLine);
            at = At::Solid;
            break;
        }
    }
    if (at != At::Outside)
        fail(s.file, in.line(), "the ASCII STL file ends inside a " + std::string(at == At::Solid ? "solid (no 'endsolid')" : "facet") +
                                    ": the file is truncated");
    if (s.triangles.empty()) fail(s.file, 0, "the STL file has no triangles");
}

void readStl(const std::string& bytes, TriangleSurface& s) {
    if (bytes.size() >= 84) {
        std::uint32_t count = 0;
        std::memcpy(&count, bytes.data() + 80, 4);
        if (std::uint64_t(bytes.size()) == 84 + 50 * std::uint64_t(count)) return readBinaryStl(bytes, s);
    }
    size_t first = 0;
    while (first < bytes.size() && std::isspace((unsigned char)bytes[first])) ++first;
    const bool ascii = bytes.size() - first >= 5 && keywordIs(std::string_view(bytes).substr(first, 5), "solid");
    if (ascii) {
        // a binary file whose header starts with "solid" but whose size is wrong: say so, not "malformed"
        const bool text = std::none_of(bytes.begin(), bytes.end(), [](char c) { return c == '\0'; });
        if (text) return readAsciiStl(bytes, s);
    }
    if (bytes.size() < 84)
        failByte(s.file, (long long)bytes.size(), "the file ends inside the 84-byte header of a binary STL file (it has " +
                                                      std::to_string(bytes.size()) + " bytes) and is no ASCII STL file either");
    std::uint32_t count = 0;
    std::memcpy(&count, bytes.data() + 80, 4);
    failByte(s.file, 80, "the binary STL header announces " + std::to_string(count) + " triangles, which take " +
                             std::to_string(84 + 50 * std::uint64_t(count)) + " bytes; the file has " + std::to_string(bytes.size()) +
                             " bytes (truncated, or not an STL file)");
}

/// An OBJ face corner "i", "i/t", "i//n" or "i/t/n": the vertex index, 0-based (negative: relative).
int objIndex(std::string_view t, long long vertices, const std::string& file, long long line) {
    const std::string_view v = t.substr(0, t.find('/'));
    long long i = 0;
    const auto [ptr, ec] = std::from_chars(v.data(), v.data() + v.size(), i);
    if (ec != std::errc() || ptr != v.data() + v.size() || i == 0)
        fail(file, line, "malformed face corner " + quoted(t) + ": expected a vertex number (1, 2 ... or -1 for the last one)");
    const long long k = i > 0 ? i - 1 : vertices + i;
    if (k < 0 || k >= vertices)
        fail(file, line, "the face names vertex " + std::string(v) + ", and " + std::to_string(vertices) +
                             " vertices are defined before it; fix the face's vertex numbers");
    return int(k);
}

void readObj(const std::string& text, TriangleSurface& s) {
    s.format = "OBJ";
    Lines in(text, s.file);
    while (in.next()) {
        const auto& tk = in.tokens();
        if (tk.empty() || tk[0][0] == '#') continue;
        const std::string_view k = tk[0];
        if (k == "v") {
            if (tk.size() != 4 && tk.size() != 5)
                fail(s.file, in.line(), "a 'v' line has 3 coordinates (and an optional weight), this one has " + std::to_string(tk.size() - 1) + " values");
            if (s.points.size() >= 2147483647u) fail(s.file, in.line(), "too many vertices");
            s.points.emplace_back(in.real(1, "x coordinate"), in.real(2, "y coordinate"), in.real(3, "z coordinate"));
        } else if (k == "f") {
            if (tk.size() < 4) fail(s.file, in.line(), "a face has at least 3 vertices, this one has " + std::to_string(tk.size() - 1));
            const long long nv = (long long)s.points.size();
            const int v0 = objIndex(tk[1], nv, s.file, in.line());
            int prev = objIndex(tk[2], nv, s.file, in.line());
            for (size_t c = 3; c < tk.size(); ++c) {
                const int next = objIndex(tk[c], nv, s.file, in.line());
                const std::array<int, 3> t{v0, prev, next};
                checkDistinct(s, t, in.line(), "face");
                addTriangle(s, t, in.line());
                prev = next;
            }
        } else if (k == "vn" || k == "vt" || k == "vp" || k == "g" || k == "o" || k == "s" || k == "usemtl" || k == "mtllib" ||
                   k == "l" || k == "p") {
            continue;  // normals, texture coordinates, groups, materials, lines, points: not needed
        } else {
            fail(s.file, in.line(), "unknown OBJ record " + quoted(k) +
                                        ": a surface file has 'v' and 'f' lines (vn, vt, g, o, s, usemtl, mtllib, l, p are ignored)");
        }
    }
    if (s.triangles.empty()) fail(s.file, 0, "the OBJ file has no faces ('f' lines)");
}

} // namespace

TriangleSurface readSurface(const std::string& path) {
    TriangleSurface s;
    s.file = path;
    std::string ext = std::filesystem::path(path).extension().string();
    for (auto& c : ext) c = char(std::tolower((unsigned char)c));
    if (ext != ".stl" && ext != ".obj" && ext != ".vtp")
        fail(path, 0, "unknown surface file extension '" + ext + "': supported are .stl (ASCII or binary), .obj and .vtp (VTK XML PolyData)");
    std::error_code ec;
    if (!std::filesystem::exists(path, ec))
        fail(path, 0, "surface file '" + path + "' does not exist; check the file name and the folder it is in");
    const std::string bytes = core::readRegularFile(path, "surface file", core::kMaxMeshFileBytes, {path, 0});
    if (bytes.empty()) fail(path, 0, "the surface file is empty");
    if (ext == ".stl") readStl(bytes, s);
    else if (ext == ".obj") readObj(bytes, s);
    else detail::readVtp(bytes, s);
    return s;
}

core::SourceLoc triangleLocation(const TriangleSurface& s, size_t tri) {
    if (tri >= s.origin.size()) return {s.file, 0};
    if (s.byteOffsets) return {s.file, 0, s.origin[tri]};
    return {s.file, int(std::min<long long>(s.origin[tri], 2147483647LL))};
}

} // namespace fascia::surface
