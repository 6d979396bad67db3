// The Monitor's kinetic energy, strain energy and residual columns against closed forms: a rigid
// translation's 1/2 M v^2 (M = rho V), a uniformly stretched cube's W(F) V with W of
// CompressibleNeoHookean (HEML eq. (26)) computed here from F, and the residual of a body at an
// equilibrium (0) and out of it (the norm of the free loads, known in closed form).
#include "fascia/sim/Simulation.h"

#include <catch2/catch.hpp>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using fascia::Mat3;
using fascia::Vec3;
using fascia::core::Error;
using fascia::core::Simulation;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

fs::path freshDir(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("fascia-monitor-energy-" + std::to_string(getpid())) / name;
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

/// The rows of a CSV file, split at commas.
std::vector<std::vector<std::string>> csv(const fs::path& p) {
    std::ifstream in(p);
    std::vector<std::vector<std::string>> out;
    for (std::string l; std::getline(in, l);) {
        std::vector<std::string> row;
        std::stringstream ss(l);
        for (std::string c; std::getline(ss, c, ',');) row.push_back(c);
        out.push_back(row);
    }
    return out;
}

/// A 0.2 x 0.1 x 0.3 box of CompressibleNeoHookean (mu 3000, lambda 5000, C1 = mu/2), rho 1000.
std::string box(const std::string& forceField, const std::string& element, const std::string& extra) {
    return "<Node name=\"root\" dt=\"0.0005\">\n"
           "  <GridMesh name=\"grid\" min=\"0 0 0\" max=\"0.2 0.1 0.3\" resolution=\"3 2 4\" element=\"" + element + "\"/>\n"
           "  <MechanicalObject name=\"state\"/>\n"
           "  <LumpedMass density=\"1000\"/>\n"
           "  <CompressibleNeoHookean mu=\"3000\" lambda=\"5000\"/>\n"
           "  <" + forceField + " name=\"ff\"/>\n"
           "  <SemiImplicitEuler/>\n" + extra +
           "</Node>\n";
}

const char* kMonitor = "  <Monitor name=\"mon\" indices=\"0\" kineticEnergy=\"true\" strainEnergy=\"true\" residual=\"true\"/>\n";

} // namespace

TEST_CASE("the monitor's kinetic energy is 1/2 M v^2 of a rigid translation", "[Monitor]") {
    const fs::path dir = freshDir("kinetic");
    auto sim = Simulation::fromString(box("TLEDForceField", "hexahedra", kMonitor), "scene.xml", ".", {dir.string(), 0});
    auto& st = sim->state("state");
    const Vec3 v0(0.3, -0.4, 1.2);
    for (auto& v : st.v()) v = v0;
    sim->start();  // the first row: the state as set
    sim->finish();
    const auto rows = csv(dir / "mon.csv");
    REQUIRE(rows.size() == 2);
    REQUIRE(rows[0].size() == 7);
    CHECK(rows[0][4] == "kineticEnergy [J]");
    CHECK(rows[0][5] == "strainEnergy [J]");
    CHECK(rows[0][6] == "residual [N]");
    const double M = 1000 * 0.2 * 0.1 * 0.3;
    CHECK(std::stod(rows[1][4]) == Approx(0.5 * M * v0.squaredNorm()).epsilon(1e-10));
    CHECK(std::stod(rows[1][5]) == Approx(0).margin(1e-14));  // at rest shape: no strain energy
}

TEST_CASE("the monitor's strain energy of a uniformly stretched box is W(F) times its volume", "[Monitor]") {
    const bool tled = GENERATE(true, false);
    CAPTURE(tled);
    const fs::path dir = freshDir(tled ? "strain-tled" : "strain-heml");
    auto sim = Simulation::fromString(box(tled ? "TLEDForceField" : "HEMLForceField", tled ? "hexahedra" : "tetrahedra6", kMonitor),
                                      "scene.xml", ".", {dir.string(), 0});
    auto& st = sim->state("state");
    Mat3 F;
    F << 1.1, 0.05, 0, 0, 0.95, 0.02, 0, 0, 1.05;
    for (size_t i = 0; i < st.size(); ++i) st.x()[i] = F * st.x0()[i];
    sim->start();
    sim->finish();
    const auto rows = csv(dir / "mon.csv");
    REQUIRE(rows.size() == 2);
    const double mu = 3000, lambda = 5000, C1 = mu / 2, J = F.determinant(), I1 = (F.transpose() * F).trace();
    const double W = C1 * (I1 - 3) - mu * std::log(J) + lambda / 2 * std::log(J) * std::log(J);  // HEML eq. (26)
    CHECK(std::stod(rows[1][5]) == Approx(W * 0.2 * 0.1 * 0.3).epsilon(1e-9));
    CHECK(W > 10);
}

TEST_CASE("the monitor's residual is 0 at an equilibrium and the norm of the free loads out of it", "[Monitor]") {
    SECTION("a homogeneous stretch held on its whole boundary is in equilibrium") {
        const fs::path dir = freshDir("residual-eq");
        std::string held;
        for (const char* g : {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"})
            held += std::string("  <FixedConstraint group=\"") + g + "\"/>\n";
        auto sim = Simulation::fromString(box("TLEDForceField", "hexahedra", held + kMonitor), "scene.xml", ".", {dir.string(), 0});
        auto& st = sim->state("state");
        for (size_t i = 0; i < st.size(); ++i) st.x()[i] = Vec3(1.1, 0.9, 1.2).asDiagonal() * st.x0()[i];
        // the scale of the forces: those of the force field alone, on the boundary nodes
        auto* ff = dynamic_cast<fascia::core::BaseForceField*>(sim->find("ff"));
        fascia::Positions f(st.size(), Vec3::Zero());
        ff->addForce(st, f, 0);
        double scale = 0;
        for (auto& fi : f) scale += fi.squaredNorm();
        scale = std::sqrt(scale);
        sim->start();
        sim->finish();
        const auto rows = csv(dir / "mon.csv");
        REQUIRE(rows.size() == 2);
        CAPTURE(scale);
        CHECK(scale > 1);
        CHECK(std::stod(rows[1][6]) < 1e-12 * scale);
        // the state's forces are left as they were (the residual evaluates them on the side)
        for (auto& fi : st.f()) REQUIRE(fi == Vec3::Zero());
    }
    SECTION("loads on a body at rest: the norm of the loads on its free nodes") {
        const fs::path dir = freshDir("residual-load");
        // 12 nodes on zmax carry (1, 2, 2) N each, |f| = 3; the loads on the fixed zmin are removed
        auto sim = Simulation::fromString(box("TLEDForceField", "hexahedra",
                                              "  <FixedConstraint group=\"zmin\"/>\n"
                                              "  <ConstantForce group=\"zmax\" force=\"1 2 2\"/>\n"
                                              "  <ConstantForce group=\"zmin\" force=\"5 5 5\"/>\n" +
                                                  std::string(kMonitor)),
                                          "scene.xml", ".", {dir.string(), 0});
        sim->start();
        sim->finish();
        const auto rows = csv(dir / "mon.csv");
        REQUIRE(rows.size() == 2);
        CHECK(std::stod(rows[1][6]) == Approx(3 * std::sqrt(12.0)).epsilon(1e-10));
    }
}

TEST_CASE("monitor energies without what they need are located errors", "[Monitor]") {
    auto errorOf = [](const std::string& xml) {
        try {
            Simulation::fromString(xml, "scene.xml");
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    CHECK_THAT(errorOf("<Node name=\"root\" dt=\"0.01\">\n  <MechanicalObject name=\"s\" position=\"0 0 0\"/>\n"
                       "  <Monitor name=\"m\" indices=\"0\" strainEnergy=\"true\"/>\n</Node>\n"),
               Contains("scene.xml:3: error: Monitor 'm': strainEnergy needs an element force field, but none acts on the state 's'"));
    CHECK_THAT(errorOf("<Node name=\"root\" dt=\"0.01\">\n  <MechanicalObject name=\"s\" position=\"0 0 0\"/>\n"
                       "  <Monitor name=\"m\" indices=\"0\" kineticEnergy=\"true\"/>\n</Node>\n"),
               Contains("scene.xml:3: error: Monitor 'm': kineticEnergy needs the masses, but no mass acts on the state 's'"));
}
