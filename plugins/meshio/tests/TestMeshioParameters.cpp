// The parameters of Monitor, VTKExporter, BoxROI and MeshLoader, each checked by its effect, and the
// meshio components' input errors at scene level.
#include "MeshLoader.h"
#include "fascia/sim/Simulation.h"

#include <catch2/catch.hpp>

#include <Eigen/Dense>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <fstream>
#include <iostream>
#include <sstream>
#include <unistd.h>

using fascia::Mat3;
using fascia::Positions;
using fascia::Vec3;
using fascia::core::Error;
using fascia::core::Simulation;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

fs::path freshDir(const std::string& name) {
    fs::path d = fs::temp_directory_path() / ("fascia-meshio-par-" + name + "-" + std::to_string(getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

std::string slurp(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

std::vector<std::string> split(const std::string& line) {
    std::vector<std::string> out;
    std::istringstream in(line);
    for (std::string c; std::getline(in, c, ',');) out.push_back(c);
    return out;
}

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);) out.push_back(l);
    return out;
}

std::string errorIn(const std::string& xml, const fs::path& dir) {
    try {
        Simulation::fromString(xml, "scene.xml", ".", {dir.string(), 0});
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

struct CaptureCerr {
    std::ostringstream out;
    std::streambuf* old = std::cerr.rdbuf(out.rdbuf());
    ~CaptureCerr() { std::cerr.rdbuf(old); }
};

/// A HEML-elastic bar fixed at xmin and sagging under gravity (lines 1-8), `extra` from line 9.
std::string elasticBar(const std::string& extra) {
    return "<Node name=\"root\" dt=\"0.001\" gravity=\"0 0 -9.81\">\n"
           "  <GridMesh name=\"grid\" min=\"0 0 0\" max=\"0.2 0.1 0.1\" resolution=\"3 2 2\" element=\"tetrahedra6\"/>\n"
           "  <MechanicalObject name=\"state\"/>\n"
           "  <LumpedMass density=\"1000\"/>\n"
           "  <NeoHookean youngModulus=\"3000\" poissonRatio=\"0.45\"/>\n"
           "  <HEMLForceField name=\"ff\"/>\n"
           "  <SemiImplicitEuler/>\n"
           "  <FixedConstraint name=\"base\" group=\"xmin\"/>\n"
           "  " + extra + "\n"
           "</Node>\n";
}

/// Two states: a at rest (8 nodes), b moving at 1 m/s along x (27 nodes); `inA` goes into node a.
std::string twoStates(const std::string& inA, const std::string& inB = "") {
    return "<Node name=\"root\" dt=\"0.01\">\n"
           "  <Node name=\"a\">\n"
           "    <GridMesh name=\"ga\" resolution=\"1 1 1\"/>\n    <MechanicalObject name=\"sa\"/>\n"
           "    <LumpedMass totalMass=\"1\"/>\n    <SemiImplicitEuler/>\n"
           "    " + inA + "\n"
           "  </Node>\n"
           "  <Node name=\"b\">\n"
           "    <GridMesh name=\"gb\" min=\"0 0 0\" max=\"1 1 1\" resolution=\"2 2 2\"/>\n"
           "    <MechanicalObject name=\"sb\" initialVelocity=\"1 0 0\"/>\n"
           "    <LumpedMass totalMass=\"1\"/>\n    <SemiImplicitEuler/>\n"
           "    " + inB + "\n"
           "  </Node>\n"
           "</Node>\n";
}

/// J of tetrahedron e: the volume ratio, from the mesh and the state (independent of the force field).
double volumeRatio(const fascia::MeshData& mesh, const fascia::core::BaseMechanicalState& st, int e) {
    const auto& t = mesh.tetrahedra[size_t(e)];
    Mat3 V, v;
    for (int k = 0; k < 3; ++k) {
        V.col(k) = st.x0()[t[k + 1]] - st.x0()[t[0]];
        v.col(k) = st.x()[t[k + 1]] - st.x()[t[0]];
    }
    return v.determinant() / V.determinant();
}

vtkUnstructuredGrid* readVtu(vtkXMLUnstructuredGridReader* reader, const fs::path& p) {
    REQUIRE(fs::exists(p));
    reader->SetFileName(p.string().c_str());
    reader->Update();
    return reader->GetOutput();
}

} // namespace

TEST_CASE("Monitor records positions, velocities, reactions and element quantities of an elastic body every N steps",
          "[Monitor]") {
    auto dir = freshDir("monitor");
    auto sim = Simulation::fromString(elasticBar("<Monitor name=\"mon\" indices=\"5 11\" positions=\"true\" displacements=\"false\" "
                                                 "velocities=\"true\" reactionOf=\"@base\" elements=\"3 40\" elementFields=\"J\" every=\"3\"/>"),
                                      "scene.xml", ".", {dir.string(), 0});
    auto& st = sim->state("state");
    const auto& mesh = dynamic_cast<fascia::core::BaseTopology*>(sim->find("grid"))->meshData();
    const auto& base = mesh.nodeGroups.at("xmin");
    // the expected rows, taken from the state after each recorded step (the initial state is step 0)
    std::vector<std::vector<double>> expected;
    auto record = [&] {
        std::vector<double> r{sim->time()};
        for (int i : {5, 11}) {
            for (int a = 0; a < 3; ++a) r.push_back(st.x()[i][a]);
            for (int a = 0; a < 3; ++a) r.push_back(st.v()[i][a]);
        }
        Vec3 reaction = Vec3::Zero();
        for (int i : base) reaction += st.reaction()[i];
        for (int a = 0; a < 3; ++a) r.push_back(reaction[a]);
        for (int e : {3, 40}) r.push_back(volumeRatio(mesh, st, e));
        expected.push_back(r);
    };
    record();
    for (int n = 1; n <= 31; ++n) {
        sim->step();
        if (n % 3 == 0) record();
    }
    record();  // the final state (step 31), which finish() records whatever every
    sim->finish();
    const auto rows = lines(slurp(dir / "mon.csv"));
    REQUIRE(rows.size() == 1 + 12);  // header, steps 0 3 ... 30, 31
    CHECK(rows[0] == "time [s],x5_x [m],x5_y [m],x5_z [m],v5_x [m/s],v5_y [m/s],v5_z [m/s],"
                     "x11_x [m],x11_y [m],x11_z [m],v11_x [m/s],v11_y [m/s],v11_z [m/s],"
                     "reaction_x [N],reaction_y [N],reaction_z [N],J[3] [-],J[40] [-]");
    for (size_t r = 0; r < expected.size(); ++r) {
        const auto cells = split(rows[r + 1]);
        REQUIRE(cells.size() == expected[r].size());
        for (size_t c = 0; c < cells.size(); ++c) {
            INFO("row " << r + 1 << ", column " << c);
            CHECK(std::stod(cells[c]) == Approx(expected[r][c]).epsilon(1e-10).margin(1e-13));
        }
    }
    // the body has moved and deformed: the checks above compare non-trivial values
    CHECK(std::abs(expected.back()[15]) > 1e-3);      // the support carries the elastic forces
    CHECK(std::abs(expected.back()[16] - 1) > 1e-7);  // J of element 3 is no longer 1 (far above the 1e-10 above)
}

TEST_CASE("Monitor records the element quantities of the force field it links to, not of the first one",
          "[Monitor]") {
    auto dir = freshDir("monitor-ff");
    // two HEML force fields on one state, b ten times stiffer than a at the same Poisson's ratio:
    // at any state b's von Mises stress is exactly 10 times a's (the neo-Hookean stress is linear in
    // mu and kappa at fixed nu)
    const std::string xml =
        "<Node name=\"root\" dt=\"0.0005\" gravity=\"0 0 -9.81\">\n"
        "  <GridMesh name=\"grid\" min=\"0 0 0\" max=\"0.2 0.1 0.1\" resolution=\"3 2 2\" element=\"tetrahedra6\"/>\n"
        "  <MechanicalObject name=\"state\"/>\n"
        "  <LumpedMass density=\"1000\"/>\n"
        "  <NeoHookean name=\"soft\" youngModulus=\"3000\" poissonRatio=\"0.45\"/>\n"
        "  <NeoHookean name=\"stiff\" youngModulus=\"30000\" poissonRatio=\"0.45\"/>\n"
        "  <HEMLForceField name=\"a\" material=\"@soft\"/>\n"
        "  <HEMLForceField name=\"b\" material=\"@stiff\"/>\n"
        "  <SemiImplicitEuler/>\n"
        "  <FixedConstraint name=\"base\" group=\"xmin\"/>\n"
        "  <Monitor name=\"ofB\" forceField=\"@b\" elements=\"3 40\" elementFields=\"vonMises\" displacements=\"false\"/>\n"
        "  <Monitor name=\"ofA\" forceField=\"@a\" elements=\"3 40\" elementFields=\"vonMises\" displacements=\"false\"/>\n"
        "  <Monitor name=\"first\" elements=\"3 40\" elementFields=\"vonMises\" displacements=\"false\"/>\n"
        "</Node>\n";
    auto sim = Simulation::fromString(xml, "scene.xml", ".", {dir.string(), 0});
    sim->run(20);
    auto& st = sim->state("state");
    auto vonMises = [&](const char* ff) {
        std::vector<fascia::core::CellField> fields;
        dynamic_cast<fascia::core::BaseForceField*>(sim->find(ff))->cellData(st, fields);
        for (auto& f : fields)
            if (f.name == "vonMises") return f.values;
        FAIL("no vonMises from " << ff);
        return std::vector<double>{};
    };
    const auto a = vonMises("a"), b = vonMises("b");
    sim->finish();
    auto lastRow = [&](const char* file) {
        const auto rows = lines(slurp(dir / file));
        REQUIRE(rows.size() == 1 + 21);
        CHECK(rows[0] == "time [s],vonMises[3] [Pa],vonMises[40] [Pa]");
        const auto cells = split(rows.back());
        REQUIRE(cells.size() == 3);
        return std::vector<double>{std::stod(cells[1]), std::stod(cells[2])};
    };
    const auto ofB = lastRow("ofB.csv"), ofA = lastRow("ofA.csv"), first = lastRow("first.csv");
    for (int k = 0; k < 2; ++k) {
        const size_t e = k == 0 ? 3 : 40;
        INFO("element " << e);
        REQUIRE(a[e] > 1e-3);  // the body is stressed
        CHECK(b[e] == Approx(10 * a[e]).epsilon(1e-10));
        CHECK(ofB[size_t(k)] == Approx(b[e]).epsilon(1e-10));
        CHECK(ofA[size_t(k)] == Approx(a[e]).epsilon(1e-10));
        CHECK(first[size_t(k)] == Approx(a[e]).epsilon(1e-10));  // the default: the first element force field
    }
}

namespace {

/// One node of `twinScenes`: a state, a material and the force fields in `ffs`.
std::string mechanicsNode(const std::string& name, const std::string& state, const std::string& ffs) {
    return "  <Node name=\"" + name + "\">\n    " + state + "\n"
           "    <NeoHookean youngModulus=\"3000\" poissonRatio=\"0.45\"/>\n    " + ffs + "\n  </Node>\n";
}

/// The forces of every force field in `ffs` at the same deformed state, 3 numbers per node.
Positions forcesAt(Simulation& sim, const std::string& state, const std::vector<std::string>& ffs, const std::string& ff) {
    auto& st = sim.state(state);
    const Mat3 F = (Mat3() << 1.05, 0.02, -0.01, 0.0, 0.97, 0.03, 0.01, -0.02, 1.02).finished();
    for (size_t i = 0; i < st.size(); ++i) st.x()[i] = F * st.x0()[i] + 0.001 * Vec3(std::sin(3.0 * i), std::cos(5.0 * i), 0);
    Positions f(st.size(), Vec3::Zero());
    REQUIRE(std::find(ffs.begin(), ffs.end(), ff) != ffs.end());
    auto* field = dynamic_cast<fascia::core::BaseForceField*>(sim.find(ff));
    REQUIRE(field);
    field->addForce(st, f, 0);
    return f;
}

double maxDiff(const Positions& a, const Positions& b) {
    REQUIRE(a.size() == b.size());
    double d = 0;
    for (size_t i = 0; i < a.size(); ++i) d = std::max(d, (a[i] - b[i]).norm());
    return d;
}

double maxNorm(const Positions& a) {
    double d = 0;
    for (const auto& v : a) d = std::max(d, v.norm());
    return d;
}

} // namespace

TEST_CASE("MeshLoader's positions, tetrahedra, hexahedra and mesh outputs linked into the state and the force fields give "
          "the forces of the implicit mesh source",
          "[MeshLoader]") {
    const std::string dir = std::string(FASCIA_SOURCE_DIR);
    const std::string organ = dir + "/scenes/meshes/organ_2428.msh", hex = dir + "/plugins/meshio/tests/data/hex2.msh";
    // "src" holds the loaders and nothing else, and no mesh source is in the context of "linked":
    // what its components get comes through the links only (without them their init fails)
    const std::string xml =
        "<Node name=\"root\" dt=\"1e-5\">\n"
        "  <Node name=\"src\">\n"
        "    <MeshLoader name=\"loader\" filename=\"" + organ + "\"/>\n"
        "    <MeshLoader name=\"hexLoader\" filename=\"" + hex + "\" scale=\"0.1\"/>\n"
        "  </Node>\n" +
        mechanicsNode("implicit", "<MeshLoader name=\"own\" filename=\"" + organ + "\"/>\n    <MechanicalObject name=\"si\"/>",
                      "<HEMLForceField name=\"hi\"/>\n    <TLEDForceField name=\"ti\"/>") +
        mechanicsNode("linked", "<MechanicalObject name=\"sl\" position=\"@/root/src/loader.positions\"/>",
                      "<HEMLForceField name=\"hTets\" tetrahedra=\"@/root/src/loader.tetrahedra\"/>\n"
                      "    <HEMLForceField name=\"hMesh\" mesh=\"@/root/src/loader.mesh\"/>\n"
                      "    <TLEDForceField name=\"tTets\" tetrahedra=\"@/root/src/loader.tetrahedra\"/>\n"
                      "    <TLEDForceField name=\"tMesh\" mesh=\"@/root/src/loader.mesh\"/>") +
        mechanicsNode("hexImplicit", "<MeshLoader name=\"ownHex\" filename=\"" + hex + "\" scale=\"0.1\"/>\n    <MechanicalObject name=\"hi8\"/>",
                      "<TLEDForceField name=\"th\"/>") +
        mechanicsNode("hexLinked", "<MechanicalObject name=\"hl8\" position=\"@/root/src/hexLoader.positions\"/>",
                      "<TLEDForceField name=\"thLinked\" hexahedra=\"@/root/src/hexLoader.hexahedra\"/>") +
        "</Node>\n";
    CaptureCerr quiet;  // no integrator and no mass: "it will not move" warnings; the forces are asked for directly
    auto sim = Simulation::fromString(xml, "scene.xml");
    auto& si = sim->state("si");
    auto& sl = sim->state("sl");
    REQUIRE(sl.size() == 621);
    for (size_t i = 0; i < si.size(); ++i) REQUIRE(sl.x0()[i] == si.x0()[i]);
    const std::vector<std::string> tets{"hi", "ti", "hTets", "hMesh", "tTets", "tMesh"};
    const Positions hemlRef = forcesAt(*sim, "si", tets, "hi"), tledRef = forcesAt(*sim, "si", tets, "ti");
    REQUIRE(maxNorm(hemlRef) > 1e-6);
    for (const char* ff : {"hTets", "hMesh"}) {
        INFO(ff);
        CHECK(maxDiff(forcesAt(*sim, "sl", tets, ff), hemlRef) <= 1e-12 * maxNorm(hemlRef));
    }
    for (const char* ff : {"tTets", "tMesh"}) {
        INFO(ff);
        CHECK(maxDiff(forcesAt(*sim, "sl", tets, ff), tledRef) <= 1e-12 * maxNorm(tledRef));
    }
    auto& hexState = sim->state("hl8");
    REQUIRE(hexState.size() == 12);
    const std::vector<std::string> hexes{"th", "thLinked"};
    const Positions hexRef = forcesAt(*sim, "hi8", hexes, "th");
    REQUIRE(maxNorm(hexRef) > 1e-9);
    CHECK(dynamic_cast<fascia::core::BaseForceField*>(sim->find("thLinked"))->elementCount() == 2);
    CHECK(maxDiff(forcesAt(*sim, "hl8", hexes, "thLinked"), hexRef) <= 1e-12 * maxNorm(hexRef));
}

namespace {

/// The triangles output of mesh source `name`, read by name as a linking component would.
fascia::Triangles trianglesOf(Simulation& sim, const std::string& name) {
    auto* c = sim.find(name);
    REQUIRE(c);
    auto* p = dynamic_cast<fascia::core::Param<fascia::Triangles>*>(c->findParam("triangles"));
    REQUIRE(p);
    return p->get();
}

/// sum of the area-weighted normals (zero for a closed surface) and the enclosed volume by the
/// divergence theorem, V = sum over triangles of x0 . (n A) / 3 (positive when turned outwards)
std::pair<Vec3, double> surfaceSums(const Positions& x, const fascia::Triangles& tris) {
    Vec3 n = Vec3::Zero();
    double v = 0;
    for (const auto& t : tris) {
        const Vec3 a = 0.5 * (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]);
        n += a;
        v += x[t[0]].dot(a) / 3;
    }
    return {n, v};
}

double tetVolume(const Positions& x, const std::array<int, 4>& t) {
    return (x[t[1]] - x[t[0]]).dot((x[t[2]] - x[t[0]]).cross(x[t[3]] - x[t[0]])) / 6;
}

} // namespace

TEST_CASE("GridMesh's triangles output is its boundary, two triangles per face square, turned outwards", "[GridMesh]") {
    const std::string element = GENERATE(as<std::string>{}, "tetrahedra6", "tetrahedra5", "hexahedra");
    CAPTURE(element);
    auto sim = Simulation::fromString("<Node name=\"root\">\n"
                                      "  <GridMesh name=\"grid\" min=\"-0.1 0 0.2\" max=\"0.3 0.1 0.5\" resolution=\"4 2 3\" element=\"" +
                                      element + "\"/>\n</Node>\n");
    const auto tris = trianglesOf(*sim, "grid");
    const auto& mesh = dynamic_cast<fascia::core::BaseTopology*>(sim->find("grid"))->meshData();
    CHECK(tris.size() == size_t(4 * (4 * 2 + 2 * 3 + 3 * 4)));
    const Vec3 lo(-0.1, 0, 0.2), hi(0.3, 0.1, 0.5), centre = (lo + hi) / 2;
    std::set<std::array<int, 3>> seen;
    for (const auto& t : tris) {
        std::array<int, 3> key = t;
        std::sort(key.begin(), key.end());
        CHECK(seen.insert(key).second);  // no triangle twice
        const Vec3 a = mesh.points[t[0]], b = mesh.points[t[1]], c = mesh.points[t[2]];
        const Vec3 n = (b - a).cross(c - a);
        REQUIRE(n.norm() > 0);
        // on one face of the box (one coordinate equal to a bound at its three corners), with the
        // normal along that face's outward axis
        int onFace = 0;
        for (int ax = 0; ax < 3; ++ax)
            for (double bound : {lo[ax], hi[ax]})
                if (a[ax] == bound && b[ax] == bound && c[ax] == bound) {
                    ++onFace;
                    CHECK(std::abs(n[ax]) == Approx(n.norm()).epsilon(1e-12));
                    CHECK(n[ax] * (bound - centre[ax]) > 0);
                }
        CHECK(onFace == 1);
    }
    const auto [nsum, volume] = surfaceSums(mesh.points, tris);
    CHECK(nsum.norm() < 1e-15);
    CHECK(volume == Approx(0.4 * 0.1 * 0.3).epsilon(1e-12));
    CHECK(mesh.triangleGroup == std::vector<int>(tris.size(), 0));
}

TEST_CASE("MeshLoader's triangles output is the Gmsh file's boundary, turned outwards", "[MeshLoader]") {
    const std::string organ = std::string(FASCIA_SOURCE_DIR) + "/scenes/meshes/organ_2428.msh";
    auto sim = Simulation::fromString("<Node name=\"root\">\n  <MeshLoader name=\"loader\" filename=\"" + organ +
                                      "\" translation=\"0.5 -0.2 0.1\"/>\n</Node>\n");
    const auto tris = trianglesOf(*sim, "loader");
    const auto& mesh = dynamic_cast<fascia::core::BaseTopology*>(sim->find("loader"))->meshData();
    // physical surface 2 holds the 834 boundary triangles (scenes/meshes/README.md, and the file)
    REQUIRE(tris.size() == 834);
    // each triangle is the face of exactly one tetrahedron and turned away from its fourth node
    std::map<std::array<int, 3>, std::vector<int>> opposite;  // sorted face -> the fourth node of each tetrahedron
    double tetSum = 0;
    for (const auto& t : mesh.tetrahedra) {
        tetSum += tetVolume(mesh.points, t);
        for (int k = 0; k < 4; ++k) {
            std::array<int, 3> f{t[(k + 1) % 4], t[(k + 2) % 4], t[(k + 3) % 4]};
            std::sort(f.begin(), f.end());
            opposite[f].push_back(t[k]);
        }
    }
    for (const auto& t : tris) {
        std::array<int, 3> key = t;
        std::sort(key.begin(), key.end());
        const auto it = opposite.find(key);
        REQUIRE(it != opposite.end());
        CHECK(it->second.size() == 1);
        const Vec3 n = (mesh.points[t[1]] - mesh.points[t[0]]).cross(mesh.points[t[2]] - mesh.points[t[0]]);
        CHECK(n.dot(mesh.points[t[0]] - mesh.points[it->second[0]]) > 0);
    }
    size_t boundaryFaces = 0;
    for (const auto& [f, o] : opposite) boundaryFaces += o.size() == 1;
    CHECK(boundaryFaces == tris.size());  // the whole boundary
    // closed and outward: the normals sum to zero and the divergence theorem gives the tetrahedra's
    // volume (about 1.43e-3 m^3, scenes/meshes/README.md), translated or not
    const auto [nsum, volume] = surfaceSums(mesh.points, tris);
    CHECK(nsum.norm() < 1e-15);
    CHECK(tetSum == Approx(1.43e-3).epsilon(0.01));
    CHECK(volume == Approx(tetSum).epsilon(1e-12));
}

TEST_CASE("Monitor takes a node group, a file name and another node's state", "[Monitor]") {
    auto dir = freshDir("monitor-group");
    auto sim = Simulation::fromString(twoStates("<Monitor name=\"other\" state=\"@/root/b/sb\" indices=\"3\"/>",
                                                "<Monitor name=\"g\" group=\"xmax\" indices=\"0\" filename=\"sub/dir/g.csv\"/>"),
                                      "scene.xml", ".", {dir.string(), 0});
    sim->run(4);
    sim->finish();
    CHECK(!fs::exists(dir / "g.csv"));
    const auto rows = lines(slurp(dir / "sub/dir/g.csv"));
    REQUIRE(rows.size() == 1 + 5);
    // the group's nodes (in the mesh's order), then the extra index, displacements only (the default)
    const auto& gb = dynamic_cast<fascia::core::BaseTopology*>(sim->find("gb"))->meshData();
    std::vector<int> nodes = gb.nodeGroups.at("xmax");
    REQUIRE(nodes.size() == 9);
    nodes.push_back(0);
    std::string header = "time [s]";
    for (int i : nodes)
        for (const char* a : {"x", "y", "z"}) header += ",u" + std::to_string(i) + "_" + a + " [m]";
    CHECK(rows[0] == header);
    const auto last = split(rows.back());
    REQUIRE(last.size() == 1 + 3 * nodes.size());
    for (size_t k = 0; k < nodes.size(); ++k) CHECK(std::stod(last[1 + 3 * k]) == Approx(0.04).epsilon(1e-10));
    // state="@/root/b/sb" from node a: b's node 3 moves at 1 m/s, a's node 3 stays put
    const auto other = lines(slurp(dir / "other.csv"));
    REQUIRE(other.size() == 1 + 5);
    CHECK(split(other[0])[1] == "u3_x [m]");
    CHECK(std::stod(split(other.back())[1]) == Approx(0.04).epsilon(1e-10));
}

TEST_CASE("VTKExporter writes no cell data with cellData false, names its files by filename and writes a linked state",
          "[VTKExporter]") {
    auto dir = freshDir("vtk-params");
    vtkNew<vtkXMLUnstructuredGridReader> reader;
    SECTION("cellData") {
        auto sim = Simulation::fromString(elasticBar("<VTKExporter name=\"with\"/>\n  <VTKExporter name=\"without\" cellData=\"false\"/>"),
                                          "scene.xml", ".", {dir.string(), 0});
        sim->run(2);
        sim->finish();
        vtkUnstructuredGrid* with = readVtu(reader, dir / "with_000002.vtu");
        REQUIRE(with->GetNumberOfCells() == 12 * 6);
        vtkDataArray* J = with->GetCellData()->GetArray("J");
        REQUIRE(J);
        const auto& mesh = dynamic_cast<fascia::core::BaseTopology*>(sim->find("grid"))->meshData();
        CHECK(J->GetTuple1(7) == Approx(volumeRatio(mesh, sim->state("state"), 7)).epsilon(1e-12));
        vtkNew<vtkXMLUnstructuredGridReader> reader2;
        vtkUnstructuredGrid* without = readVtu(reader2, dir / "without_000002.vtu");
        CHECK(without->GetNumberOfCells() == 12 * 6);  // the cells are still written
        CHECK(without->GetCellData()->GetNumberOfArrays() == 0);
        CHECK(without->GetPointData()->GetArray("displacement"));
    }
    SECTION("filename and state") {
        auto sim = Simulation::fromString(twoStates("<VTKExporter name=\"out\" filename=\"series/moving\" state=\"@/root/b/sb\"/>"),
                                          "scene.xml", ".", {dir.string(), 0});
        sim->run(3);
        sim->finish();
        CHECK(!fs::exists(dir / "out.pvd"));
        CHECK_THAT(slurp(dir / "series/moving.pvd"), Contains("file=\"moving_000003.vtu\""));
        vtkUnstructuredGrid* g = readVtu(reader, dir / "series/moving_000003.vtu");
        auto& sb = sim->state("sb");
        REQUIRE(g->GetNumberOfPoints() == 27);
        vtkDataArray* u = g->GetPointData()->GetArray("displacement");
        REQUIRE(u);
        for (size_t i = 0; i < sb.size(); ++i) CHECK(u->GetComponent(vtkIdType(i), 0) == sb.x()[i][0] - sb.x0()[i][0]);
        CHECK(u->GetComponent(26, 0) == Approx(0.03).epsilon(1e-12));
    }
}

TEST_CASE("BoxROI lists the tetrahedra inside its box, and selects from given positions with the bounds included",
          "[BoxROI]") {
    SECTION("tetrahedronIndices") {
        auto sim = Simulation::fromString("<Node name=\"root\" dt=\"0.001\">\n"
                                          "  <GridMesh name=\"grid\" min=\"0 0 0\" max=\"0.3 0.3 0.3\" resolution=\"3 3 3\"/>\n"
                                          "  <BoxROI name=\"box\" box=\"0.05 -1 -1 0.25 1 0.25\"/>\n</Node>\n");
        auto* box = sim->find("box");
        const auto& tets = dynamic_cast<fascia::core::Param<fascia::IndexList>*>(box->findParam("tetrahedronIndices"))->get();
        const auto& hexes = dynamic_cast<fascia::core::Param<fascia::IndexList>*>(box->findParam("hexahedronIndices"))->get();
        const auto& mesh = dynamic_cast<fascia::core::BaseTopology*>(sim->find("grid"))->meshData();
        auto in = [](const Vec3& p) { return p[0] >= 0.05 && p[0] <= 0.25 && p[2] <= 0.25; };
        fascia::IndexList expected;
        for (size_t e = 0; e < mesh.tetrahedra.size(); ++e) {
            bool all = true;
            for (int n : mesh.tetrahedra[e]) all = all && in(mesh.points[n]);
            if (all) expected.push_back(int(e));
        }
        CHECK(expected.size() == 3 * 2 * 6);  // the cells x in [0.1, 0.2], z in [0, 0.2]: 3 x 2 of them
        CHECK(tets == expected);
        CHECK(hexes.empty());
    }
    SECTION("position") {
        auto sim = Simulation::fromString("<Node name=\"root\" dt=\"0.001\">\n"
                                          "  <GridMesh name=\"grid\" resolution=\"1 1 1\"/>\n"
                                          "  <BoxROI name=\"box\" box=\"0 0 0 1 2 3\" position=\"0 0 0  1 2 3  0.5 1 1.5  1.0001 1 1  0.5 -0.0001 1\"/>\n"
                                          "</Node>\n");
        auto* box = sim->find("box");
        CHECK(dynamic_cast<fascia::core::Param<fascia::IndexList>*>(box->findParam("indices"))->get() == fascia::IndexList{0, 1, 2});
        // the elements refer to the mesh's nodes, not to the given positions: none listed
        CHECK(dynamic_cast<fascia::core::Param<fascia::IndexList>*>(box->findParam("tetrahedronIndices"))->get().empty());
    }
}

TEST_CASE("MeshLoader fixOrientation from a scene flips inverted elements and says so", "[MeshLoader]") {
    auto dir = freshDir("inverted");
    // plugins/meshio/tests/data/cube_gmsh22.msh with the first two nodes of element 4 swapped
    std::string text = slurp(std::string(FASCIA_SOURCE_DIR) + "/plugins/meshio/tests/data/cube_gmsh22.msh");
    const std::string good = "4 4 2 1 1 10 20 40 50", bad = "4 4 2 1 1 20 10 40 50";
    REQUIRE(text.find(good) != std::string::npos);
    text.replace(text.find(good), good.size(), bad);
    const fs::path mesh = dir / "inverted.msh";
    std::ofstream(mesh) << text;
    auto scene = [&](const std::string& fix) {
        return "<Node name=\"root\" dt=\"0.001\">\n  <MeshLoader name=\"m\" filename=\"" + mesh.string() + "\"" + fix + "/>\n</Node>\n";
    };
    const std::string e = errorIn(scene(""), dir);
    CHECK_THAT(e, Contains("inverted") && Contains("fixOrientation") && Contains("read by MeshLoader 'm' at scene.xml:2"));
    CaptureCerr cap;
    auto sim = Simulation::fromString(scene(" fixOrientation=\"true\""), "scene.xml");
    auto* loader = dynamic_cast<fascia::meshio::MeshLoader*>(sim->find("m"));
    REQUIRE(loader);
    CHECK(loader->flippedElements() == 1);
    CHECK_THAT(cap.out.str(), Contains("scene.xml:2: warning: MeshLoader 'm': flipped 1 inverted element(s) of '" + mesh.string() + "'"));
    double total = 0;
    for (auto& t : loader->meshData().tetrahedra) {
        const auto& p = loader->meshData().points;
        const double v = (p[t[1]] - p[t[0]]).dot((p[t[2]] - p[t[0]]).cross(p[t[3]] - p[t[0]])) / 6;
        CHECK(v > 0);
        total += v;
    }
    CHECK(total == Approx(1.0).epsilon(1e-14));
}

TEST_CASE("Monitor, VTKExporter and BoxROI input errors are located", "[Monitor][VTKExporter][BoxROI]") {
    auto dir = freshDir("errors");
    SECTION("Monitor without a state") {
        CHECK_THAT(errorIn("<Node name=\"root\" dt=\"0.001\">\n  <Monitor name=\"mon\" indices=\"0\"/>\n</Node>\n", dir),
                   Contains("scene.xml:2: error: Monitor 'mon': no MechanicalObject in its context: put one in the same node "
                            "or link it with state=\"@...\""));
    }
    SECTION("Monitor group without a mesh source") {
        CHECK_THAT(errorIn("<Node name=\"root\" dt=\"0.001\">\n  <MechanicalObject name=\"mo\" position=\"0 0 0\"/>\n"
                           "  <Monitor name=\"mon\" group=\"top\"/>\n</Node>\n", dir),
                   Contains("scene.xml:3: error: Monitor 'mon': group = \"top\" but no mesh source is in the context"));
    }
    SECTION("Monitor unknown group") {
        CHECK_THAT(errorIn(elasticBar("<Monitor name=\"mon\" group=\"top\"/>"), dir),
                   Contains("scene.xml:9: error: Monitor 'mon': no node group 'top' in 'grid'"));
    }
    SECTION("Monitor toolPosition without a tool") {
        CHECK_THAT(errorIn(elasticBar("<Monitor name=\"mon\" indices=\"0\" toolPosition=\"true\"/>"), dir),
                   Contains("scene.xml:9: error: Monitor 'mon': toolPosition=\"true\" records a tool's position: give the tool too"));
    }
    SECTION("Monitor element out of range") {
        CHECK_THAT(errorIn(elasticBar("<Monitor name=\"mon\" indices=\"0\" elements=\"72\"/>"), dir),
                   Contains("scene.xml:9: error: Monitor 'mon': element index 72 is out of range: 'ff' has 72 elements"));
    }
    SECTION("Monitor unknown element quantity") {
        const std::string e = errorIn(elasticBar("<Monitor name=\"mon\" indices=\"0\" elements=\"1\" elementFields=\"J sigma\"/>"), dir);
        CHECK_THAT(e, Contains("scene.xml:9: error: Monitor 'mon': 'ff' offers no element quantity 'sigma'"));
        CHECK_THAT(e, Contains("it offers: J, vonMises"));
    }
    SECTION("Monitor file that cannot be written") {
        std::ofstream(dir / "blocker") << "a file, not a folder";
        CHECK_THAT(errorIn(elasticBar("<Monitor name=\"mon\" indices=\"0\" filename=\"blocker/m.csv\"/>"), dir),
                   Contains("scene.xml:9: error: Monitor 'mon': cannot write '"));
    }
    SECTION("VTKExporter file name that names a folder") {
        CHECK_THAT(errorIn(elasticBar("<VTKExporter name=\"out\" filename=\"series/\"/>"), dir),
                   Contains("scene.xml:9: error: VTKExporter 'out': filename must name files, e.g. \"liver\""));
    }
    SECTION("VTKExporter without a state") {
        CHECK_THAT(errorIn("<Node name=\"root\" dt=\"0.001\">\n  <VTKExporter name=\"out\"/>\n</Node>\n", dir),
                   Contains("scene.xml:2: error: VTKExporter 'out': no MechanicalObject in its context"));
    }
    SECTION("BoxROI without points") {
        CHECK_THAT(errorIn("<Node name=\"root\" dt=\"0.001\">\n  <BoxROI name=\"box\" box=\"0 0 0 1 1 1\"/>\n</Node>\n", dir),
                   Contains("scene.xml:2: error: BoxROI 'box': no points: set position or put a mesh source (MeshLoader, GridMesh) "
                            "in the context"));
    }
    SECTION("BoxROI that selects nothing warns") {
        CaptureCerr cap;
        Simulation::fromString("<Node name=\"root\" dt=\"0.001\">\n  <GridMesh resolution=\"1 1 1\"/>\n"
                               "  <BoxROI name=\"box\" box=\"2 2 2 3 3 3\"/>\n</Node>\n",
                               "scene.xml");
        CHECK_THAT(cap.out.str(), Contains("scene.xml:3: warning: BoxROI 'box': the box selects no node"));
    }
}
