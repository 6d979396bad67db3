// Runs end where they are asked to end: Simulation::runUntil(T) ends on T exactly, its last step
// shortened, with the same state as that last step done by hand (setDt(T - n dt), step()), for
// both force fields with a Prony series (whose coefficients depend on dt) and for the integrators
// (central difference keeps a history that a dt change restarts); the final state is written by
// every Monitor and VTKExporter whatever their `every`; a dt larger than the end time is a located
// error.
#include "fascia/sim/Simulation.h"

#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using fascia::core::Error;
using fascia::core::Simulation;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

/// A viscoelastic cube, compressed by a prescribed ramp, under gravity, with a monitor and an
/// exporter recording every 7 steps.
std::string cube(const std::string& forceField, const std::string& integrator, const std::string& element) {
    return "<Node name=\"root\" dt=\"0.002\" gravity=\"0 0 -9.81\">\n"
           "  <GridMesh name=\"grid\" min=\"0 0 0\" max=\"0.1 0.1 0.1\" resolution=\"2 2 2\" element=\"" + element + "\"/>\n"
           "  <MechanicalObject name=\"state\"/>\n"
           "  <LumpedMass density=\"1000\"/>\n"
           "  <NeoHookean mu=\"3000\" kappa=\"8000\"/>\n"
           "  <ViscoelasticProny alpha=\"0.4\" tau=\"0.01\" apply=\"isochoric\"/>\n"
           "  <" + forceField + " name=\"ff\"/>\n"
           "  <" + integrator + "/>\n"
           "  <FixedConstraint group=\"zmin\"/>\n"
           "  <PrescribedDisplacement group=\"zmax\" displacement=\"0 0 -0.01\" curve=\"ramp 0.02\"/>\n"
           "  <Monitor name=\"mon\" indices=\"13\" velocities=\"true\" every=\"7\"/>\n"
           "  <VTKExporter name=\"vtk\" every=\"7\"/>\n"
           "</Node>\n";
}

fs::path freshDir(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("fascia-runend-" + std::to_string(getpid())) / name;
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

std::vector<std::string> lines(const fs::path& p) {
    std::ifstream in(p);
    std::vector<std::string> out;
    for (std::string l; std::getline(in, l);) out.push_back(l);
    return out;
}

struct Case {
    const char* forceField;
    const char* integrator;
    const char* element;
};
const Case kCases[] = {{"TLEDForceField", "CentralDifference", "hexahedra"},
                       {"HEMLForceField", "SemiImplicitEuler", "tetrahedra6"},
                       {"TLEDForceField", "ExplicitEuler damping=\"50\"", "tetrahedra6"}};

} // namespace

TEST_CASE("a run to an end time that is not a multiple of dt ends on it exactly, as a last step shortened by hand",
          "[Simulation]") {
    for (const Case& c : kCases) {
        CAPTURE(c.forceField, c.integrator);
        const std::string xml = cube(c.forceField, c.integrator, c.element);
        const double T = 0.0231;  // 11 steps of 0.002 s, then one of 0.0011 s
        auto a = Simulation::fromString(xml, "scene.xml", ".", {freshDir("a").string(), 0});
        a->runUntil(T);
        CHECK(a->time() == T);
        CHECK(a->stepCount() == 12);
        CHECK(a->dt() == 0.002);  // dt is back after the last step
        auto b = Simulation::fromString(xml, "scene.xml", ".", {freshDir("b").string(), 0});
        b->run(11);
        b->setDt(T - 11 * 0.002);
        b->step();
        auto& sa = a->state("state");
        auto& sb = b->state("state");
        REQUIRE(sa.size() == sb.size());
        for (size_t i = 0; i < sa.size(); ++i) {
            INFO("node " << i);
            REQUIRE(sa.x()[i] == sb.x()[i]);
            REQUIRE(sa.v()[i] == sb.v()[i]);
        }
        // it moved: the comparison is of a deformed, moving state
        CHECK(std::abs(sa.x()[13][2] - sa.x0()[13][2]) > 1e-5);  // the centre node
        // a run continues from T with whole steps of dt again
        a->runUntil(T + 0.004);
        CHECK(a->time() == Approx(T + 0.004).epsilon(1e-15));
        CHECK(a->stepCount() == 14);
        // an end time that is a multiple of dt takes whole steps only
        auto m = Simulation::fromString(xml, "scene.xml", ".", {freshDir("m").string(), 0});
        m->runUntil(0.02);
        CHECK(m->stepCount() == 10);
        CHECK(m->time() == 0.02);
        CHECK(m->dt() == 0.002);
    }
}

TEST_CASE("the final state is written by every monitor and exporter whatever their every", "[Monitor][VTKExporter]") {
    const fs::path dir = freshDir("final");
    {
        auto sim = Simulation::fromString(cube("TLEDForceField", "CentralDifference", "hexahedra"), "scene.xml", ".",
                                          {dir.string(), 0});
        sim->runUntil(0.0231);  // steps 0 7 (monitor, exporter), then the final step 12
        sim->finish();
        const auto rows = lines(dir / "mon.csv");
        REQUIRE(rows.size() == 1 + 3);
        CHECK(rows[1].substr(0, 2) == "0,");
        CHECK(std::stod(rows[3].substr(0, rows[3].find(','))) == 0.0231);
        // the last row is the final state
        std::ostringstream u;
        u.precision(12);
        auto& st = sim->state("state");
        u << 0.0231 << "," << st.x()[13][0] - st.x0()[13][0];
        CHECK(rows[3].substr(0, u.str().size()) == u.str());
        for (const char* f : {"vtk_000000.vtu", "vtk_000007.vtu", "vtk_000012.vtu"}) CHECK(fs::exists(dir / f));
        CHECK(!fs::exists(dir / "vtk_000011.vtu"));
        std::ifstream pvd(dir / "vtk.pvd");
        std::stringstream ss;
        ss << pvd.rdbuf();
        CHECK_THAT(ss.str(), Contains("file=\"vtk_000012.vtu\""));
    }
    // a final state already written (step 14 = 2 x 7) is not written twice
    const fs::path dir2 = freshDir("final2");
    auto sim = Simulation::fromString(cube("TLEDForceField", "CentralDifference", "hexahedra"), "scene.xml", ".", {dir2.string(), 0});
    sim->run(14);
    sim->finish();
    CHECK(lines(dir2 / "mon.csv").size() == 1 + 3);
}

TEST_CASE("a dt larger than the end time is a located error", "[Simulation]") {
    auto sim = Simulation::fromString(cube("TLEDForceField", "CentralDifference", "hexahedra"), "scene.xml", ".",
                                      {freshDir("dt").string(), 0});
    try {
        sim->runUntil(0.0015);
        FAIL("no error");
    } catch (const Error& e) {
        CHECK_THAT(e.what(), Contains("scene.xml:1: error: Node 'root': dt = 0.002 s is larger than the end time 0.0015 s: "
                                      "not even one step fits"));
    }
    CHECK(sim->stepCount() == 0);
    sim->runUntil(0.002);  // one whole step fits
    CHECK(sim->stepCount() == 1);
    // after steps the rule is the same: the end time against dt, not the time left (0.0011 s is one
    // shortened step; an end time of 0.0015 s is still an error, also once the run is past it)
    sim->runUntil(0.0031);
    CHECK(sim->stepCount() == 2);
    CHECK(sim->time() == Approx(0.0031).epsilon(1e-12));
    CHECK_THROWS_WITH(sim->runUntil(0.0015), Contains("dt = 0.002 s is larger than the end time 0.0015 s"));
    CHECK(sim->stepCount() == 2);
}
