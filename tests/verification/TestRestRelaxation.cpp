// A body at rest stays at rest under viscoelastic relaxation (the creep of docs/materials.md,
// section 3): every built-in law (materials::BuiltinMaterials) with every ViscoelasticProny apply
// value, in HEMLForceField and TLEDForceField, through the conformance harness's restDrift
// (fascia/materials/Conformance.h).
// Where relaxing a part would relax a rest stress (the laws that are not stress-free at rest), the
// combination is a located input error naming the law and the valid apply values.
#include "fascia/base/Error.h"
#include "fascia/materials/BuiltinMaterials.h"
#include "fascia/materials/Conformance.h"
#include "fascia/sim/Simulation.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>

using fascia::core::Simulation;
using Catch::Matchers::Contains;
namespace conf = fascia::materials::conformance;

namespace {

/// The material element of a built-in law with its example parameters (kExample).
std::string materialXml(const std::string& law) {
    std::string out = "<" + law + " name=\"mat\"";
    for (const auto& [k, v] : fascia::materials::exampleParameters(law)) out += " " + k + "=\"" + v + "\"";
    return out + "/>";
}

/// A unit cube of 2 x 2 x 2 cells, unloaded, on rollers (each min face held along its normal) or
/// with every node held ("fixed"), with a Prony series (alpha 0.5, tau 0.1 s) on `apply`. The
/// ViscoelasticProny is on line 7 of the scene.
std::string restScene(const std::string& material, const std::string& ff, const std::string& element, const std::string& apply,
                      bool allFixed) {
    const std::string supports = allFixed
        ? "  <FixedConstraint name=\"all\" indices=\"@mesh.allNodes\"/>\n"
        : "  <FixedConstraint name=\"rollx\" group=\"xmin\" directions=\"1 0 0\"/>\n"
          "  <FixedConstraint name=\"rolly\" group=\"ymin\" directions=\"0 1 0\"/>\n"
          "  <FixedConstraint name=\"rollz\" group=\"zmin\" directions=\"0 0 1\"/>\n";
    return "<Node name=\"root\" dt=\"auto\" dtSafety=\"0.5\">\n"
           " <Node name=\"body\">\n"
           "  <GridMesh name=\"mesh\" min=\"0 0 0\" max=\"1 1 1\" resolution=\"2 2 2\" element=\"" + element + "\"/>\n"
           "  <MechanicalObject name=\"state\"/>\n"
           "  <LumpedMass density=\"1\"/>\n"
           "  " + material + "\n"
           "  <ViscoelasticProny name=\"visco\" alpha=\"0.5\" tau=\"0.1\" apply=\"" + apply + "\"/>\n"
           "  <" + ff + " name=\"ff\"/>\n"
           "  <SemiImplicitEuler/>\n" + supports +
           " </Node>\n</Node>\n";
}

/// The grid's node indices 0..26 (the scene links no node list, so the all-fixed variant lists them).
std::string allNodes() {
    std::string s;
    for (int i = 0; i < 27; ++i) s += (i ? " " : "") + std::to_string(i);
    return s;
}

std::string withAllNodes(std::string xml) {
    const std::string key = "@mesh.allNodes";
    const size_t at = xml.find(key);
    if (at != std::string::npos) xml.replace(at, key.size(), allNodes());
    return xml;
}

/// Steps to reach t = 2 s (the time of the drift measured below), at least 50.
long stepsTo2s(const Simulation& sim) { return std::max(50L, long(std::ceil(2.0 / sim.dt()))); }

} // namespace

TEST_CASE("The cube of CompressibleNeoHookean on rollers that once crept stays at rest with a Prony series at apply isochoric",
          "[ViscoelasticProny]") {
    // before the split of docs/materials.md, section 3: E = 1, nu = 0.3, alpha = 0.5, tau = 0.1 s
    // drifted to u = 0.078 m at the corner by t = 2 s
    const std::string ff = GENERATE(as<std::string>{}, "HEMLForceField", "TLEDForceField");
    CAPTURE(ff);
    auto sim = Simulation::fromString(
        restScene("<CompressibleNeoHookean name=\"mat\" youngModulus=\"1\" poissonRatio=\"0.3\"/>", ff, "tetrahedra6",
                  "isochoric", false),
        "rest.xml");
    auto& s = dynamic_cast<fascia::core::BaseMechanicalState&>(*sim->find("state"));
    const conf::RestReport r = conf::restDrift(*sim, s, stepsTo2s(*sim), 1.0);
    CAPTURE(sim->time(), r.maxDisplacement, r.steps);
    REQUIRE(sim->time() >= 2.0);
    CHECK(r.maxDisplacement < 1e-12);
}

TEST_CASE("Every built-in law with every apply value stays at rest or is a located error", "[ViscoelasticProny]") {
    const std::string ff = GENERATE(as<std::string>{}, "HEMLForceField", "TLEDForceField");
    const std::string element = ff == "HEMLForceField" ? std::string("tetrahedra6")
                                                       : GENERATE(as<std::string>{}, "tetrahedra6", "hexahedra");
    const std::string apply = GENERATE(as<std::string>{}, "isochoric", "volumetric", "both");
    for (const std::string& law : fascia::materials::builtinMaterialNames()) {
        CAPTURE(ff, element, apply, law);
        // laws that are not stress-free at rest (HEML Table 3's "incompressible" laws): only the
        // isochoric part, stress-free at rest after the split of RelaxationSplit.h, may relax
        const bool restFree = law != "IncompressibleNeoHookean" && law != "IncompressibleMooneyRivlin";
        const std::string xml = restScene(materialXml(law), ff, element, apply, false);
        if (!restFree && apply != "isochoric") {
            try {
                Simulation::fromString(xml, "rest.xml");
                FAIL("no error for a relaxation of a part that carries a stress at rest");
            } catch (const fascia::core::Error& e) {
                CHECK(e.kind() == fascia::core::ErrorKind::Input);
                const std::string what = e.what();
                CHECK_THAT(what, Contains("rest.xml:7:"));
                CHECK_THAT(what, Contains(law + " 'mat'"));
                CHECK_THAT(what, Contains("valid for this law: apply=\"isochoric\""));
            }
            continue;
        }
        // reactions with every node held: constant over the steps (the relaxed part carries no
        // stress at rest, so nothing relaxes); for stress-free laws they stay at round-off
        {
            auto sim = Simulation::fromString(withAllNodes(restScene(materialXml(law), ff, element, apply, true)), "rest.xml");
            auto& s = dynamic_cast<fascia::core::BaseMechanicalState&>(*sim->find("state"));
            // force scale: the example moduli (~1e3 Pa) times a cell face (0.25 m^2)
            const conf::RestReport r = conf::restDrift(*sim, s, 100, 1000.0 * 0.25);
            CAPTURE(r.maxReactionChange, r.firstReaction);
            CHECK(r.maxReactionChange < 1e-12);
        }
        if (!restFree) continue;
        // free on rollers: no motion beyond round-off
        auto sim = Simulation::fromString(xml, "rest.xml");
        auto& s = dynamic_cast<fascia::core::BaseMechanicalState&>(*sim->find("state"));
        const conf::RestReport r = conf::restDrift(*sim, s, 400, 1000.0 * 0.25);
        CAPTURE(r.maxDisplacement, r.firstReaction, sim->time());
        CHECK(r.maxDisplacement < 1e-12);
        CHECK(r.firstReaction < 1e-12);
    }
}
