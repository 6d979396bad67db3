// Restart is bitwise: 200 steps straight and 100 (and 98) steps, a checkpoint, a restore and the rest give the
// same positions, velocities and output files (every byte of the Monitor's CSV, the .vtu files and
// the .pvd), for HEML and TLED, with and without a Prony series, with each integrator of
// plugins/mechanics (ExplicitEuler, SemiImplicitEuler, CentralDifference, DynamicRelaxation), the
// restored half on 1 and on 2 threads; a changed mesh file is another scene; a run at three times
// the critical step diverges within a step, and its last good state is the straight run's.
#include "fascia/base/Error.h"
#include "fascia/sim/Simulation.h"

#include <catch2/catch.hpp>

#include <omp.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

using fascia::Positions;
using fascia::core::Error;
using fascia::core::ErrorKind;
using fascia::core::LoadOptions;
using fascia::core::Simulation;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

struct Case {
    std::string forceField, integrator;
    bool prony;
    std::string element = "tetrahedra6";  ///< GridMesh's element: TLED also on hexahedra
};

/// A cube held at its base, pushed down at its top by a ramp, under gravity and a ConstantForce with a
/// curve; a Monitor (velocities, energies and the residual, which evaluates the forces after every
/// row) every 7 steps and a VTKExporter every 10. The dynamic cases take 8 x 8 x 8 cells (3,072
/// tetrahedra: several blocks, so that the thread count could matter; 4 x 4 x 4 hexahedra); the static
/// solver 2 x 2 x 2.
std::string cube(const Case& c) {
    const bool statics = c.integrator == "DynamicRelaxation", hexahedra = c.element == "hexahedra";
    const std::string integrator = c.integrator == "ExplicitEuler" ? "ExplicitEuler damping=\"40\""
                                   : statics                      ? "DynamicRelaxation"
                                                                  : c.integrator + " damping=\"5\"";
    std::string xml = "<Node name=\"root\" dt=\"" + std::string(statics ? "0.01" : "auto") + "\" gravity=\"0 0 -9.81\">\n"
                      "  <GridMesh name=\"grid\" min=\"0 0 0\" max=\"0.1 0.1 0.1\" resolution=\"" +
                      std::string(statics ? "2 2 2" : hexahedra ? "4 4 4" : "8 8 8") + "\" element=\"" + c.element + "\"/>\n"
                      "  <MechanicalObject name=\"state\"/>\n"
                      "  <LumpedMass density=\"1000\"/>\n"
                      "  <NeoHookean mu=\"3000\" kappa=\"30000\"/>\n";
    if (c.prony) xml += "  <ViscoelasticProny alpha=\"0.3 0.2\" tau=\"0.002 0.05\" apply=\"both\"/>\n";
    xml += "  <" + c.forceField + " name=\"ff\"/>\n"
           "  <" + integrator + " name=\"integrator\"/>\n"
           "  <FixedConstraint name=\"base\" group=\"zmin\"/>\n"
           "  <PrescribedDisplacement name=\"push\" group=\"zmax\" displacement=\"0 0 -0.01\" curve=\"ramp " +
           std::string(statics ? "2" : "0.01") + "\"/>\n"
           "  <ConstantForce name=\"load\" group=\"xmax\" totalForce=\"0.02 0 0\" curve=\"ramp " +
           std::string(statics ? "2" : "0.005") + "\"/>\n"
           "  <Monitor name=\"mon\" indices=\"5 20\" velocities=\"true\" reactionOf=\"@base\" kineticEnergy=\"true\" "
           "strainEnergy=\"true\" residual=\"true\" every=\"7\"/>\n";
#if FASCIA_HAVE_VTK
    xml += "  <VTKExporter name=\"vtk\" every=\"10\"/>\n";
#endif
    return xml + "</Node>\n";
}

fs::path freshDir(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("fascia-restart-" + std::to_string(getpid())) / name;
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

bool sameBits(const Positions& a, const Positions& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data()->data(), b.data()->data(), 24 * a.size()) == 0);
}

/// Every file of folder a has the same bytes in folder b, and b has no other file.
void checkSameFiles(const fs::path& a, const fs::path& b) {
    std::vector<std::string> na, nb;
    for (auto& e : fs::directory_iterator(a)) na.push_back(e.path().filename().string());
    for (auto& e : fs::directory_iterator(b)) nb.push_back(e.path().filename().string());
    std::sort(na.begin(), na.end());
    std::sort(nb.begin(), nb.end());
    CHECK(na == nb);
    CHECK(na.size() > 1);
    for (const auto& n : na) {
        CAPTURE(n);
        CHECK(slurp(a / n) == slurp(b / n));
    }
}

std::unique_ptr<Simulation> load(const std::string& xml, const fs::path& out) {
    LoadOptions o;
    o.outputDir = out.string();
    return Simulation::fromString(xml, "cube.xml", ".", o);
}

struct Threads {
    explicit Threads(int n) : before(omp_get_max_threads()) { omp_set_num_threads(n); }
    ~Threads() { omp_set_num_threads(before); }
    int before;
};

} // namespace

TEST_CASE("200 steps straight and 100 plus a restore plus 100 give the same state and files", "[Simulation]") {
    const Case c = GENERATE(Case{"HEMLForceField", "SemiImplicitEuler", false}, Case{"HEMLForceField", "SemiImplicitEuler", true},
                            Case{"HEMLForceField", "CentralDifference", false}, Case{"HEMLForceField", "CentralDifference", true},
                            Case{"HEMLForceField", "ExplicitEuler", false}, Case{"HEMLForceField", "ExplicitEuler", true},
                            Case{"HEMLForceField", "DynamicRelaxation", false}, Case{"HEMLForceField", "DynamicRelaxation", true},
                            Case{"TLEDForceField", "SemiImplicitEuler", false}, Case{"TLEDForceField", "SemiImplicitEuler", true},
                            Case{"TLEDForceField", "CentralDifference", false}, Case{"TLEDForceField", "CentralDifference", true},
                            Case{"TLEDForceField", "ExplicitEuler", false}, Case{"TLEDForceField", "ExplicitEuler", true},
                            Case{"TLEDForceField", "DynamicRelaxation", false}, Case{"TLEDForceField", "DynamicRelaxation", true},
                            Case{"TLEDForceField", "SemiImplicitEuler", false, "hexahedra"}, Case{"TLEDForceField", "SemiImplicitEuler", true, "hexahedra"},
                            Case{"TLEDForceField", "CentralDifference", false, "hexahedra"}, Case{"TLEDForceField", "CentralDifference", true, "hexahedra"},
                            Case{"TLEDForceField", "ExplicitEuler", false, "hexahedra"}, Case{"TLEDForceField", "ExplicitEuler", true, "hexahedra"},
                            Case{"TLEDForceField", "DynamicRelaxation", false, "hexahedra"}, Case{"TLEDForceField", "DynamicRelaxation", true, "hexahedra"});
    const int threads = GENERATE(1, 2);
    CAPTURE(c.forceField, c.integrator, c.prony, c.element, threads);
    const std::string xml = cube(c);
    const fs::path a = freshDir("straight"), b = freshDir("restarted"), ck = freshDir("ckpt") / "cube.ckpt";
    const fs::path ck98 = ck.parent_path() / "cube98.ckpt";
    Positions x, v;
    {
        Threads one(1);
        auto sim = load(xml, a);
        sim->run(200);
        x = sim->state("state").x();
        v = sim->state("state").v();
        sim->finish();
    }
    {
        // two checkpoints: at step 98, a Monitor row (every 7), whose residual evaluated the forces
        // at that step's time, so that the next step evaluates them at the same time again (a Prony
        // state's committed value Yprev is what it goes on from); at step 100, no row, so that the
        // next step's evaluation is at a new time (the current value Ycur is committed)
        Threads t(threads);
        auto first = load(xml, b);
        first->run(98);
        first->save(ck98.string());
        first->run(2);
        first->save(ck.string());
        first->finish();
    }
    for (const auto& [checkpoint, at] : {std::make_pair(ck, 100L), std::make_pair(ck98, 98L)}) {
        CAPTURE(at);
        {
            Threads t(3 - threads);  // the other thread count for the second half
            auto second = load(xml, b);
            second->restore(checkpoint.string());
            CHECK(second->stepCount() == at);
            second->run(200 - at);
            CHECK(sameBits(second->state("state").x(), x));
            CHECK(sameBits(second->state("state").v(), v));
            second->finish();
        }
        checkSameFiles(a, b);
    }
}

TEST_CASE("A checkpoint of a scene whose mesh file changed is refused, naming the mesh loader", "[Simulation]") {
    const fs::path d = freshDir("mesh");
    fs::copy_file(fs::path(FASCIA_SOURCE_DIR) / "plugins/meshio/tests/data/cube_gmsh22.msh", d / "cube.msh");
    const std::string xml = "<Node name=\"root\" dt=\"0.0001\">\n"
                            "  <MeshLoader name=\"loader\" filename=\"" + (d / "cube.msh").string() + "\"/>\n"
                            "  <MechanicalObject name=\"state\"/>\n  <LumpedMass density=\"1000\"/>\n"
                            "  <NeoHookean mu=\"3000\" kappa=\"30000\"/>\n  <HEMLForceField/>\n  <SemiImplicitEuler/>\n"
                            "</Node>\n";
    {
        auto sim = Simulation::fromString(xml);
        sim->run(3);
        sim->save((d / "a.ckpt").string());
    }
    {
        auto same = Simulation::fromString(xml);
        same->restore((d / "a.ckpt").string());
        CHECK(same->stepCount() == 3);
    }
    // the same mesh with one more comment line: the file's content is part of the scene hash
    std::string text = slurp(d / "cube.msh");
    std::ofstream(d / "cube.msh", std::ios::binary) << text << "$Comments\nchanged\n$EndComments\n";
    auto changed = Simulation::fromString(xml);
    try {
        changed->restore((d / "a.ckpt").string());
        FAIL("a changed mesh file was accepted");
    } catch (const Error& e) {
        CHECK(e.kind() == ErrorKind::Input);
        CHECK_THAT(std::string(e.what()), Contains("a.ckpt: error: the checkpoint was written by another scene: MeshLoader "
                                                   "'/root/loader' differs (a parameter, or the content of a file it reads)"));
    }
}

namespace {
/// The cube of cube() with SemiImplicitEuler and no damping, at `factor` times its critical step.
std::string unstable(double factor, const std::string& forceField) {
    Case c{forceField, "SemiImplicitEuler", true};
    std::string xml = cube(c);
    auto probe = load(xml, freshDir("probe"));  // (its exporter writes into a folder of its own)
    std::ostringstream dt;
    dt.precision(17);
    dt << factor * probe->criticalTimeStep();
    xml.replace(xml.find("dt=\"auto\""), 9, "dt=\"" + dt.str() + "\"");
    xml.replace(xml.find(" damping=\"5\""), 12, "");
    return xml;
}
} // namespace

TEST_CASE("A run at three times the critical step diverges within a step and its last good state is the straight run's before the growth",
          "[Simulation][MechanicalGroup]") {
    const std::string ff = GENERATE(std::string("HEMLForceField"), std::string("TLEDForceField"));
    const long every = GENERATE(1L, 100L);  // a snapshot every step, or a replay
    CAPTURE(ff, every);
    const std::string xml = unstable(3.0, ff);
    const fs::path out = freshDir("diverged"), ck = out / "last.ckpt";
    auto sim = load(xml, out);
    sim->setSnapshotEvery(every);
    std::string message;
    try {
        sim->run(100000);
        FAIL("the run did not diverge");
    } catch (const Error& e) {
        CHECK(e.kind() == ErrorKind::Simulation);
        message = e.message();
    }
    INFO(message);
    const long failed = sim->failedStep();
    REQUIRE(failed > 1);
    // caught by the kinetic energy, before anything is infinite: the state named, the step, the time,
    // the worst element of the force field and a stable dt
    CHECK_THAT(message, Contains("[/root/state] step " + std::to_string(failed) + ": the kinetic energy grew more than 10 "
                                 "times its largest earlier value at each of the last 4 steps"));
    CHECK_THAT(message, Contains("(the end of step " + std::to_string(failed) + ")"));
    CHECK_THAT(message, Contains("; worst element: ") && Contains(" of " + ff + " '/root/ff' (J = ") &&
                            Contains(", rest centroid "));
    const double crit = sim->criticalTimeStep();
    std::ostringstream stable;
    stable.precision(6);
    stable << "; a stable dt: " << crit * 0.5 << " s (the stable step " << crit << " s x dtSafety 0.5";
    CHECK_THAT(message, Contains(stable.str()));
    // the last good state: the start of the first of the 4 growing steps, bitwise the straight run's
    const long good = std::max(0L, failed - 4);
    CHECK(sim->saveLastGoodState(ck.string()) == good);
    // (both in one folder of their own: the restore continues the straight run's output files)
    const fs::path straightDir = freshDir("straight");
    auto straight = load(xml, straightDir);
    straight->run(good);
    auto restored = load(xml, straightDir);
    restored->restore(ck.string());
    CHECK(restored->stepCount() == good);
    CHECK(sameBits(restored->state("state").x(), straight->state("state").x()));
    CHECK(sameBits(restored->state("state").v(), straight->state("state").v()));
    // it fails again at the same step
    try {
        restored->run(20);
        FAIL("the restored run did not diverge");
    } catch (const Error& e) {
        CHECK(e.message() == message);
    }
}

TEST_CASE("The kinetic energy rule does not fire on a stable run", "[Simulation][MechanicalGroup]") {
    // dt="auto" on the loaded, viscous cube: 400 steps (the push, its ramp and the settling) pass
    // (in a folder of its own: two tests writing vtk.pvd into the build folder at once raced)
    auto sim = load(cube(Case{"HEMLForceField", "SemiImplicitEuler", true}), freshDir("stable"));
    sim->run(400);
    CHECK(sim->failedStep() == -1);
    CHECK(sim->stepCount() == 400);
}

TEST_CASE("A restore into the folder of a run that went on past the checkpoint writes the straight run's files",
          "[Simulation]") {
    // the first run goes on 30 steps after its checkpoint (rows and files the restored run must replace)
    const Case c = GENERATE(Case{"HEMLForceField", "CentralDifference", true}, Case{"TLEDForceField", "SemiImplicitEuler", true});
    CAPTURE(c.forceField, c.integrator);
    const std::string xml = cube(c);
    const fs::path a = freshDir("straight"), b = freshDir("restarted"), ck = freshDir("ckpt") / "cube.ckpt";
    {
        auto sim = load(xml, a);
        sim->run(200);
    }
    {
        auto first = load(xml, b);
        first->run(100);
        first->save(ck.string());
        first->run(30);
    }
    auto second = load(xml, b);
    second->restore(ck.string());
    second->run(100);
    second->finish();
    checkSameFiles(a, b);
}
