// The STL/OBJ reader and the closed-surface check (fascia/surface/TriangleSurface.h).
#include "SurfaceTestSupport.h"

#include <catch2/catch.hpp>

using namespace fascia;
using namespace fascia::surface;
using fascia::surface::test::TempFile;

using fascia::surface::test::inputError;

namespace {
/// The unit cube as 6 quads (1-based OBJ), faces outwards.
const char* kCubeObj =
    "# unit cube\n"
    "o cube\n"
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    "vn 0 0 1\nvt 0 0\n"
    "s off\n"
    "f 1 4 3 2\n"
    "f 5/1 6/1 7/1 8/1\n"
    "f 1//1 2//1 6//1 5//1\n"
    "f 2/1/1 3/1/1 7/1/1 6/1/1\n"
    "f -5 -1 -2 -6\n"  // 4 8 7 3
    "f 4 1 5 8\n";
} // namespace

TEST_CASE("An ASCII STL tetrahedron reads as 4 merged vertices and 4 outward triangles", "[TriangleSurface]") {
    TempFile f("tet.stl", test::asciiStl(test::tetPoints(), test::tetFaces()));
    const TriangleSurface s = readSurface(f.str());
    CHECK(s.format == "STL ASCII");
    CHECK(s.points.size() == 4);
    REQUIRE(s.triangles.size() == 4);
    CHECK(s.origin[0] == 2);  // the first 'facet' line
    CHECK(s.origin[1] == 9);
    const SurfaceReport r = inspectSurface(s.points, s.triangles);
    CHECK(r.closed());
    CHECK(r.volume == Approx(1.0 / 6).epsilon(1e-12));
}

TEST_CASE("A binary STL file reads the same surface, also when its header starts with solid", "[TriangleSurface]") {
    const std::string header = GENERATE(std::string("binary STL"), std::string("solid but binary"));
    TempFile f("tet.STL", test::binaryStl(test::tetPoints(), test::tetFaces(), header));
    const TriangleSurface s = readSurface(f.str());
    CHECK(s.format == "STL binary");
    CHECK(s.byteOffsets);
    REQUIRE(s.points.size() == 4);
    REQUIRE(s.triangles.size() == 4);
    CHECK(s.origin[1] == 84 + 50);
    CHECK(s.points[s.triangles[3][2]] == Vec3(0, 0, 1));
    CHECK(inspectSurface(s.points, s.triangles).volume == Approx(1.0 / 6).epsilon(1e-12));
}

TEST_CASE("An OBJ cube of quads becomes 12 triangles, fans in file order, with relative and slashed indices", "[TriangleSurface]") {
    TempFile f("cube.obj", kCubeObj);
    TriangleSurface s = readSurface(f.str());
    CHECK(s.format == "OBJ");
    CHECK(s.points.size() == 8);
    REQUIRE(s.triangles.size() == 12);
    CHECK(s.triangles[0] == std::array<int, 3>{0, 3, 2});
    CHECK(s.triangles[1] == std::array<int, 3>{0, 2, 1});
    CHECK(s.triangles[8] == std::array<int, 3>{3, 7, 6});  // from "f -5 -1 -2 -6"
    CHECK(s.origin[8] == 18);
    CHECK_FALSE(requireClosedSurface(s, "a test"));
    CHECK(enclosedVolume(s.points, s.triangles) == Approx(1.0).epsilon(1e-12));
}

TEST_CASE("A pentagon face is split into a fan of 3 triangles around its first vertex", "[TriangleSurface]") {
    TempFile f("penta.obj", "v 0 0 0\nv 1 0 0\nv 2 1 0\nv 1 2 0\nv 0 1 0\nf 1 2 3 4 5\n");
    const TriangleSurface s = readSurface(f.str());
    REQUIRE(s.triangles.size() == 3);
    CHECK(s.triangles[0] == std::array<int, 3>{0, 1, 2});
    CHECK(s.triangles[1] == std::array<int, 3>{0, 2, 3});
    CHECK(s.triangles[2] == std::array<int, 3>{0, 3, 4});
}

TEST_CASE("Bad surface files are input errors located at their line or byte", "[TriangleSurface]") {
    SECTION("an unknown extension") {
        TempFile f("tet.ply", "ply\n");
        CHECK_THAT(inputError([&] { readSurface(f.str()); }),
                   Catch::Contains("unknown surface file extension '.ply': supported are .stl (ASCII or binary), .obj and .vtp"));
    }
    SECTION("a missing file") {
        CHECK_THAT(inputError([&] { readSurface("/nonexistent/x.obj"); }), Catch::Contains("does not exist"));
    }
    SECTION("an empty file") {
        TempFile f("e.stl", "");
        CHECK_THAT(inputError([&] { readSurface(f.str()); }), Catch::Contains("is empty"));
    }
    SECTION("a truncated binary STL file is refused before anything is allocated") {
        std::string b = test::binaryStl(test::tetPoints(), test::tetFaces());
        b.resize(b.size() - 10);
        TempFile f("t.stl", b);
        CHECK_THAT(inputError([&] { readSurface(f.str()); }),
                   Catch::Contains("t.stl: byte 80: error: the binary STL header announces 4 triangles, which take 284 bytes; the file has 274"));
    }
    SECTION("a binary STL file announcing four billion triangles") {
        std::string b = test::binaryStl(test::tetPoints(), test::tetFaces());
        b[80] = b[81] = b[82] = b[83] = '\xff';
        TempFile f("huge.stl", b);
        CHECK_THAT(inputError([&] { readSurface(f.str()); }), Catch::Contains("announces 4294967295 triangles"));
    }
    SECTION("a non-finite coordinate in a binary STL file, at its byte") {
        std::string b = test::binaryStl(test::tetPoints(), test::tetFaces());
        const float inf = 1e30f * 1e30f;
        std::memcpy(&b[84 + 50 + 12 + 12 + 4], &inf, 4);  // triangle 2, vertex 2, y
        TempFile f("inf.stl", b);
        CHECK_THAT(inputError([&] { readSurface(f.str()); }), Catch::Contains("inf.stl: byte 158: error: triangle 2 has a non-finite vertex"));
    }
    SECTION("a malformed number in an ASCII STL file") {
        std::string t = test::asciiStl(test::tetPoints(), test::tetFaces());
        t.replace(t.find("vertex 0.000000 1.000000"), 24, "vertex 0.000000 1.0x0000");
        TempFile f("bad.stl", t);
        CHECK_THAT(inputError([&] { readSurface(f.str()); }), Catch::Contains("bad.stl:5: error: malformed number '1.0x0000' for the y coordinate"));
    }
    SECTION("an ASCII STL facet with four vertices") {
        TempFile f("four.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid\n");
        CHECK_THAT(inputError([&] { readSurface(f.str()); }), Catch::Contains("four.stl:7: error: a fourth vertex in the facet of line 2"));
    }
    SECTION("an ASCII STL file that ends inside a facet") {
        TempFile f("cut.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n");
        CHECK_THAT(inputError([&] { readSurface(f.str()); }), Catch::Contains("cut.stl:4: error: the ASCII STL file ends inside a facet"));
    }
    SECTION("an ASCII STL facet with two equal corners") {
        TempFile f("flat.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 0 0\nendloop\nendfacet\nendsolid\n");
        CHECK_THAT(inputError([&] { readSurface(f.str()); }), Catch::Contains("flat.stl:2: error: the facet uses one vertex twice"));
    }
    SECTION("an OBJ face naming a vertex that does not exist") {
        TempFile f("v.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n");
        CHECK_THAT(inputError([&] { readSurface(f.str()); }), Catch::Contains("v.obj:5: error: the face names vertex 9, and 3 vertices"));
    }
    SECTION("an OBJ face with two corners") {
        TempFile f("two.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n");
        CHECK_THAT(inputError([&] { readSurface(f.str()); }), Catch::Contains("two.obj:3: error: a face has at least 3 vertices"));
    }
    SECTION("an unknown OBJ record") {
        TempFile f("k.obj", "v 0 0 0\ncurv 0 1\n");
        CHECK_THAT(inputError([&] { readSurface(f.str()); }), Catch::Contains("k.obj:2: error: unknown OBJ record 'curv'"));
    }
    SECTION("an OBJ vertex with a non-finite coordinate") {
        TempFile f("n.obj", "v 0 0 0\nv 1 nan 0\n");
        CHECK_THAT(inputError([&] { readSurface(f.str()); }), Catch::Contains("n.obj:2: error: "));
    }
    SECTION("an OBJ file without faces") {
        TempFile f("nof.obj", "v 0 0 0\n");
        CHECK_THAT(inputError([&] { readSurface(f.str()); }), Catch::Contains("has no faces"));
    }
}

#if !FASCIA_SURFACE_WITH_VTK
TEST_CASE("A .vtp surface in a build without VTK is a located error that says so", "[TriangleSurface][vtp]") {
    TempFile f("skin.vtp", "<VTKFile type=\"PolyData\" version=\"0.1\"><PolyData/></VTKFile>\n");
    CHECK_THAT(inputError([&] { readSurface(f.str()); }),
               Catch::StartsWith(f.str() + ": error: this build has no VTK support: '" + f.str() + "' is a VTK XML PolyData (.vtp) surface") &&
                   Catch::Contains("-DFASCIA_WITH_VTK=ON"));
    // what cannot be read at all says so first, as for the other formats
    CHECK_THAT(inputError([&] { readSurface("/nonexistent/skin.vtp"); }), Catch::Contains("does not exist"));
}
#endif

TEST_CASE("An open, non-manifold or misoriented surface is a located error for what needs a closed one", "[TriangleSurface]") {
    SECTION("a cube with a face missing is open, located at a triangle next to the hole") {
        std::string obj = kCubeObj;
        obj.replace(obj.find("f 5/1 6/1 7/1 8/1\n"), 18, "");
        TempFile f("open.obj", obj);
        TriangleSurface s = readSurface(f.str());
        CHECK(inspectSurface(s.points, s.triangles).openEdges == 4);
        CHECK_THAT(inputError([&] { requireClosedSurface(s, "SurfaceTool 'probe'"); }),
                   Catch::Contains("open.obj:15: error: the edge between vertices 5") &&
                       Catch::Contains("the surface is open (4 edges on its border); close its holes; SurfaceTool 'probe' needs a closed"));
    }
    SECTION("a cube with one face turned inside out is misoriented") {
        std::string obj = kCubeObj;
        obj.replace(obj.find("f 4 1 5 8\n"), 10, "f 8 5 1 4\n");
        TempFile f("mis.obj", obj);
        TriangleSurface s = readSurface(f.str());
        CHECK(inspectSurface(s.points, s.triangles).misorientedEdges == 4);
        CHECK_THAT(inputError([&] { requireClosedSurface(s, "a test"); }),
                   Catch::Contains("mis.obj:19: error: ") && Catch::Contains("not consistently oriented (4 such edges)"));
    }
    SECTION("a third triangle on an edge of a closed tetrahedron is non-manifold") {
        Positions p = test::tetPoints();
        p.emplace_back(1, 1, -1);
        Triangles t = test::tetFaces();
        t.push_back({0, 1, 4});
        TempFile f("nm.stl", test::binaryStl(p, t));
        TriangleSurface s = readSurface(f.str());
        const SurfaceReport r = inspectSurface(s.points, s.triangles);
        CHECK(r.nonManifoldEdges == 1);
        CHECK(r.openEdges == 2);
        CHECK_THAT(inputError([&] { requireClosedSurface(s, "a test"); }), Catch::Contains("nm.stl: byte ") && Catch::Contains(": error: ") && Catch::Contains("1 non-manifold"));
    }
    SECTION("a tetrahedron with only non-manifold edges") {
        Triangles t = test::tetFaces();
        t.push_back({0, 2, 1});  // a face twice: its three edges have three triangles each
        TriangleSurface s;
        s.points = test::tetPoints();
        s.triangles = t;
        CHECK_THAT(inputError([&] { requireClosedSurface(s, "a test"); }), Catch::Contains("not edge-manifold (3 such edges)"));
    }
}

TEST_CASE("A closed surface facing inwards is turned outwards and says so", "[TriangleSurface]") {
    TriangleSurface s;
    s.points = test::tetPoints();
    s.triangles = test::tetFaces();
    for (auto& t : s.triangles) std::swap(t[0], t[1]);
    CHECK(enclosedVolume(s.points, s.triangles) == Approx(-1.0 / 6));
    CHECK(requireClosedSurface(s, "a test"));
    CHECK(enclosedVolume(s.points, s.triangles) == Approx(1.0 / 6));
    CHECK_FALSE(requireClosedSurface(s, "a test"));
}

TEST_CASE("The enclosed volume of a surface far from the origin keeps its digits", "[TriangleSurface]") {
    Positions p = test::tetPoints();
    for (auto& x : p) x += Vec3(1e6, -2e6, 3e6);
    CHECK(enclosedVolume(p, test::tetFaces()) == Approx(1.0 / 6).epsilon(1e-9));
}
