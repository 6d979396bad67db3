// Tests of the mesh readers in a build without VTK (FASCIA_WITH_VTK=OFF; built only there): .vtu
// meshes are refused with a located error, the other formats (legacy .vtk included) still read.
#include <catch2/catch.hpp>

#include "MeshReaders.h"
#include "fascia/base/Error.h"

#include <string>

using namespace fascia;
using namespace fascia::meshio;

namespace {

const std::string kMeshes = FASCIA_SOURCE_DIR "/scenes/meshes/";
const std::string kData = FASCIA_SOURCE_DIR "/plugins/meshio/tests/data/";

/// Reading path throws an input error located in path (the whole file, line 0) whose message holds
/// every key; returns the message.
std::string requireInputError(const std::string& path, std::initializer_list<const char*> keys) {
    try {
        readMesh(path);
    } catch (const core::Error& e) {
        CHECK(e.kind() == core::ErrorKind::Input);
        CHECK(e.loc().file == path);
        CHECK(e.loc().line == 0);
        for (const char* k : keys) CHECK(e.message().find(k) != std::string::npos);
        return e.message();
    }
    FAIL("reading '" << path << "' did not throw");
    return {};
}

} // namespace

TEST_CASE("Without VTK a legacy .vtk mesh still reads, through our own legacy reader", "[MeshLoader]") {
    ReadReport report;
    const MeshData m = readMesh(kData + "cube.vtk", {}, &report);  // a unit cube in 5 tetrahedra, 2 triangles
    CHECK(report.format == "VTK legacy");
    CHECK(m.points.size() == 8);
    CHECK(m.tetrahedra.size() == 5);
    CHECK(m.triangles.size() == 2);
    CHECK(totalVolume(m) == Approx(1.0).epsilon(1e-14));
    CHECK(m.cellArrays.at("fibres").size() == 15);
}

TEST_CASE("Without VTK a .vtu mesh is refused with a located error", "[MeshLoader]") {
    requireInputError(kMeshes + "volumetricTongue.vtu",
                      {"this build has no VTK support: '", "volumetricTongue.vtu' is a VTK XML (.vtu) mesh"});
}

TEST_CASE("Without VTK a missing .vtk file is still reported as missing", "[MeshLoader]") {
    requireInputError(kData + "no_such_mesh.vtk", {"does not exist"});
}

TEST_CASE("Without VTK the Gmsh and TetGen readers still read their meshes", "[MeshLoader]") {
    ReadReport report;
    const MeshData gmsh = readMesh(kMeshes + "organ_2428.msh", {}, &report);
    CHECK(report.format == "Gmsh 2.2 ASCII");
    CHECK(gmsh.points.size() == 621);  // the counts of scenes/meshes/README.md
    CHECK(gmsh.tetrahedra.size() == 2421);
    CHECK(gmsh.triangles.size() == 834);
    const MeshData tetgen = readMesh(kData + "cube0.node", {}, &report);  // a unit cube in 6 tetrahedra
    CHECK(report.format == "TetGen");
    CHECK(tetgen.points.size() == 8);
    CHECK(tetgen.tetrahedra.size() == 6);
    CHECK(totalVolume(tetgen) == Approx(1.0).epsilon(1e-14));
}
