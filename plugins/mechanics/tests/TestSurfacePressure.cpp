// SurfacePressure as a follower load: forces on deformed states against hand computations (the
// gradient of the enclosed volume, Nanson's formula), the ramp, and triangle groups from a Gmsh file.
#include "SurfacePressure.h"
#include "fascia/sim/Simulation.h"

#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <unistd.h>

using fascia::Mat3;
using fascia::Positions;
using fascia::Vec3;
using fascia::core::Error;
using fascia::core::Simulation;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

std::string gridScene(const std::string& pressure, const std::string& element = "tetrahedra6") {
    return "<Node name=\"root\" dt=\"0.001\">\n"
           "  <GridMesh name=\"grid\" min=\"0 0 0\" max=\"0.2 0.1 0.3\" resolution=\"3 2 4\" element=\"" + element + "\"/>\n"
           "  <MechanicalObject name=\"state\"/>\n"
           "  <LumpedMass density=\"1000\"/>\n"
           "  <SemiImplicitEuler/>\n"
           "  " + pressure + "\n"
           "</Node>\n";
}

/// The pressure's nodal forces at the state's current positions and time t.
Positions forces(Simulation& sim, const std::string& name, double t) {
    auto* ff = dynamic_cast<fascia::core::BaseForceField*>(sim.find(name));
    REQUIRE(ff);
    auto& st = sim.state("state");
    Positions f(st.size(), Vec3::Zero());
    ff->addForce(st, f, t);
    return f;
}

Vec3 sum(const Positions& f) {
    Vec3 s = Vec3::Zero();
    for (auto& v : f) s += v;
    return s;
}

const fascia::MeshData& meshOf(Simulation& sim, const std::string& name) {
    auto* topo = dynamic_cast<fascia::core::BaseTopology*>(sim.find(name));
    REQUIRE(topo);
    return topo->meshData();
}

/// Signed volume of the body: the sum of its tetrahedra's volumes (independent of any surface).
double volume(const fascia::MeshData& mesh, const Positions& x) {
    double v = 0;
    for (auto& t : mesh.tetrahedra) v += (x[t[1]] - x[t[0]]).dot((x[t[2]] - x[t[0]]).cross(x[t[3]] - x[t[0]])) / 6.0;
    return v;
}

std::string errorOf(const std::string& xml) {
    try {
        Simulation::fromString(xml, "scene.xml");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

/// The unit cube of plugins/meshio/tests/data/cube_gmsh22.msh (five tetrahedra, tag 1), with boundary
/// triangles in three physical groups: 2 the bottom z = 0 (outward normal -z), 3 the top z = 1 (its
/// first triangle written with the inward orientation, which must be turned outwards), and 4 one
/// triangle through the cube that bounds no tetrahedron.
const char* kCubeWithFaces = R"($MeshFormat
2.2 0 8
$EndMeshFormat
$Nodes
8
10 0 0 0
20 1 0 0
30 1 1 0
40 0 1 0
50 0 0 1
60 1 0 1
70 1 1 1
80 0 1 1
$EndNodes
$Elements
10
1 2 2 2 5 10 40 20
2 2 2 2 5 20 40 30
3 2 2 3 6 60 50 70
4 2 2 3 6 50 70 80
5 2 2 4 7 10 20 70
6 4 2 1 1 10 20 40 50
7 4 2 1 1 30 40 20 70
8 4 2 1 1 60 50 70 20
9 4 2 1 1 80 70 50 40
10 4 2 1 1 20 40 50 70
$EndElements
)";

std::string writeCube() {
    const fs::path dir = fs::temp_directory_path() / ("fascia-pressure-" + std::to_string(getpid()));
    fs::create_directories(dir);
    const fs::path p = dir / "cube_faces.msh";
    std::ofstream(p) << kCubeWithFaces;
    return p.string();
}

std::string cubeScene(const std::string& pressure) {
    return "<Node name=\"root\" dt=\"0.001\">\n"
           "  <MeshLoader name=\"mesh\" filename=\"" + writeCube() + "\"/>\n"
           "  <MechanicalObject name=\"state\"/>\n"
           "  <LumpedMass density=\"1000\"/>\n"
           "  <SemiImplicitEuler/>\n"
           "  " + pressure + "\n"
           "</Node>\n";
}

struct CaptureCerr {
    std::ostringstream out;
    std::streambuf* old = std::cerr.rdbuf(out.rdbuf());
    ~CaptureCerr() { std::cerr.rdbuf(old); }
};

/// A deformation gradient with stretch, shear and a rotation, det > 0.
Mat3 someF() {
    Mat3 U;
    U << 1.2, 0.1, 0.0, 0.0, 0.9, 0.2, 0.05, 0.0, 1.1;
    return Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix() * U;
}

} // namespace

TEST_CASE("a pressure on a closed surface gives minus p times the gradient of the enclosed volume on any deformed state",
          "[SurfacePressure]") {
    // For a closed triangulated surface, -p A n with a third on each corner equals -p dV/dx_i exactly
    // (the extra terms x_i x (x_j - x_k) summed around a node's ring of triangles telescope to zero).
    // V here is the sum of the tetrahedra's volumes, linear in each single coordinate, so the central
    // difference below is exact up to round-off. A dead load (forces from the rest positions) or a
    // wrong orientation fails it.
    auto sim = Simulation::fromString(gridScene("<SurfacePressure name=\"p\" pressure=\"1000\"/>"));
    auto& st = sim->state("state");
    const auto& mesh = meshOf(*sim, "grid");
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-0.015, 0.015);  // cells are 0.05 .. 0.075 m
    const Mat3 R = Eigen::AngleAxisd(0.4, Vec3(0.3, -1, 0.5).normalized()).toRotationMatrix();
    for (size_t i = 0; i < st.size(); ++i) st.x()[i] = R * (st.x0()[i] + Vec3(u(rng), u(rng), u(rng))) + Vec3(0.1, -0.2, 0.3);
    const Positions f = forces(*sim, "p", 0.0);
    const double h = 1e-3;
    double worst = 0, largest = 0;
    for (size_t i = 0; i < st.size(); ++i)
        for (int a = 0; a < 3; ++a) {
            Positions x = st.x();
            x[i][a] += h;
            const double vp = volume(mesh, x);
            x[i][a] -= 2 * h;
            const double vm = volume(mesh, x);
            const double expected = -1000 * (vp - vm) / (2 * h);
            worst = std::max(worst, std::abs(f[i][a] - expected));
            largest = std::max(largest, std::abs(expected));
        }
    CAPTURE(worst, largest);
    CHECK(largest > 1.0);  // about p times a third of the area around a node
    CHECK(worst < 1e-9 * largest);
    // and nothing net, in force or in moment, on the deformed closed surface
    Vec3 moment = Vec3::Zero();
    for (size_t i = 0; i < st.size(); ++i) moment += st.x()[i].cross(f[i]);
    CHECK(sum(f).norm() < 1e-12);
    CHECK(moment.norm() < 1e-12);
}

TEST_CASE("a pressure on one face follows a homogeneous deformation by Nanson's formula", "[SurfacePressure]") {
    // x = F X + c maps an area vector N dA to J F^-T N dA (Nanson), so each nodal force of the face
    // becomes J F^-T times its rest value, and the total -p J F^-T N A with N = e_z, A = 0.2 x 0.1.
    auto sim = Simulation::fromString(gridScene("<SurfacePressure name=\"p\" pressure=\"1000\" nodeGroup=\"zmax\"/>"));
    auto& st = sim->state("state");
    const Positions rest = forces(*sim, "p", 0.0);
    CHECK(sum(rest)[2] == Approx(-1000 * 0.2 * 0.1).epsilon(1e-12));
    const Mat3 F = someF();
    const double J = F.determinant();
    const Mat3 cof = J * F.inverse().transpose();
    for (size_t i = 0; i < st.size(); ++i) st.x()[i] = F * st.x0()[i] + Vec3(0.5, 0.1, -0.2);
    const Positions f = forces(*sim, "p", 0.0);
    const Vec3 expectedTotal = -1000 * 0.2 * 0.1 * cof * Vec3::UnitZ();
    CHECK((sum(f) - expectedTotal).norm() < 1e-12 * expectedTotal.norm());
    int loaded = 0;
    for (size_t i = 0; i < st.size(); ++i) {
        INFO("node " << i);
        CHECK((f[i] - cof * rest[i]).norm() < 1e-12);
        if (rest[i].norm() > 0) ++loaded;
    }
    CHECK(loaded == 4 * 3);  // the nodes of the zmax face only
}

TEST_CASE("rampTime grows the pressure linearly from zero, then holds it", "[SurfacePressure]") {
    auto sim = Simulation::fromString(gridScene("<SurfacePressure name=\"p\" pressure=\"1000\" rampTime=\"0.5\" nodeGroup=\"zmax\"/>"));
    const double full = -1000 * 0.2 * 0.1;
    CHECK(sum(forces(*sim, "p", 0.0)).norm() == 0.0);
    CHECK(sum(forces(*sim, "p", 0.125))[2] == Approx(0.25 * full).epsilon(1e-12));
    CHECK(sum(forces(*sim, "p", 0.4))[2] == Approx(0.8 * full).epsilon(1e-12));
    CHECK(sum(forces(*sim, "p", 0.5))[2] == Approx(full).epsilon(1e-12));
    CHECK(sum(forces(*sim, "p", 3.0))[2] == Approx(full).epsilon(1e-12));
    // in a run: the forces of a step are those at its start time, so after n steps of dt the free top
    // face has felt the impulse of the ramp up to (n - 1) dt
    auto run = Simulation::fromString(gridScene("<SurfacePressure name=\"p\" pressure=\"1000\" rampTime=\"0.5\" nodeGroup=\"zmax\"/>"));
    run->run(10);  // no stiffness: the top nodes are free points
    double momentum = 0;
    const auto& st = run->state("state");
    const auto& mass = run->groups().front().mass;
    for (size_t i = 0; i < st.size(); ++i) momentum += mass[i] * st.v()[i][2];
    // leapfrog with its half-step start: impulse dt (f0/2 + f1 + ... + f9), f_k = full k dt / 0.5
    double impulse = 0;
    for (int k = 0; k < 10; ++k) impulse += (k == 0 ? 0.5 : 1.0) * 0.001 * full * (k * 0.001 / 0.5);
    // (the free nodes move by about 1e-8 m, so the follower load changes by a few parts in 1e10)
    CHECK(momentum == Approx(impulse).epsilon(1e-8));
}

TEST_CASE("triangleGroup selects the physical group of a Gmsh file's triangles, turned outwards", "[SurfacePressure]") {
    // group 2 is the bottom z = 0 (outward -z: the pressure pushes +z), group 3 the top z = 1, whose
    // first triangle the file gives inwards; each face has area 1
    auto bottom = Simulation::fromString(cubeScene("<SurfacePressure name=\"p\" pressure=\"100\" triangleGroup=\"2\"/>"));
    auto top = Simulation::fromString(cubeScene("<SurfacePressure name=\"p\" pressure=\"100\" triangleGroup=\"3\"/>"));
    auto count = [](Simulation& s) { return dynamic_cast<fascia::mechanics::SurfacePressure*>(s.find("p"))->triangleCount(); };
    CHECK(count(*bottom) == 2);
    CHECK(count(*top) == 2);
    CHECK((sum(forces(*bottom, "p", 0)) - Vec3(0, 0, 100)).norm() < 1e-12);
    const Positions ftop = forces(*top, "p", 0);
    CHECK((sum(ftop) - Vec3(0, 0, -100)).norm() < 1e-12);
    for (size_t i = 0; i < ftop.size(); ++i) {
        INFO("node " << i);
        const bool onTop = top->state("state").x0()[i][2] == 1.0;
        CHECK((ftop[i].norm() > 0) == onTop);
        CHECK(ftop[i][2] <= 0);  // every triangle of the top pushes down, the flipped one included
    }
    // deformed: x = F X, the top's force is -p J F^-T e_z
    const Mat3 F = someF();
    auto& st = top->state("state");
    for (size_t i = 0; i < st.size(); ++i) st.x()[i] = F * st.x0()[i];
    const Vec3 expected = -100 * F.determinant() * F.inverse().transpose() * Vec3::UnitZ();
    CHECK((sum(forces(*top, "p", 0)) - expected).norm() < 1e-12);
}

TEST_CASE("SurfacePressure input errors are located", "[SurfacePressure]") {
    SECTION("a triangle group on a hexahedral mesh") {
        CHECK_THAT(errorOf(gridScene("<SurfacePressure name=\"p\" pressure=\"1\" triangleGroup=\"1\"/>", "hexahedra")),
                   Contains("scene.xml:6: error: SurfacePressure 'p': the mesh has no tetrahedra, so no triangle groups"));
    }
    SECTION("a node group the mesh does not have") {
        CHECK_THAT(errorOf(gridScene("<SurfacePressure name=\"p\" pressure=\"1\" nodeGroup=\"corner\"/>", "hexahedra")),
                   Contains("scene.xml:6: error: SurfacePressure 'p': no node group 'corner' in the mesh"));
    }
    SECTION("rampTime and curve together") {
        CHECK_THAT(errorOf(gridScene("<SurfacePressure name=\"p\" pressure=\"1\" rampTime=\"1\" curve=\"ramp 1\"/>")),
                   Contains("scene.xml:6: error: SurfacePressure 'p': give curve or rampTime, not both"));
    }
    SECTION("a triangle group on a mesh without triangles") {
        // liver.msh has tetrahedra only (scenes/meshes/README.md); a GridMesh has its boundary triangles
        const std::string liver = std::string(FASCIA_SOURCE_DIR) + "/scenes/meshes/liver.msh";
        CHECK_THAT(errorOf("<Node name=\"root\" dt=\"0.001\">\n"
                           "  <MeshLoader name=\"mesh\" filename=\"" + liver + "\"/>\n"
                           "  <MechanicalObject name=\"state\"/>\n"
                           "  <LumpedMass density=\"1000\"/>\n"
                           "  <SemiImplicitEuler/>\n"
                           "  <SurfacePressure name=\"p\" pressure=\"1\" triangleGroup=\"2\"/>\n"
                           "</Node>\n"),
                   Contains("scene.xml:6: error: SurfacePressure 'p': the mesh has no triangles, so no triangle groups"));
    }
    SECTION("a triangle group that does not exist") {
        CHECK_THAT(errorOf(cubeScene("<SurfacePressure name=\"p\" pressure=\"1\" triangleGroup=\"9\"/>")),
                   Contains("scene.xml:6: error: SurfacePressure 'p': selects no boundary face"));
    }
    SECTION("a group of triangles that bound no tetrahedron") {
        CHECK_THAT(errorOf(cubeScene("<SurfacePressure name=\"p\" pressure=\"1\" triangleGroup=\"4\"/>")),
                   Contains("scene.xml:6: error: SurfacePressure 'p': selects no boundary face"));
    }
    SECTION("a triangle that bounds no tetrahedron is left out with a warning") {
        CaptureCerr cap;
        auto sim = Simulation::fromString(cubeScene("<SurfacePressure name=\"p\" pressure=\"1\"/>"), "scene.xml");
        CHECK(dynamic_cast<fascia::mechanics::SurfacePressure*>(sim->find("p"))->triangleCount() == 4);
        CHECK_THAT(cap.out.str(), Contains("scene.xml:6: warning: SurfacePressure 'p': 1 triangle(s) are the face of no tetrahedron"));
    }
    SECTION("no mesh source") {
        CHECK_THAT(errorOf("<Node name=\"root\" dt=\"0.001\">\n  <MechanicalObject name=\"state\" position=\"0 0 0\"/>\n"
                           "  <SurfacePressure name=\"p\" pressure=\"1\"/>\n</Node>\n"),
                   Contains("scene.xml:3: error: SurfacePressure 'p': needs a mesh source (MeshLoader, GridMesh) in its context"));
    }
}

namespace {

/// Volume of a hexahedral mesh, the sum over its trilinear hexahedra of the integral of det(dx/dxi)
/// over [-1, 1]^3 by 2x2x2 Gauss points: exact, det(dx/dxi) being of degree 2 in each of xi, eta,
/// zeta. Each row of dx/dxi is linear in one coordinate of the nodes, so V is linear in each single
/// coordinate (central differences of it are exact up to round-off). Computed from the volume, not
/// from any surface.
double hexVolume(const fascia::MeshData& mesh, const Positions& x) {
    static const double s[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                   {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};  // VTK order
    const double g = 1 / std::sqrt(3.0);
    double v = 0;
    for (auto& h : mesh.hexahedra)
        for (int q = 0; q < 8; ++q) {
            const double p[3] = {s[q][0] * g, s[q][1] * g, s[q][2] * g};
            Mat3 J = Mat3::Zero();
            for (int a = 0; a < 8; ++a)
                for (int d = 0; d < 3; ++d) {
                    double dN = s[a][d] / 8.0;
                    for (int e = 0; e < 3; ++e)
                        if (e != d) dN *= 1 + s[a][e] * p[e];
                    J.col(d) += dN * x[h[a]];
                }
            v += J.determinant();
        }
    return v;
}

} // namespace

TEST_CASE("a pressure on the closed surface of a hexahedral mesh gives minus p times the gradient of the enclosed volume",
          "[SurfacePressure]") {
    // The faces are bilinear patches; with nodes moved at random they are not flat, so a face split
    // into two triangles, or a quarter of -p A n on each corner, fails this. V is the hexahedra's
    // volume (above), linear in each coordinate: the central difference is exact up to round-off.
    auto sim = Simulation::fromString(gridScene("<SurfacePressure name=\"p\" pressure=\"1000\"/>", "hexahedra"));
    auto& st = sim->state("state");
    const auto& mesh = meshOf(*sim, "grid");
    auto* sp = dynamic_cast<fascia::mechanics::SurfacePressure*>(sim->find("p"));
    REQUIRE(sp);
    CHECK(sp->quadCount() == 2 * (3 * 2 + 2 * 4 + 3 * 4));  // the boundary faces of 3 x 2 x 4 cells
    CHECK(sp->triangleCount() == 0);
    CHECK(hexVolume(mesh, st.x0()) == Approx(0.2 * 0.1 * 0.3).epsilon(1e-12));
    // at rest: nothing net on the closed surface, and each face pushes inwards
    const Positions rest = forces(*sim, "p", 0.0);
    CHECK(sum(rest).norm() < 1e-12);
    for (size_t i = 0; i < st.size(); ++i)
        if (st.x0()[i][2] == 0.3) CHECK(rest[i][2] < 0);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-0.015, 0.015);  // cells are 0.05 .. 0.075 m
    const Mat3 R = Eigen::AngleAxisd(-0.9, Vec3(1, 0.4, -0.2).normalized()).toRotationMatrix();
    const Mat3 F = someF();
    for (size_t i = 0; i < st.size(); ++i)
        st.x()[i] = R * F * (st.x0()[i] + Vec3(u(rng), u(rng), u(rng))) + Vec3(-0.3, 0.2, 0.1);
    const Positions f = forces(*sim, "p", 0.0);
    const double h = 1e-3;
    double worst = 0, largest = 0;
    for (size_t i = 0; i < st.size(); ++i)
        for (int a = 0; a < 3; ++a) {
            Positions x = st.x();
            x[i][a] += h;
            const double vp = hexVolume(mesh, x);
            x[i][a] -= 2 * h;
            const double vm = hexVolume(mesh, x);
            const double expected = -1000 * (vp - vm) / (2 * h);
            worst = std::max(worst, std::abs(f[i][a] - expected));
            largest = std::max(largest, std::abs(expected));
        }
    CAPTURE(worst, largest);
    CHECK(largest > 1.0);
    CHECK(worst < 1e-9 * largest);
    Vec3 moment = Vec3::Zero();
    for (size_t i = 0; i < st.size(); ++i) moment += st.x()[i].cross(f[i]);
    CHECK(sum(f).norm() < 1e-12);
    CHECK(moment.norm() < 1e-12);
}

TEST_CASE("a pressure on one hexahedral face follows a homogeneous deformation by Nanson's formula", "[SurfacePressure]") {
    // as for the triangles: x = F X + c maps each nodal force to J F^-T times its rest value
    auto sim = Simulation::fromString(gridScene("<SurfacePressure name=\"p\" pressure=\"1000\" nodeGroup=\"zmax\"/>", "hexahedra"));
    auto& st = sim->state("state");
    CHECK(dynamic_cast<fascia::mechanics::SurfacePressure*>(sim->find("p"))->quadCount() == 3 * 2);
    const Positions rest = forces(*sim, "p", 0.0);
    CHECK(sum(rest)[2] == Approx(-1000 * 0.2 * 0.1).epsilon(1e-12));
    // a flat face's corner gets a quarter of each of its cells' force: -p A / 4 per cell corner
    const double cellArea = (0.2 / 3) * (0.1 / 2);
    for (size_t i = 0; i < st.size(); ++i)
        if (st.x0()[i] == Vec3(0, 0, 0.3)) CHECK(rest[i][2] == Approx(-1000 * cellArea / 4).epsilon(1e-12));
    const Mat3 F = someF();
    const Mat3 cof = F.determinant() * F.inverse().transpose();
    for (size_t i = 0; i < st.size(); ++i) st.x()[i] = F * st.x0()[i] + Vec3(0.5, 0.1, -0.2);
    const Positions f = forces(*sim, "p", 0.0);
    const Vec3 expectedTotal = -1000 * 0.2 * 0.1 * cof * Vec3::UnitZ();
    CHECK((sum(f) - expectedTotal).norm() < 1e-12 * expectedTotal.norm());
    for (size_t i = 0; i < st.size(); ++i) {
        INFO("node " << i);
        CHECK((f[i] - cof * rest[i]).norm() < 1e-12);
    }
}
