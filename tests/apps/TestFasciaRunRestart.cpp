// fascia-run --checkpoint, --checkpoint-every and --restart: a run of 200 steps and one of 100 steps
// restarted for 100 more give the same files, byte for byte (HEML and TLED, with and without Prony
// series, every integrator, on 1 and 2 threads); a bad or foreign checkpoint exits 2 and writes
// nothing; a diverging run exits 3 and leaves its last good state as a checkpoint.
#include "FasciaRunWorkspace.h"

#include "fascia/sim/Simulation.h"

#include <catch2/catch.hpp>

#include <cstring>

using namespace fasciaruntest;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

/// A cube held at its base, pushed at its top, with a Prony series or none, the integrator given,
/// a Monitor every 5 steps and (with VTK) a VTKExporter every 10.
std::string cube(const std::string& forceField, const std::string& integrator, bool prony, const std::string& dt = "auto") {
    const bool statics = integrator == "DynamicRelaxation";
    const std::string integ = integrator == "ExplicitEuler" ? "ExplicitEuler damping=\"40\""
                              : statics                      ? "DynamicRelaxation"
                                                             : integrator + " damping=\"5\"";
    std::string xml = "<Node name=\"root\" dt=\"" + std::string(statics ? "0.01" : dt) + "\" gravity=\"0 0 -9.81\">\n"
                      "  <GridMesh name=\"grid\" min=\"0 0 0\" max=\"0.1 0.1 0.1\" resolution=\"" +
                      std::string(statics ? "2 2 2" : "4 4 4") + "\"/>\n"
                      "  <MechanicalObject name=\"state\"/>\n  <LumpedMass density=\"1000\"/>\n"
                      "  <NeoHookean name=\"mat\" mu=\"3000\" kappa=\"30000\"/>\n";
    if (prony) xml += "  <ViscoelasticProny alpha=\"0.3 0.2\" tau=\"0.002 0.05\" apply=\"both\"/>\n";
    xml += "  <" + forceField + " name=\"ff\"/>\n  <" + integ + " name=\"integrator\"/>\n"
           "  <FixedConstraint name=\"base\" group=\"zmin\"/>\n"
           "  <PrescribedDisplacement name=\"push\" group=\"zmax\" displacement=\"0 0 -0.01\" curve=\"ramp " +
           std::string(statics ? "2" : "0.01") + "\"/>\n"
           "  <Monitor name=\"mon\" indices=\"5 20\" velocities=\"true\" kineticEnergy=\"true\" residual=\"true\" every=\"5\"/>\n";
#if FASCIA_HAVE_VTK
    xml += "  <VTKExporter name=\"vtk\" every=\"10\"/>\n";
#endif
    return xml + "</Node>\n";
}

/// The files of two folders of the workspace are the same, byte for byte.
void checkSameFiles(const Workspace& w, const std::string& a, const std::string& b) {
    const auto na = w.filesIn(a), nb = w.filesIn(b);
    CHECK(na == nb);
    CHECK(na.size() > 1);
    for (const auto& n : na) {
        CAPTURE(n);
        CHECK(slurpFile(w.dir() / a / n) == slurpFile(w.dir() / b / n));
    }
}

bool sameBits(const fascia::Positions& a, const fascia::Positions& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data()->data(), b.data()->data(), 24 * a.size()) == 0);
}

} // namespace

TEST_CASE("fascia-run restarted from a checkpoint writes the same files as a run straight through", "[fascia-run]") {
    const std::string ff = GENERATE(std::string("HEMLForceField"), std::string("TLEDForceField"));
    const std::string integrator = GENERATE(std::string("SemiImplicitEuler"), std::string("CentralDifference"),
                                            std::string("ExplicitEuler"), std::string("DynamicRelaxation"));
    const bool prony = GENERATE(false, true);
    CAPTURE(ff, integrator, prony);
    Workspace w;
    w.write("cube.xml", cube(ff, integrator, prony));
    auto straight = w.run("cube.xml --steps 200 --output a --threads 1 --quiet");
    INFO(straight.err);
    REQUIRE(straight.code == 0);
    // checkpoints at 30, 60, 90 and at the end (100), each over the last
    auto first = w.run("cube.xml --steps 100 --output b --threads 2 --checkpoint cube.ckpt --checkpoint-every 30 --quiet");
    INFO(first.err);
    REQUIRE(first.code == 0);
    CHECK(fs::exists(w.dir() / "cube.ckpt"));
    CHECK_FALSE(fs::exists(w.dir() / "cube.ckpt.tmp"));
    auto second = w.run("cube.xml --restart cube.ckpt --steps 100 --output b --threads 1 --quiet");
    INFO(second.err);
    REQUIRE(second.code == 0);
    CHECK_THAT(second.summary(), StartsWith("fascia-run: 100 steps, "));
    checkSameFiles(w, "a", "b");
}

TEST_CASE("fascia-run restarted from its end checkpoint or from an earlier one writes the same files", "[fascia-run]") {
    Workspace w;
    w.write("cube.xml", cube("HEMLForceField", "CentralDifference", true));
    auto every = w.run("cube.xml --steps 70 --output a --checkpoint every.ckpt --checkpoint-every 60 --quiet");
    REQUIRE(every.code == 0);
    auto at60 = w.run("cube.xml --steps 60 --output b --checkpoint at60.ckpt --quiet");
    REQUIRE(at60.code == 0);
    // the end checkpoint (step 70) overwrote the one of step 60; restarting each for 10 or 20 steps
    auto r70 = w.run("cube.xml --restart every.ckpt --steps 10 --output a --quiet");
    auto r60 = w.run("cube.xml --restart at60.ckpt --steps 20 --output b --quiet");
    INFO(r70.err << r60.err);
    CHECK(r70.code == 0);
    CHECK(r60.code == 0);
    checkSameFiles(w, "a", "b");
}

TEST_CASE("fascia-run --restart with a bad or foreign checkpoint exits 2 and writes nothing", "[fascia-run]") {
    Workspace w;
    w.write("cube.xml", cube("HEMLForceField", "SemiImplicitEuler", true));
    REQUIRE(w.run("cube.xml --steps 20 --output a --checkpoint good.ckpt --quiet").code == 0);
    const std::string good = slurpFile(w.dir() / "good.ckpt");
    const auto before = w.filesIn("a");
    std::vector<std::string> contents;
    for (const auto& f : before) contents.push_back(slurpFile(w.dir() / "a" / f));
    auto restartWith = [&](const std::string& bytes, const std::string& scene = "cube.xml") {
        {
            std::ofstream out(w.dir() / "bad.ckpt", std::ios::binary);
            out << bytes;
        }
        auto r = w.run(scene + " --restart bad.ckpt --steps 10 --output a --quiet");
        CHECK(r.code == 2);
        CHECK(r.summary().empty());
        // nothing written: the output folder as the first run left it
        CHECK(w.filesIn("a") == before);
        for (size_t k = 0; k < before.size(); ++k) CHECK(slurpFile(w.dir() / "a" / before[k]) == contents[k]);
        return r.firstErrLine();
    };
    SECTION("a flipped byte") {
        std::string b = good;
        b[b.size() / 3] ^= 0x01;
        CHECK(restartWith(b) == "bad.ckpt: error: checksum mismatch: the checkpoint is corrupt (changed or damaged since it was written)");
    }
    SECTION("truncated") {
        CHECK(restartWith(good.substr(0, 100)) ==
              "bad.ckpt: error: truncated checkpoint: 100 bytes, its header announces " + std::to_string(good.size()));
    }
    SECTION("the wrong magic") {
        CHECK(restartWith("not a checkpoint at all, but long enough for a header") ==
              "bad.ckpt: error: not a Fascia checkpoint (it does not start with \"FASCIACK\")");
    }
    SECTION("another version") {
        std::string b = good;
        b[8] = 7;
        CHECK(restartWith(b) == "bad.ckpt: error: checkpoint format version 7; this build reads version 1");
    }
    SECTION("another scene") {
        std::string xml = cube("HEMLForceField", "SemiImplicitEuler", true);
        xml.replace(xml.find("mu=\"3000\""), 9, "mu=\"3100\"");
        w.write("other.xml", xml);
        CHECK(restartWith(good, "other.xml") == "bad.ckpt: error: the checkpoint was written by another scene: NeoHookean "
                                                "'/root/mat' differs (a parameter, or the content of a file it reads)");
    }
    SECTION("a missing file") {
        auto r = w.run("cube.xml --restart none.ckpt --steps 10 --output a --quiet");
        CHECK(r.code == 2);
        CHECK(r.firstErrLine() == "none.ckpt: error: cannot read the checkpoint: No such file or directory");
        CHECK(w.filesIn("a") == before);
    }
    SECTION("a checkpoint at the end time") {
        auto r = w.run("cube.xml --restart good.ckpt --time 0.000001 --output a --quiet");
        CHECK(r.code == 2);
        CHECK_THAT(r.firstErrLine(), StartsWith("good.ckpt: error: the checkpoint is at t = ") &&
                                         Contains("at or past the end time 0.000001 s: nothing to run"));
    }
}

TEST_CASE("fascia-run refuses bad checkpoint options", "[fascia-run]") {
    Workspace w;
    w.write("cube.xml", cube("HEMLForceField", "SemiImplicitEuler", false));
    for (const char* args : {"--checkpoint-every 10", "--checkpoint c.ckpt --checkpoint-every 0",
                             "--checkpoint c.ckpt --checkpoint-every x", "--checkpoint", "--restart"}) {
        CAPTURE(args);
        auto r = w.run(std::string("cube.xml --steps 5 ") + args);
        CHECK(r.code == 1);
        CHECK_THAT(r.err, StartsWith("fascia-run: --"));
        CHECK_FALSE(fs::exists(w.dir() / "c.ckpt"));
    }
    auto r = w.run("cube.xml --steps 5 --output out --checkpoint nofolder/c.ckpt");
    CHECK(r.code == 1);
    CHECK(r.firstErrLine() == "error: --checkpoint 'nofolder/c.ckpt': cannot write into the folder 'nofolder': No such file or directory");
    CHECK(w.filesIn("out").empty());
}

TEST_CASE("A diverging fascia-run exits 3 and leaves the state before the growth as a checkpoint", "[fascia-run]") {
    const bool named = GENERATE(false, true);  // to --checkpoint FILE, or to OUTPUT/diverged.ckpt
    CAPTURE(named);
    Workspace w;
    const std::string stable = cube("HEMLForceField", "SemiImplicitEuler", true);
    // the in-process runs write into a folder of the workspace, not the build folder (where two
    // tests at once raced on vtk.pvd)
    fascia::core::LoadOptions inWorkspace;
    inWorkspace.outputDir = (w.dir() / "inproc").string();
    fs::create_directories(inWorkspace.outputDir);
    const double crit = fascia::core::Simulation::fromString(stable, "<string>", ".", inWorkspace)->criticalTimeStep();
    std::ostringstream dt;
    dt.precision(17);
    dt << 3 * crit;
    std::string xml = cube("HEMLForceField", "SemiImplicitEuler", true, dt.str());
    xml.replace(xml.find(" damping=\"5\""), 12, "");
    w.write("cube.xml", xml);
    auto r = w.run("cube.xml --steps 5000 --output out --quiet" + std::string(named ? " --checkpoint last.ckpt" : ""));
    INFO(r.err);
    CHECK(r.code == 3);
    const std::string at = "[/root/state] step ";
    REQUIRE(r.err.find(at) != std::string::npos);
    const long failed = std::stol(r.err.substr(r.err.find(at) + at.size()));
    CHECK_THAT(r.err, Contains("the kinetic energy grew more than 10 times") && Contains("(the end of step " + std::to_string(failed)) &&
                          Contains("worst element: ") && Contains("of HEMLForceField '/root/ff' (J = ") &&
                          Contains("a stable dt: "));
    const std::string file = named ? "last.ckpt" : "out/diverged.ckpt";
    const long good = std::max(0L, failed - 4);  // the start of the 4 steps of growth
    CHECK_THAT(r.err, Contains("fascia-run: the last good state (step " + std::to_string(good) + ", t = ") &&
                          Contains("is in '" + (named ? file : "out/diverged.ckpt") + "'"));
    REQUIRE(fs::exists(w.dir() / file));
    // the checkpoint is the state of a run straight to the step before
    auto straight = fascia::core::Simulation::fromString(xml, "<string>", ".", inWorkspace);
    straight->run(good);
    auto restored = fascia::core::Simulation::fromString(xml, "<string>", ".", inWorkspace);
    restored->restore((w.dir() / file).string());
    CHECK(restored->stepCount() == good);
    CHECK(sameBits(restored->state("state").x(), straight->state("state").x()));
    CHECK(sameBits(restored->state("state").v(), straight->state("state").v()));
    // and a restart from it with a stable dt goes on
    std::ostringstream small;
    small.precision(17);
    small << 0.5 * crit;
    auto again = w.run("cube.xml --restart " + file + " --dt " + small.str() + " --steps 50 --output out --quiet");
    INFO(again.err);
    CHECK(again.code == 0);
}
