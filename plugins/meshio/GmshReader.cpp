#include "GmshReader.h"
#include "NodeIdMap.h"
#include "TextScanner.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string_view>
#include <utility>
#include <vector>

namespace fascia::meshio::detail {
namespace {

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
    GmshReader(const std::string& text, const std::string& file, MeshBuilder& b) : m_sc(text, file), m_file(file), m_b(b) {}

    void read() {
        if (!m_sc.nextRecord()) fail(m_file, 1, "mesh file '" + m_file + "' is empty");
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
        // the file ends where the missing section was due
        if (!m_haveNodes) fail(m_file, std::max(1, m_sc.line()), m_version == 1 ? "the file ends without a $NOD section" : "the file ends without a $Nodes section");
        if (!m_haveElements)
            fail(m_file, std::max(1, m_sc.line()), m_version == 1 ? "the file ends without an $ELM section" : "the file ends without an $Elements section");
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
                 "node " + std::to_string(id) + " has a non-finite coordinate (" + formatNumber(x, 6) + " " + formatNumber(y, 6) +
                     " " + formatNumber(z, 6) + "); every coordinate must be a finite number");
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
        // each entity is a line of at least 10 bytes ("1 0 0 0 0\n"): no count may pass what is left
        // of the file, so that the sum below cannot overflow
        const long long left = m_sc.remaining();
        for (const long long c : counts)
            if (c > left / 10)
                fail(m_file, countLine,
                     "the $Entities header announces " + std::to_string(c) + " entities of one dimension, more than the " +
                         std::to_string(left) + " bytes left in the file can hold (an entity takes 10 bytes or more): "
                         "the header is corrupt");
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

    TextScanner m_sc;
    const std::string& m_file;
    MeshBuilder& m_b;
    int m_version = 0;
    bool m_haveNodes = false, m_haveElements = false;
    std::vector<long long> m_ids;
    std::vector<int> m_lines;
    NodeIdMap m_map;
    std::vector<long long> m_tags;
    std::vector<int> m_idx;
    std::map<std::pair<int, int>, std::vector<int>> m_entities;  ///< 4.1: (dim, entity) -> physical tags
};

} // namespace

void readGmsh(const std::string& path, MeshBuilder& b) {
    const std::string text = readWholeFile(path);
    GmshReader(text, path, b).read();
}

} // namespace fascia::meshio::detail
