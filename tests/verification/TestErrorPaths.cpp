// Input errors of the force fields, materials and Prony series at scene level: each scene below
// triggers one check of a component's init, and the test asserts the whole located message
// (file:line: error: Class 'name': text), so that a check that no longer fires, fires at the wrong
// place or says something else fails here.
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

/// One grid cell (8 nodes, 6 tetrahedra or one hexahedron): the material on line 5, the force field
/// on line 6, `extra` on line 7.
std::string cell(const std::string& material, const std::string& forceField, const std::string& extra = "",
                 const std::string& element = "tetrahedra6") {
    return "<Node name=\"root\" dt=\"0.001\">\n"
           "  <GridMesh name=\"grid\" resolution=\"1 1 1\" element=\"" + element + "\"/>\n"
           "  <MechanicalObject name=\"state\"/>\n"
           "  <LumpedMass density=\"1000\"/>\n"
           "  " + material + "\n"
           "  " + forceField + "\n"
           "  " + extra + "\n"
           "  <SemiImplicitEuler/>\n"
           "</Node>\n";
}

const std::string kMat = "<NeoHookean name=\"mat\" youngModulus=\"3000\" poissonRatio=\"0.45\"/>";

/// The error of a scene with this material under a HEML force field, on line 5.
std::string materialError(const std::string& material) { return errorOf(cell(material, "<HEMLForceField name=\"ff\"/>")); }

} // namespace

TEST_CASE("HEMLForceField element and material errors are located at its line", "[HEMLForceField]") {
    const std::string at = "scene.xml:6: error: HEMLForceField 'ff': ";
    SECTION("both mesh and tetrahedra") {
        CHECK_THAT(errorOf(cell(kMat, "<HEMLForceField name=\"ff\" mesh=\"@grid.mesh\" tetrahedra=\"@grid.tetrahedra\"/>")),
                   Contains(at + "give the tetrahedra either by 'mesh' or by 'tetrahedra', not both"));
    }
    SECTION("a mesh of hexahedra") {
        CHECK_THAT(errorOf(cell(kMat, "<HEMLForceField name=\"ff\"/>", "", "hexahedra")), Contains(at + "the mesh has no tetrahedra"));
    }
    SECTION("a tetrahedron past the state's nodes") {
        CHECK_THAT(errorOf(cell(kMat, "<HEMLForceField name=\"ff\" tetrahedra=\"0 1 2 9\"/>")),
                   Contains(at + "tetrahedron 0 has node 9 but there are 8 nodes"));
    }
    SECTION("no material") {
        CHECK_THAT(errorOf(cell("", "<HEMLForceField name=\"ff\"/>")),
                   Contains(at + "no material: add one (e.g. <NeoHookean youngModulus=\"3000\" poissonRatio=\"0.45\"/>) to the "
                                 "node, set material=\"@name\", or give groupMaterials"));
    }
    SECTION("a stiffness together with a material") {
        CHECK_THAT(errorOf(cell(kMat, "<HEMLForceField name=\"ff\" stiffness=\"10\" material=\"@mat\"/>")),
                   Contains(at + "'stiffness' selects the mass-spring mode, which uses no material: remove "
                                 "'material'/'groupMaterials' or 'stiffness'"));
    }
    SECTION("a Prony series in mass-spring mode") {
        CHECK_THAT(errorOf(cell("", "<HEMLForceField name=\"ff\" stiffness=\"10\"/>", "<ViscoelasticProny alpha=\"0.5\" tau=\"0.1\"/>")),
                   Contains(at + "ViscoelasticProny is not supported in mass-spring mode"));
    }
    SECTION("a fibre array the mesh does not have") {
        CHECK_THAT(errorOf(cell("<TransverselyIsotropic mu=\"1000\" kappa=\"10000\" eta=\"500\"/>",
                                "<HEMLForceField name=\"ff\" fibreArray=\"fibres\"/>")),
                   Contains(at + "fibreArray = \"fibres\": the mesh has no such cell array (no cell array 'fibres')"));
    }
}

TEST_CASE("HEMLForceField groupMaterials errors are located at its line", "[HEMLForceField]") {
    const std::string at = "scene.xml:6: error: HEMLForceField 'ff': ";
    auto heml = [](const std::string& groups, const std::string& more = "") {
        return errorOf(cell(kMat, "<HEMLForceField name=\"ff\" groupMaterials=\"" + groups + "\"" + more + "/>"));
    };
    // one parser for HEML and TLED (fascia/elements/GroupMaterials.h): the same texts as the TLED case below
    CHECK_THAT(heml("1"), Contains(at + "groupMaterials = \"1\" is not a list of pairs: give pairs of a group (tag number or "
                                        "name) and a material path, e.g. \"1 @liver 2 @vessel\""));
    CHECK(heml("0 mat").empty());  // the '@' is optional (TLED's rule, which its tests assert)
    CHECK_THAT(heml("liver @mat"), Contains(at + "groupMaterials: 'liver' is neither a group tag nor a group name of the mesh"));
    CHECK_THAT(heml("0 @nope"), Contains(at + "groupMaterials: no component '@nope' for group 0"));
    CHECK_THAT(heml("0 @state"), Contains(at + "groupMaterials: '@state' (for group 0) is a MechanicalObject, not a material"));
    CHECK_THAT(heml("0 @mat 0 @mat"), Contains(at + "groupMaterials: group 0 is given twice"));
    CHECK_THAT(heml("5 @mat"), Contains(at + "no material for tetrahedron 0 of group 0: list the group in groupMaterials or set "
                                             "material=\"@...\""));
    // without a mesh every element is in group 0 (TLED's rule)
    CHECK(heml("0 @mat", " tetrahedra=\"@grid.tetrahedra\"").empty());
}

TEST_CASE("TLEDForceField element, material and Prony errors are located at its line", "[TLEDForceField]") {
    const std::string at = "scene.xml:6: error: TLEDForceField 'ff': ";
    auto tled = [](const std::string& attrs, const std::string& material = kMat, const std::string& extra = "") {
        return errorOf(cell(material, "<TLEDForceField name=\"ff\" " + attrs + "/>", extra));
    };
    CHECK_THAT(tled("mesh=\"@grid.mesh\" tetrahedra=\"@grid.tetrahedra\""),
               Contains(at + "both mesh and tetrahedra/hexahedra are given: give the elements one way"));
    CHECK_THAT(tled("tetrahedra=\"@grid.tetrahedra\" fibreArray=\"fibres\""),
               Contains(at + "'fibreArray' names a cell array of a mesh: give mesh=\"@loader.mesh\""));
    CHECK_THAT(tled("fibreArray=\"fibres\""), Contains(at + "fibreArray = \"fibres\": the mesh has no such cell array") &&
                                                 Contains("scene.xml:6: note: the mesh has no cell arrays"));
    CHECK_THAT(tled("tetrahedra=\"0 1 2 9\""), Contains(at + "elements use node 9 but the state 'state' has 8 nodes"));
    CHECK_THAT(tled("", ""), Contains(at + "no material: add one (e.g. <NeoHookean youngModulus=\"3000\" poissonRatio=\"0.45\"/>) "
                                           "to the node, set material=\"@name\", or give groupMaterials"));
    CHECK_THAT(tled("groupMaterials=\"1\""), Contains(at + "groupMaterials = \"1\" is not a list of pairs"));
    CHECK_THAT(tled("groupMaterials=\"0 @nope\""), Contains(at + "groupMaterials: no component '@nope' for group 0"));
    CHECK_THAT(tled("groupMaterials=\"0 @state\""),
               Contains(at + "groupMaterials: '@state' (for group 0) is a MechanicalObject, not a material"));
    CHECK_THAT(tled("groupMaterials=\"0 @mat 0 @mat\""), Contains(at + "groupMaterials: group 0 is given twice"));
    CHECK_THAT(tled("groupMaterials=\"5 @mat\""), Contains(at + "no material for tetrahedron 0 of group 0"));
    CHECK_THAT(tled("", kMat, "<ViscoelasticProny alpha=\"0.3\" tau=\"0.1\"/><ViscoelasticProny alpha=\"0.2\" tau=\"1\"/>"),
               Contains(at + "two ViscoelasticProny components in its node relax the same part of the stress"));
}

TEST_CASE("material parameter errors are located at the material's line", "[IncompressibleMooneyRivlin][CompressibleMooneyRivlin][NeoHookean]") {
    SECTION("Mooney-Rivlin with C1 + C2 <= 0") {
        CHECK_THAT(materialError("<IncompressibleMooneyRivlin name=\"mr\" C1=\"100\" C2=\"-100\"/>"),
                   Contains("scene.xml:5: error: IncompressibleMooneyRivlin 'mr': C1 + C2 must be positive (it is half the shear modulus)"));
        CHECK_THAT(materialError("<CompressibleMooneyRivlin name=\"mr\" C1=\"-50\" C2=\"20\" kappa=\"1000\"/>"),
                   Contains("scene.xml:5: error: CompressibleMooneyRivlin 'mr': C1 + C2 must be positive (it is half the shear modulus)"));
    }
    SECTION("moduli given two ways, or half given") {
        CHECK_THAT(materialError("<NeoHookean name=\"nh\" mu=\"1000\" kappa=\"5000\" youngModulus=\"3000\"/>"),
                   Contains("scene.xml:5: error: NeoHookean 'nh': 'youngModulus' is given together with 'mu'"));
        CHECK_THAT(materialError("<NeoHookean name=\"nh\" poissonRatio=\"0.3\"/>"),
                   Contains("scene.xml:5: error: NeoHookean 'nh': 'poissonRatio' is given without 'youngModulus'"));
        CHECK_THAT(materialError("<NeoHookean name=\"nh\" mu=\"1000\"/>"),
                   Contains("scene.xml:5: error: NeoHookean 'nh': 'mu' is given without 'kappa'"));
    }
    SECTION("a bulk modulus that is not positive") {
        CHECK_THAT(materialError("<CompressibleNeoHookean name=\"cnh\" mu=\"1000\" lambda=\"-1000\"/>"),
                   Contains("scene.xml:5: error: CompressibleNeoHookean 'cnh': lambda gives a non-positive bulk modulus "
                            "lambda + 2 mu/3; use lambda > -2 mu/3"));
        CHECK_THAT(materialError("<StVenantKirchhoff name=\"svk\" mu=\"1000\" lambda=\"-1000\"/>"),
                   Contains("scene.xml:5: error: StVenantKirchhoff 'svk': lambda = -1000") &&
                       Contains("gives a non-positive bulk modulus lambda + 2 mu/3; use lambda > -2 mu/3"));
    }
    SECTION("fibre directions") {
        CHECK_THAT(materialError("<TransverselyIsotropic name=\"ti\" mu=\"1000\" kappa=\"10000\" eta=\"500\" direction=\"0 0 0\"/>"),
                   Contains("scene.xml:5: error: TransverselyIsotropic 'ti': 'direction' must be a non-zero vector (it is normalised)"));
        CHECK_THAT(materialError("<Orthotropic name=\"o\" mu=\"1000\" kappa=\"10000\" eta=\"500\" eta2=\"300\" direction=\"1 0 0\" "
                                 "direction2=\"2 0 0\"/>"),
                   Contains("scene.xml:5: error: Orthotropic 'o': 'direction2' is parallel to 'direction': an orthotropic "
                            "material needs two distinct fibre directions"));
    }
}

TEST_CASE("a Prony series without long-term stiffness is a located error", "[ViscoelasticProny]") {
    CHECK_THAT(errorOf(cell(kMat, "<TLEDForceField name=\"ff\"/>", "<ViscoelasticProny name=\"visco\" alpha=\"0.6 0.5\" tau=\"1 2\"/>")),
               Contains("scene.xml:7: error: ViscoelasticProny 'visco': the alpha entries sum to 1.1, which leaves no "
                        "long-term stiffness (alpha_inf = 1 - sum must be > 0, TLED eq. (6))"));
}
