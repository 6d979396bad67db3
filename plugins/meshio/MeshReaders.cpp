#include "MeshReaders.h"

#include "fascia/base/Error.h"
#include "fascia/base/InputFile.h"

#include <vtkCallbackCommand.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkCellTypes.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkDataSet.h>
#include <vtkDataSetReader.h>
#include <vtkIdList.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkObject.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkUnstructuredGridReader.h>
#include <vtkDataObjectTypes.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string_view>
#include <unordered_map>
#include <utility>

namespace fascia::meshio {
namespace {

namespace fs = std::filesystem;
using fascia::core::SourceLoc;

const char* const kSupported =
    "supported are .msh (Gmsh ASCII 1, 2.2, 4.1), .vtk (VTK legacy), .vtu (VTK XML) and .node/.ele (TetGen)";

[[noreturn]] void fail(const std::string& file, int line, const std::string& message,
                       std::vector<std::string> notes = {}) {
    fascia::core::throwInputError(SourceLoc{file, line}, message, std::move(notes));
}

std::string quoted(std::string_view s) {
    // keep messages readable even when the token is a long run of garbage
    std::string out = "'";
    out.append(s.substr(0, 60));
    if (s.size() > 60) out += "...";
    return out + "'";
}

std::string lowerExtension(const std::string& path) {
    std::string ext = fs::path(path).extension().string();
    for (auto& c : ext) c = char(std::tolower((unsigned char)c));
    return ext;
}

std::string plural(long long n, const std::string& word) {
    return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
}

std::string fmtNumber(double v) {
    std::ostringstream os;
    os.precision(6);
    os << v;
    return os.str();
}

/// Fails unless path names a regular file we can open.
void checkReadable(const std::string& path) {
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (!fs::exists(st)) {
        std::error_code ec2;
        const fs::path abs = fs::absolute(path, ec2);
        const bool relative = !ec2 && fs::path(path).is_relative();
        fail(path, 0, "mesh file '" + path + "' does not exist" +
                          (relative ? " (looked for " + abs.string() + ")" : std::string()) +
                          "; check the file name and the folder it is in");
    }
    if (fs::is_directory(st)) fail(path, 0, "'" + path + "' is a folder, not a mesh file");
    core::requireRegularFile(path, "mesh file", core::kMaxMeshFileBytes, {path, 0});  // no FIFO, device or giant
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        const int err = errno;
        fail(path, 0, "cannot open mesh file '" + path + "' for reading (" + std::strerror(err) +
                          "); check its permissions");
    }
}

/// A reservation for a count read from a file: a hint, capped so that a corrupt header announcing
/// billions of records cannot exhaust memory before the records themselves are found missing.
size_t reserveHint(long long n) { return size_t(std::clamp<long long>(n, 0, 1 << 22)); }

std::string readWholeFile(const std::string& path) {
    checkReadable(path);
    std::ifstream in(path, std::ios::binary);
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    in.seekg(0, std::ios::beg);
    std::string text;
    if (size > 0) {
        text.resize(size_t(size));
        in.read(text.data(), size);
        if (in.gcount() != size) fail(path, 0, "cannot read mesh file '" + path + "': read error after " +
                                                   std::to_string(in.gcount()) + " of " + std::to_string(size) + " bytes");
    }
    if (text.size() >= 3 && text.compare(0, 3, "\xEF\xBB\xBF") == 0) text.erase(0, 3);  // UTF-8 byte-order mark
    return text;
}

// ------------------------------------------------------------------------------------------------
// Line-aware tokenizer: records are one per line; a record that ends early or has extra values is
// an error located at its own line.

inline bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

class Scanner {
public:
    Scanner(std::string_view text, const std::string& file, char comment = '\0')
        : m_p(text.data()), m_end(text.data() + text.size()), m_file(file), m_comment(comment) {}

    const std::string& file() const { return m_file; }
    int line() const { return m_line; }
    /// Line of the last token read (for "the file ends after line N").
    int lastLine() const { return m_lastTokenLine; }
    /// Describes the records of the current section for "ends early" messages, e.g. "'id x y z'".
    void setRecordFormat(std::string fmt) { m_format = std::move(fmt); }

    /// Moves to the first token of the next line that has one; false at the end of the file.
    bool nextRecord() {
        for (;;) {
            while (m_p < m_end && isBlank(*m_p)) ++m_p;
            if (m_p == m_end) return false;
            if (*m_p == '\n') {
                ++m_line;
                ++m_p;
                continue;
            }
            if (m_comment && *m_p == m_comment) {
                skipRestOfLine();
                continue;
            }
            return true;
        }
    }
    /// First character of the record nextRecord() moved to.
    char peek() const { return m_p < m_end ? *m_p : '\0'; }

    /// Next token on the current line; empty at the end of the line.
    std::string_view token() {
        while (m_p < m_end && isBlank(*m_p)) ++m_p;
        if (m_p == m_end || *m_p == '\n' || (m_comment && *m_p == m_comment)) return {};
        const char* s = m_p;
        while (m_p < m_end && !isBlank(*m_p) && *m_p != '\n' && !(m_comment && *m_p == m_comment)) ++m_p;
        m_lastTokenLine = m_line;
        return {s, size_t(m_p - s)};
    }
    bool lineHasMore() {
        while (m_p < m_end && isBlank(*m_p)) ++m_p;
        return !(m_p == m_end || *m_p == '\n' || (m_comment && *m_p == m_comment));
    }
    /// The rest of the current line, trimmed.
    std::string_view restOfLine() {
        while (m_p < m_end && isBlank(*m_p)) ++m_p;
        const char* s = m_p;
        while (m_p < m_end && *m_p != '\n') ++m_p;
        const char* e = m_p;
        while (e > s && isBlank(e[-1])) --e;
        if (e > s) m_lastTokenLine = m_line;
        return {s, size_t(e - s)};
    }
    void skipRestOfLine() {
        const void* nl = std::memchr(m_p, '\n', size_t(m_end - m_p));
        m_p = nl ? static_cast<const char*>(nl) : m_end;
    }
    void expectEndOfLine(const std::string& after) {
        const std::string_view t = token();
        if (!t.empty())
            fail(m_file, m_line, "unexpected " + quoted(t) + " after " + after + ": the line has more values than expected" +
                                     formatHint());
    }

    /// A required token of the current record.
    std::string_view field(const char* what) {
        const std::string_view t = token();
        if (t.empty()) fail(m_file, m_line, std::string("the line ends before the ") + what + formatHint());
        return t;
    }
    long long integer(const char* what) { return toInteger(field(what), what); }
    int smallInteger(const char* what) {
        const long long v = integer(what);
        if (v < -2147483647LL || v > 2147483647LL)
            fail(m_file, m_line, std::string("the ") + what + " " + std::to_string(v) + " is out of range");
        return int(v);
    }
    double real(const char* what) { return toReal(field(what), what); }

    long long toInteger(std::string_view t, const char* what) const {
        const char* b = t.data();
        const char* e = b + t.size();
        if (b < e && *b == '+' && e - b > 1 && b[1] != '-') ++b;
        long long v = 0;
        const auto [ptr, ec] = std::from_chars(b, e, v);
        if (ec == std::errc::result_out_of_range)
            fail(m_file, m_line, std::string("the ") + what + " " + quoted(t) + " is out of range");
        if (ec != std::errc() || ptr != e)
            fail(m_file, m_line, std::string("malformed number ") + quoted(t) + " for the " + what +
                                     ": expected a whole number" + formatHint());
        return v;
    }
    double toReal(std::string_view t, const char* what) const {
        const char* b = t.data();
        const char* e = b + t.size();
        if (b < e && *b == '+' && e - b > 1 && b[1] != '-') ++b;
        double v = 0;
        const auto [ptr, ec] = std::from_chars(b, e, v, std::chars_format::general);
        if (ec == std::errc::result_out_of_range) {
            // underflow to a denormal/zero is harmless; overflow is not
            const double big = std::strtod(std::string(t).c_str(), nullptr);
            if (std::isinf(big))
                fail(m_file, m_line, std::string("the ") + what + " " + quoted(t) + " is out of range");
            return big;
        }
        if (ec != std::errc() || ptr != e)
            fail(m_file, m_line, std::string("malformed number ") + quoted(t) + " for the " + what +
                                     ": expected a decimal number such as 0.25 or -1.5e-3" + formatHint());
        return v;
    }

private:
    std::string formatHint() const { return m_format.empty() ? std::string() : " (records here are " + m_format + ")"; }

    const char* m_p;
    const char* m_end;
    const std::string& m_file;
    char m_comment;
    int m_line = 1;
    int m_lastTokenLine = 1;
    std::string m_format;
};

// ------------------------------------------------------------------------------------------------
// File node ids -> 0-based indices.

class NodeIdMap {
public:
    /// ids[i] is the file's id of node i, lines[i] the line it is on (for duplicate errors).
    void build(const std::vector<long long>& ids, const std::vector<int>& lines, const std::string& file) {
        m_dense = true;
        m_table.clear();
        m_hash.clear();
        if (ids.empty()) return;
        const long long lo = *std::min_element(ids.begin(), ids.end());
        const long long hi = *std::max_element(ids.begin(), ids.end());
        m_dense = lo >= 0 && hi < 4 * (long long)ids.size() + 1024;
        if (m_dense) {
            m_table.assign(size_t(hi) + 1, -1);
            for (size_t i = 0; i < ids.size(); ++i) {
                int& slot = m_table[size_t(ids[i])];
                if (slot >= 0) duplicate(ids[i], lines[size_t(slot)], lines[i], file);
                slot = int(i);
            }
        } else {
            m_hash.reserve(ids.size() * 2);
            for (size_t i = 0; i < ids.size(); ++i) {
                const auto [it, inserted] = m_hash.emplace(ids[i], int(i));
                if (!inserted) duplicate(ids[i], lines[size_t(it->second)], lines[i], file);
            }
        }
    }
    int find(long long id) const {
        if (m_dense) return id >= 0 && id < (long long)m_table.size() ? m_table[size_t(id)] : -1;
        const auto it = m_hash.find(id);
        return it == m_hash.end() ? -1 : it->second;
    }

private:
    [[noreturn]] static void duplicate(long long id, int firstLine, int line, const std::string& file) {
        fail(file, line, "node id " + std::to_string(id) + " appears twice (first on line " + std::to_string(firstLine) +
                             "): node ids must be unique");
    }
    bool m_dense = true;
    std::vector<int> m_table;
    std::unordered_map<long long, int> m_hash;
};

// ------------------------------------------------------------------------------------------------
// Where elements and nodes came from, for located validation errors.

struct ElementOrigin {
    std::string nodeFile, elementFile;     ///< files holding the nodes / the elements
    std::vector<int> nodeLine;             ///< per node (empty: unknown)
    std::vector<long long> nodeId;         ///< file id per node (empty: the index is the id)
    std::vector<int> tetLine, hexLine;     ///< per element (empty: unknown)
    std::vector<long long> tetNumber, hexNumber;  ///< file number per element (empty: none)
    std::string elementWord = "element";   ///< "cell" for VTK files
};

std::string nodeName(const ElementOrigin& o, int index) {
    if (index >= 0 && size_t(index) < o.nodeId.size()) return std::to_string(o.nodeId[size_t(index)]);
    return std::to_string(index);
}

/// Collects everything a reader produces; shared by all formats.
struct Builder {
    MeshData mesh;
    ElementOrigin origin;
    ReadReport* report = nullptr;
    std::map<std::pair<int, int>, std::string> names;  ///< (dim, tag) -> name; dim -1: any

    /// Adds the nodes of one element to group (dim, tag); tag 0 is no group.
    void markGroup(int dim, int tag, const int* nodes, size_t n) {
        if (tag == 0) return;
        const std::pair<int, int> key{dim, tag};
        if (m_lastId < 0 || m_lastKey != key) {
            const auto [it, added] = m_groupIds.emplace(key, int(m_lists.size()));
            if (added) m_lists.emplace_back();
            m_lastId = it->second;
            m_lastKey = key;
            if (m_lastAdded.size() != mesh.points.size()) m_lastAdded.assign(mesh.points.size(), -1);
        }
        // elements of a group mostly come together: skip nodes this group just took
        auto& list = m_lists[size_t(m_lastId)];
        for (size_t i = 0; i < n; ++i) {
            int& last = m_lastAdded[size_t(nodes[i])];
            if (last != m_lastId) {
                list.push_back(nodes[i]);
                last = m_lastId;
            }
        }
    }
    void skip(const std::string& kind) { ++report->skipped[kind]; }

    /// nodeGroups ("physical:<tag>" and names) and groupNames from the collected lists and names.
    void finishGroups() {
        auto sortUnique = [](IndexList& l) {
            std::sort(l.begin(), l.end());
            l.erase(std::unique(l.begin(), l.end()), l.end());
        };
        auto merged = [&](IndexList a, const IndexList& b) {
            a.insert(a.end(), b.begin(), b.end());
            sortUnique(a);
            return a;
        };
        for (auto& l : m_lists) sortUnique(l);
        std::map<int, IndexList> byTag;
        for (const auto& [key, id] : m_groupIds) {
            auto& dst = byTag[key.second];
            dst = dst.empty() ? m_lists[size_t(id)] : merged(dst, m_lists[size_t(id)]);
        }
        for (auto& [tag, l] : byTag) mesh.nodeGroups["physical:" + std::to_string(tag)] = std::move(l);
        // names in (dim, tag) order: for a tag named in several dimensions the highest one names it
        for (const auto& [key, name] : names) {
            IndexList nodes = mesh.nodeGroups[name];  // a name given to several groups gathers them
            for (const auto& k : {key, std::pair<int, int>{-1, key.second}}) {  // -1: dimension not known
                const auto it = m_groupIds.find(k);
                if (it != m_groupIds.end()) nodes = merged(std::move(nodes), m_lists[size_t(it->second)]);
            }
            mesh.nodeGroups[name] = std::move(nodes);
            mesh.groupNames[key.second] = name;
        }
        m_groupIds.clear();
        m_lists.clear();
        m_lastAdded.clear();
        m_lastId = -1;
    }

private:
    std::map<std::pair<int, int>, int> m_groupIds;  ///< (dim, tag) -> index in m_lists
    std::vector<IndexList> m_lists;                 ///< nodes per group, unsorted, maybe repeated
    std::vector<int> m_lastAdded;                   ///< per node: the group that added it last
    int m_lastId = -1;
    std::pair<int, int> m_lastKey{0, 0};
};

// ------------------------------------------------------------------------------------------------
// Validation

std::string elementName(const ElementOrigin& o, bool hex, size_t i) {
    const auto& numbers = hex ? o.hexNumber : o.tetNumber;
    const char* kind = hex ? "hexahedron" : "tetrahedron";
    if (i < numbers.size()) return o.elementWord + " " + std::to_string(numbers[i]) + " (a " + kind + ")";
    return std::string(kind) + " " + std::to_string(i) + " (0-based)";
}

int elementLine(const ElementOrigin& o, bool hex, size_t i) {
    const auto& lines = hex ? o.hexLine : o.tetLine;
    return i < lines.size() ? lines[i] : 0;
}

template <size_t N>
std::string nodeListText(const ElementOrigin& o, const std::array<int, N>& e) {
    std::string s;
    for (size_t k = 0; k < N; ++k) s += (k ? " " : "") + nodeName(o, e[k]);
    return s;
}

template <size_t N>
double longestEdgeCubed(const Positions& p, const std::array<int, N>& e) {
    double l2 = 0;
    if constexpr (N == 4) {
        for (int a = 0; a < 4; ++a)
            for (int b = a + 1; b < 4; ++b) l2 = std::max(l2, (p[size_t(e[a])] - p[size_t(e[b])]).squaredNorm());
    } else {
        static const int edges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                         {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
        for (const auto& ed : edges) l2 = std::max(l2, (p[size_t(e[ed[0]])] - p[size_t(e[ed[1]])]).squaredNorm());
    }
    return l2 * std::sqrt(l2);
}

template <class Group>
void normalizeGroup(Group& g, size_t n, const char* what) {
    if (g.size() == n) return;
    if (g.empty()) {
        g.assign(n, 0);
        return;
    }
    throw fascia::core::Error(fascia::core::ErrorKind::Internal, {},
                              std::string("mesh has ") + std::to_string(g.size()) + " " + what + " group tags for " +
                                  std::to_string(n) + " elements");
}

void validateImpl(MeshData& mesh, const ElementOrigin& o, const ReadOptions& opt, ReadReport& report) {
    normalizeGroup(mesh.tetrahedronGroup, mesh.tetrahedra.size(), "tetrahedron");
    normalizeGroup(mesh.hexahedronGroup, mesh.hexahedra.size(), "hexahedron");
    normalizeGroup(mesh.triangleGroup, mesh.triangles.size(), "triangle");

    if (mesh.tetrahedra.empty() && mesh.hexahedra.empty()) {
        std::string found;
        if (!mesh.triangles.empty()) found = plural((long long)mesh.triangles.size(), "triangle");
        for (const auto& [kind, n] : report.skipped) found += (found.empty() ? "" : ", ") + plural(n, kind);
        fail(o.elementFile, 0,
             "'" + o.elementFile + "' has no volume elements (tetrahedra or hexahedra)" +
                 (found.empty() ? std::string(" and no elements at all") : "; it has " + found) +
                 ": a deformable body needs a volume mesh of linear tetrahedra or hexahedra (e.g. gmsh -3, "
                 "element order 1)");
    }

    const int nPoints = int(mesh.points.size());
    auto checkNodes = [&](const auto& elems, const char* kind, auto lineOf, auto nameOf) {
        for (size_t i = 0; i < elems.size(); ++i)
            for (int v : elems[i])
                if (v < 0 || v >= nPoints)
                    fail(o.elementFile, lineOf(i),
                         nameOf(i) + " names node " + std::to_string(v) + ", but the mesh has " +
                             plural(nPoints, "node") + " (valid " + kind + " node indices are 0 to " +
                             std::to_string(nPoints - 1) + "); fix the element's node list");
    };
    checkNodes(mesh.tetrahedra, "tetrahedron", [&](size_t i) { return elementLine(o, false, i); },
               [&](size_t i) { return elementName(o, false, i); });
    checkNodes(mesh.hexahedra, "hexahedron", [&](size_t i) { return elementLine(o, true, i); },
               [&](size_t i) { return elementName(o, true, i); });
    checkNodes(mesh.triangles, "triangle", [](size_t) { return 0; },
               [&](size_t i) { return "triangle " + std::to_string(i) + " (0-based)"; });

    for (size_t i = 0; i < mesh.points.size(); ++i) {
        const Vec3& x = mesh.points[i];
        if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]))
            fail(o.nodeFile, i < o.nodeLine.size() ? o.nodeLine[i] : 0,
                 "node " + nodeName(o, int(i)) + " has a non-finite coordinate (" + fmtNumber(x[0]) + " " +
                     fmtNumber(x[1]) + " " + fmtNumber(x[2]) + "); every coordinate must be a finite number");
    }

    constexpr double kDegenerate = 1e-12;
    auto checkVolumes = [&](auto& elems, bool hex) {
        const char* kind = hex ? "hexahedra" : "tetrahedra";
        long long inverted = 0;
        size_t firstInverted = 0;
        double firstVolume = 0;
        for (size_t i = 0; i < elems.size(); ++i) {
            auto& e = elems[i];
            double v;
            if constexpr (std::tuple_size_v<std::decay_t<decltype(e)>> == 4)
                v = tetrahedronSignedVolume(mesh.points[size_t(e[0])], mesh.points[size_t(e[1])],
                                            mesh.points[size_t(e[2])], mesh.points[size_t(e[3])]);
            else
                v = hexahedronVolume(mesh.points, e);
            const double l3 = longestEdgeCubed(mesh.points, e);
            if (!(std::abs(v) > kDegenerate * l3))
                fail(o.elementFile, elementLine(o, hex, i),
                     elementName(o, hex, i) + " is degenerate: its volume is " + fmtNumber(v) +
                         ", zero relative to its longest edge cubed (" + fmtNumber(l3) + "); its nodes (" +
                         nodeListText(o, e) + ") are repeated, coincide or lie in one plane: "
                         "remove or re-mesh this element");
            if (v < 0) {
                if (inverted++ == 0) {
                    firstInverted = i;
                    firstVolume = v;
                }
                if (opt.fixOrientation) {
                    if constexpr (std::tuple_size_v<std::decay_t<decltype(e)>> == 4)
                        std::swap(e[2], e[3]);
                    else
                        for (int k = 0; k < 4; ++k) std::swap(e[size_t(k)], e[size_t(k + 4)]);
                }
            }
        }
        if (inverted == 0) return;
        if (opt.fixOrientation) {
            report.flippedElements += int(inverted);
            return;
        }
        std::vector<std::string> notes;
        if (inverted > 1)
            notes.push_back(std::to_string(inverted) + " of " + std::to_string(elems.size()) + " " + kind +
                            " are inverted");
        fail(o.elementFile, elementLine(o, hex, firstInverted),
             elementName(o, hex, firstInverted) + " is inverted: its signed volume is " + fmtNumber(firstVolume) +
                 " < 0 with its nodes in the file's order (" + nodeListText(o, elems[firstInverted]) +
                 "); reorder its nodes, or set fixOrientation to flip inverted elements when loading",
             std::move(notes));
    };
    checkVolumes(mesh.tetrahedra, false);
    checkVolumes(mesh.hexahedra, true);
}

// ------------------------------------------------------------------------------------------------
// Gmsh

struct GmshType {
    int dim;
    const char* name;
    int nodes;
};

GmshType gmshType(int t) {
    switch (t) {
    case 1: return {1, "line", 2};
    case 2: return {2, "triangle", 3};
    case 3: return {2, "quadrangle", 4};
    case 4: return {3, "tetrahedron", 4};
    case 5: return {3, "hexahedron", 8};
    case 6: return {3, "prism", 6};
    case 7: return {3, "pyramid", 5};
    case 8: return {1, "3-node line", 3};
    case 9: return {2, "6-node triangle", 6};
    case 10: return {2, "9-node quadrangle", 9};
    case 11: return {3, "10-node tetrahedron", 10};
    case 12: return {3, "27-node hexahedron", 27};
    case 13: return {3, "18-node prism", 18};
    case 14: return {3, "14-node pyramid", 14};
    case 15: return {0, "point", 1};
    case 16: return {2, "8-node quadrangle", 8};
    case 17: return {3, "20-node hexahedron", 20};
    case 18: return {3, "15-node prism", 15};
    case 19: return {3, "13-node pyramid", 13};
    case 20: return {2, "9-node triangle", 9};
    case 21: return {2, "10-node triangle", 10};
    case 22: return {2, "12-node triangle", 12};
    case 23: return {2, "15-node triangle", 15};
    case 24: return {2, "15-node incomplete triangle", 15};
    case 25: return {2, "21-node triangle", 21};
    case 26: return {1, "4-node line", 4};
    case 27: return {1, "5-node line", 5};
    case 28: return {1, "6-node line", 6};
    case 29: return {3, "20-node tetrahedron", 20};
    case 30: return {3, "35-node tetrahedron", 35};
    case 31: return {3, "56-node tetrahedron", 56};
    case 92: return {3, "64-node hexahedron", 64};
    case 93: return {3, "125-node hexahedron", 125};
    default: return {-1, nullptr, -1};
    }
}

class GmshReader {
public:
    GmshReader(const std::string& text, const std::string& file, Builder& b) : m_sc(text, file), m_file(file), m_b(b) {}

    void read() {
        if (!m_sc.nextRecord()) fail(m_file, 0, "mesh file '" + m_file + "' is empty");
        const std::string_view first = m_sc.token();
        if (first == "$NOD" || first == "$NOE") {
            m_version = 1;
            m_b.report->format = "Gmsh 1 (legacy)";
        } else if (first == "$MeshFormat") {
            readMeshFormat();
        } else if (first == "$Comments") {
            // 2.x files may start with comments; the $MeshFormat must follow them
            skipSection("Comments", m_sc.line());
            if (!m_sc.nextRecord() || m_sc.token() != "$MeshFormat")
                fail(m_file, m_sc.line(), "expected $MeshFormat after $Comments");
            readMeshFormat();
        } else {
            fail(m_file, m_sc.line(),
                 "not a Gmsh mesh: the file starts with " + quoted(first) +
                     ", expected $MeshFormat (Gmsh 2.2/4.1) or $NOD (Gmsh 1); is it a mesh of another format with "
                     "a .msh extension?");
        }
        if (m_version == 1) {
            m_sc.expectEndOfLine(std::string(first));
            readNodes1or2("$NOD", "$ENDNOD");
        }
        while (m_sc.nextRecord()) {
            const int line = m_sc.line();
            const std::string_view tok = m_sc.token();
            if (tok.empty() || tok[0] != '$')
                fail(m_file, line, "unexpected " + quoted(tok) + " outside of any section: expected a section header such as $Nodes or $Elements");
            m_sc.expectEndOfLine(std::string(tok));
            if (m_version == 1) {
                if (tok == "$NOD" || tok == "$NOE") fail(m_file, line, "second $NOD section: a mesh file has one");
                else if (tok == "$ELM") readElements1();
                else skipSection(std::string(tok.substr(1)), line);
            } else if (tok == "$MeshFormat") {
                fail(m_file, line, "second $MeshFormat section: one file holds one mesh");
            } else if (tok == "$PhysicalNames") {
                readPhysicalNames();
            } else if (tok == "$Entities") {
                if (m_version == 4) readEntities();
                else skipSection("Entities", line);
            } else if (tok == "$Nodes") {
                if (m_haveNodes) fail(m_file, line, "second $Nodes section: a mesh file has one");
                if (m_version == 4) readNodes4();
                else readNodes1or2("$Nodes", "$EndNodes");
            } else if (tok == "$Elements") {
                if (m_haveElements) fail(m_file, line, "second $Elements section: a mesh file has one");
                if (!m_haveNodes) fail(m_file, line, "$Elements section before the $Nodes section: the nodes must come first");
                if (m_version == 4) readElements4();
                else readElements2();
            } else {
                skipSection(std::string(tok.substr(1)), line);  // $NodeData, $Periodic, $Comments, ...
            }
        }
        if (!m_haveNodes) fail(m_file, 0, "the file has no $Nodes section");
        if (!m_haveElements) fail(m_file, 0, m_version == 1 ? "the file has no $ELM section" : "the file has no $Elements section");
    }

private:
    void readMeshFormat() {
        m_sc.expectEndOfLine("$MeshFormat");
        if (!m_sc.nextRecord()) fail(m_file, m_sc.lastLine(), "the file ends inside $MeshFormat");
        const int line = m_sc.line();
        m_sc.setRecordFormat("'version file-type data-size'");
        const std::string_view version = m_sc.field("version");
        const long long fileType = m_sc.integer("file type");
        m_sc.integer("data size");
        m_sc.skipRestOfLine();
        if (fileType != 0)
            fail(m_file, line,
                 "binary Gmsh files are not supported, only ASCII: re-export the mesh as ASCII (Gmsh: File > Export "
                 "> 'Mesh - Gmsh MSH' without 'Save in binary format', or run "
                 "'gmsh in.msh -save -format msh22 -o out.msh')");
        const double v = m_sc.toReal(version, "version");
        if (v >= 2.0 && v < 3.0) {
            m_version = 2;
            m_b.report->format = "Gmsh " + std::string(version) + " ASCII";
        } else if (v >= 4.1 && v < 4.2) {
            m_version = 4;
            m_b.report->format = "Gmsh 4.1 ASCII";
        } else {
            fail(m_file, line,
                 "Gmsh format version " + std::string(version) +
                     " is not supported; supported are 1, 2.2 and 4.1: re-export the mesh with "
                     "'gmsh in.msh -save -format msh22 -o out.msh' (or msh41)");
        }
        if (!m_sc.nextRecord()) fail(m_file, m_sc.lastLine(), "the file ends before $EndMeshFormat: the file is truncated");
        if (m_sc.token() != "$EndMeshFormat")
            fail(m_file, m_sc.line(), "expected $EndMeshFormat after the version line of $MeshFormat");
        m_sc.skipRestOfLine();
    }

    void skipSection(const std::string& name, int startLine) {
        const std::string end = (m_version == 1 ? "$END" : "$End") + name;
        while (m_sc.nextRecord()) {
            const std::string_view t = m_sc.token();
            if (t == end || (m_version == 1 && t == "$End" + name)) {
                m_sc.skipRestOfLine();
                return;
            }
            m_sc.skipRestOfLine();
        }
        fail(m_file, m_sc.lastLine(),
             "section $" + name + " (line " + std::to_string(startLine) + ") has no " + end +
                 ": the file is truncated");
    }

    /// Moves to record i of n in a counted section; fails if the section or the file ends first.
    void sectionRecord(const char* section, const char* items, long long i, long long n, int countLine) {
        if (!m_sc.nextRecord())
            fail(m_file, m_sc.lastLine(),
                 std::string("the file ends inside the ") + section + " section after " + std::to_string(i) + " of " +
                     std::to_string(n) + " " + items + " (the count is on line " + std::to_string(countLine) +
                     "): the file is truncated; export or copy it again");
        if (m_sc.peek() == '$')
            fail(m_file, m_sc.line(),
                 std::string(section) + " section ends after " + std::to_string(i) + " of " + std::to_string(n) + " " +
                     items + " (the count is on line " + std::to_string(countLine) +
                     "): the file is truncated or the count is wrong");
    }
    void sectionEnd(const char* endTag, const char* section, long long n, const char* items, int countLine) {
        if (!m_sc.nextRecord())
            fail(m_file, m_sc.lastLine(), std::string("the file ends before ") + endTag + ": the file is truncated");
        const int line = m_sc.line();
        const std::string_view t = m_sc.token();
        if (t != endTag)
            fail(m_file, line,
                 std::string("expected ") + endTag + " after the " + std::to_string(n) + " " + items +
                     " announced on line " + std::to_string(countLine) + ", found " + quoted(t) + ": the " + section +
                     " section has more records than its count says");
        m_sc.expectEndOfLine(endTag);
    }
    long long count(const char* section, const char* what) {
        if (!m_sc.nextRecord()) fail(m_file, m_sc.lastLine(), std::string("the file ends right after ") + section);
        const long long n = m_sc.integer(what);
        if (n < 0) fail(m_file, m_sc.line(), std::string("negative ") + what + " " + std::to_string(n));
        return n;
    }

    void readNodes1or2(const char* section, const char* endTag) {
        const long long n = count(section, "number of nodes");
        const int countLine = m_sc.line();
        m_sc.expectEndOfLine("the number of nodes");
        m_sc.setRecordFormat("'node-id x y z'");
        auto& pts = m_b.mesh.points;
        pts.reserve(reserveHint(n));
        m_ids.reserve(reserveHint(n));
        m_lines.reserve(reserveHint(n));
        for (long long i = 0; i < n; ++i) {
            sectionRecord(section, "nodes", i, n, countLine);
            const long long id = m_sc.integer("node id");
            const double x = m_sc.real("x coordinate");
            const double y = m_sc.real("y coordinate");
            const double z = m_sc.real("z coordinate");
            m_sc.expectEndOfLine("the z coordinate");
            addNode(id, x, y, z);
        }
        sectionEnd(endTag, section, n, "nodes", countLine);
        finishNodes();
    }

    void addNode(long long id, double x, double y, double z) {
        const int line = m_sc.line();
        if (id < 0) fail(m_file, line, "negative node id " + std::to_string(id) + ": node ids must be positive");
        if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
            fail(m_file, line,
                 "node " + std::to_string(id) + " has a non-finite coordinate (" + fmtNumber(x) + " " + fmtNumber(y) +
                     " " + fmtNumber(z) + "); every coordinate must be a finite number");
        m_b.mesh.points.emplace_back(x, y, z);
        m_ids.push_back(id);
        m_lines.push_back(line);
    }
    void finishNodes() {
        m_map.build(m_ids, m_lines, m_file);
        m_b.origin.nodeId = std::move(m_ids);
        m_b.origin.nodeLine = std::move(m_lines);
        m_haveNodes = true;
        m_sc.setRecordFormat("");
    }

    int nodeIndex(long long id, long long element) {
        const int idx = m_map.find(id);
        if (idx < 0)
            fail(m_file, m_sc.line(),
                 "element " + std::to_string(element) + " names node " + std::to_string(id) +
                     ", which is not in the " + (m_version == 1 ? "$NOD" : "$Nodes") +
                     " section; fix the element's node list or add the node");
        return idx;
    }

    /// Keeps or skips one element; nodeTags are the file's ids.
    void addElement(long long number, int type, int dim, const std::vector<int>& phys) {
        const GmshType info = gmshType(type);
        const int line = m_sc.line();
        if (info.nodes > 0 && int(m_tags.size()) != info.nodes)
            fail(m_file, line,
                 "element " + std::to_string(number) + " of type " + std::to_string(type) + " (" + info.name + ") has " +
                     plural((long long)m_tags.size(), "node") + ", but a " + info.name + " has " +
                     std::to_string(info.nodes) + "; fix the element's node list");
        if (m_tags.empty()) fail(m_file, line, "element " + std::to_string(number) + " has no nodes");
        m_idx.resize(m_tags.size());
        for (size_t k = 0; k < m_tags.size(); ++k) m_idx[k] = nodeIndex(m_tags[k], number);
        const int group = phys.empty() ? 0 : phys[0];
        auto& mesh = m_b.mesh;
        if (type == 4) {
            mesh.tetrahedra.push_back({m_idx[0], m_idx[1], m_idx[2], m_idx[3]});
            mesh.tetrahedronGroup.push_back(group);
            m_b.origin.tetLine.push_back(line);
            m_b.origin.tetNumber.push_back(number);
        } else if (type == 5) {
            std::array<int, 8> h;
            std::copy(m_idx.begin(), m_idx.end(), h.begin());
            mesh.hexahedra.push_back(h);
            mesh.hexahedronGroup.push_back(group);
            m_b.origin.hexLine.push_back(line);
            m_b.origin.hexNumber.push_back(number);
        } else if (type == 2) {
            mesh.triangles.push_back({m_idx[0], m_idx[1], m_idx[2]});
            mesh.triangleGroup.push_back(group);
        } else {
            m_b.skip(info.name ? std::string(info.name) : "Gmsh element type " + std::to_string(type));
        }
        const int d = dim >= 0 ? dim : info.dim;
        for (int t : phys) m_b.markGroup(d, t, m_idx.data(), m_idx.size());
    }

    void readElements1() {
        const long long n = count("$ELM", "number of elements");
        const int countLine = m_sc.line();
        m_sc.expectEndOfLine("the number of elements");
        m_sc.setRecordFormat("'elm-number elm-type reg-phys reg-elem number-of-nodes node-list'");
        reserveElements(n);
        std::vector<int> phys;
        for (long long i = 0; i < n; ++i) {
            sectionRecord("$ELM", "elements", i, n, countLine);
            const long long number = m_sc.integer("element number");
            const int type = m_sc.smallInteger("element type");
            const int regPhys = m_sc.smallInteger("physical region (reg-phys)");
            m_sc.integer("elementary region (reg-elem)");
            const long long nn = m_sc.integer("number of nodes");
            if (nn < 0 || nn > 1000) fail(m_file, m_sc.line(), "element " + std::to_string(number) + " has " + std::to_string(nn) + " nodes");
            m_tags.resize(size_t(nn));
            for (long long k = 0; k < nn; ++k) m_tags[size_t(k)] = m_sc.integer("node id");
            m_sc.expectEndOfLine("the " + plural(nn, "node") + " of element " + std::to_string(number));
            phys.clear();
            if (regPhys != 0) phys.push_back(regPhys);
            addElement(number, type, -1, phys);
        }
        sectionEnd("$ENDELM", "$ELM", n, "elements", countLine);
        m_haveElements = true;
    }

    void readElements2() {
        const long long n = count("$Elements", "number of elements");
        const int countLine = m_sc.line();
        m_sc.expectEndOfLine("the number of elements");
        m_sc.setRecordFormat("'elm-number elm-type number-of-tags tags... node-list'");
        reserveElements(n);
        std::vector<int> phys;
        for (long long i = 0; i < n; ++i) {
            sectionRecord("$Elements", "elements", i, n, countLine);
            const long long number = m_sc.integer("element number");
            const int type = m_sc.smallInteger("element type");
            const long long ntags = m_sc.integer("number of tags");
            if (ntags < 0 || ntags > 1000) fail(m_file, m_sc.line(), "element " + std::to_string(number) + " has " + std::to_string(ntags) + " tags");
            phys.clear();
            for (long long k = 0; k < ntags; ++k) {
                const int t = m_sc.smallInteger("tag");
                if (k == 0 && t != 0) phys.push_back(t);  // first tag: physical group
            }
            m_tags.clear();
            while (m_sc.lineHasMore()) m_tags.push_back(m_sc.integer("node id"));
            addElement(number, type, -1, phys);
        }
        sectionEnd("$EndElements", "$Elements", n, "elements", countLine);
        m_haveElements = true;
    }

    void readPhysicalNames() {
        const long long n = count("$PhysicalNames", "number of physical names");
        const int countLine = m_sc.line();
        m_sc.expectEndOfLine("the number of physical names");
        m_sc.setRecordFormat("'dimension tag \"name\"'");
        for (long long i = 0; i < n; ++i) {
            sectionRecord("$PhysicalNames", "names", i, n, countLine);
            const int dim = m_sc.smallInteger("dimension");
            const int tag = m_sc.smallInteger("physical tag");
            std::string_view name = m_sc.restOfLine();
            if (name.size() >= 2 && name.front() == '"' && name.back() == '"') name = name.substr(1, name.size() - 2);
            if (name.empty()) fail(m_file, m_sc.line(), "physical group " + std::to_string(tag) + " has an empty name");
            m_b.names[{dim, tag}] = std::string(name);
        }
        sectionEnd("$EndPhysicalNames", "$PhysicalNames", n, "names", countLine);
        m_sc.setRecordFormat("");
    }

    void readEntities() {
        if (!m_sc.nextRecord()) fail(m_file, m_sc.lastLine(), "the file ends right after $Entities");
        const int countLine = m_sc.line();
        m_sc.setRecordFormat("'numPoints numCurves numSurfaces numVolumes'");
        long long counts[4];
        for (auto& c : counts) {
            c = m_sc.integer("number of entities");
            if (c < 0) fail(m_file, countLine, "negative number of entities");
        }
        m_sc.expectEndOfLine("the four entity counts");
        const long long total = counts[0] + counts[1] + counts[2] + counts[3];
        long long done = 0;
        for (int dim = 0; dim < 4; ++dim) {
            m_sc.setRecordFormat(dim == 0 ? "'tag x y z numPhysicalTags physicalTags...'"
                                           : "'tag minX minY minZ maxX maxY maxZ numPhysicalTags physicalTags... "
                                             "numBounding boundingTags...'");
            for (long long i = 0; i < counts[dim]; ++i, ++done) {
                sectionRecord("$Entities", "entities", done, total, countLine);
                const int tag = m_sc.smallInteger("entity tag");
                for (int k = 0; k < (dim == 0 ? 3 : 6); ++k) m_sc.real("entity coordinate");
                const long long np = m_sc.integer("number of physical tags");
                if (np < 0 || np > 100000) fail(m_file, m_sc.line(), "bad number of physical tags " + std::to_string(np));
                auto& phys = m_entities[{dim, tag}];
                for (long long k = 0; k < np; ++k) phys.push_back(m_sc.smallInteger("physical tag"));
                m_sc.skipRestOfLine();  // bounding entities
            }
        }
        sectionEnd("$EndEntities", "$Entities", total, "entities", countLine);
        m_sc.setRecordFormat("");
    }

    void readNodes4() {
        if (!m_sc.nextRecord()) fail(m_file, m_sc.lastLine(), "the file ends right after $Nodes");
        const int countLine = m_sc.line();
        m_sc.setRecordFormat("'numEntityBlocks numNodes minNodeTag maxNodeTag'");
        const long long blocks = m_sc.integer("number of entity blocks");
        const long long n = m_sc.integer("number of nodes");
        m_sc.integer("smallest node tag");
        m_sc.integer("largest node tag");
        m_sc.expectEndOfLine("the node counts");
        if (blocks < 0 || n < 0) fail(m_file, countLine, "negative count in the $Nodes header");
        auto& pts = m_b.mesh.points;
        pts.reserve(reserveHint(n));
        m_ids.reserve(reserveHint(n));
        m_lines.reserve(reserveHint(n));
        long long done = 0;
        std::vector<long long> blockIds;
        for (long long b = 0; b < blocks; ++b) {
            sectionRecord("$Nodes", "nodes", done, n, countLine);
            m_sc.setRecordFormat("'entityDim entityTag parametric numNodesInBlock'");
            m_sc.integer("entity dimension");
            m_sc.integer("entity tag");
            const long long parametric = m_sc.integer("parametric flag");
            const long long inBlock = m_sc.integer("number of nodes in the block");
            m_sc.expectEndOfLine("the block header");
            if (inBlock < 0 || done + inBlock > n)
                fail(m_file, m_sc.line(),
                     "node block of " + std::to_string(inBlock) + " nodes exceeds the " + std::to_string(n) +
                         " nodes announced on line " + std::to_string(countLine) +
                         ": the counts of the file disagree; re-export it");
            blockIds.resize(size_t(inBlock));
            m_sc.setRecordFormat("'nodeTag'");
            for (long long k = 0; k < inBlock; ++k) {
                sectionRecord("$Nodes", "nodes", done, n, countLine);
                blockIds[size_t(k)] = m_sc.integer("node tag");
                m_sc.expectEndOfLine("the node tag");
            }
            m_sc.setRecordFormat(parametric ? "'x y z u [v [w]]'" : "'x y z'");
            for (long long k = 0; k < inBlock; ++k) {
                sectionRecord("$Nodes", "nodes", done, n, countLine);
                const double x = m_sc.real("x coordinate");
                const double y = m_sc.real("y coordinate");
                const double z = m_sc.real("z coordinate");
                if (parametric) m_sc.skipRestOfLine();
                else m_sc.expectEndOfLine("the z coordinate");
                addNode(blockIds[size_t(k)], x, y, z);
                ++done;
            }
        }
        if (done != n)
            fail(m_file, m_sc.lastLine(),
                 "$Nodes section ends after " + std::to_string(done) + " of " + std::to_string(n) +
                     " nodes (the count is on line " + std::to_string(countLine) + "): the blocks hold fewer nodes than announced");
        sectionEnd("$EndNodes", "$Nodes", n, "nodes", countLine);
        finishNodes();
    }

    void readElements4() {
        if (!m_sc.nextRecord()) fail(m_file, m_sc.lastLine(), "the file ends right after $Elements");
        const int countLine = m_sc.line();
        m_sc.setRecordFormat("'numEntityBlocks numElements minElementTag maxElementTag'");
        const long long blocks = m_sc.integer("number of entity blocks");
        const long long n = m_sc.integer("number of elements");
        m_sc.integer("smallest element tag");
        m_sc.integer("largest element tag");
        m_sc.expectEndOfLine("the element counts");
        if (blocks < 0 || n < 0) fail(m_file, countLine, "negative count in the $Elements header");
        reserveElements(n);
        long long done = 0;
        const std::vector<int> none;
        for (long long b = 0; b < blocks; ++b) {
            sectionRecord("$Elements", "elements", done, n, countLine);
            m_sc.setRecordFormat("'entityDim entityTag elementType numElementsInBlock'");
            const int dim = m_sc.smallInteger("entity dimension");
            const int entity = m_sc.smallInteger("entity tag");
            const int type = m_sc.smallInteger("element type");
            const long long inBlock = m_sc.integer("number of elements in the block");
            m_sc.expectEndOfLine("the block header");
            if (inBlock < 0 || done + inBlock > n)
                fail(m_file, m_sc.line(),
                     "element block of " + std::to_string(inBlock) + " elements exceeds the " + std::to_string(n) +
                         " elements announced on line " + std::to_string(countLine) +
                         ": the counts of the file disagree; re-export it");
            const auto it = m_entities.find({dim, entity});
            const std::vector<int>& phys = it == m_entities.end() ? none : it->second;
            m_sc.setRecordFormat("'elementTag nodeTags...'");
            for (long long k = 0; k < inBlock; ++k, ++done) {
                sectionRecord("$Elements", "elements", done, n, countLine);
                const long long number = m_sc.integer("element tag");
                m_tags.clear();
                while (m_sc.lineHasMore()) m_tags.push_back(m_sc.integer("node tag"));
                addElement(number, type, dim, phys);
            }
        }
        if (done != n)
            fail(m_file, m_sc.lastLine(),
                 "$Elements section ends after " + std::to_string(done) + " of " + std::to_string(n) +
                     " elements (the count is on line " + std::to_string(countLine) + "): the blocks hold fewer elements than announced");
        sectionEnd("$EndElements", "$Elements", n, "elements", countLine);
        m_haveElements = true;
    }

    void reserveElements(long long n) {
        auto& m = m_b.mesh;
        m.tetrahedra.reserve(reserveHint(n));
        m.tetrahedronGroup.reserve(reserveHint(n));
        m_b.origin.tetLine.reserve(reserveHint(n));
        m_b.origin.tetNumber.reserve(reserveHint(n));
    }

    Scanner m_sc;
    const std::string& m_file;
    Builder& m_b;
    int m_version = 0;
    bool m_haveNodes = false, m_haveElements = false;
    std::vector<long long> m_ids;
    std::vector<int> m_lines;
    NodeIdMap m_map;
    std::vector<long long> m_tags;
    std::vector<int> m_idx;
    std::map<std::pair<int, int>, std::vector<int>> m_entities;  ///< 4.1: (dim, entity) -> physical tags
};

// ------------------------------------------------------------------------------------------------
// TetGen .node / .ele

void readTetGen(const std::string& given, Builder& b) {
    const std::string ext = lowerExtension(given);
    fs::path base = fs::path(given);
    const bool extUpper = !ext.empty() && fs::path(given).extension().string() != ext;
    auto sibling = [&](const char* e) {
        fs::path p = base;
        std::string x = e;
        if (extUpper)
            for (auto& c : x) c = char(std::toupper((unsigned char)c));
        return p.replace_extension(x).string();
    };
    const std::string nodeFile = ext == ".node" ? given : sibling(".node");
    const std::string eleFile = ext == ".ele" ? given : sibling(".ele");
    const std::string other = ext == ".node" ? eleFile : nodeFile;
    {
        std::error_code ec;
        if (!fs::exists(other, ec))
            fail(given, 0,
                 "a TetGen mesh needs both files: '" + other + "' was not found beside '" + given +
                     "' (TetGen writes name.node with the nodes and name.ele with the tetrahedra)");
    }
    b.report->format = "TetGen";
    b.origin.nodeFile = nodeFile;
    b.origin.elementFile = eleFile;

    // .node: "<#points> <dimension> <#attributes> <#boundary markers>", then "id x y z [attrs] [marker]"
    const std::string nodeText = readWholeFile(nodeFile);
    Scanner sn(nodeText, nodeFile, '#');
    if (!sn.nextRecord()) fail(nodeFile, 0, "TetGen node file '" + nodeFile + "' is empty");
    sn.setRecordFormat("'#points dimension #attributes #boundary-markers'");
    const long long n = sn.integer("number of points");
    const long long dim = sn.integer("dimension");
    sn.skipRestOfLine();
    const int countLine = sn.line();
    if (n <= 0)
        fail(nodeFile, countLine,
             "the TetGen node file declares " + std::to_string(n) + " points; a mesh needs its points in the .node file");
    if (dim != 3) fail(nodeFile, countLine, "the TetGen node file is " + std::to_string(dim) + "-dimensional; only 3-D meshes are supported");
    sn.setRecordFormat("'point-id x y z [attributes] [boundary-marker]'");
    std::vector<long long> ids;
    std::vector<int> lines;
    ids.reserve(reserveHint(n));
    lines.reserve(reserveHint(n));
    b.mesh.points.reserve(reserveHint(n));
    for (long long i = 0; i < n; ++i) {
        if (!sn.nextRecord())
            fail(nodeFile, sn.lastLine(),
                 "the TetGen node file ends after " + std::to_string(i) + " of " + std::to_string(n) +
                     " points (the count is on line " + std::to_string(countLine) + "): the file is truncated");
        const long long id = sn.integer("point id");
        const double x = sn.real("x coordinate"), y = sn.real("y coordinate"), z = sn.real("z coordinate");
        sn.skipRestOfLine();
        if (id < 0) fail(nodeFile, sn.line(), "negative point id " + std::to_string(id));
        if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
            fail(nodeFile, sn.line(),
                 "point " + std::to_string(id) + " has a non-finite coordinate (" + fmtNumber(x) + " " + fmtNumber(y) +
                     " " + fmtNumber(z) + "); every coordinate must be a finite number");
        b.mesh.points.emplace_back(x, y, z);
        ids.push_back(id);
        lines.push_back(sn.line());
    }
    if (sn.nextRecord())
        fail(nodeFile, sn.line(),
             "the TetGen node file has more records than the " + std::to_string(n) + " points announced on line " +
                 std::to_string(countLine));
    NodeIdMap map;
    map.build(ids, lines, nodeFile);

    // .ele: "<#tetrahedra> <nodes per tetrahedron> <#attributes>", then "id n1 n2 n3 n4 [attrs]"
    const std::string eleText = readWholeFile(eleFile);
    Scanner se(eleText, eleFile, '#');
    if (!se.nextRecord()) fail(eleFile, 0, "TetGen element file '" + eleFile + "' is empty");
    se.setRecordFormat("'#tetrahedra nodes-per-tetrahedron #attributes'");
    const long long m = se.integer("number of tetrahedra");
    const long long per = se.integer("nodes per tetrahedron");
    long long nattr = 0;
    if (se.lineHasMore()) nattr = se.integer("number of attributes");
    se.expectEndOfLine("the number of attributes");
    const int eleCountLine = se.line();
    if (m < 0) fail(eleFile, eleCountLine, "negative number of tetrahedra");
    if (per == 10)
        fail(eleFile, eleCountLine,
             "second-order (10-node) tetrahedra are not supported: mesh with linear (4-node) tetrahedra (tetgen "
             "without -o2)");
    if (per != 4) fail(eleFile, eleCountLine, "a TetGen tetrahedron has 4 nodes, the header says " + std::to_string(per));
    se.setRecordFormat("'tetrahedron-id n1 n2 n3 n4 [attributes]'");
    auto& mesh = b.mesh;
    mesh.tetrahedra.reserve(reserveHint(m));
    for (long long i = 0; i < m; ++i) {
        if (!se.nextRecord())
            fail(eleFile, se.lastLine(),
                 "the TetGen element file ends after " + std::to_string(i) + " of " + std::to_string(m) +
                     " tetrahedra (the count is on line " + std::to_string(eleCountLine) + "): the file is truncated");
        const long long number = se.integer("tetrahedron id");
        std::array<int, 4> t;
        for (int k = 0; k < 4; ++k) {
            const long long id = se.integer("node id");
            t[size_t(k)] = map.find(id);
            if (t[size_t(k)] < 0)
                fail(eleFile, se.line(),
                     "tetrahedron " + std::to_string(number) + " names node " + std::to_string(id) +
                         ", which is not in '" + nodeFile + "'; fix the element's node list");
        }
        int group = 0;
        if (nattr > 0) {
            const double region = se.real("region attribute");
            if (std::isfinite(region) && region == std::floor(region) && std::abs(region) < 2e9) group = int(region);
            for (long long k = 1; k < nattr; ++k) se.real("attribute");
        }
        se.expectEndOfLine(nattr > 0 ? "the attributes" : "the four nodes");
        mesh.tetrahedra.push_back(t);
        mesh.tetrahedronGroup.push_back(group);
        b.origin.tetLine.push_back(se.line());
        b.origin.tetNumber.push_back(number);
        b.markGroup(3, group, t.data(), 4);
    }
    if (se.nextRecord())
        fail(eleFile, se.line(),
             "the TetGen element file has more records than the " + std::to_string(m) +
                 " tetrahedra announced on line " + std::to_string(eleCountLine));
    b.origin.nodeId = std::move(ids);
    b.origin.nodeLine = std::move(lines);
}

// ------------------------------------------------------------------------------------------------
// VTK

/// Collects VTK's error messages, and warnings that report read errors; prints nothing.
class CapturingOutputWindow : public vtkOutputWindow {
public:
    static CapturingOutputWindow* New();
    vtkTypeMacro(CapturingOutputWindow, vtkOutputWindow)
    void DisplayText(const char*) override {}
    void DisplayErrorText(const char* text) override {
        if (text) errors.emplace_back(text);
    }
    void DisplayWarningText(const char* text) override { warning(text); }
    void DisplayGenericWarningText(const char* text) override { warning(text); }
    void DisplayDebugText(const char*) override {}
    std::vector<std::string> errors;

protected:
    CapturingOutputWindow() = default;

private:
    void warning(const char* text) {
        // the legacy reader reports bad or missing data ("Error reading ascii data...") as a warning
        if (text && std::strstr(text, "rror")) errors.emplace_back(text);
    }
};
vtkStandardNewMacro(CapturingOutputWindow)

/// VTK's readers print their errors and return an empty output instead of throwing. While a catcher
/// lives, VTK's messages go to it instead of the console (output window and vtkLogger's stderr);
/// errors() says what went wrong.
class VtkMessageCatcher {
public:
    VtkMessageCatcher()
        : m_previous(vtkOutputWindow::GetInstance()), m_display(vtkObject::GetGlobalWarningDisplay()),
          m_logVerbosity(vtkLogger::GetCurrentVerbosityCutoff()) {
        vtkObject::GlobalWarningDisplayOn();  // off would drop the messages before our observers see them
        vtkOutputWindow::SetInstance(m_window);
        // messages of objects nobody observes (the XML parser, the pipeline) also go to vtkLogger
        vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
        m_callback->SetClientData(this);
        m_callback->SetCallback(&VtkMessageCatcher::onMessage);
    }
    ~VtkMessageCatcher() {
        vtkLogger::SetStderrVerbosity(m_logVerbosity);
        vtkOutputWindow::SetInstance(m_previous);
        vtkObject::SetGlobalWarningDisplay(m_display);
    }
    VtkMessageCatcher(const VtkMessageCatcher&) = delete;
    VtkMessageCatcher& operator=(const VtkMessageCatcher&) = delete;

    void watch(vtkObject* obj) {
        obj->AddObserver(vtkCommand::ErrorEvent, m_callback);
        obj->AddObserver(vtkCommand::WarningEvent, m_callback);
    }
    bool hasErrors() const { return !m_errors.empty() || !m_window->errors.empty(); }
    std::string errors() const {
        std::vector<std::string> all = m_errors;
        for (const auto& e : m_window->errors) all.push_back(clean(e));
        std::string out;
        for (const auto& e : all)
            if (!e.empty() && out.find(e) == std::string::npos) out += (out.empty() ? "" : "; ") + e;
        return out;
    }

private:
    /// VTK writes "ERROR: In /path/file.cxx, line N\nvtkClass (0x...): message\n..."; keeps the
    /// message's first line, and drops the pipeline's "returned failure for request" dumps.
    static std::string clean(std::string text) {
        if (text.compare(0, 6, "ERROR:") == 0 || text.compare(0, 8, "Warning:") == 0 ||
            text.compare(0, 15, "Generic Warning") == 0) {
            const auto nl = text.find('\n');
            text = nl == std::string::npos ? std::string() : text.substr(nl + 1);
        }
        const auto colon = text.find("): ");
        if (colon != std::string::npos && text.compare(0, 3, "vtk") == 0) text = text.substr(colon + 3);
        const auto nl = text.find('\n');
        if (nl != std::string::npos) text.resize(nl);
        while (!text.empty() && std::isspace((unsigned char)text.back())) text.pop_back();
        if (text.find("returned failure for request") != std::string::npos) return {};
        return text;
    }
    static void onMessage(vtkObject*, unsigned long event, void* self, void* callData) {
        auto* me = static_cast<VtkMessageCatcher*>(self);
        if (!callData) return;
        const char* text = static_cast<const char*>(callData);
        if (event == vtkCommand::ErrorEvent || std::strstr(text, "rror")) me->m_errors.push_back(clean(text));
    }

    vtkSmartPointer<vtkOutputWindow> m_previous;
    int m_display;
    vtkLogger::Verbosity m_logVerbosity;
    vtkNew<CapturingOutputWindow> m_window;
    vtkNew<vtkCallbackCommand> m_callback;
    std::vector<std::string> m_errors;
};

std::string vtkCellName(int type) {
    switch (type) {
    case VTK_EMPTY_CELL: return "empty cell";
    case VTK_VERTEX: return "point";
    case VTK_POLY_VERTEX: return "poly-point";
    case VTK_LINE: return "line";
    case VTK_POLY_LINE: return "polyline";
    case VTK_TRIANGLE_STRIP: return "triangle strip";
    case VTK_POLYGON: return "polygon";
    case VTK_PIXEL: return "pixel";
    case VTK_QUAD: return "quadrangle";
    case VTK_WEDGE: return "prism";
    case VTK_PYRAMID: return "pyramid";
    case VTK_QUADRATIC_EDGE: return "3-node line";
    case VTK_QUADRATIC_TRIANGLE: return "6-node triangle";
    case VTK_QUADRATIC_QUAD: return "8-node quadrangle";
    case VTK_QUADRATIC_TETRA: return "10-node tetrahedron";
    case VTK_QUADRATIC_HEXAHEDRON: return "20-node hexahedron";
    case VTK_QUADRATIC_WEDGE: return "15-node prism";
    case VTK_QUADRATIC_PYRAMID: return "13-node pyramid";
    case VTK_TRIQUADRATIC_HEXAHEDRON: return "27-node hexahedron";
    case VTK_POLYHEDRON: return "polyhedron";
    default: {
        const char* cls = vtkCellTypes::GetClassNameFromTypeId(type);
        return "VTK cell type " + std::to_string(type) + (cls && *cls ? std::string(" (") + cls + ")" : std::string());
    }
    }
}

void readVtk(const std::string& path, bool xml, Builder& b) {
    checkReadable(path);
    b.origin.elementWord = "cell";
    VtkMessageCatcher catcher;
    vtkSmartPointer<vtkUnstructuredGrid> grid;
    if (xml) {
        b.report->format = "VTK XML";
        vtkNew<vtkXMLUnstructuredGridReader> reader;
        catcher.watch(reader);
        if (!reader->CanReadFile(path.c_str()))
            fail(path, 0,
                 "'" + path + "' is not a VTK XML unstructured grid: a .vtu file starts with <VTKFile "
                 "type=\"UnstructuredGrid\" ...>; check that the file is complete and of the right kind");
        reader->SetFileName(path.c_str());
        reader->Update();
        if (catcher.hasErrors() || reader->GetErrorCode() != 0)
            fail(path, 0,
                 "VTK could not read '" + path + "'" + (catcher.hasErrors() ? ": " + catcher.errors() : std::string()) +
                     "; check that the file is a complete VTK XML unstructured grid");
        grid = reader->GetOutput();
    } else {
        b.report->format = "VTK legacy";
        {
            // vtkDataSetReader reads the header only, to name the dataset kind when it is not a grid
            vtkNew<vtkDataSetReader> probe;
            catcher.watch(probe);
            probe->SetFileName(path.c_str());
            const int type = probe->ReadOutputType();
            if (type < 0 || catcher.hasErrors())
                fail(path, 0,
                     "'" + path + "' is not a VTK legacy file VTK can read" +
                         (catcher.hasErrors() ? " (" + catcher.errors() + ")" : std::string()) +
                         "; it must start with '# vtk DataFile Version x.x', a title line, ASCII or BINARY, and "
                         "'DATASET UNSTRUCTURED_GRID'");
            if (type != VTK_UNSTRUCTURED_GRID) {
                const char* name = vtkDataObjectTypes::GetClassNameFromTypeId(type);
                fail(path, 0,
                     "'" + path + "' holds a " + (name ? std::string(name) : "type " + std::to_string(type)) +
                         " dataset; only DATASET UNSTRUCTURED_GRID has volume cells (tetrahedra, hexahedra)");
            }
        }
        vtkNew<vtkUnstructuredGridReader> reader;
        catcher.watch(reader);
        reader->SetFileName(path.c_str());
        reader->Update();
        vtkUnstructuredGrid* out = reader->GetOutput();
        if (catcher.hasErrors() || reader->GetErrorCode() != 0 || !out)
            fail(path, 0,
                 "VTK could not read '" + path + "'" + (catcher.hasErrors() ? ": " + catcher.errors() : std::string()) +
                     "; check that the file is complete");
        grid = out;
    }

    const vtkIdType nPoints = grid->GetNumberOfPoints();
    const vtkIdType nCells = grid->GetNumberOfCells();
    if (nPoints == 0 && nCells == 0)
        fail(path, 0, "'" + path + "' has no points and no cells: VTK read an empty grid; is the file complete?");
    auto& mesh = b.mesh;
    mesh.points.resize(size_t(nPoints));
    for (vtkIdType i = 0; i < nPoints; ++i) {
        double x[3];
        grid->GetPoint(i, x);
        mesh.points[size_t(i)] = Vec3(x[0], x[1], x[2]);
    }

    // physical groups
    vtkDataArray* groups = nullptr;
    vtkCellData* cd = grid->GetCellData();
    for (const char* gname : {"gmsh:physical", "CellEntityIds"}) {
        vtkDataArray* a = cd ? cd->GetArray(gname) : nullptr;
        if (a && a->GetNumberOfComponents() == 1 && a->GetNumberOfTuples() == nCells) {
            groups = a;
            break;
        }
    }

    std::vector<vtkIdType> tetCells, hexCells;
    vtkNew<vtkIdList> ids;
    std::vector<int> nodes;
    for (vtkIdType c = 0; c < nCells; ++c) {
        const int type = grid->GetCellType(c);
        grid->GetCellPoints(c, ids);
        nodes.resize(size_t(ids->GetNumberOfIds()));
        for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k) {
            const vtkIdType v = ids->GetId(k);
            if (v < 0 || v >= nPoints)
                fail(path, 0,
                     "cell " + std::to_string(c) + " names point " + std::to_string(v) + ", but the file has " +
                         plural(nPoints, "point") + " (0-based indices 0 to " + std::to_string(nPoints - 1) + ")");
            nodes[size_t(k)] = int(v);
        }
        const int group = groups ? int(std::lround(groups->GetComponent(c, 0))) : 0;
        if (type == VTK_TETRA && nodes.size() == 4) {
            mesh.tetrahedra.push_back({nodes[0], nodes[1], nodes[2], nodes[3]});
            mesh.tetrahedronGroup.push_back(group);
            b.origin.tetNumber.push_back(c);
            tetCells.push_back(c);
        } else if ((type == VTK_HEXAHEDRON || type == VTK_VOXEL) && nodes.size() == 8) {
            std::array<int, 8> h;
            if (type == VTK_VOXEL)  // voxels number their corners like a grid: (0,1,3,2, 4,5,7,6)
                h = {nodes[0], nodes[1], nodes[3], nodes[2], nodes[4], nodes[5], nodes[7], nodes[6]};
            else
                std::copy(nodes.begin(), nodes.end(), h.begin());
            mesh.hexahedra.push_back(h);
            mesh.hexahedronGroup.push_back(group);
            b.origin.hexNumber.push_back(c);
            hexCells.push_back(c);
        } else if (type == VTK_TRIANGLE && nodes.size() == 3) {
            mesh.triangles.push_back({nodes[0], nodes[1], nodes[2]});
            mesh.triangleGroup.push_back(group);
        } else {
            b.skip(vtkCellName(type));
        }
        if (group != 0) b.markGroup(-1, group, nodes.data(), nodes.size());
    }

    // per-cell arrays with 1 or 3 components, restricted to the volume cells (tets first, then hexes)
    if (cd) {
        for (int a = 0; a < cd->GetNumberOfArrays(); ++a) {
            vtkDataArray* arr = cd->GetArray(a);
            if (!arr || !arr->GetName() || arr->GetNumberOfTuples() != nCells) continue;
            const int nc = arr->GetNumberOfComponents();
            if (nc != 1 && nc != 3) continue;
            std::vector<double> values;
            values.reserve((tetCells.size() + hexCells.size()) * size_t(nc));
            for (const auto* list : {&tetCells, &hexCells})
                for (vtkIdType c : *list)
                    for (int k = 0; k < nc; ++k) values.push_back(arr->GetComponent(c, k));
            mesh.cellArrays[arr->GetName()] = std::move(values);
        }
    }
}

} // namespace

// ------------------------------------------------------------------------------------------------

double tetrahedronSignedVolume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    return (b - a).dot((c - a).cross(d - a)) / 6.0;
}

double hexahedronVolume(const std::array<Vec3, 8>& x) {
    // The volume is the integral of det J over the unit cube. Each column of J is bilinear in the two
    // other parametric coordinates, so det J has degree <= 2 in each coordinate and the 2x2x2 Gauss
    // rule integrates it exactly, warped faces included.
    static const int corner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                     {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    const double g[2] = {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)};
    double volume = 0;
    for (double u : g)
        for (double v : g)
            for (double w : g) {
                const double q[3] = {u, v, w};
                Mat3 J = Mat3::Zero();
                for (int i = 0; i < 8; ++i) {
                    double f[3], df[3];  // 1-D shape factor and its derivative per direction
                    for (int k = 0; k < 3; ++k) {
                        f[k] = corner[i][k] ? q[k] : 1.0 - q[k];
                        df[k] = corner[i][k] ? 1.0 : -1.0;
                    }
                    J.col(0) += x[size_t(i)] * (df[0] * f[1] * f[2]);
                    J.col(1) += x[size_t(i)] * (f[0] * df[1] * f[2]);
                    J.col(2) += x[size_t(i)] * (f[0] * f[1] * df[2]);
                }
                volume += J.determinant() / 8.0;
            }
    return volume;
}

double hexahedronVolume(const Positions& points, const std::array<int, 8>& hex) {
    std::array<Vec3, 8> x;
    for (size_t i = 0; i < 8; ++i) x[i] = points[size_t(hex[i])];
    return hexahedronVolume(x);
}

double totalVolume(const MeshData& mesh) {
    double v = 0;
    for (const auto& t : mesh.tetrahedra)
        v += tetrahedronSignedVolume(mesh.points[size_t(t[0])], mesh.points[size_t(t[1])], mesh.points[size_t(t[2])],
                                     mesh.points[size_t(t[3])]);
    for (const auto& h : mesh.hexahedra) v += hexahedronVolume(mesh.points, h);
    return v;
}

void validateMesh(MeshData& mesh, const std::string& file, const ReadOptions& opt, ReadReport* report) {
    ReadReport local;
    ElementOrigin origin;
    origin.nodeFile = origin.elementFile = file;
    validateImpl(mesh, origin, opt, report ? *report : local);
}

MeshData readMesh(const std::string& path, const ReadOptions& opt, ReadReport* report) {
    ReadReport local;
    ReadReport& rep = report ? *report : local;
    rep = ReadReport{};
    Builder b;
    b.report = &rep;
    b.origin.nodeFile = b.origin.elementFile = path;
    const std::string ext = lowerExtension(path);
    try {
        if (ext == ".msh") {
            const std::string text = readWholeFile(path);
            GmshReader(text, path, b).read();
        } else if (ext == ".vtk" || ext == ".vtu") {
            readVtk(path, ext == ".vtu", b);
        } else if (ext == ".node" || ext == ".ele") {
            readTetGen(path, b);
        }
    } catch (const std::bad_alloc&) {
        fail(path, 0, "mesh file '" + path + "' announces more records than fit in memory: its header is corrupt");
    }
    if (ext != ".msh" && ext != ".vtk" && ext != ".vtu" && ext != ".node" && ext != ".ele") {
        fail(path, 0,
             (ext.empty() ? std::string("mesh file '") + path + "' has no extension"
                          : "unknown mesh file extension '" + ext + "' of '" + path + "'") +
                 ": " + kSupported);
    }
    b.finishGroups();
    validateImpl(b.mesh, b.origin, opt, rep);
    return std::move(b.mesh);
}

} // namespace fascia::meshio
