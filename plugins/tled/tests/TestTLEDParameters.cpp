// TLEDForceField parameters given in XML, checked by their effect against the independent direct-FE
// reference of plugins/materials/tests/LawReference.h: an explicit material="@..." link that picks
// the second of two materials in the node, and a non-default J0.
#include "../../materials/tests/LawReference.h"
#include "fascia/tled/TLEDForceField.h"
#include "fascia/sim/Simulation.h"

#include <catch2/catch.hpp>

#include <random>
#include <string>

using namespace fascia;

namespace {

std::string attributes(const lawref::LawSpec& s) {
    std::string a;
    for (const auto& [k, v] : s.params()) a += " " + k + "=\"" + v + "\"";
    return a;
}

std::string scene(const lawref::LawSpec& first, const lawref::LawSpec& second, const std::string& ffAttributes) {
    return "<Node name=\"root\" dt=\"1e-4\">\n"
           "  <Node name=\"body\">\n"
           "    <GridMesh name=\"grid\" min=\"0 0 0\" max=\"0.02 0.02 0.03\" resolution=\"2 2 3\" element=\"tetrahedra6\"/>\n"
           "    <MechanicalObject name=\"mo\"/>\n"
           "    <LumpedMass density=\"1000\"/>\n"
           "    <SemiImplicitEuler/>\n"
           "    <" + first.type + " name=\"first\"" + attributes(first) + "/>\n"
           "    <" + second.type + " name=\"second\"" + attributes(second) + "/>\n"
           "    <TLEDForceField name=\"ff\"" + ffAttributes + "/>\n"
           "  </Node>\n"
           "</Node>\n";
}

struct Probe {
    Positions f, X, x;
    Tetrahedra tets;
};

/// Forces of the scene's force field at x = A X plus a jitter.
Probe probe(core::Simulation& sim, const Mat3& A) {
    auto* ff = dynamic_cast<tled::TLEDForceField*>(sim.find("ff"));
    REQUIRE(ff);
    auto& mo = sim.state("mo");
    std::mt19937 rng(2);
    std::uniform_real_distribution<double> u(-1, 1);
    for (size_t i = 0; i < mo.size(); ++i) mo.x()[i] = A * mo.x0()[i] + 3e-4 * Vec3(u(rng), u(rng), u(rng));
    Probe p;
    p.f.assign(mo.size(), Vec3::Zero());
    ff->addForce(mo, p.f, 0);
    p.X = mo.x0();
    p.x = mo.x();
    p.tets = *ff->tetrahedra();
    return p;
}

} // namespace

TEST_CASE("TLED with a material link to the second of two materials uses it, not the first one in the node", "[TLEDForceField]") {
    lawref::LawSpec first = lawref::lawNamed("NeoHookean");
    lawref::LawSpec second = lawref::lawNamed("TransverselyIsotropic");
    second.mu = 1500;
    auto sim = core::Simulation::fromString(scene(first, second, " material=\"@second\""), "link.xml");
    const Mat3 A = (Mat3() << 1.1, 0.05, 0.0, 0.0, 0.95, 0.03, 0.02, 0.0, 1.04).finished();
    const Probe p = probe(*sim, A);
    const Positions refSecond = lawref::tetForces(p.X, p.tets, p.x, [&](size_t) { return second; });
    const Positions refFirst = lawref::tetForces(p.X, p.tets, p.x, [&](size_t) { return first; });
    CHECK(lawref::relativeDifference(p.f, refSecond) < 1e-9);
    CHECK(lawref::relativeDifference(p.f, refFirst) > 0.05);
}

TEST_CASE("TLED J0 given in XML moves the start of the tangent continuation", "[TLEDForceField]") {
    const lawref::LawSpec law = lawref::lawNamed("CompressibleNeoHookean");
    const double J0 = GENERATE(0.4, 0.75);
    auto sim = core::Simulation::fromString(scene(law, law, " material=\"@first\" J0=\"" + std::to_string(J0) + "\""), "j0.xml");
    // J about 0.6: between the two J0
    const Mat3 A = (Mat3() << 0.85, 0.05, 0.0, 0.0, 0.84, 0.02, 0.0, 0.0, 0.84).finished();
    const Probe p = probe(*sim, A);
    const Positions ref = lawref::tetForces(p.X, p.tets, p.x, [&](size_t) { return law; }, J0);
    const Positions other = lawref::tetForces(p.X, p.tets, p.x, [&](size_t) { return law; }, J0 == 0.4 ? 0.75 : 0.4);
    CAPTURE(J0);
    CHECK(lawref::relativeDifference(p.f, ref) < 1e-9);
    CHECK(lawref::relativeDifference(p.f, other) > 1e-3);
}
