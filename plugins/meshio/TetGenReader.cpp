#include "TetGenReader.h"
#include "NodeIdMap.h"
#include "TextScanner.h"

#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <system_error>
#include <utility>
#include <vector>

namespace fascia::meshio::detail {
namespace {

namespace fs = std::filesystem;

/// .node: "<#points> <dimension> <#attributes> <#boundary markers>", then "id x y z [attrs] [marker]".
/// Fills b.mesh.points; ids and lines get the file's id and the line of each point.
void readNodeFile(const std::string& nodeFile, MeshBuilder& b, std::vector<long long>& ids, std::vector<int>& lines) {
    const std::string nodeText = readWholeFile(nodeFile);
    TextScanner sn(nodeText, nodeFile, '#');
    if (!sn.nextRecord()) fail(nodeFile, 1, "TetGen node file '" + nodeFile + "' is empty");
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
                 "point " + std::to_string(id) + " has a non-finite coordinate (" + formatNumber(x, 6) + " " + formatNumber(y, 6) +
                     " " + formatNumber(z, 6) + "); every coordinate must be a finite number");
        b.mesh.points.emplace_back(x, y, z);
        ids.push_back(id);
        lines.push_back(sn.line());
    }
    if (sn.nextRecord())
        fail(nodeFile, sn.line(),
             "the TetGen node file has more records than the " + std::to_string(n) + " points announced on line " +
                 std::to_string(countLine));
}

/// .ele: "<#tetrahedra> <nodes per tetrahedron> <#attributes>", then "id n1 n2 n3 n4 [attrs]"; the
/// region attribute (the first one, when it is a whole number) is the element's group.
void readEleFile(const std::string& eleFile, const std::string& nodeFile, const NodeIdMap& map, MeshBuilder& b) {
    const std::string eleText = readWholeFile(eleFile);
    TextScanner se(eleText, eleFile, '#');
    if (!se.nextRecord()) fail(eleFile, 1, "TetGen element file '" + eleFile + "' is empty");
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
}

/// The .node and .ele files of the TetGen mesh named by `given` (either of them), the other one with
/// an extension of the same case.
std::pair<std::string, std::string> tetGenFiles(const std::string& given) {
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
    return {ext == ".node" ? given : sibling(".node"), ext == ".ele" ? given : sibling(".ele")};
}

} // namespace

void checkTetGenFiles(const std::string& given) {
    const auto [nodeFile, eleFile] = tetGenFiles(given);
    const std::string other = nodeFile == given ? eleFile : nodeFile;
    std::error_code ec;
    if (!fs::exists(other, ec))
        fail(given, 0,
             "a TetGen mesh needs both files: '" + other + "' was not found beside '" + given +
                 "' (TetGen writes name.node with the nodes and name.ele with the tetrahedra)");
    checkReadable(nodeFile);
    checkReadable(eleFile);
}

void readTetGen(const std::string& given, MeshBuilder& b) {
    checkTetGenFiles(given);
    const auto [nodeFile, eleFile] = tetGenFiles(given);
    b.report->format = "TetGen";
    b.origin.nodeFile = nodeFile;
    b.origin.elementFile = eleFile;

    std::vector<long long> ids;
    std::vector<int> lines;
    readNodeFile(nodeFile, b, ids, lines);
    NodeIdMap map;
    map.build(ids, lines, nodeFile);
    readEleFile(eleFile, nodeFile, map, b);
    b.origin.nodeId = std::move(ids);
    b.origin.nodeLine = std::move(lines);
}

} // namespace fascia::meshio::detail
