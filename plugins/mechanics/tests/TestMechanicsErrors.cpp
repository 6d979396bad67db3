// Mechanics input errors at scene level: each one located at its element's line, with the whole message.
#include "fascia/sim/Simulation.h"

#include <catch2/catch.hpp>

#include <string>

using fascia::core::Error;
using fascia::core::Simulation;
using Catch::Matchers::Contains;

namespace {

std::string errorOf(const std::string& xml) {
    try {
        Simulation::fromString(xml, "scene.xml");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

/// A 2 x 2 x 2 node grid (named faces xmin ... zmax), lines 1-5, then `extra` from line 6.
std::string grid(const std::string& extra, const std::string& state = "<MechanicalObject name=\"mo\"/>") {
    return "<Node name=\"root\" dt=\"0.001\">\n"
           "  <GridMesh name=\"grid\" resolution=\"1 1 1\"/>\n"
           "  " + state + "\n"
           "  <LumpedMass name=\"mass\" density=\"1000\"/>\n"
           "  <SemiImplicitEuler/>\n"
           "  " + extra + "\n"
           "</Node>\n";
}

/// Three free points without a mesh, lines 1-3, then `extra` from line 4.
std::string cloud(const std::string& extra) {
    return "<Node name=\"root\" dt=\"0.001\">\n"
           "  <MechanicalObject name=\"mo\" position=\"0 0 0  1 0 0  0 1 0\"/>\n"
           "  <SemiImplicitEuler/>\n"
           "  " + extra + "\n"
           "</Node>\n";
}

} // namespace

TEST_CASE("ConstantForce input errors are located", "[ConstantForce]") {
    CHECK_THAT(errorOf(grid("<ConstantForce name=\"load\" group=\"zmax\"/>")),
               Contains("scene.xml:6: error: ConstantForce 'load': give force (per node) or totalForce"));
    CHECK_THAT(errorOf(grid("<ConstantForce name=\"load\" indices=\"\" force=\"1 0 0\"/>")),
               Contains("scene.xml:6: error: ConstantForce 'load': selects no node"));
}

TEST_CASE("LumpedMass input errors are located", "[LumpedMass]") {
    SECTION("neither density nor total mass") {
        CHECK_THAT(errorOf(cloud("<LumpedMass name=\"m\"/>")),
                   Contains("scene.xml:4: error: LumpedMass 'm': give density (kg/m^3) or totalMass (kg)"));
    }
    SECTION("a density without volume elements") {
        CHECK_THAT(errorOf(cloud("<LumpedMass name=\"m\" density=\"1000\"/>")),
                   Contains("scene.xml:4: error: LumpedMass 'm': density needs volume elements, but no mesh with "
                            "tetrahedra or hexahedra is in the context; give totalMass instead"));
    }
    SECTION("a mesh of another size than the state") {
        CHECK_THAT(errorOf(grid("", "<MechanicalObject name=\"mo\" position=\"0 0 0  1 0 0  0 1 0\"/>")),
                   Contains("scene.xml:4: error: LumpedMass 'mass': the mesh source 'grid' has 8 points but the state "
                            "'mo' has 3 nodes"));
    }
}

TEST_CASE("MechanicalObject input errors are located", "[MechanicalObject]") {
    CHECK_THAT(errorOf("<Node name=\"root\" dt=\"0.001\">\n  <MechanicalObject name=\"mo\"/>\n</Node>\n"),
               Contains("scene.xml:2: error: MechanicalObject 'mo': no positions: set position="));
    CHECK_THAT(errorOf("<Node name=\"root\" dt=\"0.001\">\n  <MechanicalObject name=\"mo\" position=\"\"/>\n</Node>\n"),
               Contains("scene.xml:2: error: MechanicalObject 'mo': has no nodes"));
}

TEST_CASE("node selections report conflicting, missing and unknown groups", "[FixedConstraint][ConstantForce]") {
    SECTION("indices and group together") {
        CHECK_THAT(errorOf(grid("<FixedConstraint name=\"fix\" indices=\"0\" group=\"zmin\"/>")),
                   Contains("scene.xml:6: error: FixedConstraint 'fix': give indices or group, not both"));
    }
    SECTION("a group without a mesh source") {
        CHECK_THAT(errorOf(cloud("<LumpedMass totalMass=\"1\"/>\n  <FixedConstraint name=\"fix\" group=\"zmin\"/>")),
                   Contains("scene.xml:5: error: FixedConstraint 'fix': group = \"zmin\" but no mesh source (MeshLoader, "
                            "GridMesh) is in the context"));
    }
    SECTION("an unknown group, with the close name and the list") {
        const std::string e = errorOf(grid("<ConstantForce name=\"load\" group=\"zmx\" force=\"1 0 0\"/>"));
        CHECK_THAT(e, Contains("scene.xml:6: error: ConstantForce 'load': no node group 'zmx'"));
        CHECK_THAT(e, Contains("did you mean 'zmax'?") && Contains("groups of 'grid': xmax, xmin, ymax, ymin, zmax, zmin"));
    }
    SECTION("an axis mask that selects no axis") {
        CHECK_THAT(errorOf(grid("<FixedConstraint name=\"fix\" group=\"zmin\" directions=\"0 0 0\"/>")),
                   Contains("scene.xml:6: error: FixedConstraint 'fix': directions = \"0 0 0\" selects no axis"));
    }
    SECTION("a group of nodes past the state's end") {
        // the grid's 8 nodes, but a state of 3 nodes (no mass, which would complain first)
        CHECK_THAT(errorOf("<Node name=\"root\" dt=\"0.001\">\n  <GridMesh name=\"grid\" resolution=\"1 1 1\"/>\n"
                           "  <MechanicalObject name=\"mo\" position=\"0 0 0  1 0 0  0 1 0\"/>\n"
                           "  <FixedConstraint name=\"fix\" group=\"zmax\"/>\n</Node>\n"),
                   Contains("scene.xml:4: error: FixedConstraint 'fix': node index 7 is out of range: the state 'mo' has 3 nodes"));
    }
}

TEST_CASE("SurfacePressure refuses a mesh of another size than its state", "[SurfacePressure]") {
    CHECK_THAT(errorOf("<Node name=\"root\" dt=\"0.001\">\n  <GridMesh name=\"grid\" resolution=\"1 1 1\"/>\n"
                       "  <MechanicalObject name=\"mo\" position=\"0 0 0  1 0 0  0 1 0\"/>\n"
                       "  <SurfacePressure name=\"p\" pressure=\"1\"/>\n</Node>\n"),
               Contains("scene.xml:4: error: SurfacePressure 'p': the mesh source 'grid' has 8 points but the state 'mo' has 3 nodes"));
}

TEST_CASE("DynamicRelaxation refuses tolerances outside (0, 1) and maxIterations below 1 at their line",
          "[DynamicRelaxation]") {
    const auto [attr, text] = GENERATE(table<std::string, std::string>({
        {"tolerance=\"0\"", "scene.xml:6: error: DynamicRelaxation 'dr': tolerance = 0 is outside (0, 1)"},
        {"tolerance=\"1\"", "scene.xml:6: error: DynamicRelaxation 'dr': tolerance = 1 is outside (0, 1)"},
        {"displacementTolerance=\"-1e-6\"", "scene.xml:6: error: DynamicRelaxation 'dr': displacementTolerance = -1e-06 is outside (0, 1)"},
        {"maxIterations=\"0\"", "scene.xml:6: error: DynamicRelaxation 'dr': maxIterations = 0 is"},
        {"damping=\"10\"", "scene.xml:6: error: DynamicRelaxation 'dr': unknown attribute 'damping'"}}));
    CAPTURE(attr);
    std::string xml = grid("<DynamicRelaxation name=\"dr\" " + attr + "/>");
    xml.replace(xml.find("<SemiImplicitEuler/>"), 20, "");
    CHECK_THAT(errorOf(xml), Contains(text));
}

TEST_CASE("DynamicRelaxation on a state with no elastic force field is a simulation error naming it",
          "[DynamicRelaxation]") {
    // a point cloud under gravity: nothing holds it, no static solution exists
    auto sim = Simulation::fromString("<Node name=\"root\" dt=\"1\" gravity=\"0 0 -9.81\">\n"
                                      "  <MechanicalObject name=\"mo\" position=\"0 0 0  1 0 0\"/>\n"
                                      "  <LumpedMass totalMass=\"2\"/>\n"
                                      "  <DynamicRelaxation name=\"dr\"/>\n"
                                      "</Node>\n",
                                      "scene.xml");
    try {
        sim->step();
        FAIL("no error");
    } catch (const Error& e) {
        CHECK(e.kind() == fascia::core::ErrorKind::Simulation);
        CHECK_THAT(e.what(), Contains("[/root/dr] step 1: the state 'mo' shows no stiffness"));
    }
}

TEST_CASE("A FixedConstraint and a PrescribedDisplacement on one node and axis are a located error naming both",
          "[FixedConstraint][PrescribedDisplacement]") {
    // grid(): faces zmin (nodes 0-3) and xmin (nodes 0 2 4 6) share nodes 0 and 2
    SECTION("the same face, all axes") {
        CHECK_THAT(errorOf(grid("<FixedConstraint name=\"base\" group=\"zmin\"/>\n"
                                "  <PrescribedDisplacement name=\"pull\" group=\"zmin\" displacement=\"0 0 0.01\"/>")),
                   Contains("scene.xml:7: error: PrescribedDisplacement 'pull': node 0 axis x is also constrained by "
                            "FixedConstraint '/root/base' (scene.xml:6), and this one prescribes its motion") &&
                       Contains("note: remove the node from one of them, or let them hold different axes"));
    }
    SECTION("the fixed one second, on a shared edge and one axis") {
        CHECK_THAT(errorOf(grid("<PrescribedDisplacement name=\"pull\" group=\"xmin\" displacement=\"0 0 0.01\" directions=\"0 0 1\"/>\n"
                                "  <FixedConstraint name=\"base\" group=\"zmin\" directions=\"0 0 1\"/>")),
                   Contains("scene.xml:7: error: FixedConstraint 'base': node 0 axis z is also constrained by "
                            "PrescribedDisplacement '/root/pull' (scene.xml:6), and that one prescribes its motion"));
    }
    SECTION("two prescribed displacements") {
        CHECK_THAT(errorOf(grid("<PrescribedDisplacement name=\"a\" indices=\"5\" displacement=\"0.01 0 0\"/>\n"
                                "  <PrescribedDisplacement name=\"b\" indices=\"7 5\" displacement=\"0 0.01 0\"/>")),
                   Contains("scene.xml:7: error: PrescribedDisplacement 'b': node 5 axis x is also constrained by "
                            "PrescribedDisplacement '/root/a'"));
    }
}

TEST_CASE("Constraints on different axes of one node, or holding it at rest together, still run", "[FixedConstraint][PrescribedDisplacement]") {
    // z held on the base, the pulled face (xmax, which shares nodes 1 3 with zmin) moved along x only
    auto sim = Simulation::fromString(grid("<FixedConstraint name=\"base\" group=\"zmin\" directions=\"0 0 1\"/>\n"
                                           "  <FixedConstraint name=\"side\" group=\"xmin\"/>\n"
                                           "  <PrescribedDisplacement name=\"pull\" group=\"xmax\" displacement=\"0.01 0 0\" "
                                           "directions=\"1 0 0\" shape=\"step\"/>"),
                                      "scene.xml");
    sim->step();
    auto& s = sim->state("mo");
    // node 1 (xmax, zmin): x follows the prescribed displacement, z stays held; node 0 (xmin, zmin) is
    // held by two FixedConstraints in z (they agree)
    CHECK(s.x()[1].x() == Approx(s.x0()[1].x() + 0.01).epsilon(1e-14));
    CHECK(s.x()[1].z() == s.x0()[1].z());
    CHECK(s.x()[0] == s.x0()[0]);
}
