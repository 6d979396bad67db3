// Tests of our legacy VTK reader (LegacyVTKReader.cpp), built with and without VTK: the same cube
// written in ASCII and BINARY, file versions 3.0 and 5.1, reads to the same mesh, and files whose
// counts lie (the inputs that crashed VTK's own legacy reader, or that it accepted) are located
// errors. The files are generated here; the writer below follows the legacy format (big-endian
// binary data after each keyword line).
#include <catch2/catch.hpp>

#include "MeshReaders.h"
#include "fascia/base/Error.h"

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <unistd.h>
#include <vector>

using namespace fascia;
using namespace fascia::meshio;
namespace fs = std::filesystem;

namespace {

std::string writeFile(const std::string& name, const std::string& text) {
    static const fs::path dir = [] {
        const fs::path d = fs::temp_directory_path() / ("fascia_legacy_vtk_test_" + std::to_string(::getpid()));
        fs::create_directories(d);
        return d;
    }();
    const std::string p = (dir / name).string();
    std::ofstream(p, std::ios::binary) << text;
    return p;
}

/// Builds a legacy file: keyword lines are text, arrays text or big-endian binary.
struct LegacyText {
    bool binary = false;
    std::string s;
    void line(const std::string& l) { s += l + "\n"; }
    void bigEndian(std::uint64_t v, int bytes) {
        for (int k = bytes - 1; k >= 0; --k) s += char((v >> (8 * k)) & 0xFF);
    }
    void ints(const std::vector<long long>& v, int bytes) {
        for (size_t i = 0; i < v.size(); ++i) {
            if (binary) bigEndian(std::uint64_t(v[i]), bytes);
            else s += (i ? " " : "") + std::to_string(v[i]);
        }
        s += "\n";
    }
    void doubles(const std::vector<double>& v) {
        for (size_t i = 0; i < v.size(); ++i) {
            if (binary) {
                std::uint64_t u;
                std::memcpy(&u, &v[i], 8);
                bigEndian(u, 8);
            } else {
                char buf[40];
                std::snprintf(buf, sizeof buf, "%s%.17g", i ? " " : "", v[i]);
                s += buf;
            }
        }
        s += "\n";
    }
};

const std::vector<double> kCorners = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
const std::vector<std::vector<long long>> kCells = {{0, 1, 3, 4}, {2, 3, 1, 6}, {5, 4, 6, 1}, {7, 6, 4, 3},
                                                    {1, 3, 4, 6}, {0, 6},       {0, 3, 1},    {1, 3, 2}};
const std::vector<long long> kTypes = {10, 10, 10, 10, 10, 3, 5, 5};

/// The unit cube in 5 tetrahedra, a line (skipped) and 2 triangles, with groups, a fibre vector, a
/// FIELD of stiffness (1 component) and uv (2: not kept), and point data (ignored).
std::string cubeFile(bool binary, bool version5) {
    LegacyText t;
    t.binary = binary;
    t.line(version5 ? "# vtk DataFile Version 5.1" : "# vtk DataFile Version 3.0");
    t.line("unit cube");
    t.line(binary ? "BINARY" : "ASCII");
    t.line("DATASET UNSTRUCTURED_GRID");
    t.line("FIELD FieldData 1");
    t.line("TIME 1 1 double");
    t.doubles({0.5});
    t.line("POINTS 8 double");
    t.doubles(kCorners);
    if (version5) {
        std::vector<long long> offsets{0}, conn;
        for (const auto& c : kCells) {
            conn.insert(conn.end(), c.begin(), c.end());
            offsets.push_back((long long)conn.size());
        }
        t.line("CELLS 9 " + std::to_string(conn.size()));
        t.line("OFFSETS vtktypeint64");
        t.ints(offsets, 8);
        t.line("CONNECTIVITY vtktypeint64");
        t.ints(conn, 8);
    } else {
        std::vector<long long> v;
        for (const auto& c : kCells) {
            v.push_back((long long)c.size());
            v.insert(v.end(), c.begin(), c.end());
        }
        t.line("CELLS 8 " + std::to_string(v.size()));
        t.ints(v, 4);
    }
    t.line("CELL_TYPES 8");
    t.ints(kTypes, 4);
    t.line("CELL_DATA 8");
    t.line("SCALARS CellEntityIds int 1");
    t.line("LOOKUP_TABLE default");
    t.ints({7, 7, 7, 7, 7, 0, 9, 9}, 4);
    t.line("VECTORS fibres double");
    std::vector<double> f;
    for (int i = 0; i < 8; ++i) f.insert(f.end(), {double(i), 10.0 * i, 100.0 * i});
    t.doubles(f);
    t.line("FIELD FieldData 2");
    t.line("stiffness 1 8 double");
    t.doubles({1000, 1001, 1002, 1003, 1004, 1005, 1006, 1007});
    t.line("uv 2 8 double");
    t.doubles(std::vector<double>(16, 0.25));
    t.line("POINT_DATA 8");
    t.line("SCALARS temperature double");
    t.line("LOOKUP_TABLE default");
    t.doubles(std::vector<double>(8, 37));
    return t.s;
}

/// Reading path fails with an input error located in path at `line` (ASCII files) or, when
/// byte >= 0, at that byte offset (BINARY files); the message holds every key.
void requireError(const std::string& path, int line, long long byte, const std::vector<std::string>& keys) {
    std::string what;
    bool thrown = false;
    try {
        readMesh(path);
    } catch (const core::Error& e) {
        thrown = true;
        what = e.what();
        CHECK(e.kind() == core::ErrorKind::Input);
        CHECK(e.loc().file == path);
        CHECK(e.loc().line == (byte >= 0 ? 0 : line));
        CHECK(e.loc().byte == (byte >= 0 ? byte : -1));
    }
    INFO("message: " << what);
    REQUIRE(thrown);
    const std::string where =
        byte >= 0 ? path + ": byte " + std::to_string(byte) + ": error: " : path + ":" + std::to_string(line) + ": error: ";
    CHECK(what.rfind(where, 0) == 0);
    for (const auto& k : keys) CHECK_THAT(what, Catch::Contains(k));
}

} // namespace

TEST_CASE("A legacy VTK cube reads the same in ASCII and BINARY, file versions 3.0 and 5.1", "[MeshLoader]") {
    const bool binary = GENERATE(false, true);
    const bool version5 = GENERATE(false, true);
    CAPTURE(binary, version5);
    const std::string p = writeFile(std::string("cube_") + (binary ? "b" : "a") + (version5 ? "5" : "3") + ".vtk",
                                    cubeFile(binary, version5));
    ReadReport report;
    const MeshData m = readMesh(p, {}, &report);
    CHECK(report.format == "VTK legacy");
    REQUIRE(m.points.size() == 8);
    for (size_t i = 0; i < 8; ++i) CHECK(m.points[i] == Vec3(kCorners[3 * i], kCorners[3 * i + 1], kCorners[3 * i + 2]));
    REQUIRE(m.tetrahedra.size() == 5);
    for (size_t i = 0; i < 5; ++i)
        for (size_t k = 0; k < 4; ++k) CHECK(m.tetrahedra[i][k] == kCells[i][k]);
    CHECK(m.triangles.size() == 2);
    CHECK(m.hexahedra.empty());
    CHECK(report.skipped == std::map<std::string, int>{{"line", 1}});
    CHECK(totalVolume(m) == Approx(1.0).epsilon(1e-14));
    CHECK(m.tetrahedronGroup == std::vector<int>(5, 7));
    CHECK(m.triangleGroup == std::vector<int>{9, 9});
    CHECK(m.nodeGroups.at("physical:9") == IndexList{0, 1, 2, 3});
    CHECK(m.cellArrays.at("stiffness") == std::vector<double>{1000, 1001, 1002, 1003, 1004});
    CHECK(m.cellArrays.at("CellEntityIds") == std::vector<double>(5, 7));
    const auto& f = m.cellArrays.at("fibres");
    REQUIRE(f.size() == 15);
    for (int i = 0; i < 5; ++i) CHECK((f[3 * i] == i && f[3 * i + 1] == 10 * i && f[3 * i + 2] == 100 * i));
    CHECK(m.cellArrays.count("uv") == 0);           // 2 components
    CHECK(m.cellArrays.count("temperature") == 0);  // point data
    CHECK(m.cellArrays.size() == 3);
}

TEST_CASE("A float legacy VTK array is rounded to float as VTK stores it", "[MeshLoader]") {
    const std::string text = "# vtk DataFile Version 2.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 float\n"
                             "0 0 0 0.1 0 0 0 1 0 0 0 1\nCELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\n";
    const MeshData m = readMesh(writeFile("float.vtk", text));
    CHECK(m.points[1].x() == double(0.1f));
    CHECK(m.points[1].x() != 0.1);
}

TEST_CASE("A legacy VTK file whose CELLS counts lie is a located error", "[MeshLoader][errors]") {
    const std::string head = "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n"
                             "0 0 0 1 0 0 0 1 0 0 0 1\n";
    SECTION("a CELLS size larger than the file (VTK's reader overflowed a heap buffer)") {
        const std::string p = writeFile("size.vtk", head + "CELLS 1 1000000\n4 0 1 2 3\nCELL_TYPES 1\n10\n");
        requireError(p, 7, -1, {"CELLS: the file announces 1000000 x 1 values, more than the", "bytes left in the file"});
    }
    SECTION("a per-cell point count past the CELLS size") {
        const std::string p = writeFile("npts.vtk", head + "CELLS 2 10\n4 0 1 2 3\n9 0 1 2 3\nCELL_TYPES 2\n10 10\n");
        requireError(p, 9, -1, {"cell 1 announces 9 points, but only 4 values of the CELLS size 10 are left"});
    }
    SECTION("a CELLS size the cells do not use up") {
        const std::string p = writeFile("unused.vtk", head + "CELLS 1 6\n4 0 1 2 3 3\nCELL_TYPES 1\n10\n");
        requireError(p, 7, -1, {"CELLS announces a size of 6 values, but its 1 cell use 5"});
    }
    SECTION("a cell whose point count does not fit its type") {
        const std::string p = writeFile("short.vtk", head + "CELLS 1 4\n3 0 1 2\nCELL_TYPES 1\n10\n");
        requireError(p, 8, -1, {"cell 0 has type 10 (tetrahedron) with 3 points; it must have 4"});
    }
    SECTION("a binary CELLS header that lies is located by its byte offset") {
        LegacyText t;
        t.binary = true;
        t.line("# vtk DataFile Version 4.2");
        t.line("t");
        t.line("BINARY");
        t.line("DATASET UNSTRUCTURED_GRID");
        t.line("POINTS 4 double");
        t.doubles({0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1});
        const long long at = (long long)t.s.size() + 8;  // "CELLS 2 " then the size
        t.line("CELLS 2 3000000000");
        t.ints({4, 0, 1, 2, 3}, 4);
        const std::string p = writeFile("bsize.vtk", t.s);
        requireError(p, 0, at, {"CELLS: the file announces 3000000000 x 1 values", "4 bytes per int value"});
    }
    SECTION("a binary per-cell point count past the CELLS size") {
        LegacyText t;
        t.binary = true;
        t.line("# vtk DataFile Version 4.2");
        t.line("t");
        t.line("BINARY");
        t.line("DATASET UNSTRUCTURED_GRID");
        t.line("POINTS 4 double");
        t.doubles({0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1});
        t.line("CELLS 2 10");
        const long long at = (long long)t.s.size() + 20;  // the second cell's count, after 5 ints
        t.ints({4, 0, 1, 2, 3, 1000, 0, 1, 2, 3}, 4);
        t.line("CELL_TYPES 2");
        t.ints({10, 10}, 4);
        const std::string p = writeFile("bnpts.vtk", t.s);
        requireError(p, 0, at, {"cell 1 announces 1000 points, but only 4 values of the CELLS size 10 are left"});
    }
}

TEST_CASE("A VTK 5.1 file with decreasing OFFSETS is a located error", "[MeshLoader][errors]") {
    const std::string text = "# vtk DataFile Version 5.1\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n"
                             "0 0 0 1 0 0 0 1 0 0 0 1\nCELLS 3 8\nOFFSETS vtktypeint64\n0 4\n2\n"
                             "CONNECTIVITY vtktypeint64\n0 1 2 3 0 1 2 3\nCELL_TYPES 2\n10 10\n";
    requireError(writeFile("offsets.vtk", text), 10, -1,
                 {"offset 2 is 2, less than the offset before it (4): offsets must not decrease"});
    const std::string past = "# vtk DataFile Version 5.1\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n"
                             "0 0 0 1 0 0 0 1 0 0 0 1\nCELLS 2 4\nOFFSETS vtktypeint64\n0 9\n"
                             "CONNECTIVITY vtktypeint64\n0 1 2 3\nCELL_TYPES 1\n10\n";
    requireError(writeFile("offsets_past.vtk", past), 9, -1, {"offset 1 is 9, past the 4 connectivity values"});
}

TEST_CASE("A 400-byte legacy VTK file announcing billions of points is refused at once", "[MeshLoader][errors]") {
    // VTK's reader touched 15.6 GB for such a file; every count is now bounded by the file's size
    std::string text = "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 2000000000 float\n";
    text += std::string(400 - text.size() - 1, '0') + "\n";
    const std::string p = writeFile("huge.vtk", text);
    requireError(p, 5, -1, {"POINTS: the file announces 2000000000 x 3 values", "the count is wrong or the file is truncated"});
    const std::string field = "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n"
                              "0 0 0 1 0 0 0 1 0 0 0 1\nCELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\nCELL_DATA 1\n"
                              "FIELD f 1\nbig 4611686018427387904 4 double\n1\n";
    requireError(writeFile("hugefield.vtk", field), 13, -1, {"FIELD array 'big': the file announces 4 x 4611686018427387904 values"});
}

TEST_CASE("A legacy VTK file whose cell-type array is shorter than its cells is a located error", "[MeshLoader][errors]") {
    const std::string text = "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 5 double\n"
                             "0 0 0 1 0 0 0 1 0 0 0 1 1 1 1\nCELLS 2 10\n4 0 1 2 3\n4 1 2 3 4\nCELL_TYPES 1\n10\n";
    requireError(writeFile("types.vtk", text), 10, -1, {"CELL_TYPES has 1 type, but CELLS has 2 cells", "one type per cell"});
    const std::string data = "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n"
                             "0 0 0 1 0 0 0 1 0 0 0 1\nCELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\nCELL_DATA 3\n";
    requireError(writeFile("celldata.vtk", data), 11, -1, {"CELL_DATA has 3 values, but CELLS has 1 cell"});
}

TEST_CASE("Malformed legacy VTK headers and values are located errors", "[MeshLoader][errors]") {
    const std::string head = "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\n";
    requireError(writeFile("v9.vtk", "# vtk DataFile Version 9.0\nt\nASCII\n"), 1, -1, {"unsupported legacy VTK file version '9.0'"});
    requireError(writeFile("fmt.vtk", "# vtk DataFile Version 3.0\nt\nTEXT\n"), 3, -1, {"expected ASCII or BINARY"});
    requireError(writeFile("bit.vtk", head + "POINTS 1 bit\n0\n"), 5, -1, {"unsupported data type 'bit'"});
    requireError(writeFile("nan.vtk", head + "POINTS 1 double\n0 x 0\n"), 6, -1, {"malformed number 'x' in POINTS"});
    requireError(writeFile("twice.vtk", head + "POINTS 1 double\n0 0 0\nPOINTS 1 double\n0 0 0\n"), 7, -1,
                 {"a second POINTS section"});
    requireError(writeFile("kw.vtk", head + "POINTS 1 double\n0 0 0\nPOLYGONS 1 2\n"), 7, -1, {"unexpected 'polygons'"});
    requireError(writeFile("neg.vtk", head + "POINTS -1 double\n"), 5, -1, {"the number of points '-1' is not a whole number >= 0"});
}
