#pragma once
// The cases of the device-resident state (CudaStep.h), run through the emulation
// (TestCudaResidency.cpp) and through real launches (TestCudaDevice.cpp) with the same checks.
#include "CudaTestSupport.h"

#include "fascia/base/Error.h"

#include <filesystem>
#include <unistd.h>

namespace cudatest::residency {

namespace fs = std::filesystem;

/// Positions and velocities after `steps` steps of the scene with `root` in its root node (empty:
/// the CPU), with a program's write after `writeAt` steps when writeAt > 0.
inline std::pair<Positions, Positions> run(const std::string& root, int steps, int writeAt = 0, const std::string& integrator = "<SemiImplicitEuler damping=\"5\"/>") {
    auto sim = core::Simulation::fromString(scene(deviceLaw("TransverselyIsotropic"), root, kLift, integrator, Mesh::Mixed));
    sim->init();
    for (int s = 0; s < steps; ++s) {
        if (s == writeAt && writeAt > 0) {
            auto& mo = sim->state("mo");  // (a read: the device brings the state back)
            mo.x()[30] += Vec3(1e-4, -2e-4, 3e-4);
            mo.v()[31] += Vec3(0.01, 0.0, -0.02);
        }
        sim->step();
    }
    auto& mo = sim->state("mo");
    return {mo.x(), mo.v()};
}

/// No copy comes back while nothing reads the state; a read gives the device's state (to `tol` of
/// the CPU's displacement: 1e-11 in double, 1e-4 in float).
inline void stateStaysOnDevice(const std::string& root, double tol = 1e-11) {
    auto sim = core::Simulation::fromString(scene(deviceLaw("TransverselyIsotropic"), root));
    sim->init();
    const core::BaseMechanicalState& raw = *sim->groups().at(0).state;  // the host copy, read without a fetch
    const Positions x0 = raw.x();
    for (int s = 0; s < 50; ++s) sim->step();
    CHECK(raw.x() == x0);  // still the initial state: nothing came back
    const Positions x = sim->state("mo").x();  // fetched
    CHECK(x != x0);
    CHECK(raw.x() == x);
    auto cpu = core::Simulation::fromString(scene(deviceLaw("TransverselyIsotropic"), ""));
    for (int s = 0; s < 50; ++s) cpu->step();
    const double err = displacementError(x, cpu->state("mo").x(), x0);
    CAPTURE(sci(err));
    CHECK(err <= tol);
}

/// A program reads the state, moves a node and changes a velocity: the device continues from that,
/// as the CPU does (and a run without the write ends elsewhere).
inline void writesAreTakenUp(const std::string& root) {
    const auto cpu = run("", 60, 25), dev = run(root, 60, 25), without = run(root, 60);
    const Positions X = core::Simulation::fromString(scene(deviceLaw("TransverselyIsotropic"), ""))->state("mo").x0();
    const double err = displacementError(dev.first, cpu.first, X), moved = displacementError(without.first, cpu.first, X);
    CAPTURE(sci(err), sci(moved));
    CHECK(err <= 1e-11);
    CHECK(moved >= 1e-3);
}

/// A time step far above the critical one: the state overflows. With the device's record read
/// every step, every 7 and every 100 steps, the error names the same first step, comes at the
/// first check after it, and the last good state is the start of that step.
inline void firstBadStepFound(const std::string& rootOpen) {
    long first = -1;
    for (int every : {1, 7, 100}) {
        CAPTURE(every);
        auto sim = core::Simulation::fromString(scene(deviceLaw("NeoHookean"), rootOpen + " checkEvery=\"" + std::to_string(every) + "\"/>"));
        sim->init();
        sim->setDt(0.5);
        long failedAt = -1;
        std::string message;
        try {
            for (int s = 0; s < 1000; ++s) sim->step();
        } catch (const core::Error& e) {
            CHECK(e.kind() == core::ErrorKind::Simulation);
            failedAt = sim->stepCount() + 1;
            message = e.what();
        }
        REQUIRE(failedAt > 0);
        const long bad = sim->groups().at(0).firstBadStep;
        CAPTURE(message, bad, failedAt);
        REQUIRE(bad > 0);
        if (first < 0) first = bad;
        CHECK(bad == first);
        CHECK(failedAt == (bad + every - 1) / every * every);
        CHECK(message.find("is not finite on the device since step " + std::to_string(bad)) != std::string::npos);
        // the last good state: the start of the first bad step, finite
        const fs::path file = fs::temp_directory_path() / ("fascia_cuda_lastgood_" + std::to_string(getpid()) + ".ckpt");
        CHECK(sim->saveLastGoodState(file.string()) == bad - 1);
        fs::remove(file);
        for (const Vec3& p : sim->state("mo").x()) REQUIRE(p.allFinite());
    }
    CHECK(first > 1);
}

/// 60 steps in one run and 30 + a checkpoint + a restore + 30 give bitwise the same x and v, with
/// both integrators (the kick of SemiImplicitEuler, the increments of CentralDifference) and with a
/// Prony series (its states, clock and coefficients).
inline void restartIsBitwise(const std::string& root) {
    const std::string integrator = GENERATE(as<std::string>{}, "<SemiImplicitEuler damping=\"5\"/>", "<CentralDifference damping=\"5\"/>");
    const std::string prony = GENERATE(as<std::string>{}, "", "<ViscoelasticProny alpha=\"0.5 0.2\" tau=\"0.01 0.002\" apply=\"isochoric\"/>");
    CAPTURE(integrator, prony);
    const Law law = deviceLaw("TransverselyIsotropic");
    const std::string body = kLift + prony;
    const auto whole = [&] {
        auto sim = core::Simulation::fromString(scene(law, root, body, integrator, Mesh::Mixed));
        sim->run(60);
        return std::pair{sim->state("mo").x(), sim->state("mo").v()};
    }();
    const fs::path file = fs::temp_directory_path() / ("fascia_cuda_restart_" + std::to_string(getpid()) + ".ckpt");
    {
        auto sim = core::Simulation::fromString(scene(law, root, body, integrator, Mesh::Mixed));
        sim->run(30);
        sim->save(file.string());
    }
    auto sim = core::Simulation::fromString(scene(law, root, body, integrator, Mesh::Mixed));
    sim->restore(file.string());
    sim->run(30);
    fs::remove(file);
    CHECK(sim->stepCount() == 60);
    CHECK(sim->state("mo").x() == whole.first);
    CHECK(sim->state("mo").v() == whole.second);
}

/// The constraints' reactions (state reaction(), what a Monitor's reaction columns and a haptic
/// loop read) after 400 steps with the clamp, the roller, the prescribed lift and a Prony series,
/// with either integrator, against the CPU's: to `tol` of the largest reaction (the clamp carries
/// the pull and the body's weight, the lift its own load); a node no constraint holds has none.
inline void reactionsFollow(const std::string& root, double tol) {
    const std::string integrator = GENERATE(as<std::string>{}, "<SemiImplicitEuler damping=\"5\"/>", "<CentralDifference damping=\"5\"/>");
    CAPTURE(integrator);
    const std::string body = kLift + prony();
    const auto reactions = [&](const std::string& r) {
        auto sim = core::Simulation::fromString(scene(deviceLaw("TransverselyIsotropic"), r, body, integrator, Mesh::Mixed));
        sim->run(400);
        return sim->state("mo").reaction();
    };
    const Positions cpu = reactions(""), dev = reactions(root);
    REQUIRE(dev.size() == cpu.size());
    double err = 0, largest = 0;
    for (size_t i = 0; i < cpu.size(); ++i) {
        err = std::max(err, (dev[i] - cpu[i]).norm());
        largest = std::max(largest, cpu[i].norm());
    }
    CAPTURE(sci(err), sci(largest));
    CHECK(largest > 1e-3);  // (the pull alone is 9 x 4.6e-3 N)
    CHECK(err <= tol * largest);
    for (size_t i : {size_t(20), size_t(27)}) CHECK(dev[i] == Vec3::Zero());  // (free nodes)
    CHECK(dev[12][0] != 0.0);  // the roller holds x
}

/// The element force field's stress output (cellData, what an exporter writes) after 400 steps with
/// a Prony series, TLED on the mixed mesh and HEML, against the CPU's: the relaxed stresses read the
/// device's Prony states (viscoelastic/ElementHistory.h), to `tol` of the largest von Mises stress;
/// and far from the elastic stresses of the same state.
inline void relaxedStressesFollow(const std::string& root, double tol) {
    const std::string ff = GENERATE(as<std::string>{}, "TLEDForceField", "HEMLForceField");
    CAPTURE(ff);
    BodyParts parts{"<GridMesh name=\"grid\" min=\"0 0 0\" max=\"0.02 0.02 0.03\" resolution=\"2 2 3\" element=\"tetrahedra6\"/>",
                    deviceLaw("TransverselyIsotropic").element, ff == "TLEDForceField" ? mixedElements() : "", ff};
    const auto field = [&](const std::string& r, const std::string& body, const char* name) {
        auto sim = core::Simulation::fromString(scene(parts, r, kLift + body));
        sim->run(400);
        const auto& mo = sim->state("mo");  // (fetched)
        std::vector<core::CellField> fields;
        dynamic_cast<core::BaseForceField*>(sim->find("ff"))->cellData(mo, fields);
        for (const core::CellField& f : fields)
            if (f.name == name) return f.values;
        FAIL("no cell field " << name);
        return std::vector<double>{};
    };
    const std::vector<double> cpu = field("", prony(), "vonMises"), dev = field(root, prony(), "vonMises");
    const std::vector<double> elastic = field(root, "", "vonMises");
    REQUIRE(dev.size() == cpu.size());
    double err = 0, apart = 0, largest = 0;
    for (size_t e = 0; e < cpu.size(); ++e) {
        err = std::max(err, std::abs(dev[e] - cpu[e]));
        apart = std::max(apart, std::abs(elastic[e] - cpu[e]));
        largest = std::max(largest, std::abs(cpu[e]));
    }
    CAPTURE(sci(err), sci(apart), sci(largest));
    CHECK(err <= tol * largest);
    CHECK(apart >= 0.05 * largest);
}

} // namespace cudatest::residency
