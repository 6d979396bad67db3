// The .vtp reader (readSurface on VTK XML PolyData, fascia/surface/TriangleSurface.h), in a build
// with VTK: files that VTK's own writer makes, in every data mode, read back to the triangles of
// the same surface in .stl; polygons, strips, vertices and lines; bad files as errors located in
// the file, with nothing printed by VTK.
#include "SurfaceTestSupport.h"

#include <catch2/catch.hpp>

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <fcntl.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <limits>

using namespace fascia;
using namespace fascia::surface;
using fascia::surface::test::inputError;
using fascia::surface::test::TempFile;
using Cells = std::vector<std::vector<vtkIdType>>;

namespace {

/// How VTK's writer stores the arrays.
struct Mode {
    std::string data;        ///< "ascii", "binary" (inline base64), "raw" or "base64" (appended)
    std::string compressor;  ///< "none", "zlib", "lz4" or "lzma"
    bool header64 = false;
};

vtkSmartPointer<vtkCellArray> cellArray(const Cells& cells) {
    auto a = vtkSmartPointer<vtkCellArray>::New();
    for (const auto& c : cells) a->InsertNextCell(vtkIdType(c.size()), c.data());
    return a;
}

/// A polydata of the points and cells, with a point array as Fascia writes one (which the reader skips).
vtkSmartPointer<vtkPolyData> polyData(const Positions& p, const Cells& polys, const Cells& strips = {}, const Cells& verts = {},
                                      const Cells& lines = {}) {
    auto poly = vtkSmartPointer<vtkPolyData>::New();
    vtkNew<vtkPoints> pts;
    pts->SetDataTypeToDouble();
    for (const auto& x : p) pts->InsertNextPoint(x.data());
    poly->SetPoints(pts);
    poly->SetPolys(cellArray(polys));
    poly->SetStrips(cellArray(strips));
    poly->SetVerts(cellArray(verts));
    poly->SetLines(cellArray(lines));
    vtkNew<vtkDoubleArray> u;
    u->SetName("displacement");
    u->SetNumberOfComponents(3);
    u->SetNumberOfTuples(vtkIdType(p.size()));
    u->Fill(0.5);
    poly->GetPointData()->AddArray(u);
    return poly;
}

Cells cellsOf(const Triangles& t) {
    Cells c;
    for (const auto& f : t) c.push_back({f[0], f[1], f[2]});
    return c;
}

/// The bytes of the .vtp that VTK's XML writer makes of poly.
std::string vtpBytes(vtkPolyData* poly, const Mode& m = {"raw", "lz4"}) {
    vtkNew<vtkXMLPolyDataWriter> w;
    w->SetInputData(poly);
    w->WriteToOutputStringOn();
    if (m.data == "ascii") w->SetDataModeToAscii();
    else if (m.data == "binary") w->SetDataModeToBinary();
    else w->SetDataModeToAppended();
    w->SetEncodeAppendedData(m.data == "base64");
    if (m.compressor == "zlib") w->SetCompressorTypeToZLib();
    else if (m.compressor == "lz4") w->SetCompressorTypeToLZ4();
    else if (m.compressor == "lzma") w->SetCompressorTypeToLZMA();
    else w->SetCompressorTypeToNone();
    w->SetHeaderTypeToUInt32();
    if (m.header64) w->SetHeaderTypeToUInt64();
    REQUIRE(w->Write() == 1);
    return w->GetOutputString();
}

/// What f prints on stderr while it runs (VTK's reader prints its complaints there unless caught).
template <class F>
std::string stderrOf(F&& f) {
    TempFile out("stderr.txt", "");
    std::fflush(stderr);
    const int saved = ::dup(2), fd = ::open(out.str().c_str(), O_WRONLY | O_TRUNC);
    ::dup2(fd, 2);
    ::close(fd);
    f();
    std::fflush(stderr);
    ::dup2(saved, 2);
    ::close(saved);
    std::ifstream in(out.path);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

/// The input error of reading `bytes` as the surface `name`; VTK prints nothing meanwhile.
std::string vtpError(const std::string& bytes, const std::string& name = "bad.vtp") {
    TempFile f(name, bytes);
    std::string message;
    CHECK(stderrOf([&] { message = inputError([&] { readSurface(f.str()); }); }).empty());
    return message;
}

/// The byte an error message names ("file: byte N: error: ..."), -1 when none.
long long byteOf(const std::string& message) {
    const size_t p = message.find(": byte ");
    long long n = -1;
    if (p != std::string::npos) std::from_chars(message.data() + p + 7, message.data() + message.size(), n);
    return n;
}

/// Where the data of appended array `name` starts: after <AppendedData>'s '_', at its offset.
size_t appendedArray(const std::string& bytes, const std::string& name) {
    const size_t tag = bytes.find("Name=\"" + name + "\""), offset = bytes.find("offset=\"", tag) + 8;
    REQUIRE(tag != std::string::npos);
    return bytes.find('_', bytes.find("<AppendedData")) + 1 + std::stoul(bytes.substr(offset, 20));
}

/// The cube [0.25, 1.5]^3 as 6 quads, outwards (the OBJ cube of TestSurfaceReader.cpp, moved).
Positions cubePoints() {
    Positions p;
    for (int k = 0; k < 8; ++k) p.emplace_back(0.25 + 1.25 * ((k == 1 || k == 2 || k == 5 || k == 6) ? 1 : 0),
                                                0.25 + 1.25 * ((k == 2 || k == 3 || k == 6 || k == 7) ? 1 : 0), 0.25 + 1.25 * (k >= 4 ? 1 : 0));
    return p;
}
const Cells kCubeQuads = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {3, 7, 6, 2}, {3, 0, 4, 7}};

} // namespace

TEST_CASE("A .vtp that VTK writes, in any data mode, reads back to the triangles of the same surface in .stl", "[TriangleSurface][vtp]") {
    const Mode mode = GENERATE(Mode{"ascii", "none"}, Mode{"binary", "none"}, Mode{"binary", "zlib", true}, Mode{"raw", "none"},
                               Mode{"raw", "lz4"} /* as Fascia writes surfaces */, Mode{"raw", "zlib", true}, Mode{"base64", "lzma"},
                               Mode{"base64", "none", true});
    CAPTURE(mode.data, mode.compressor, mode.header64);
    // the cube's 12 triangles in a binary STL file, its vertices merged as they come
    Triangles fans;
    for (const auto& q : kCubeQuads) fans.push_back({int(q[0]), int(q[1]), int(q[2])}), fans.push_back({int(q[0]), int(q[2]), int(q[3])});
    TempFile stlFile("cube.stl", test::binaryStl(cubePoints(), fans));
    const TriangleSurface stl = readSurface(stlFile.str());
    REQUIRE(stl.triangles.size() == 12);

    const std::string bytes = vtpBytes(polyData(stl.points, cellsOf(stl.triangles)), mode);
    TempFile vtpFile("cube.vtp", bytes);
    TriangleSurface vtp = readSurface(vtpFile.str());
    CHECK(vtp.format == "VTK XML PolyData");
    CHECK(vtp.byteOffsets);
    CHECK(vtp.points == stl.points);
    CHECK(vtp.triangles == stl.triangles);
    REQUIRE(vtp.origin.size() == 12);
    CHECK_FALSE(requireClosedSurface(vtp, "a test"));  // closed, outwards
    CHECK(enclosedVolume(vtp.points, vtp.triangles) == enclosedVolume(stl.points, stl.triangles));
    // each triangle is located at its cell's first point in the file (all at the connectivity
    // array's tag when it is compressed)
    for (size_t t = 0; t < 12; ++t) {
        CAPTURE(t);
        const long long at = vtp.origin[t];
        REQUIRE(at > 0);
        REQUIRE(at < (long long)bytes.size());
        if (mode.data == "ascii") CHECK(bytes.substr(size_t(at), 2) == std::to_string(stl.triangles[t][0]) + " ");
        if (mode.data == "raw" && mode.compressor == "none") {
            long long v = 0;
            std::memcpy(&v, bytes.data() + at, 8);  // vtkIdType, little endian
            CHECK(v == stl.triangles[t][0]);
        }
        if (mode.compressor != "none") CHECK(bytes.compare(size_t(at), 10, "<DataArray") == 0);
    }
}

TEST_CASE("The polygons of a .vtp surface become fans as OBJ faces do, its strips triangles facing one way, and vertices and lines are ignored",
          "[TriangleSurface][vtp]") {
    SECTION("the cube of 6 quads, with a vertex and a line") {
        TempFile f("cube.vtp", vtpBytes(polyData(cubePoints(), kCubeQuads, {}, {{0}, {6}}, {{0, 6}})));
        TriangleSurface s = readSurface(f.str());
        CHECK(s.points == cubePoints());
        REQUIRE(s.triangles.size() == 12);
        CHECK(s.triangles[0] == std::array<int, 3>{0, 3, 2});
        CHECK(s.triangles[1] == std::array<int, 3>{0, 2, 1});
        CHECK(s.triangles[10] == std::array<int, 3>{3, 0, 4});
        CHECK(s.triangles[11] == std::array<int, 3>{3, 4, 7});
        CHECK_FALSE(requireClosedSurface(s, "a test"));
        CHECK(enclosedVolume(s.points, s.triangles) == Approx(1.25 * 1.25 * 1.25).epsilon(1e-14));
    }
    SECTION("a pentagon, and two strips joined by repeated points") {
        const Positions p = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0), Vec3(3, 0, 0), Vec3(4, 0, 0), Vec3(3, 1, 0),
                             Vec3(4, 1, 0), Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(2, 1, 1), Vec3(1, 2, 1), Vec3(0, 1, 1)};
        // the strips 0 1 2 3 and 4 5 6 7 as one, as strippers join them: 3 and 4 repeated
        TempFile f("mixed.vtp", vtpBytes(polyData(p, {{8, 9, 10, 11, 12}}, {{0, 1, 2, 3, 3, 4, 4, 5, 6, 7}}), {"ascii", "none"}));
        const TriangleSurface s = readSurface(f.str());
        const Triangles expect = {{8, 9, 10}, {8, 10, 11}, {8, 11, 12},  // the pentagon's fan, then the strip's triangles
                                  {0, 1, 2}, {2, 1, 3}, {4, 5, 6}, {6, 5, 7}};  // (2 3 3) (3 3 4) (3 4 4) (4 4 5) dropped
        CHECK(s.triangles == expect);
        for (const auto& t : s.triangles) {  // all face +z
            const Vec3 n = (s.points[size_t(t[1])] - s.points[size_t(t[0])]).cross(s.points[size_t(t[2])] - s.points[size_t(t[0])]);
            CHECK(n[2] > 0);
        }
    }
}

TEST_CASE("Bad .vtp surface files are input errors located at the file or its byte, and VTK prints nothing", "[TriangleSurface][vtp]") {
    const Positions cube = cubePoints();
    SECTION("a missing file, a folder, an empty file") {
        CHECK_THAT(inputError([&] { readSurface("/nonexistent/x.vtp"); }), Catch::Contains("x.vtp: error: surface file") && Catch::Contains("does not exist"));
        TempFile f("inside", "");
        const std::string folder = (f.path.parent_path() / "folder.vtp").string();
        std::filesystem::create_directory(folder);
        CHECK_THAT(inputError([&] { readSurface(folder); }), Catch::Contains("folder.vtp: error: ") && Catch::Contains("is a folder"));
        CHECK_THAT(vtpError(""), Catch::Contains("bad.vtp: error: the surface file is empty"));
    }
    SECTION("not XML, XML of another kind, a .vtu mesh renamed") {
        CHECK_THAT(vtpError("\x7f" "ELF\x02\x01\x01"), Catch::Contains("bad.vtp: byte 0: error: not an XML file") && Catch::Contains("'?ELF"));
        CHECK_THAT(vtpError("<html><body>no surface</body></html>\n"),
                   Catch::Contains("bad.vtp: byte 0: error: the first element is <html>, not <VTKFile>: not a VTK XML file"));
        vtkNew<vtkUnstructuredGrid> grid;
        vtkNew<vtkPoints> pts;
        for (const auto& x : cube) pts->InsertNextPoint(x.data());
        grid->SetPoints(pts);
        vtkNew<vtkXMLUnstructuredGridWriter> w;
        w->SetInputData(grid);
        w->WriteToOutputStringOn();
        REQUIRE(w->Write() == 1);
        const std::string vtu = w->GetOutputString();
        const std::string message = vtpError(vtu);
        CHECK_THAT(message, Catch::Contains("error: not VTK XML PolyData: the VTKFile's type is 'UnstructuredGrid' (a .vtu mesh?)"));
        CHECK(byteOf(message) == (long long)vtu.find("<VTKFile"));
    }
    SECTION("no polygons: vertices and lines only") {
        CHECK_THAT(vtpError(vtpBytes(polyData(cube, {}, {}, {{0}}, {{0, 1, 2}}))),
                   Catch::Contains("error: the surface has no triangles: its Piece has NumberOfPolys=\"0\" and NumberOfStrips=\"0\""));
    }
    SECTION("a non-finite point, at the byte of its coordinate") {
        Positions p = cube;
        p[2][1] = std::numeric_limits<double>::quiet_NaN();
        const std::string bytes = vtpBytes(polyData(p, kCubeQuads), {"raw", "none"});
        const std::string message = vtpError(bytes);
        CHECK_THAT(message, Catch::Contains("error: point 2 has a non-finite y coordinate"));
        const long long at = byteOf(message);
        REQUIRE(at > 0);
        double v = 0;
        std::memcpy(&v, bytes.data() + at, 8);
        CHECK(std::isnan(v));
    }
    SECTION("a polygon naming a point that does not exist, at the byte of its number") {
        const std::string bytes = vtpBytes(polyData(cube, {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 9}}), {"ascii", "none"});
        const std::string message = vtpError(bytes);
        CHECK_THAT(message, Catch::Contains("error: polygon 2 of <Polys> names point 9, but the file has 8 points (0-based indices 0 to 7)"));
        CHECK(bytes.substr(size_t(byteOf(message)), 2) == "9\n");
    }
    SECTION("a polygon of two points, a polygon with a point twice") {
        // (VTK's writer crashes on a polygon of two points: its offsets are edited)
        std::string two = vtpBytes(polyData(cube, {{0, 3, 2}, {4, 5, 6}}), {"ascii", "none"});
        const size_t offsets = two.find("3 6\n", two.find("Name=\"offsets\""));
        REQUIRE(offsets != std::string::npos);
        two.replace(offsets, 3, "3 5");
        CHECK_THAT(vtpError(two), Catch::Contains("error: polygon 1 of <Polys> has 2 points: a polygon has at least 3"));
        CHECK_THAT(vtpError(vtpBytes(polyData(cube, {{0, 3, 2}, {4, 5, 5, 6}}))),
                   Catch::Contains("error: polygon 1 of <Polys> uses a point twice (points 4 5 5 of its triangle 0)"));
    }
    SECTION("appended data cut short: the header of an array announces what is not there") {
        std::string bytes = vtpBytes(polyData(cube, kCubeQuads), {"raw", "none"});
        bytes.resize(bytes.size() - 60);
        const std::string message = vtpError(bytes);
        CHECK_THAT(message, Catch::Contains("error: the data header announces 48 bytes, but only ") && Catch::Contains("the file is truncated"));
        const std::string offsets = "<DataArray type=\"Int64\" Name=\"offsets\" ";
        CHECK(bytes.compare(size_t(byteOf(message)), offsets.size(), offsets) == 0);
    }
    SECTION("XML that is not well-formed, at the byte VTK's parser names") {
        std::string bytes = vtpBytes(polyData(cube, kCubeQuads), {"ascii", "none"});
        bytes.replace(bytes.find("</Points>"), 9, "</Pointz>");
        const std::string message = vtpError(bytes);
        CHECK_THAT(message, Catch::Contains(": error: VTK could not read the surface: ") && Catch::Contains("Error parsing XML") &&
                                Catch::Contains("mismatched tag"));
        const long long tag = (long long)bytes.find("</Pointz>");
        CHECK(byteOf(message) >= tag);  // (expat names the tag's name)
        CHECK(byteOf(message) < tag + 9);
    }
    SECTION("corrupt compressed data") {
        std::string bytes = vtpBytes(polyData(cube, kCubeQuads), {"raw", "zlib"});
        const size_t points = appendedArray(bytes, "Points") + 16;  // after the header of its one block
        for (size_t i = 0; i < 16; ++i) bytes[points + i] = char(0xA5);
        CHECK_THAT(vtpError(bytes), Catch::Contains("bad.vtp: error: VTK could not read the surface: ") && Catch::Contains("ncompress"));
    }
    SECTION("a compressed block announcing 2.3 GB") {
        std::string bytes = vtpBytes(polyData(cube, kCubeQuads), {"raw", "zlib"});
        const size_t data = appendedArray(bytes, "Points");
        const std::uint32_t huge = 2300000000u;
        std::memcpy(&bytes[data + 4], &huge, 4);  // the block size, and the size of its one block
        std::memcpy(&bytes[data + 8], &huge, 4);
        CHECK_THAT(vtpError(bytes), Catch::Contains("error: compressed block 0 announces 2300000000 bytes from ") &&
                                        Catch::Contains("more than any compressor expands: the header is corrupt"));
    }
    SECTION("offsets past the connectivity, before VTK allocates what they announce") {
        std::string bytes = vtpBytes(polyData(cube, kCubeQuads), {"ascii", "none"});
        const size_t offsets = bytes.find("4 8 12 16 20 24");
        REQUIRE(offsets != std::string::npos);
        bytes.replace(offsets + 13, 2, "1152921504606846976");
        const std::string message = vtpError(bytes);
        CHECK_THAT(message, Catch::Contains("error: cell 5 of <Polys> (the last) ends at offset 1152921504606846976, past the 24 values of its connectivity array"));
        CHECK(byteOf(message) == (long long)offsets + 13);
    }
    SECTION("two Pieces, an unknown compressor, an array of strings") {
        std::string bytes = vtpBytes(polyData(cube, kCubeQuads), {"ascii", "none"});
        const size_t a = bytes.find("<Piece"), b = bytes.find("</Piece>") + 8;
        std::string two = bytes;
        two.insert(b, bytes.substr(a, b - a));
        CHECK_THAT(vtpError(two), Catch::Contains("error: a second <Piece>: Fascia reads a .vtp of one Piece"));
        std::string zip = bytes;
        zip.insert(zip.find("<VTKFile") + 9, "compressor=\"vtkGZipDataCompressor\" ");
        CHECK_THAT(vtpError(zip), Catch::Contains("error: VTKFile has compressor 'vtkGZipDataCompressor'"));
        std::string text = bytes;
        text.replace(text.find("type=\"Float64\" Name=\"displacement\""), 14, "type=\"String\"");
        CHECK_THAT(vtpError(text), Catch::Contains("error: DataArray 'displacement' has the type 'String'"));
    }
}
