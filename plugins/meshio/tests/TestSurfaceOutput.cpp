// The body's boundary surface (Simulation::surface, VTKExporter surface="true") and the visual
// surface mapping (BarycentricSurfaceMapping): through the API and in .vtp files read back by VTK.
#include "BarycentricSurfaceMapping.h"
#include "MeshioTestSupport.h"
#include "fascia/sim/Simulation.h"
#include "fascia/surface/TriangleSurface.h"

#include <catch2/catch.hpp>

#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <omp.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

using fascia::Positions;
using fascia::Triangles;
using fascia::Vec3;
using fascia::core::Error;
using fascia::core::Simulation;
using fascia::meshio::BarycentricSurfaceMapping;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using meshiotest::fileNames;
using meshiotest::freshDir;
using meshiotest::pvdFiles;
using meshiotest::readVtp;
using meshiotest::slurp;

namespace {

std::string errorOf(const std::string& xml, const std::string& baseDir = ".") {
    try {
        Simulation::fromString(xml, "scene.xml", baseDir);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

/// A box body of 0.2 x 0.1 x 0.1 m without forces (an embedding program moves it), and `extra`.
std::string box(const std::string& element, const std::string& extra) {
    return "<Node name=\"root\" dt=\"0.001\">\n"
           "  <GridMesh name=\"grid\" min=\"0 0 0\" max=\"0.2 0.1 0.1\" resolution=\"4 2 2\" element=\"" + element + "\"/>\n"
           "  <MechanicalObject name=\"state\"/>\n" + extra +
           "</Node>\n";
}

double tetVolume(const Positions& p, const std::array<int, 4>& t) {
    return (p[t[1]] - p[t[0]]).dot((p[t[2]] - p[t[0]]).cross(p[t[3]] - p[t[0]])) / 6;
}

/// The six faces of the box [lo, hi], each split into m x m squares of two triangles, outwards,
/// as an OBJ file.
std::string boxSurfaceObj(const Vec3& lo, const Vec3& hi, int m) {
    std::ostringstream s;
    s.precision(17);
    int base = 1;
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            for (int j = 0; j <= m; ++j)
                for (int i = 0; i <= m; ++i) {
                    Vec3 p;
                    p[axis] = side ? hi[axis] : lo[axis];
                    p[u] = lo[u] + (hi[u] - lo[u]) * i / m;
                    p[v] = lo[v] + (hi[v] - lo[v]) * j / m;
                    s << "v " << p[0] << " " << p[1] << " " << p[2] << "\n";
                }
            for (int j = 0; j < m; ++j)
                for (int i = 0; i < m; ++i) {
                    const int a = base + i + (m + 1) * j, b = a + 1, c = a + m + 2, d = a + m + 1;
                    // (u, v, axis) is right-handed: counter-clockwise in (u, v) faces +axis
                    if (side) s << "f " << a << " " << b << " " << c << " " << d << "\n";
                    else s << "f " << a << " " << d << " " << c << " " << b << "\n";
                }
            base += (m + 1) * (m + 1);
        }
    return s.str();
}

void writeText(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

} // namespace

TEST_CASE("The body's boundary surface is available through the API, closed, turned outwards, and bounds the volume",
          "[BaseTopology][Simulation]") {
    SECTION("generated grids of tetrahedra and hexahedra") {
        const std::string element = GENERATE(as<std::string>{}, "tetrahedra6", "tetrahedra5", "hexahedra");
        CAPTURE(element);
        auto sim = Simulation::fromString(box(element, ""));
        const auto s = sim->surface("state");
        CHECK(s.points == &sim->state("state").x());
        CHECK(s.body == &sim->state("state"));
        CHECK(s.triangles->size() == size_t(4 * (4 * 2 + 2 * 2 + 2 * 4)));
        const auto r = fascia::surface::inspectSurface(*s.points, *s.triangles);
        CHECK(r.closed());
        CHECK(r.volume == Approx(0.2 * 0.1 * 0.1).epsilon(1e-12));
    }
    SECTION("a Gmsh mesh read by MeshLoader: the boundary the file lists, computed from the tetrahedra") {
        auto sim = Simulation::fromString("<Node name=\"root\" dt=\"0.001\">\n"
                                          "  <MeshLoader name=\"loader\" filename=\"scenes/meshes/organ_2428.msh\"/>\n"
                                          "  <MechanicalObject name=\"organ\"/>\n"
                                          "</Node>\n",
                                          "scene.xml", FASCIA_SOURCE_DIR);
        const auto s = sim->surface("/root/organ");
        auto* topo = dynamic_cast<fascia::core::BaseTopology*>(sim->find("loader"));
        REQUIRE(topo);
        const auto& mesh = topo->meshData();
        CHECK(s.triangles->size() == mesh.triangles.size());  // the file's physical surface "boundary"
        const auto r = fascia::surface::inspectSurface(*s.points, *s.triangles);
        CHECK(r.closed());
        double v = 0;
        for (const auto& t : mesh.tetrahedra) v += tetVolume(mesh.points, t);
        CHECK(r.volume == Approx(v).epsilon(1e-12));
        // it moves with the body: the view reads the state's positions
        sim->state("organ").x()[0] += Vec3(0.01, 0, 0);
        CHECK((*sim->surface("organ").points)[0] == sim->state("organ").x()[0]);
    }
    SECTION("a name that is no state or surface, and a state without a mesh source, are errors") {
        auto sim = Simulation::fromString(box("tetrahedra6", "  <Node name=\"free\">\n"
                                                             "    <MechanicalObject name=\"points\" position=\"0 0 0  1 0 0\"/>\n"
                                                             "  </Node>\n"));
        CHECK_THROWS_WITH(sim->surface("grid"), Contains("no mechanical state or visual surface 'grid'"));
        CHECK_THROWS_WITH(sim->surface("points"), Contains("mechanical state 'points' has no boundary surface"));
    }
}

TEST_CASE("VTKExporter writes the boundary surface as a .vtp series next to the volume, read back by VTK", "[VTKExporter]") {
    const std::string compression = GENERATE(as<std::string>{}, "lz4", "none");
    CAPTURE(compression);
    auto dir = freshDir("vtp-" + compression);
    auto sim = Simulation::fromString(box("tetrahedra6", "  <VTKExporter name=\"out\" every=\"2\" surface=\"true\" compression=\"" +
                                                             compression + "\"/>\n"),
                                      "scene.xml", ".", {dir.string(), 0});
    auto& st = sim->state("state");
    for (int step = 1; step <= 3; ++step) {
        for (size_t i = 0; i < st.size(); ++i) st.x()[i] = st.x0()[i] + Vec3(0.001 * step * st.x0()[i][0], 0, -0.002 * step);
        sim->step();
    }
    sim->finish();  // step 3, the final state, is written too
    CHECK(pvdFiles(dir / "out.pvd") == std::vector<std::string>{"out_000000.vtu", "out_000002.vtu", "out_000003.vtu"});
    CHECK(pvdFiles(dir / "out_surface.pvd") ==
          std::vector<std::string>{"out_surface_000000.vtp", "out_surface_000002.vtp", "out_surface_000003.vtp"});
    auto poly = readVtp(dir / "out_surface_000003.vtp");
    REQUIRE(poly);
    const auto s = sim->surface("state");
    // only the boundary nodes: 5 x 3 x 3 grid nodes, all but the one inside
    REQUIRE(poly->GetNumberOfPoints() == 5 * 3 * 3 - 3);
    REQUIRE(poly->GetNumberOfPolys() == vtkIdType(s.triangles->size()));
    vtkDataArray* id = poly->GetPointData()->GetArray("nodeId");
    vtkDataArray* u = poly->GetPointData()->GetArray("displacement");
    REQUIRE(id);
    REQUIRE(u);
    REQUIRE(poly->GetPointData()->GetArray("velocity"));
    for (vtkIdType i = 0; i < poly->GetNumberOfPoints(); ++i) {
        const size_t n = size_t(id->GetTuple1(i));
        double p[3], uu[3];
        poly->GetPoint(i, p);
        u->GetTuple(i, uu);
        for (int a = 0; a < 3; ++a) {
            REQUIRE(p[a] == st.x()[n][a]);
            REQUIRE(uu[a] == st.x()[n][a] - st.x0()[n][a]);
        }
    }
    // the triangles are the API's, over the state's nodes
    vtkIdType npts = 0;
    const vtkIdType* pts = nullptr;
    poly->GetPolys()->InitTraversal();
    for (size_t t = 0; t < s.triangles->size(); ++t) {
        REQUIRE(poly->GetPolys()->GetNextCell(npts, pts));
        REQUIRE(npts == 3);
        for (int k = 0; k < 3; ++k) REQUIRE(vtkIdType(id->GetTuple1(pts[k])) == (*s.triangles)[t][size_t(k)]);
    }
}

TEST_CASE("VTKExporter writes no surface unless asked, and refuses one for a body without a mesh", "[VTKExporter]") {
    auto dir = freshDir("nosurface");
    {
        auto sim = Simulation::fromString(box("hexahedra", "  <VTKExporter name=\"out\"/>\n"), "scene.xml", ".", {dir.string(), 0});
        sim->run(1);
        sim->finish();
    }
    CHECK(fs::exists(dir / "out.pvd"));
    CHECK(!fs::exists(dir / "out_surface.pvd"));
    CHECK(!fs::exists(dir / "out_surface_000000.vtp"));
    CHECK_THAT(errorOf("<Node name=\"root\" dt=\"0.001\">\n"
                       "  <MechanicalObject name=\"points\" position=\"0 0 0  1 0 0\"/>\n"
                       "  <VTKExporter name=\"out\" surface=\"true\"/>\n"
                       "</Node>\n"),
               Contains("scene.xml:3: error: VTKExporter 'out': surface=\"true\" needs the body's boundary"));
}

namespace {
/// A box body and a visual surface file beside it: the faces of `lo`..`hi`, 4 x 4 squares each.
struct MappedBox {
    fs::path dir;
    std::unique_ptr<Simulation> sim;
    MappedBox(const std::string& name, const Vec3& lo, const Vec3& hi, const std::string& attributes = "") {
        dir = freshDir(name);
        writeText(dir / "visual.obj", boxSurfaceObj(lo, hi, 4));
        sim = Simulation::fromString(box("tetrahedra5", "  <BarycentricSurfaceMapping name=\"visual\" filename=\"visual.obj\" " +
                                                            attributes + "/>\n"),
                                     "scene.xml", dir.string(), {dir.string(), 0});
    }
    BarycentricSurfaceMapping& mapping() { return *dynamic_cast<BarycentricSurfaceMapping*>(sim->find("visual")); }
};

/// x = A X + b on every node of the state.
void deformAffinely(fascia::core::BaseMechanicalState& st, const fascia::Mat3& A, const Vec3& b) {
    for (size_t i = 0; i < st.size(); ++i) st.x()[i] = A * st.x0()[i] + b;
}
} // namespace

TEST_CASE("A visual surface inside and just outside the body follows an affine motion exactly", "[BarycentricSurfaceMapping]") {
    // inside: the faces shrunk towards the centre; outside: pushed 1 mm (1 % of the box) out
    const double offset = GENERATE(-0.02, -0.001, 0.0, 0.001);
    CAPTURE(offset);
    const Vec3 o(offset, offset, offset);
    MappedBox b("affine", Vec3(0, 0, 0) - o, Vec3(0.2, 0.1, 0.1) + o);
    auto& m = b.mapping();
    const auto& tets = m.vertexTetrahedra();
    REQUIRE(tets.size() == 6 * 25);
    for (size_t v = 0; v < tets.size(); ++v) {
        INFO("vertex " << v);
        REQUIRE(tets[v] >= 0);  // every vertex found
        const auto& w = m.vertexWeights()[v];
        CHECK(w[0] + w[1] + w[2] + w[3] == Approx(1).epsilon(1e-14));
        if (offset <= 0) {
            CHECK(m.vertexDistances()[v] == 0);
            CHECK(std::min({w[0], w[1], w[2], w[3]}) >= -1e-12);  // in its tetrahedron
        } else {
            // outside by the offset: on a face's middle exactly that, at an edge or a corner up to sqrt(3) of it
            CHECK(m.vertexDistances()[v] >= offset * (1 - 1e-9));
            CHECK(m.vertexDistances()[v] <= offset * std::sqrt(3.0) * (1 + 1e-9));
        }
    }
    fascia::Mat3 A;
    A << 1.1, 0.2, -0.05, 0.03, 0.9, 0.1, -0.1, 0.05, 1.2;
    const Vec3 t(0.01, -0.02, 0.03);
    deformAffinely(b.sim->state("state"), A, t);
    b.sim->step();
    const auto s = b.sim->surface("visual");
    REQUIRE(s.points->size() == m.restPoints().size());
    CHECK(s.body == &b.sim->state("state"));
    CHECK(s.triangles->size() == 6 * 32);
    double worst = 0;
    for (size_t v = 0; v < s.points->size(); ++v) worst = std::max(worst, ((*s.points)[v] - (A * m.restPoints()[v] + t)).norm());
    CHECK(worst <= 1e-12 * 0.3);
}

TEST_CASE("The mapped surface is the same with 1 and 2 threads, bitwise", "[BarycentricSurfaceMapping]") {
    auto run = [](int threads) {
        omp_set_num_threads(threads);
        MappedBox b("threads" + std::to_string(threads), Vec3(-0.001, 0.01, 0.01), Vec3(0.201, 0.09, 0.09));
        auto& st = b.sim->state("state");
        std::mt19937 rng(3);
        std::uniform_real_distribution<double> d(-0.005, 0.005);
        for (size_t i = 0; i < st.size(); ++i) st.x()[i] = st.x0()[i] + Vec3(d(rng), d(rng), d(rng));
        b.sim->step();
        return *b.sim->surface("visual").points;
    };
    const Positions one = run(1), two = run(2);
    omp_set_num_threads(omp_get_num_procs());
    REQUIRE(one.size() == two.size());
    for (size_t v = 0; v < one.size(); ++v) REQUIRE((one[v].array() == two[v].array()).all());
}

TEST_CASE("A visual vertex farther from the body than maxDistance is a located error", "[BarycentricSurfaceMapping]") {
    auto dir = freshDir("far");
    writeText(dir / "far.obj", boxSurfaceObj(Vec3(-0.01, 0, 0), Vec3(0.2, 0.1, 0.1), 2));  // 1 cm beyond x = 0
    const std::string scene = box("tetrahedra6", "  <BarycentricSurfaceMapping name=\"visual\" filename=\"far.obj\" maxDistance=\"0.005\"/>\n");
    CHECK_THAT(errorOf(scene, dir.string()),
               Contains("scene.xml:4: error: BarycentricSurfaceMapping 'visual': vertex 1 of 'far.obj' at (-0.01 0 0) is 0.01 m from "
                        "the body, more than maxDistance = 0.005 m"));
    // the default, 5 % of the body's diagonal (0.0122 m), takes it
    CHECK(errorOf(box("tetrahedra6", "  <BarycentricSurfaceMapping name=\"visual\" filename=\"far.obj\"/>\n"), dir.string()).empty());
    // a bad file is located in the file, with where the scene asked for it
    writeText(dir / "bad.obj", "v 0 0 0\nf 1 2 3\n");
    CHECK_THAT(errorOf(box("tetrahedra6", "  <BarycentricSurfaceMapping name=\"visual\" filename=\"bad.obj\"/>\n"), dir.string()),
               Contains("bad.obj:2: error: the face names vertex 2") && Contains("note: read by BarycentricSurfaceMapping 'visual' at ") && Contains("scene.xml:4"));
    CHECK_THAT(errorOf(box("hexahedra", "  <BarycentricSurfaceMapping name=\"visual\" filename=\"far.obj\"/>\n"), dir.string()),
               Contains("the body has no tetrahedra"));
}

TEST_CASE("The mapped surface is written as a .vtp series that VTK reads back", "[BarycentricSurfaceMapping]") {
    MappedBox b("vtp", Vec3(0, 0, 0), Vec3(0.2, 0.1, 0.1), "output=\"skin\" every=\"2\"");
    auto& st = b.sim->state("state");
    for (int step = 1; step <= 4; ++step) {
        for (size_t i = 0; i < st.size(); ++i) st.x()[i] = st.x0()[i] + Vec3(0, 0, 0.01 * step * st.x0()[i][0]);
        b.sim->step();
    }
    b.sim->finish();
    CHECK(pvdFiles(b.dir / "skin.pvd") == std::vector<std::string>{"skin_000000.vtp", "skin_000002.vtp", "skin_000004.vtp"});
    auto poly = readVtp(b.dir / "skin_000004.vtp");
    REQUIRE(poly);
    const auto s = b.sim->surface("visual");
    REQUIRE(poly->GetNumberOfPoints() == vtkIdType(s.points->size()));
    REQUIRE(poly->GetNumberOfPolys() == vtkIdType(s.triangles->size()));
    vtkDataArray* u = poly->GetPointData()->GetArray("displacement");
    REQUIRE(u);
    for (vtkIdType i = 0; i < poly->GetNumberOfPoints(); ++i) {
        double p[3];
        poly->GetPoint(i, p);
        const Vec3& x = (*s.points)[size_t(i)];
        REQUIRE(Vec3(p[0], p[1], p[2]) == x);
        // the body bends as z += 0.04 x: exact for a surface on the body's faces up to rounding
        REQUIRE(u->GetComponent(i, 2) == Approx(0.04 * b.mapping().restPoints()[size_t(i)][0]).margin(1e-15));
    }
}

TEST_CASE("Fascia's own .vtp surfaces read back as surfaces: a mapping's visual surface, the exporter's boundary",
          "[BarycentricSurfaceMapping][VTKExporter]") {
    SECTION("a mapping's .vtp (lz4, as written) maps again, and follows the body as the surface it was written from") {
        const Vec3 lo(0.01, 0.01, 0.01), hi(0.19, 0.09, 0.09);
        MappedBox a("vtp-again", lo, hi, "output=\"skin\"");
        const Positions written = *a.sim->surface("visual").points;  // step 0, as the file has it
        a.sim->step();  // writes step 0 (no integrator: nothing moves)
        a.sim->finish();
        const auto s = fascia::surface::readSurface((a.dir / "skin_000000.vtp").string());
        CHECK(s.format == "VTK XML PolyData");
        CHECK(s.points == written);
        CHECK(s.triangles == *a.sim->surface("visual").triangles);
        auto b = Simulation::fromString(box("tetrahedra5", "  <BarycentricSurfaceMapping name=\"visual\" filename=\"skin_000000.vtp\"/>\n"),
                                        "scene.xml", a.dir.string(), {a.dir.string(), 0});
        auto* m = dynamic_cast<BarycentricSurfaceMapping*>(b->find("visual"));
        REQUIRE(m);
        CHECK(m->restPoints() == written);
        fascia::Mat3 A;
        A << 1.05, 0.1, 0, -0.02, 0.95, 0.03, 0, 0.04, 1.1;
        const Vec3 t(0.003, 0.002, -0.001);
        MappedBox fromObj("vtp-again-obj", lo, hi);  // the surface the file was written from
        deformAffinely(fromObj.sim->state("state"), A, t);
        deformAffinely(b->state("state"), A, t);
        fromObj.sim->step();
        b->step();
        const Positions &pa = *fromObj.sim->surface("visual").points, &pb = *b->surface("visual").points;
        REQUIRE(pa.size() == pb.size());
        double worst = 0;
        for (size_t v = 0; v < pa.size(); ++v) worst = std::max(worst, (pa[v] - pb[v]).norm());
        CHECK(worst <= 1e-14);
    }
    SECTION("the exporter's boundary surface, in each compression, is closed and outwards around the body's volume") {
        const std::string compression = GENERATE(as<std::string>{}, "lz4", "zlib", "none");
        CAPTURE(compression);
        auto dir = freshDir("vtp-read-" + compression);
        auto sim = Simulation::fromString(box("tetrahedra6", "  <VTKExporter name=\"out\" surface=\"true\" compression=\"" + compression + "\"/>\n"),
                                          "scene.xml", ".", {dir.string(), 0});
        sim->step();
        sim->finish();
        auto s = fascia::surface::readSurface((dir / "out_surface_000000.vtp").string());
        CHECK(s.triangles.size() == sim->surface("state").triangles->size());
        CHECK_FALSE(fascia::surface::requireClosedSurface(s, "a test"));
        CHECK(fascia::surface::enclosedVolume(s.points, s.triangles) == Approx(0.2 * 0.1 * 0.1).epsilon(1e-12));
    }
}

TEST_CASE("A visual surface of another node's body is mapped through its state link", "[BarycentricSurfaceMapping]") {
    auto dir = freshDir("link");
    writeText(dir / "v.obj", boxSurfaceObj(Vec3(0.05, 0.02, 0.02), Vec3(0.15, 0.08, 0.08), 1));
    auto sim = Simulation::fromString("<Node name=\"root\" dt=\"0.001\">\n"
                                      "  <Node name=\"body\">\n"
                                      "    <GridMesh name=\"grid\" min=\"0 0 0\" max=\"0.2 0.1 0.1\" resolution=\"2 1 1\"/>\n"
                                      "    <MechanicalObject name=\"state\"/>\n"
                                      "  </Node>\n"
                                      "  <Node name=\"render\">\n"
                                      "    <BarycentricSurfaceMapping name=\"visual\" filename=\"v.obj\" state=\"@../body/state\"/>\n"
                                      "  </Node>\n"
                                      "</Node>\n",
                                      "scene.xml", dir.string(), {dir.string(), 0});
    auto& st = sim->state("state");
    deformAffinely(st, fascia::Mat3::Identity(), Vec3(0.5, 0, 0));
    sim->step();
    const auto s = sim->surface("visual");
    CHECK(s.body == &st);
    CHECK((*s.points)[0].isApprox(Vec3(0.55, 0.02, 0.02), 1e-14));
}

TEST_CASE("The liver-size organ's finer visual surface is found in the mesh and follows the body", "[BarycentricSurfaceMapping]") {
    auto dir = freshDir("liver");
    auto sim = Simulation::fromFile(std::string(FASCIA_SOURCE_DIR) + "/scenes/interaction/liver_visual.xml", {dir.string(), 0});
    auto* m = dynamic_cast<BarycentricSurfaceMapping*>(sim->find("visual"));
    REQUIRE(m);
    // scenes/meshes/organ_2428_visual.obj: 3336 triangles, closed, about the organ's volume
    REQUIRE(m->restPoints().size() == 1670);
    const auto s0 = sim->surface("visual");
    const auto r = fascia::surface::inspectSurface(*s0.points, *s0.triangles);
    CHECK(r.closed());
    const auto body = fascia::surface::inspectSurface(*sim->surface("organ").points, *sim->surface("organ").triangles);
    CHECK(r.volume == Approx(body.volume).epsilon(0.03));
    size_t outside = 0;
    for (size_t v = 0; v < m->vertexTetrahedra().size(); ++v) {
        REQUIRE(m->vertexTetrahedra()[v] >= 0);
        CHECK(m->vertexDistances()[v] < 0.002);  // the smoothing moves vertices by under 2 mm
        outside += m->vertexDistances()[v] > 0;
    }
    CHECK(outside > 0);  // some vertices just outside, found through the nearest boundary triangle
    sim->run(20);
    // every vertex is the weighted sum of its tetrahedron's nodes, at the current positions
    const auto& x = sim->state("organ").x();
    auto* topo = dynamic_cast<fascia::core::BaseTopology*>(sim->find("loader"));
    REQUIRE(topo);
    const auto s = sim->surface("visual");
    double moved = 0;
    for (size_t v = 0; v < s.points->size(); ++v) {
        const auto& t = topo->meshData().tetrahedra[size_t(m->vertexTetrahedra()[v])];
        const auto& w = m->vertexWeights()[v];
        const Vec3 expect = w[0] * x[t[0]] + w[1] * x[t[1]] + w[2] * x[t[2]] + w[3] * x[t[3]];
        REQUIRE(((*s.points)[v] - expect).norm() <= 1e-15);
        moved = std::max(moved, ((*s.points)[v] - m->restPoints()[v]).norm());
    }
    CHECK(moved > 0);
    sim->finish();
}

TEST_CASE("A restored run continues the surface series like the volume one: the same .pvd files and file set",
          "[VTKExporter][BarycentricSurfaceMapping][Simulation]") {
    // a soft box sagging under gravity, held at xmin: the volume and surface series every 3 steps, the
    // mapped surface every 4; 24 steps straight against 12, a checkpoint, a restore and 12
    const fs::path a = freshDir("restart-straight"), b = freshDir("restart-restarted"), ck = freshDir("restart-ckpt") / "box.ckpt";
    writeText(a / "visual.obj", boxSurfaceObj(Vec3(0, 0, 0), Vec3(0.2, 0.1, 0.1), 2));
    writeText(b / "visual.obj", slurp(a / "visual.obj"));
    const std::string xml = "<Node name=\"root\" dt=\"0.0005\" gravity=\"0 0 -9.81\">\n"
                            "  <GridMesh name=\"grid\" min=\"0 0 0\" max=\"0.2 0.1 0.1\" resolution=\"4 2 2\" element=\"tetrahedra5\"/>\n"
                            "  <MechanicalObject name=\"state\"/>\n  <LumpedMass density=\"1000\"/>\n"
                            "  <NeoHookean mu=\"3000\" kappa=\"30000\"/>\n  <HEMLForceField/>\n  <SemiImplicitEuler damping=\"5\"/>\n"
                            "  <FixedConstraint group=\"xmin\"/>\n"
                            "  <VTKExporter name=\"out\" every=\"3\" surface=\"true\"/>\n"
                            "  <BarycentricSurfaceMapping name=\"visual\" filename=\"visual.obj\" output=\"skin\" every=\"4\"/>\n"
                            "</Node>\n";
    {
        auto sim = Simulation::fromString(xml, "scene.xml", a.string(), {a.string(), 0});
        sim->run(24);
        sim->finish();
    }
    {
        auto first = Simulation::fromString(xml, "scene.xml", b.string(), {b.string(), 0});
        first->run(12);
        first->save(ck.string());
        first->finish();
    }
    auto second = Simulation::fromString(xml, "scene.xml", b.string(), {b.string(), 0});
    second->restore(ck.string());
    second->run(12);
    second->finish();
    CHECK(pvdFiles(b / "out_surface.pvd").size() == 9);  // steps 0, 3 ... 24
    CHECK(pvdFiles(b / "skin.pvd").size() == 7);         // steps 0, 4 ... 24
    CHECK(fileNames(a) == fileNames(b));
    for (const std::string pvd : {"out.pvd", "out_surface.pvd", "skin.pvd"}) {
        CAPTURE(pvd);
        REQUIRE(fs::exists(b / pvd));
        CHECK(slurp(a / pvd) == slurp(b / pvd));
    }
    CHECK(slurp(a / "out_surface_000024.vtp") == slurp(b / "out_surface_000024.vtp"));
    CHECK(slurp(a / "skin_000024.vtp") == slurp(b / "skin_000024.vtp"));
}
