// Tests of the mesh readers: every format on the meshes of scenes/meshes and on small hand-written
// files in tests/data, and a located error for each kind of bad input.
#include <catch2/catch.hpp>

#include "MeshReaders.h"
#include "fascia/base/Error.h"

#include <Eigen/Dense>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDoubleArray.h>
#include <vtkIdList.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>
#include <vtkUnstructuredGridReader.h>
#include <vtkUnstructuredGridWriter.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>
#include <vector>

using namespace fascia;
using namespace fascia::meshio;
namespace fs = std::filesystem;

namespace {

const std::string kMeshes = FASCIA_SOURCE_DIR "/scenes/meshes/";
const std::string kData = FASCIA_SOURCE_DIR "/plugins/meshio/tests/data/";

/// A temporary folder for files the tests write, one per test process, removed at exit.
class TempDir {
public:
    TempDir() {
        m_path = fs::temp_directory_path() / ("fascia_meshio_test_" + std::to_string(::getpid()));
        fs::create_directories(m_path);
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(m_path, ec);
    }
    std::string file(const std::string& name) const { return (m_path / name).string(); }
    std::string write(const std::string& name, const std::string& text) const {
        const std::string p = file(name);
        std::ofstream out(p, std::ios::binary);
        out << text;
        return p;
    }

private:
    fs::path m_path;
};

const TempDir& tmp() {
    static TempDir dir;
    return dir;
}

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::vector<std::string> splitLines(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    return lines;
}

std::string num(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

/// What readMesh threw, if anything.
struct Caught {
    bool thrown = false;
    std::string what;
    std::string file;
    int line = -1;
    long long byte = -1;
    core::ErrorKind kind = core::ErrorKind::Internal;
};

Caught readError(const std::string& path, const ReadOptions& opt = {}) {
    Caught c;
    try {
        readMesh(path, opt);
    } catch (const core::Error& e) {
        c.thrown = true;
        c.what = e.what();
        c.file = e.loc().file;
        c.line = e.loc().line;
        c.byte = e.loc().byte;
        c.kind = e.kind();
    }
    return c;
}

/// Reading `path` fails with an input error located at errorFile:line whose text has every key.
void requireLocatedError(const std::string& path, const std::string& errorFile, int line,
                         const std::vector<std::string>& keys, const ReadOptions& opt = {}) {
    const Caught c = readError(path, opt);
    INFO("file: " << path);
    INFO("message: " << c.what);
    REQUIRE(c.thrown);
    CHECK(c.kind == core::ErrorKind::Input);
    CHECK(c.file == errorFile);
    CHECK(c.line == line);
    CHECK(c.byte == -1);
    const std::string where = line > 0 ? errorFile + ":" + std::to_string(line) + ": error: " : errorFile + ": error: ";
    CHECK(c.what.rfind(where, 0) == 0);
    for (const auto& k : keys) CHECK_THAT(c.what, Catch::Contains(k));
}

/// Reading `path` fails with an input error located at byte offset `byte` of path ("path: byte N: error: ...").
void requireErrorAtByte(const std::string& path, size_t byte, const std::vector<std::string>& keys) {
    const Caught c = readError(path);
    INFO("file: " << path);
    INFO("message: " << c.what);
    REQUIRE(c.thrown);
    CHECK(c.kind == core::ErrorKind::Input);
    CHECK(c.file == path);
    CHECK(c.line == 0);
    CHECK(c.byte == (long long)byte);
    CHECK(c.what.rfind(path + ": byte " + std::to_string(byte) + ": error: ", 0) == 0);
    for (const auto& k : keys) CHECK_THAT(c.what, Catch::Contains(k));
}

// ---- the unit cube of tests/data/cube_gmsh22.msh with contiguous ids, as lines to edit ----------

const char* const kCube22 = R"($MeshFormat
2.2 0 8
$EndMeshFormat
$Nodes
8
1 0 0 0
2 1 0 0
3 1 1 0
4 0 1 0
5 0 0 1
6 1 0 1
7 1 1 1
8 0 1 1
$EndNodes
$Elements
5
1 4 2 1 1 1 2 4 5
2 4 2 1 1 3 4 2 7
3 4 2 1 1 6 5 7 2
4 4 2 1 1 8 7 5 4
5 4 2 1 1 2 4 5 7
$EndElements
)";

const char* const kErase = "<erase>";

/// Text with lines replaced (1-based; kErase drops the line); keepLines > 0 cuts the file there.
std::string edited(const std::string& text, const std::vector<std::pair<int, std::string>>& edits, int keepLines = 0) {
    std::vector<std::string> lines = splitLines(text);
    std::map<int, std::string> byLine(edits.begin(), edits.end());
    std::string out;
    for (size_t i = 0; i < lines.size(); ++i) {
        const int n = int(i) + 1;
        if (keepLines > 0 && n > keepLines) break;
        const auto it = byLine.find(n);
        if (it == byLine.end()) out += lines[i] + "\n";
        else if (it->second != kErase) out += it->second + "\n";
    }
    return out;
}

struct BadFile {
    std::string label;
    std::vector<std::pair<int, std::string>> edits;
    int keepLines;
    int errorLine;
    std::vector<std::string> keys;
};

// ---- writers of the other formats, to read one mesh in every format -----------------------------

void writeGmsh1(const std::string& path, const MeshData& m) {
    std::ostringstream o;
    o << "$NOD\n" << m.points.size() << "\n";
    for (size_t i = 0; i < m.points.size(); ++i)
        o << i + 1 << " " << num(m.points[i].x()) << " " << num(m.points[i].y()) << " " << num(m.points[i].z()) << "\n";
    o << "$ENDNOD\n$ELM\n" << m.tetrahedra.size() + m.triangles.size() << "\n";
    int n = 0;
    for (size_t i = 0; i < m.triangles.size(); ++i) {
        const auto& t = m.triangles[i];
        o << ++n << " 2 " << m.triangleGroup[i] << " 1 3 " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << "\n";
    }
    for (size_t i = 0; i < m.tetrahedra.size(); ++i) {
        const auto& t = m.tetrahedra[i];
        o << ++n << " 4 " << m.tetrahedronGroup[i] << " 1 4 " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << " "
          << t[3] + 1 << "\n";
    }
    o << "$ENDELM\n";
    tmp().write(path, o.str());
}

/// Gmsh 4.1: one volume entity per tetrahedron group, one surface entity per triangle group.
void writeGmsh41(const std::string& path, const MeshData& m) {
    const std::vector<int> tetTags = [&] {
        std::set<int> s(m.tetrahedronGroup.begin(), m.tetrahedronGroup.end());
        return std::vector<int>(s.begin(), s.end());
    }();
    const std::vector<int> triTags = [&] {
        std::set<int> s(m.triangleGroup.begin(), m.triangleGroup.end());
        return std::vector<int>(s.begin(), s.end());
    }();
    std::ostringstream o;
    o << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
    if (!m.groupNames.empty()) {
        o << "$PhysicalNames\n" << m.groupNames.size() << "\n";
        for (const auto& [tag, name] : m.groupNames)
            o << (std::count(tetTags.begin(), tetTags.end(), tag) ? 3 : 2) << " " << tag << " \"" << name << "\"\n";
        o << "$EndPhysicalNames\n";
    }
    o << "$Entities\n0 0 " << triTags.size() << " " << tetTags.size() << "\n";
    for (size_t e = 0; e < triTags.size(); ++e)
        o << e + 1 << " -1 -1 -1 1 1 1 " << (triTags[e] ? "1 " + std::to_string(triTags[e]) : "0") << " 0\n";
    for (size_t e = 0; e < tetTags.size(); ++e)
        o << e + 1 << " -1 -1 -1 1 1 1 " << (tetTags[e] ? "1 " + std::to_string(tetTags[e]) : "0") << " 0\n";
    o << "$EndEntities\n";
    const size_t n = m.points.size();
    o << "$Nodes\n1 " << n << " 1 " << n << "\n3 1 0 " << n << "\n";
    for (size_t i = 0; i < n; ++i) o << i + 1 << "\n";
    for (const auto& p : m.points) o << num(p.x()) << " " << num(p.y()) << " " << num(p.z()) << "\n";
    o << "$EndNodes\n";
    const size_t ne = m.tetrahedra.size() + m.triangles.size();
    o << "$Elements\n" << triTags.size() + tetTags.size() << " " << ne << " 1 " << ne << "\n";
    size_t tag = 0;
    for (size_t e = 0; e < triTags.size(); ++e) {
        const auto count = std::count(m.triangleGroup.begin(), m.triangleGroup.end(), triTags[e]);
        o << "2 " << e + 1 << " 2 " << count << "\n";
        for (size_t i = 0; i < m.triangles.size(); ++i)
            if (m.triangleGroup[i] == triTags[e]) {
                const auto& t = m.triangles[i];
                o << ++tag << " " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << "\n";
            }
    }
    for (size_t e = 0; e < tetTags.size(); ++e) {
        const auto count = std::count(m.tetrahedronGroup.begin(), m.tetrahedronGroup.end(), tetTags[e]);
        o << "3 " << e + 1 << " 4 " << count << "\n";
        for (size_t i = 0; i < m.tetrahedra.size(); ++i)
            if (m.tetrahedronGroup[i] == tetTags[e]) {
                const auto& t = m.tetrahedra[i];
                o << ++tag << " " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << " " << t[3] + 1 << "\n";
            }
    }
    o << "$EndElements\n";
    tmp().write(path, o.str());
}

void writeTetGen(const std::string& base, const MeshData& m, int firstId) {
    std::ostringstream node, ele;
    node << "# written by the Fascia tests\n" << m.points.size() << " 3 0 0\n";
    for (size_t i = 0; i < m.points.size(); ++i)
        node << i + size_t(firstId) << " " << num(m.points[i].x()) << " " << num(m.points[i].y()) << " "
             << num(m.points[i].z()) << "\n";
    ele << m.tetrahedra.size() << " 4 1\n";
    for (size_t i = 0; i < m.tetrahedra.size(); ++i) {
        const auto& t = m.tetrahedra[i];
        ele << i + size_t(firstId);
        for (int v : t) ele << " " << v + firstId;
        ele << " " << m.tetrahedronGroup[i] << "\n";
    }
    tmp().write(base + ".node", node.str());
    tmp().write(base + ".ele", ele.str());
}

void writeVtkLegacy(const std::string& path, const MeshData& m) {
    std::ostringstream o;
    o << "# vtk DataFile Version 3.0\nwritten by the Fascia tests\nASCII\nDATASET UNSTRUCTURED_GRID\n";
    o << "POINTS " << m.points.size() << " double\n";
    for (const auto& p : m.points) o << num(p.x()) << " " << num(p.y()) << " " << num(p.z()) << "\n";
    const size_t cells = m.tetrahedra.size() + m.triangles.size();
    o << "CELLS " << cells << " " << 5 * m.tetrahedra.size() + 4 * m.triangles.size() << "\n";
    for (const auto& t : m.tetrahedra) o << "4 " << t[0] << " " << t[1] << " " << t[2] << " " << t[3] << "\n";
    for (const auto& t : m.triangles) o << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
    o << "CELL_TYPES " << cells << "\n";
    for (size_t i = 0; i < m.tetrahedra.size(); ++i) o << "10\n";
    for (size_t i = 0; i < m.triangles.size(); ++i) o << "5\n";
    o << "CELL_DATA " << cells << "\nSCALARS gmsh:physical int 1\nLOOKUP_TABLE default\n";
    for (int g : m.tetrahedronGroup) o << g << "\n";
    for (int g : m.triangleGroup) o << g << "\n";
    tmp().write(path, o.str());
}

/// Writes a grid with VTK's own XML writer (binary appended data unless ascii; the appended data
/// base64-encoded, VTK's default, unless raw).
std::string writeVtu(const std::string& name, vtkUnstructuredGrid* grid, bool ascii, bool raw = false) {
    const std::string path = tmp().file(name);
    vtkNew<vtkXMLUnstructuredGridWriter> w;
    w->SetFileName(path.c_str());
    w->SetInputData(grid);
    if (ascii) w->SetDataModeToAscii();
    if (raw) w->EncodeAppendedDataOff();
    REQUIRE(w->Write() == 1);
    return path;
}

vtkNew<vtkUnstructuredGrid> toVtkGrid(const MeshData& m) {
    vtkNew<vtkUnstructuredGrid> g;
    vtkNew<vtkPoints> pts;
    pts->SetDataTypeToDouble();
    for (const auto& p : m.points) pts->InsertNextPoint(p.x(), p.y(), p.z());
    g->SetPoints(pts);
    vtkNew<vtkIntArray> phys;
    phys->SetName("gmsh:physical");
    for (size_t i = 0; i < m.tetrahedra.size(); ++i) {
        const vtkIdType ids[4] = {m.tetrahedra[i][0], m.tetrahedra[i][1], m.tetrahedra[i][2], m.tetrahedra[i][3]};
        g->InsertNextCell(VTK_TETRA, 4, ids);
        phys->InsertNextValue(m.tetrahedronGroup[i]);
    }
    for (size_t i = 0; i < m.triangles.size(); ++i) {
        const vtkIdType ids[3] = {m.triangles[i][0], m.triangles[i][1], m.triangles[i][2]};
        g->InsertNextCell(VTK_TRIANGLE, 3, ids);
        phys->InsertNextValue(m.triangleGroup[i]);
    }
    g->GetCellData()->AddArray(phys);
    return g;
}

/// The unit cube of tests/data in five tetrahedra, as a VTK grid.
vtkNew<vtkUnstructuredGrid> cubeGrid() {
    vtkNew<vtkUnstructuredGrid> g;
    vtkNew<vtkPoints> pts;
    const double c[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    for (const auto& p : c) pts->InsertNextPoint(p);
    g->SetPoints(pts);
    const vtkIdType tets[5][4] = {{0, 1, 3, 4}, {2, 3, 1, 6}, {5, 4, 6, 1}, {7, 6, 4, 3}, {1, 3, 4, 6}};
    const vtkIdType tri[2][3] = {{0, 3, 1}, {1, 3, 2}};
    const vtkIdType line[2] = {0, 6};
    for (const auto& t : tets) g->InsertNextCell(VTK_TETRA, 4, t);
    g->InsertNextCell(VTK_LINE, 2, line);  // skipped
    for (const auto& t : tri) g->InsertNextCell(VTK_TRIANGLE, 3, t);
    const int n = 8;
    vtkNew<vtkDoubleArray> fibres, stiffness, uv;
    vtkNew<vtkIntArray> ids;
    fibres->SetName("fibres");
    fibres->SetNumberOfComponents(3);
    stiffness->SetName("stiffness");
    uv->SetName("uv");
    uv->SetNumberOfComponents(2);
    ids->SetName("CellEntityIds");
    for (int i = 0; i < n; ++i) {
        fibres->InsertNextTuple3(i, 10 * i, 100 * i);
        stiffness->InsertNextValue(1000.0 + i);
        uv->InsertNextTuple2(i, i);
        ids->InsertNextValue(i < 5 ? 7 : i == 5 ? 0 : 9);
    }
    g->GetCellData()->AddArray(fibres);
    g->GetCellData()->AddArray(stiffness);
    g->GetCellData()->AddArray(uv);
    g->GetCellData()->AddArray(ids);
    return g;
}

bool allPositive(const MeshData& m) {
    for (const auto& t : m.tetrahedra)
        if (tetrahedronSignedVolume(m.points[size_t(t[0])], m.points[size_t(t[1])], m.points[size_t(t[2])],
                                    m.points[size_t(t[3])]) <= 0)
            return false;
    for (const auto& h : m.hexahedra)
        if (hexahedronVolume(m.points, h) <= 0) return false;
    return true;
}

const double kEllipsoidVolume = 4.0 / 3.0 * M_PI * 0.10 * 0.07 * 0.05;

} // namespace

// =================================================================================================

TEST_CASE("Every mesh in scenes/meshes reads with its documented node and element counts", "[MeshLoader]") {
    struct Expected {
        std::string file, format;
        size_t nodes, tets, triangles;
    };
    const Expected e = GENERATE(values<Expected>({
        {"organ_2428.msh", "Gmsh 2.2", 621, 2421, 834},
        {"organ_4430.msh", "Gmsh 2.2", 1064, 4465, 1262},
        {"organ_21436.msh", "Gmsh 2.2", 4364, 21285, 3606},
        {"liver.msh", "Gmsh 1", 181, 596, 0},
        {"liver2.msh", "Gmsh 1", 507, 1493, 860},
        {"volumetricTongue.vtu", "VTK XML", 2238, 10980, 0},
    }));
    CAPTURE(e.file);
    ReadReport report;
    const MeshData m = readMesh(kMeshes + e.file, {}, &report);
    CHECK_THAT(report.format, Catch::StartsWith(e.format));
    CHECK(m.points.size() == e.nodes);
    CHECK(m.tetrahedra.size() == e.tets);
    CHECK(m.triangles.size() == e.triangles);
    CHECK(m.hexahedra.empty());
    CHECK(m.tetrahedronGroup.size() == m.tetrahedra.size());
    CHECK(m.triangleGroup.size() == m.triangles.size());
    CHECK(report.flippedElements == 0);  // the README says every tetrahedron is positively oriented
    CHECK(allPositive(m));
    CHECK(totalVolume(m) > 0);
}

TEST_CASE("The organ meshes have the volume of the ellipsoid less the cut-away sphere part", "[MeshLoader]") {
    const std::string file = GENERATE(as<std::string>{}, "organ_2428.msh", "organ_4430.msh", "organ_21436.msh");
    CAPTURE(file);
    const MeshData m = readMesh(kMeshes + file);
    const double v = totalVolume(m);
    CAPTURE(v, kEllipsoidVolume);
    // the sphere removes a few per cent; the faceted surface loses a little more
    CHECK(v < kEllipsoidVolume);
    CHECK(v > 0.95 * kEllipsoidVolume);
    // all three stand for the same body
    CHECK(v == Approx(totalVolume(readMesh(kMeshes + "organ_21436.msh"))).epsilon(0.02));
    // the bounding box is the ellipsoid's (semi-axes 0.10, 0.07, 0.05)
    Vec3 lo = m.points[0], hi = m.points[0];
    for (const auto& p : m.points) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    CHECK(hi.x() == Approx(0.10).margin(2e-3));
    CHECK(lo.x() == Approx(-0.10).margin(2e-3));
    CHECK(hi.y() == Approx(0.07).margin(2e-3));
    CHECK(hi.z() == Approx(0.05).margin(2e-3));
}

TEST_CASE("The same organ mesh gives the same counts, groups and volume in every format", "[MeshLoader]") {
    ReadReport r0;
    const MeshData ref = readMesh(kMeshes + "organ_2428.msh", {}, &r0);
    const double v0 = totalVolume(ref);
    writeGmsh1("organ_v1.msh", ref);
    writeGmsh41("organ_v41.msh", ref);
    writeTetGen("organ_tg0", ref, 0);
    writeTetGen("organ_tg1", ref, 1);
    writeVtkLegacy("organ.vtk", ref);
    vtkNew<vtkUnstructuredGrid> grid = toVtkGrid(ref);
    writeVtu("organ_binary.vtu", grid, false);
    writeVtu("organ_ascii.vtu", grid, true);

    struct Case {
        std::string file, format;
        bool hasTriangles;
    };
    const Case c = GENERATE(values<Case>({
        {"organ_v1.msh", "Gmsh 1 (legacy)", true},
        {"organ_v41.msh", "Gmsh 4.1 ASCII", true},
        {"organ_tg0.node", "TetGen", false},
        {"organ_tg1.ele", "TetGen", false},
        {"organ.vtk", "VTK legacy", true},
        {"organ_binary.vtu", "VTK XML", true},
        {"organ_ascii.vtu", "VTK XML", true},
    }));
    CAPTURE(c.file);
    ReadReport report;
    const MeshData m = readMesh(tmp().file(c.file), {}, &report);
    CHECK(report.format == c.format);
    REQUIRE(m.points.size() == ref.points.size());
    REQUIRE(m.tetrahedra.size() == ref.tetrahedra.size());
    CHECK(m.tetrahedra == ref.tetrahedra);
    CHECK(m.tetrahedronGroup == ref.tetrahedronGroup);
    if (c.hasTriangles) {
        CHECK(m.triangles.size() == ref.triangles.size());
        CHECK(m.triangleGroup == ref.triangleGroup);
        CHECK(m.nodeGroups.at("physical:2") == ref.nodeGroups.at("physical:2"));
    }
    CHECK(m.nodeGroups.at("physical:1") == ref.nodeGroups.at("physical:1"));
    double maxDiff = 0;
    for (size_t i = 0; i < m.points.size(); ++i) maxDiff = std::max(maxDiff, (m.points[i] - ref.points[i]).norm());
    CHECK(maxDiff == 0.0);
    CHECK(totalVolume(m) == Approx(v0).epsilon(1e-12));
}

TEST_CASE("A hand-written unit cube has volume 1 in every format", "[MeshLoader]") {
    struct Case {
        std::string file, format;
        size_t nodes, tets, hexes, triangles;
    };
    const Case c = GENERATE(values<Case>({
        {"cube_gmsh1.msh", "Gmsh 1 (legacy)", 8, 5, 0, 2},
        {"cube_gmsh22.msh", "Gmsh 2.2 ASCII", 8, 5, 0, 2},
        {"cube_gmsh41.msh", "Gmsh 4.1 ASCII", 8, 6, 0, 2},
        {"cube0.node", "TetGen", 8, 6, 0, 0},  // 0-based ids
        {"cube0.ele", "TetGen", 8, 6, 0, 0},
        {"cube1.node", "TetGen", 8, 5, 0, 0},  // 1-based ids
        {"cube1.ele", "TetGen", 8, 5, 0, 0},
        {"cube.vtk", "VTK legacy", 8, 5, 0, 2},
        {"hex2.msh", "Gmsh 2.2 ASCII", 12, 0, 2, 0},
    }));
    CAPTURE(c.file);
    ReadReport report;
    const MeshData m = readMesh(kData + c.file, {}, &report);
    CHECK(report.format == c.format);
    CHECK(m.points.size() == c.nodes);
    CHECK(m.tetrahedra.size() == c.tets);
    CHECK(m.hexahedra.size() == c.hexes);
    CHECK(m.triangles.size() == c.triangles);
    CHECK(totalVolume(m) == Approx(1.0).epsilon(1e-14));
    CHECK(allPositive(m));
    for (const auto& p : m.points) CHECK((p.minCoeff() >= 0 && p.maxCoeff() <= 1));
    // ids of any base land on the right coordinates: node 0 is the origin in every file
    CHECK(m.points[0].norm() == 0.0);
}

TEST_CASE("A .vtu written by VTK's writer reads back with its cells, groups and cell arrays", "[MeshLoader]") {
    const bool ascii = GENERATE(false, true);
    CAPTURE(ascii);
    vtkNew<vtkUnstructuredGrid> g = cubeGrid();
    const std::string path = writeVtu(ascii ? "cube_ascii.vtu" : "cube_binary.vtu", g, ascii);
    ReadReport report;
    const MeshData m = readMesh(path, {}, &report);
    CHECK(report.format == "VTK XML");
    CHECK(m.points.size() == 8);
    CHECK(m.tetrahedra.size() == 5);
    CHECK(m.triangles.size() == 2);
    CHECK(report.skipped == std::map<std::string, int>{{"line", 1}});
    CHECK(totalVolume(m) == Approx(1.0).epsilon(1e-14));
    // groups from CellEntityIds
    CHECK(m.tetrahedronGroup == std::vector<int>(5, 7));
    CHECK(m.triangleGroup == std::vector<int>(2, 9));
    CHECK(m.nodeGroups.at("physical:7").size() == 8);
    CHECK(m.nodeGroups.at("physical:9") == IndexList{0, 1, 2, 3});
    // arrays with 1 or 3 components, restricted to the volume cells (cells 0-4 here)
    REQUIRE(m.cellArrays.count("fibres") == 1);
    REQUIRE(m.cellArrays.count("stiffness") == 1);
    CHECK(m.cellArrays.count("uv") == 0);  // 2 components: not copied
    const auto& f = m.cellArrays.at("fibres");
    REQUIRE(f.size() == 15);
    for (int i = 0; i < 5; ++i) {
        CHECK(f[size_t(3 * i)] == i);
        CHECK(f[size_t(3 * i + 1)] == 10 * i);
        CHECK(f[size_t(3 * i + 2)] == 100 * i);
    }
    CHECK(m.cellArrays.at("stiffness") == std::vector<double>{1000, 1001, 1002, 1003, 1004});
}

TEST_CASE("VTK hexahedra and voxels become hexahedra in VTK node order", "[MeshLoader]") {
    vtkNew<vtkUnstructuredGrid> g;
    vtkNew<vtkPoints> pts;
    for (int z = 0; z < 2; ++z)
        for (int y = 0; y < 2; ++y)
            for (int x = 0; x < 3; ++x) pts->InsertNextPoint(x, y, z);  // id = x + 3y + 6z
    g->SetPoints(pts);
    const vtkIdType hex[8] = {0, 1, 4, 3, 6, 7, 10, 9};      // x in [0, 1], VTK order
    const vtkIdType voxel[8] = {1, 2, 4, 5, 7, 8, 10, 11};   // x in [1, 2], grid order
    g->InsertNextCell(VTK_HEXAHEDRON, 8, hex);
    g->InsertNextCell(VTK_VOXEL, 8, voxel);
    const MeshData m = readMesh(writeVtu("hexes.vtu", g, true));
    REQUIRE(m.hexahedra.size() == 2);
    CHECK(m.hexahedra[1] == std::array<int, 8>{1, 2, 5, 4, 7, 8, 11, 10});
    CHECK(totalVolume(m) == Approx(2.0).epsilon(1e-14));
}

TEST_CASE("Gmsh physical groups become element tags, group names and node groups", "[MeshLoader]") {
    const std::string file = GENERATE(as<std::string>{}, "cube_gmsh22.msh", "cube_gmsh41.msh");
    CAPTURE(file);
    ReadReport report;
    const MeshData m = readMesh(kData + file, {}, &report);
    CHECK(m.groupNames == std::map<int, std::string>{{1, "tissue"}, {2, "bottom"}, {3, "corner"}});
    CHECK(m.tetrahedronGroup == std::vector<int>(m.tetrahedra.size(), 1));
    CHECK(m.triangleGroup == std::vector<int>{2, 2});
    CHECK(report.skipped == std::map<std::string, int>{{"point", 1}});
    const IndexList all{0, 1, 2, 3, 4, 5, 6, 7};
    CHECK(m.nodeGroups.at("tissue") == all);
    CHECK(m.nodeGroups.at("physical:1") == all);
    CHECK(m.nodeGroups.at("bottom") == IndexList{0, 1, 2, 3});
    CHECK(m.nodeGroups.at("physical:2") == IndexList{0, 1, 2, 3});
    // a physical point is skipped as an element but still makes a node group
    CHECK(m.nodeGroups.at("corner") == IndexList{0});
    CHECK(m.nodeGroups.at("physical:3") == IndexList{0});
    CHECK(m.nodeGroups.size() == 6);
}

TEST_CASE("Gmsh 1 and TetGen files give groups by tag only", "[MeshLoader]") {
    SECTION("Gmsh 1: reg-phys of each element") {
        const MeshData m = readMesh(kData + "cube_gmsh1.msh");
        CHECK(m.groupNames.empty());
        CHECK(m.tetrahedronGroup == std::vector<int>(5, 1));
        CHECK(m.triangleGroup == std::vector<int>{2, 2});
        CHECK(m.nodeGroups.at("physical:2") == IndexList{0, 1, 2, 3});
        CHECK(m.nodeGroups.size() == 2);
    }
    SECTION("TetGen: the region attribute") {
        const MeshData m = readMesh(kData + "cube0.ele");
        CHECK(m.tetrahedronGroup == std::vector<int>(6, 5));
        CHECK(m.nodeGroups.at("physical:5").size() == 8);
    }
    SECTION("TetGen without attributes: no groups") {
        const MeshData m = readMesh(kData + "cube1.ele");
        CHECK(m.tetrahedronGroup == std::vector<int>(5, 0));
        CHECK(m.nodeGroups.empty());
    }
}

TEST_CASE("liver2's non-contiguous node ids are mapped to 0-based indices", "[MeshLoader]") {
    const std::string path = kMeshes + "liver2.msh";
    ReadReport report;
    const MeshData m = readMesh(path, {}, &report);
    // in the file: node 1393 is the last of the 507 nodes, and element 952 is "4 2 2 4 1387 1374 1393 948"
    std::map<long long, Vec3> byId;
    long long element952[4] = {0, 0, 0, 0};
    {
        std::istringstream in(slurp(path));
        std::string line;
        std::getline(in, line);  // $NOD
        std::getline(in, line);  // 507
        for (int i = 0; i < 507; ++i) {
            long long id;
            double x, y, z;
            in >> id >> x >> y >> z;
            byId[id] = Vec3(x, y, z);
        }
        while (std::getline(in, line)) {
            std::istringstream l(line);
            long long number, type, phys, elem, nn;
            if (l >> number >> type >> phys >> elem >> nn && number == 952 && type == 4)
                for (auto& v : element952) l >> v;
        }
    }
    REQUIRE(byId.begin()->first == 2);
    REQUIRE(byId.rbegin()->first == 1393);
    REQUIRE(element952[2] == 1393);
    CHECK(m.points.size() == 507);
    CHECK(m.points[506] == byId[1393]);
    // the tetrahedron of element 952 has the coordinates of the file's nodes
    bool found = false;
    for (const auto& t : m.tetrahedra) {
        bool same = true;
        for (int k = 0; k < 4; ++k) same = same && m.points[size_t(t[size_t(k)])] == byId[element952[k]];
        found = found || same;
    }
    CHECK(found);
    CHECK(report.skipped == std::map<std::string, int>{{"line", 71}});
    CHECK(m.triangles.size() == 860);
}

TEST_CASE("fixOrientation flips inverted elements and counts them", "[MeshLoader]") {
    SECTION("tetrahedra") {
        // elements 1 and 4 with two nodes swapped
        const std::string path = tmp().write(
            "inverted2.msh", edited(kCube22, {{17, "1 4 2 1 1 1 4 2 5"}, {20, "4 4 2 1 1 8 5 7 4"}}));
        requireLocatedError(path, path, 17, {"element 1 (a tetrahedron) is inverted", "fixOrientation", "2 of 5 tetrahedra are inverted"});
        ReadReport report;
        ReadOptions opt;
        opt.fixOrientation = true;
        const MeshData m = readMesh(path, opt, &report);
        CHECK(report.flippedElements == 2);
        CHECK(allPositive(m));
        CHECK(totalVolume(m) == Approx(1.0).epsilon(1e-14));
    }
    SECTION("hexahedra: the bottom and top faces are exchanged") {
        const std::string text = edited(slurp(kData + "hex2.msh"), {{22, "2 5 2 1 1 8 9 12 11 2 3 6 5"}});
        const std::string path = tmp().write("hex_inverted.msh", text);
        requireLocatedError(path, path, 22, {"element 2 (a hexahedron) is inverted"});
        ReadReport report;
        ReadOptions opt;
        opt.fixOrientation = true;
        const MeshData m = readMesh(path, opt, &report);
        CHECK(report.flippedElements == 1);
        CHECK(m.hexahedra[1] == std::array<int, 8>{1, 2, 5, 4, 7, 8, 11, 10});
        CHECK(totalVolume(m) == Approx(1.0).epsilon(1e-14));
    }
}

TEST_CASE("Gmsh files with comments, extra sections, CRLF line ends and tabs read", "[MeshLoader]") {
    std::string text = "$Comments\nmade by hand\n$EndComments\n" + std::string(kCube22) +
                       "$NodeData\n1\n\"t\"\n1\n0.0\n3\n0\n1\n1\n1 0\n$EndNodeData\n";
    // LF, then CRLF and tabs (a GENERATE, not sections: a section must check something itself)
    const bool crlfAndTabs = GENERATE(false, true);
    CAPTURE(crlfAndTabs);
    if (crlfAndTabs) {
        std::string crlf;
        for (char ch : text) {
            if (ch == '\n') crlf += "\r\n";
            else if (ch == ' ') crlf += "\t";
            else crlf += ch;
        }
        text = crlf;
    }
    const MeshData m = readMesh(tmp().write("extras.msh", text));
    CHECK(m.tetrahedra.size() == 5);
    CHECK(totalVolume(m) == Approx(1.0).epsilon(1e-14));
}

// ---- located errors ------------------------------------------------------------------------------

TEST_CASE("Bad Gmsh 2.2 files fail at the line of the problem", "[MeshLoader][errors]") {
    const BadFile c = GENERATE(values<BadFile>({
        {"nodes_cut_short", {{10, kErase}, {11, kErase}, {12, kErase}, {13, kErase}}, 0, 10,
         {"$Nodes section ends after 4 of 8 nodes", "line 5", "truncated"}},
        {"node_count_too_big", {{5, "9"}}, 0, 14, {"$Nodes section ends after 8 of 9 nodes"}},
        {"file_cut_in_elements", {}, 19, 19, {"ends inside the $Elements section after 3 of 5 elements", "truncated"}},
        {"element_count_too_small", {{16, "4"}}, 0, 21, {"expected $EndElements", "more records than its count"}},
        {"malformed_coordinate", {{7, "2 1 0.0.1 0"}}, 0, 7, {"malformed number '0.0.1'", "y coordinate"}},
        {"malformed_node_id", {{17, "1 4 2 1 1 1 2 4.5 5"}}, 0, 17, {"malformed number '4.5'", "whole number"}},
        {"missing_coordinate", {{7, "2 1 0"}}, 0, 7, {"the line ends before the z coordinate", "'node-id x y z'"}},
        {"extra_value", {{7, "2 1 0 0 5"}}, 0, 7, {"unexpected '5'"}},
        {"missing_node", {{18, "2 4 2 1 1 3 4 2 99"}}, 0, 18, {"element 2 names node 99", "not in the $Nodes section"}},
        {"nan_coordinate", {{8, "3 1 nan 0"}}, 0, 8, {"node 3 has a non-finite coordinate"}},
        {"inf_coordinate", {{8, "3 1 1 -inf"}}, 0, 8, {"node 3 has a non-finite coordinate"}},
        {"repeated_node", {{21, "5 4 2 1 1 2 4 5 5"}}, 0, 21, {"element 5 (a tetrahedron) is degenerate", "2 4 5 5"}},
        {"flat_element", {{21, "5 4 2 1 1 1 2 3 4"}}, 0, 21, {"element 5 (a tetrahedron) is degenerate", "one plane"}},
        {"inverted_element", {{17, "1 4 2 1 1 1 4 2 5"}}, 0, 17,
         {"element 1 (a tetrahedron) is inverted", "1 4 2 5", "fixOrientation"}},
        {"wrong_node_count", {{18, "2 4 2 1 1 3 4 2"}}, 0, 18, {"element 2", "has 3 nodes", "a tetrahedron has 4"}},
        {"duplicate_node_id", {{9, "3 0 1 0"}}, 0, 9, {"node id 3 appears twice", "first on line 8"}},
        {"binary", {{2, "2.2 1 8"}}, 0, 2, {"binary Gmsh files are not supported", "ASCII"}},
        {"version_4_0", {{2, "4 0 8"}}, 0, 2, {"version 4 is not supported", "2.2 and 4.1"}},
        {"not_gmsh", {{1, "solid cube"}}, 0, 1, {"not a Gmsh mesh", "'solid'"}},
        {"unterminated_section", {{22, "$EndElements\n$Foo\n1 2 3"}}, 0, 24, {"$Foo (line 23) has no $EndFoo", "truncated"}},
        {"surface_only", {{16, "1"}, {17, "1 2 2 2 2 1 2 3"}, {18, kErase}, {19, kErase}, {20, kErase}, {21, kErase}}, 0, 0,
         {"no volume elements", "1 triangle", "gmsh -3"}},
    }));
    CAPTURE(c.label);
    const std::string path = tmp().write(c.label + ".msh", edited(kCube22, c.edits, c.keepLines));
    requireLocatedError(path, path, c.errorLine, c.keys);
}

TEST_CASE("Bad Gmsh 1 and 4.1 files fail at the line of the problem", "[MeshLoader][errors]") {
    const std::string v1 = slurp(kData + "cube_gmsh1.msh");
    const std::string v41 = slurp(kData + "cube_gmsh41.msh");
    struct Case {
        std::string label;
        const std::string* text;
        std::vector<std::pair<int, std::string>> edits;
        int errorLine;
        std::vector<std::string> keys;
    };
    const Case c = GENERATE_REF(values<Case>({
        {"v1_elements_cut_short", &v1, {{19, kErase}, {20, kErase}}, 19, {"$ELM section ends after 5 of 7 elements"}},
        {"v1_nodes_cut_short", &v1, {{9, kErase}, {10, kErase}}, 9, {"$NOD section ends after 6 of 8 nodes"}},
        {"v1_wrong_node_count", &v1, {{16, "3 4 1 1 3 1 2 4"}}, 16, {"element 3", "has 3 nodes", "a tetrahedron has 4"}},
        {"v1_missing_node", &v1, {{17, "4 4 1 1 4 3 4 2 70"}}, 17, {"element 4 names node 70"}},
        {"v41_nodes_cut_short", &v41, {{33, kErase}, {34, kErase}, {35, kErase}}, 33, {"$Nodes section ends after 5 of 8 nodes"}},
        {"v41_missing_node", &v41, {{47, "6 1 4 7 9"}}, 47, {"element 6 names node 9"}},
        {"v41_malformed_entity", &v41, {{13, "1 0 0 x 1 1 0 1 2 0"}}, 13, {"malformed number 'x'"}},
        {"v41_block_too_big", &v41, {{44, "3 1 4 7"}}, 44, {"element block of 7 elements exceeds the 9 elements"}},
        // counts that sum past INT64_MAX (signed overflow, found by UBSan): each is bounded by the file
        {"v41_entity_counts_overflow", &v41, {{11, "9223372036854775807 9223372036854775807 1 1"}}, 11,
         {"the $Entities header announces 9223372036854775807 entities of one dimension", "header is corrupt"}},
        {"v41_entity_count_too_big", &v41, {{11, "1 0 1 100"}}, 11,
         {"the $Entities header announces 100 entities of one dimension, more than the", "bytes left in the file"}},
    }));
    CAPTURE(c.label);
    const std::string path = tmp().write(c.label + ".msh", edited(*c.text, c.edits));
    requireLocatedError(path, path, c.errorLine, c.keys);
}

TEST_CASE("Bad TetGen files fail in the right file at the line of the problem", "[MeshLoader][errors]") {
    const std::string node = slurp(kData + "cube1.node");
    const std::string ele = slurp(kData + "cube1.ele");
    SECTION("the .ele beside the .node is missing") {
        const std::string p = tmp().write("lonely.node", node);
        requireLocatedError(p, p, 0, {tmp().file("lonely.ele"), "not found", "TetGen"});
    }
    SECTION("the .node file is cut short") {
        const std::string n = tmp().write("short.node", edited(node, {}, 6));
        const std::string e = tmp().write("short.ele", ele);
        requireLocatedError(e, n, 6, {"ends after 5 of 8 points", "truncated"});
    }
    SECTION("a malformed coordinate") {
        const std::string n = tmp().write("malformed.node", edited(node, {{4, "3 1 1,0 0"}}));
        tmp().write("malformed.ele", ele);
        requireLocatedError(n, n, 4, {"malformed number '1,0'", "y coordinate"});
    }
    SECTION("a NaN coordinate") {
        const std::string n = tmp().write("nan.node", edited(node, {{4, "3 1 NaN 0"}}));
        tmp().write("nan.ele", ele);
        requireLocatedError(n, n, 4, {"point 3 has a non-finite coordinate"});
    }
    SECTION("an element names a missing node") {
        tmp().write("missing.node", node);
        const std::string e = tmp().write("missing.ele", edited(ele, {{3, "2 3 4 2 12"}}));
        requireLocatedError(e, e, 3, {"tetrahedron 2 names node 12"});
    }
    SECTION("an inverted element is located in the .ele file") {
        const std::string n = tmp().write("inv.node", node);
        const std::string e = tmp().write("inv.ele", edited(ele, {{4, "3 6 5 2 7"}}));
        requireLocatedError(n, e, 4, {"element 3 (a tetrahedron) is inverted", "6 5 2 7"});
    }
    SECTION("second-order tetrahedra") {
        tmp().write("order2.node", node);
        const std::string e = tmp().write("order2.ele", edited(ele, {{1, "5 10 0"}}));
        requireLocatedError(e, e, 1, {"10-node", "not supported"});
    }
}

TEST_CASE("Bad VTK files fail with a located reason and no console output", "[MeshLoader][errors]") {
    SECTION("not a VTK file") {
        const std::string p = tmp().write("garbage.vtk", "hello\n");
        requireLocatedError(p, p, 1, {"not a VTK legacy file", "DATASET UNSTRUCTURED_GRID"});
    }
    SECTION("polygonal data, not a grid") {
        const std::string p = tmp().write(
            "poly.vtk", "# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n0 0 0 1 0 0 0 1 0\n"
                        "POLYGONS 1 4\n3 0 1 2\n");
        requireLocatedError(p, p, 4, {"vtkPolyData", "only DATASET UNSTRUCTURED_GRID"});
    }
    SECTION("a truncated legacy file") {
        const std::string p = tmp().write("cut.vtk", edited(slurp(kData + "cube.vtk"), {}, 10));
        // 5 of the 8 points are left: refused from the count, before reading them
        requireLocatedError(p, p, 5, {"POINTS: the file announces 8 x 3 values, more than the 31 bytes left", "truncated"});
    }
    SECTION("a cell names a missing point") {
        const std::string p = tmp().write("badcell.vtk", edited(slurp(kData + "cube.vtk"), {{15, "4 0 1 3 40"}}));
        requireLocatedError(p, p, 15, {"cell 0 names point 40", "8 points"});
    }
    SECTION("an inverted cell") {
        const std::string p = tmp().write("invcell.vtk", edited(slurp(kData + "cube.vtk"), {{16, "4 2 1 3 6"}}));
        requireLocatedError(p, p, 16, {"cell 1 (a tetrahedron) is inverted", "fixOrientation"});
    }
    SECTION("a truncated .vtu") {
        vtkNew<vtkUnstructuredGrid> g = cubeGrid();
        const std::string full = slurp(writeVtu("whole.vtu", g, true));
        const std::string cut = full.substr(0, full.size() / 2);
        const std::string p = tmp().write("cut.vtu", cut);
        // the half left holds the point and cell data, not the Points array (VTK writes it after them)
        REQUIRE(cut.find("<Points>") == std::string::npos);
        requireErrorAtByte(p, cut.find("<Piece"), {"the Piece announces 8 points "
                                      "but has no Points array: the file is incomplete or truncated"});
    }
    SECTION("not a .vtu") {
        const std::string p = tmp().write("garbage.vtu", "<html></html>\n");
        requireLocatedError(p, p, 0, {"not a VTK XML unstructured grid"});
    }
}

/// Byte offset of the '<' of the first tag of text that holds `inside`.
size_t tagOffset(const std::string& text, const std::string& inside) {
    const size_t at = text.find(inside);
    REQUIRE(at != std::string::npos);
    return text.rfind('<', at);
}

TEST_CASE("A .vtu whose data headers or counts lie is a located error before VTK allocates", "[MeshLoader][errors]") {
    vtkNew<vtkUnstructuredGrid> g = cubeGrid();
    SECTION("a compressed block header announcing 2.3 GB (VTK's ReadBlock crashed on it)") {
        std::string text = slurp(writeVtu("cube_z.vtu", g, false, true));
        REQUIRE(text.find("compressor=\"vtkZLibDataCompressor\"") != std::string::npos);
        const bool h64 = text.find("header_type=\"UInt64\"") != std::string::npos;
        const size_t data = text.find('_', text.find("<AppendedData")) + 1;
        const size_t w = h64 ? 8 : 4;
        const unsigned long long big = 2300000000ULL;
        for (size_t word : {1, 2})  // the block size and the last block's size, little-endian
            for (size_t k = 0; k < w; ++k) text[data + word * w + k] = char(k < 8 ? (big >> (8 * k)) & 0xFF : 0);
        const std::string p = tmp().write("cube_bigblock.vtu", text);
        const size_t at = tagOffset(text, "offset=\"0\"");
        requireErrorAtByte(p, at, {"compressed block 0 announces 2300000000 bytes from",
                                      "more than any compressor expands"});
    }
    SECTION("a compressed header announcing more blocks than the file holds") {
        std::string text = slurp(writeVtu("cube_z2.vtu", g, false, true));
        const size_t data = text.find('_', text.find("<AppendedData")) + 1;
        for (size_t k = 0; k < 4; ++k) text[data + k] = char(0x7F);  // the block count
        const std::string p = tmp().write("cube_blocks.vtu", text);
        requireErrorAtByte(p, tagOffset(text, "offset=\"0\""), {"the compressed data header announces",
                                      "blocks, more than the file holds"});
    }
    SECTION("NumberOfPoints larger than the Points array") {
        std::string text = slurp(writeVtu("cube_a.vtu", g, true));
        const size_t at = text.find("NumberOfPoints=\"8\"");
        REQUIRE(at != std::string::npos);
        text.replace(at, 18, "NumberOfPoints=\"800000000000\"");
        const std::string p = tmp().write("cube_points.vtu", text);
        requireErrorAtByte(p, tagOffset(text, "Name=\"Points\""), {"DataArray 'Points' of Points holds 24 values",
                                      "NumberOfPoints 800000000000 needs 2400000000000"});
    }
    SECTION("a Piece with points but no Points array") {
        std::string text = slurp(writeVtu("cube_np.vtu", g, true));
        const size_t b = text.find("<Points>"), e = text.find("</Points>");
        REQUIRE((b != std::string::npos && e != std::string::npos));
        text.erase(b, e + 9 - b);
        const std::string p = tmp().write("cube_nopoints.vtu", text);
        requireErrorAtByte(p, text.find("<Piece"), {"the Piece announces 8 points but has no Points array"});
    }
    SECTION("a cell type array shorter than the cells") {
        std::string text = slurp(writeVtu("cube_t.vtu", g, true));
        const size_t tag = tagOffset(text, "Name=\"types\"");
        const size_t body = text.find('>', tag) + 1;
        const size_t last = text.find_last_of("0123456789", text.find('<', body));  // drop the last type
        text.erase(last, 1);
        const std::string p = tmp().write("cube_types.vtu", text);
        requireErrorAtByte(p, tag, {"DataArray 'types' of Cells holds 7 values",
                                      "NumberOfCells 8 needs 8"});
    }
}

/// The unit cube of cubeGrid() as 5 tetrahedra only, the second one inverted (nodes 3 2 1 6).
vtkNew<vtkUnstructuredGrid> invertedCubeGrid() {
    vtkNew<vtkUnstructuredGrid> g;
    vtkNew<vtkPoints> pts;
    pts->SetDataTypeToDouble();
    const double c[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    for (const auto& p : c) pts->InsertNextPoint(p);
    g->SetPoints(pts);
    const vtkIdType tets[5][4] = {{0, 1, 3, 4}, {3, 2, 1, 6}, {5, 4, 6, 1}, {7, 6, 4, 3}, {1, 3, 4, 6}};
    for (const auto& t : tets) g->InsertNextCell(VTK_TETRA, 4, t);
    return g;
}

/// A .vtu of grid in one of VTK's encodings: "ascii", "binary" (inline base64), "appended-base64",
/// "appended-raw", each uncompressed, or zlib-compressed: "binary-zlib", "appended-base64-zlib",
/// "appended-zlib" (raw); `more` sets anything else on the writer (compressor, header type, byte
/// order, block size) before it writes.
std::string writeVtuAs(const std::string& name, vtkUnstructuredGrid* grid, const std::string& mode,
                       const std::function<void(vtkXMLUnstructuredGridWriter&)>& more = {}) {
    const std::string path = tmp().file(name);
    vtkNew<vtkXMLUnstructuredGridWriter> w;
    w->SetFileName(path.c_str());
    w->SetInputData(grid);
    const bool zlib = mode.find("zlib") != std::string::npos;
    if (mode == "ascii") w->SetDataModeToAscii();
    else if (mode.rfind("binary", 0) == 0) w->SetDataModeToBinary();
    else w->SetDataModeToAppended();
    if (mode == "appended-raw" || mode == "appended-zlib") w->EncodeAppendedDataOff();
    if (zlib) w->SetCompressorTypeToZLib();
    else w->SetCompressorTypeToNone();
    if (more) more(*w);  // the caller's other settings
    REQUIRE(w->Write() == 1);
    return path;
}

/// Where, in a .vtu that VTK wrote, value k of the DataArray named `array` is, computed from the
/// file's own tags: ascii, the k-th number; base64, the 4-character group of its first byte;
/// appended raw, its first byte; zlib (one block), the block's first byte (base64: the header's
/// 4 words are encoded apart, then the block).
size_t expectedValueByte(const std::string& text, const std::string& array, size_t k, const std::string& mode) {
    const size_t tag = tagOffset(text, "Name=\"" + array + "\"");
    const std::string tagText = text.substr(tag, text.find('>', tag) - tag);
    const size_t tb = tagText.find("64\"") != std::string::npos ? 8 : tagText.find("32\"") != std::string::npos ? 4 : 1;
    const size_t w = text.find("header_type=\"UInt64\"") != std::string::npos ? 8 : 4;
    if (mode == "ascii") {
        size_t p = text.find('>', tag) + 1, n = 0;
        for (;; ++p) {
            while (std::isspace((unsigned char)text[p])) ++p;
            if (n++ == k) return p;
            while (!std::isspace((unsigned char)text[p])) ++p;
        }
    }
    size_t data = 0;
    if (mode.rfind("binary", 0) == 0) {
        data = text.find('>', tag) + 1;
        while (std::isspace((unsigned char)text[data])) ++data;
    } else {
        const size_t o = tagText.find("offset=\"");
        data = text.find('_', text.find("<AppendedData")) + 1 + std::stoul(tagText.substr(o + 8));
    }
    if (mode == "binary" || mode == "appended-base64") return data + (w + k * tb) / 3 * 4;
    if (mode == "appended-raw") return data + w + k * tb;
    if (mode == "appended-zlib") return data + 4 * w;  // one block, after the 4 header words
    return data + (4 * w + 2) / 3 * 4;                 // base64 zlib: the header's characters, then the block
}

TEST_CASE("The checks before VTK pass every .vtu VTK's writer makes: encodings, compressors, header types, byte orders", "[MeshLoader][vtu]") {
    // the header and data checks (VTUHeaderCheck.cpp, VTUDataCheck.cpp) mirror VTK 9.1's reader;
    // a valid file they refused would be a regression of their own
    vtkNew<vtkUnstructuredGrid> g = cubeGrid();
    vtkNew<vtkDoubleArray> named;  // an apostrophe in a double-quoted name is plain XML
    named->SetName("Young's modulus");
    named->SetNumberOfTuples(g->GetNumberOfCells());
    for (vtkIdType c = 0; c < g->GetNumberOfCells(); ++c) named->SetValue(c, 1000.0 + double(c));
    g->GetCellData()->AddArray(named);
    int files = 0;
    for (const char* data : {"ascii", "binary", "appended-raw", "appended-base64"})
        for (int compressor = 0; compressor < 4; ++compressor)
            for (int header64 = 0; header64 < 2; ++header64)
                for (int big = 0; big < 2; ++big) {
                    if (std::string(data) == "ascii" && compressor > 0) continue;  // ascii is not compressed
                    const std::string name = std::string(data) + "_c" + std::to_string(compressor) + "_h" + std::to_string(header64) +
                                             "_b" + std::to_string(big) + ".vtu";
                    CAPTURE(name);
                    const std::string path = writeVtuAs(name, g, data, [&](vtkXMLUnstructuredGridWriter& w) {
                        if (compressor == 1) w.SetCompressorTypeToZLib();
                        if (compressor == 2) w.SetCompressorTypeToLZ4();
                        if (compressor == 3) w.SetCompressorTypeToLZMA();
                        if (header64) w.SetHeaderTypeToUInt64();
                        else w.SetHeaderTypeToUInt32();
                        if (big) w.SetByteOrderToBigEndian();
                        else w.SetByteOrderToLittleEndian();
                        w.SetBlockSize(64);  // several compressed blocks per array
                    });
                    const MeshData m = readMesh(path);
                    CHECK(m.points.size() == 8);
                    CHECK(m.tetrahedra.size() == 5);
                    ++files;
                }
    CHECK(files == 52);
}

TEST_CASE("Errors found after VTK read a .vtu are located at the byte of the cell or point", "[MeshLoader][errors]") {
    const std::string mode = GENERATE(as<std::string>{}, "ascii", "binary", "appended-base64", "appended-raw", "binary-zlib",
                                      "appended-base64-zlib", "appended-zlib");
    CAPTURE(mode);
    vtkNew<vtkUnstructuredGrid> g = invertedCubeGrid();
    SECTION("an inverted cell: at its first connectivity value (value 4)") {
        const std::string p = writeVtuAs("inverted_" + mode + ".vtu", g, mode);
        const std::string text = slurp(p);
        const size_t at = expectedValueByte(text, "connectivity", 4, mode);
        requireErrorAtByte(p, at, {"cell 1 (a tetrahedron) is inverted", "fixOrientation"});
        if (mode == "ascii") CHECK(text.substr(at, 2) == "3 ");  // the cell's first node
        if (mode == "appended-raw") {
            long long first = -1;
            std::memcpy(&first, text.data() + at, 8);
            CHECK(first == 3);
        }
    }
    if (mode == "appended-raw")
        SECTION("a non-finite point coordinate: at the point's x") {
            g->GetPoints()->SetPoint(2, std::nan(""), 1, 0);
            const std::string p = writeVtuAs("nan_point.vtu", g, mode);
            const std::string text = slurp(p);
            const size_t at = expectedValueByte(text, "Points", 3 * 2, mode);
            double x = 0;
            std::memcpy(&x, text.data() + at, 8);
            CHECK(std::isnan(x));
            requireErrorAtByte(p, at, {"node 2 has a non-finite coordinate"});
        }
    if (mode == "ascii")
        SECTION("an empty grid: at its Piece") {
            vtkNew<vtkUnstructuredGrid> empty;
            vtkNew<vtkPoints> none;
            empty->SetPoints(none);
            const std::string p = writeVtuAs("empty.vtu", empty, mode);
            requireErrorAtByte(p, slurp(p).find("<Piece"), {"has no points and no cells"});
        }
}

/// What the VTK-based legacy reader of earlier versions made of a .vtk file: VTK's own legacy
/// reader, then the conversion it used (kept cells, groups, 1- and 3-component cell arrays).
MeshData viaVtkLegacyReader(const std::string& path) {
    vtkNew<vtkUnstructuredGridReader> r;
    r->SetFileName(path.c_str());
    r->Update();
    vtkUnstructuredGrid* grid = r->GetOutput();
    REQUIRE(grid);
    MeshData m;
    for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i) {
        double x[3];
        grid->GetPoint(i, x);
        m.points.emplace_back(x[0], x[1], x[2]);
    }
    const vtkIdType nCells = grid->GetNumberOfCells();
    vtkDataArray* groups = nullptr;
    for (const char* gname : {"gmsh:physical", "CellEntityIds"}) {
        vtkDataArray* a = grid->GetCellData()->GetArray(gname);
        if (!groups && a && a->GetNumberOfComponents() == 1 && a->GetNumberOfTuples() == nCells) groups = a;
    }
    std::vector<vtkIdType> tets, hexes;
    vtkNew<vtkIdList> ids;
    for (vtkIdType c = 0; c < nCells; ++c) {
        grid->GetCellPoints(c, ids);
        std::vector<int> n;
        for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k) n.push_back(int(ids->GetId(k)));
        const int group = groups ? int(std::lround(groups->GetComponent(c, 0))) : 0;
        const int type = grid->GetCellType(c);
        if (type == VTK_TETRA) {
            m.tetrahedra.push_back({n[0], n[1], n[2], n[3]});
            m.tetrahedronGroup.push_back(group);
            tets.push_back(c);
        } else if (type == VTK_HEXAHEDRON || type == VTK_VOXEL) {
            m.hexahedra.push_back(type == VTK_VOXEL ? std::array<int, 8>{n[0], n[1], n[3], n[2], n[4], n[5], n[7], n[6]}
                                                    : std::array<int, 8>{n[0], n[1], n[2], n[3], n[4], n[5], n[6], n[7]});
            m.hexahedronGroup.push_back(group);
            hexes.push_back(c);
        } else if (type == VTK_TRIANGLE) {
            m.triangles.push_back({n[0], n[1], n[2]});
            m.triangleGroup.push_back(group);
        }
    }
    vtkCellData* cd = grid->GetCellData();
    for (int a = 0; a < cd->GetNumberOfArrays(); ++a) {
        vtkDataArray* arr = cd->GetArray(a);
        if (!arr || !arr->GetName() || arr->GetNumberOfTuples() != nCells) continue;
        const int nc = arr->GetNumberOfComponents();
        if (nc != 1 && nc != 3) continue;
        auto& v = m.cellArrays[arr->GetName()];
        for (const auto* list : {&tets, &hexes})
            for (vtkIdType c : *list)
                for (int k = 0; k < nc; ++k) v.push_back(arr->GetComponent(c, k));
    }
    return m;
}

std::string writeVtkWithVtk(const std::string& name, vtkUnstructuredGrid* grid, bool binary, int version) {
    const std::string path = tmp().file(name);
    vtkNew<vtkUnstructuredGridWriter> w;
    w->SetFileName(path.c_str());
    w->SetInputData(grid);
    if (binary) w->SetFileTypeToBinary();
    w->SetFileVersion(version);
    REQUIRE(w->Write() == 1);
    return path;
}

TEST_CASE("Our legacy VTK reader gives the MeshData VTK's legacy reader gave, in ASCII, BINARY and 5.1", "[MeshLoader]") {
    const MeshData organ = readMesh(kMeshes + "organ_2428.msh");
    writeVtkLegacy("organ_hand.vtk", organ);
    vtkNew<vtkUnstructuredGrid> organGrid = toVtkGrid(organ);
    vtkNew<vtkUnstructuredGrid> cube = cubeGrid();
    std::vector<std::string> files = {kData + "cube.vtk", tmp().file("organ_hand.vtk")};
    for (int version : {vtkDataWriter::VTK_LEGACY_READER_VERSION_4_2, vtkDataWriter::VTK_LEGACY_READER_VERSION_5_1})
        for (bool binary : {false, true}) {
            const std::string tag = std::to_string(version) + (binary ? "b" : "a");
            files.push_back(writeVtkWithVtk("cube_" + tag + ".vtk", cube, binary, version));
            files.push_back(writeVtkWithVtk("organ_" + tag + ".vtk", organGrid, binary, version));
        }
    for (const auto& f : files) {
        CAPTURE(f);
        const MeshData want = viaVtkLegacyReader(f);
        ReadReport report;
        const MeshData got = readMesh(f, {}, &report);
        CHECK(report.format == "VTK legacy");
        CHECK(got.points == want.points);
        CHECK(got.tetrahedra == want.tetrahedra);
        CHECK(got.hexahedra == want.hexahedra);
        CHECK(got.triangles == want.triangles);
        CHECK(got.tetrahedronGroup == want.tetrahedronGroup);
        CHECK(got.triangleGroup == want.triangleGroup);
        CHECK(got.cellArrays == want.cellArrays);
        CHECK(!want.tetrahedra.empty());
    }
}

TEST_CASE("Missing, unreadable and unknown files fail with a clear message", "[MeshLoader][errors]") {
    SECTION("a missing file names its path") {
        const std::string p = tmp().file("nowhere/organ.msh");
        requireLocatedError(p, p, 0, {"mesh file '" + p + "' does not exist"});
        const std::string v = tmp().file("nowhere.vtu");
        requireLocatedError(v, v, 0, {"does not exist"});
    }
    SECTION("an unknown extension lists the supported ones") {
        const std::string p = tmp().write("mesh.obj", "v 0 0 0\n");
        requireLocatedError(p, p, 0, {"unknown mesh file extension '.obj'", ".msh", ".vtk", ".vtu", ".node/.ele"});
    }
    SECTION("an empty file") {
        const std::string p = tmp().write("empty.msh", "");
        requireLocatedError(p, p, 1, {"is empty"});
    }
    SECTION("a folder") {
        const std::string p = tmp().file("folder.msh");
        fs::create_directories(p);
        requireLocatedError(p, p, 0, {"is a folder"});
    }
    SECTION("a file without read permission") {
        const std::string p = tmp().write("secret.msh", kCube22);
        fs::permissions(p, fs::perms::none);
        if (geteuid() != 0) {
            requireLocatedError(p, p, 0, {"cannot open mesh file '" + p + "'", "permissions"});
        } else {
            // root reads whatever the permission bits say, so this cannot be checked here: say so
            // (the next section reaches the same error as root too)
            WARN("running as root: a file without read permission is still readable; skipped, "
                 "the socket section checks the error instead");
            CHECK(std::ifstream(p).good());
        }
    }
    SECTION("a file nobody can open, root included: a socket") {
        const std::string p = tmp().file("socket.msh");
        const int fd = socket(AF_UNIX, SOCK_STREAM, 0);
        REQUIRE(fd >= 0);
        sockaddr_un addr{};
        addr.sun_family = AF_UNIX;
        REQUIRE(p.size() < sizeof addr.sun_path);
        std::copy(p.begin(), p.end(), addr.sun_path);
        REQUIRE(bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) == 0);
        // it exists and is no folder, but no regular file: refused from its type before open()
        requireLocatedError(p, p, 0, {"'" + p + "' is a socket, not a mesh file", "must be a regular file"});
        close(fd);
    }
}

// ---- the checks and volumes on their own --------------------------------------------------------

TEST_CASE("validateMesh checks generated meshes", "[MeshLoader]") {
    MeshData m;
    m.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(1, 1, 1)};
    m.tetrahedra = {{0, 1, 2, 3}, {1, 2, 3, 4}};
    const std::string where = "generated by the test";
    ReadOptions opt;
    ReadReport report;
    SECTION("a good mesh: group vectors are filled") {
        validateMesh(m, where, opt, &report);
        CHECK(m.tetrahedronGroup == std::vector<int>{0, 0});
        CHECK(report.flippedElements == 0);
    }
    SECTION("an inverted tetrahedron fails, or is flipped") {
        std::swap(m.tetrahedra[1][0], m.tetrahedra[1][1]);
        CHECK_THROWS_WITH(validateMesh(m, where, opt, &report),
                          Catch::StartsWith(where + ": error: tetrahedron 1 (0-based) is inverted"));
        opt.fixOrientation = true;
        validateMesh(m, where, opt, &report);
        CHECK(report.flippedElements == 1);
        CHECK(allPositive(m));
    }
    SECTION("a node index out of range") {
        m.tetrahedra[1][3] = 5;
        CHECK_THROWS_WITH(validateMesh(m, where, opt, nullptr), Catch::Contains("names node 5, but the mesh has 5 nodes"));
    }
    SECTION("a NaN coordinate") {
        m.points[4].x() = std::nan("");
        CHECK_THROWS_WITH(validateMesh(m, where, opt, nullptr), Catch::Contains("node 4 has a non-finite coordinate"));
    }
    SECTION("a degenerate tetrahedron, relative to its size") {
        const double s = GENERATE(1e-6, 1.0, 1e6);
        CAPTURE(s);
        for (auto& p : m.points) p *= s;
        m.points[4] = s * Vec3(0.5, 0.5, 0.0);  // in the plane of nodes 1 and 2 and the origin's side
        m.tetrahedra[1] = {0, 1, 2, 4};
        CHECK_THROWS_WITH(validateMesh(m, where, opt, nullptr), Catch::Contains("tetrahedron 1 (0-based) is degenerate"));
    }
    SECTION("a small but sound tetrahedron is not degenerate") {
        for (auto& p : m.points) p *= 1e-9;
        CHECK_NOTHROW(validateMesh(m, where, opt, nullptr));
    }
    SECTION("no volume elements") {
        m.tetrahedra.clear();
        m.triangles = {{0, 1, 2}};
        CHECK_THROWS_WITH(validateMesh(m, where, opt, nullptr), Catch::Contains("no volume elements"));
    }
}

TEST_CASE("Element volumes", "[MeshLoader]") {
    const Vec3 o(0, 0, 0), x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
    CHECK(tetrahedronSignedVolume(o, x, y, z) == Approx(1.0 / 6.0));
    CHECK(tetrahedronSignedVolume(o, y, x, z) == Approx(-1.0 / 6.0));

    std::array<Vec3, 8> cube = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0),
                                Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(1, 1, 1), Vec3(0, 1, 1)};
    CHECK(hexahedronVolume(cube) == Approx(1.0).epsilon(1e-14));

    SECTION("an affine image of the cube has volume |det A|") {
        Mat3 A;
        A << 2.0, 0.3, 0.1, -0.2, 1.5, 0.4, 0.05, 0.2, 0.7;
        const Vec3 t(3, -1, 2);
        std::array<Vec3, 8> h;
        for (size_t i = 0; i < 8; ++i) h[i] = A * cube[i] + t;
        CHECK(hexahedronVolume(h) == Approx(A.determinant()).epsilon(1e-13));
    }
    SECTION("warped faces: z = 1 + u v on the top face gives 1 + 1/4") {
        cube[6] = Vec3(1, 1, 2);
        CHECK(hexahedronVolume(cube) == Approx(1.25).epsilon(1e-14));
    }
    SECTION("exchanging the bottom and top faces turns the sign") {
        std::array<Vec3, 8> h;
        for (size_t i = 0; i < 4; ++i) {
            h[i] = cube[i + 4];
            h[i + 4] = cube[i];
        }
        CHECK(hexahedronVolume(h) == Approx(-1.0).epsilon(1e-14));
    }
    SECTION("the Positions overload picks the nodes") {
        Positions pts(cube.begin(), cube.end());
        std::reverse(pts.begin(), pts.end());
        CHECK(hexahedronVolume(pts, {7, 6, 5, 4, 3, 2, 1, 0}) == Approx(1.0).epsilon(1e-14));
    }
}

TEST_CASE("A generated Gmsh file of 200 000 tetrahedra reads completely", "[MeshLoader][large]") {
    // a 40 x 40 x 21 grid of cubes of side h, six tetrahedra each around the cube's diagonal
    const int nx = 40, ny = 40, nz = 21;
    const double h = 0.01;
    auto id = [&](int i, int j, int k) { return 1 + i + (nx + 1) * (j + (ny + 1) * k); };
    std::string text = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n";
    const int nNodes = (nx + 1) * (ny + 1) * (nz + 1);
    text += std::to_string(nNodes) + "\n";
    for (int k = 0; k <= nz; ++k)
        for (int j = 0; j <= ny; ++j)
            for (int i = 0; i <= nx; ++i)
                text += std::to_string(id(i, j, k)) + " " + num(i * h) + " " + num(j * h) + " " + num(k * h) + "\n";
    const int nTets = 6 * nx * ny * nz;
    text += "$EndNodes\n$Elements\n" + std::to_string(nTets) + "\n";
    // corners in VTK order as (di, dj, dk), and the six tetrahedra of the unit cube around 0-6
    const int c[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    const int six[6][4] = {{0, 1, 2, 6}, {0, 1, 6, 5}, {0, 3, 6, 2}, {0, 3, 7, 6}, {0, 4, 5, 6}, {0, 4, 6, 7}};
    int e = 0;
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i)
                for (const auto& t : six) {
                    text += std::to_string(++e) + " 4 2 1 1";
                    for (int v : t) text += " " + std::to_string(id(i + c[v][0], j + c[v][1], k + c[v][2]));
                    text += "\n";
                }
    text += "$EndElements\n";
    const MeshData m = readMesh(tmp().write("grid200k.msh", text));
    CHECK(int(m.points.size()) == nNodes);
    CHECK(int(m.tetrahedra.size()) == nTets);
    CHECK(nTets > 200000);
    CHECK(totalVolume(m) == Approx(nx * ny * nz * h * h * h).epsilon(1e-10));
    CHECK(m.nodeGroups.at("physical:1").size() == size_t(nNodes));
}
