// The device step through real CUDA launches, against TLEDForceField, HEMLForceField and the
// integrators as the emulation tests check its kernel bodies on the CPU. Where no device is usable every case exits 77,
// which ctest reports as skipped (SKIP_RETURN_CODE, plugins/cuda/CMakeLists.txt), never as passed.
#include "CudaTestSupport.h"
#include "GroupCases.h"
#include "HEMLCases.h"
#include "LoadCases.h"
#include "ResidencyCases.h"

#include <cstdio>
#include <cstdlib>

using namespace cudatest;

namespace {

/// Exits 77 (skipped) when there is no usable CUDA device.
void requireDevice() {
    std::string why;
    if (cuda::cudaDevices(why) == 0) {
        std::printf("skipped: %s\n", why.c_str());
        std::fflush(stdout);
        std::exit(77);
    }
}

/// A runner of real CUDA launches, 128 threads a block: what the cases below compare with the CPU.
std::unique_ptr<cuda::StepRunner> gpuRunner(const cuda::StepSetup& s, cuda::Precision p) { return cuda::makeCudaRunner(s, p, 128); }

} // namespace

TEST_CASE("The GPU element and node kernels give TLED's forces on every node", "[CudaStep]") {
    requireDevice();
    const Law law = GENERATE(from_range(deviceLaws()));
    const Mesh mesh = GENERATE(Mesh::Tets, Mesh::Hexes, Mesh::Mixed);
    const double scale = GENERATE(0.3, 1.0, 3.0);
    const bool useFloat = GENERATE(false, true);
    CAPTURE(law.name, meshName(mesh), scale, useFloat);
    ForceProbe p = probeForces(law, scale, mesh);
    const double err = forceError(gpuRunner, p,
                                  useFloat ? cuda::Precision::Float : cuda::Precision::Double);
    CAPTURE(sci(err));
    CHECK(err <= (useFloat ? 1e-5 : 1e-12));
}

TEST_CASE("CudaStep on the GPU follows the CPU trajectory over 1000 steps", "[CudaStep]") {
    requireDevice();
    const Law law = GENERATE(from_range(deviceLaws()));
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    CAPTURE(law.name, precision);
    const Pair r = runBoth(law, "", "<SemiImplicitEuler damping=\"5\"/>", Mesh::Tets, onGpu(precision), 1000);
    CAPTURE(sci(r.err));
    CHECK(r.err <= (deviceTolerance(precision)));
}

TEST_CASE("CudaStep on the GPU follows the CPU trajectory of hexahedra over 1000 steps", "[CudaStep]") {
    requireDevice();
    const Mesh mesh = GENERATE(Mesh::Hexes, Mesh::Mixed);
    const Law law = GENERATE(from_range(deviceLaws()));
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    CAPTURE(meshName(mesh), law.name, precision);
    const Pair r = runBoth(law, "", "<SemiImplicitEuler damping=\"5\"/>", mesh, onGpu(precision), 1000);
    CAPTURE(sci(r.err));
    CHECK(r.err <= (deviceTolerance(precision)));
}

TEST_CASE("CudaStep on the GPU follows CentralDifference and PrescribedDisplacement over 1000 steps", "[CudaStep]") {
    requireDevice();
    const std::string integrator = GENERATE(as<std::string>{}, "<CentralDifference/>", "<CentralDifference damping=\"5\"/>",
                                            "<SemiImplicitEuler damping=\"5\"/>");
    const bool lift = GENERATE(false, true);
    const Mesh mesh = GENERATE(Mesh::Tets, Mesh::Mixed);
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    CAPTURE(integrator, lift, meshName(mesh), precision);
    const Pair r = runBoth(deviceLaw("TransverselyIsotropic"), lift ? kLift : "", integrator, mesh,
                           onGpu(precision), 1000);
    CAPTURE(sci(r.err));
    // (CentralDifference in double: the CPU's rounding in x, test_cuda_emulation)
    const bool damped = integrator == "<CentralDifference damping=\"5\"/>", central = integrator.find("Central") != std::string::npos;
    CHECK(r.err <= (precision == "float" ? 1e-4 : damped ? 5e-9 : central ? 1e-10 : 1e-11));
}

TEST_CASE("CudaStep on the GPU follows TLEDForceField with a Prony series over 1000 steps", "[CudaStep][ViscoelasticProny]") {
    requireDevice();
    const std::string integrator = GENERATE(as<std::string>{}, "<SemiImplicitEuler damping=\"5\"/>", "<CentralDifference/>",
                                            "<CentralDifference damping=\"5\"/>");
    const Mesh mesh = GENERATE(Mesh::Tets, Mesh::Mixed);
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    CAPTURE(integrator, meshName(mesh), precision);
    const Pair r = runBoth(deviceLaw("TransverselyIsotropic"), prony(), integrator, mesh, onGpu(precision), 1000);
    CAPTURE(sci(r.err));
    const bool damped = integrator == "<CentralDifference damping=\"5\"/>", central = integrator.find("Central") != std::string::npos;
    CHECK(r.err <= (precision == "float" ? 1e-4 : damped ? 5e-9 : central ? 1e-10 : 1e-11));
    CHECK(r.moved > 1e-4);
}

TEST_CASE("CudaStep on the GPU relaxes either part, or both, of every law as TLEDForceField does", "[CudaStep][ViscoelasticProny]") {
    requireDevice();
    const Law law = GENERATE(from_range(deviceLaws()));
    const std::string apply = GENERATE(as<std::string>{}, "isochoric", "volumetric", "both");
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    CAPTURE(law.name, apply, precision);
    // (500 steps: see test_cuda_emulation)
    const std::string cpuError = initError(scene(law, "", prony(apply)));
    if (!cpuError.empty()) {
        CHECK(initError(scene(law, onGpu(precision), prony(apply))) == cpuError);  // refused alike
        return;
    }
    const Pair r = runBoth(law, prony(apply), "<SemiImplicitEuler damping=\"5\"/>", Mesh::Mixed, onGpu(precision), 500);
    CAPTURE(sci(r.err));
    CHECK(r.err <= (precision == "float" ? 1e-4 : 1e-11));
}

TEST_CASE("CudaStep on the GPU runs a series per part, of different lengths, as TLEDForceField does", "[CudaStep][ViscoelasticProny]") {
    requireDevice();
    const Law law = GENERATE(deviceLaw("CompressibleNeoHookean"), deviceLaw("HolzapfelGasserOgden"));
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    CAPTURE(law.name, precision);
    const Pair r = runBoth(law, kTwoSeries, "<SemiImplicitEuler damping=\"5\"/>", Mesh::Mixed, onGpu(precision), 1000);
    CAPTURE(sci(r.err));
    CHECK(r.err <= (precision == "float" ? 1e-4 : 1e-11));
}

TEST_CASE("CudaStep on the GPU gives bitwise the same trajectory for any block size", "[CudaStep]") {
    requireDevice();
    const Law law = deviceLaw("TransverselyIsotropic");
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    CAPTURE(precision);
    const auto run = [&](int block) {
        return trajectoryEnd(law, "<CudaStep precision=\"" + precision + "\" blockSize=\"" + std::to_string(block) + "\"/>", 200);
    };
    const Positions a = run(256);
    for (int block : {32, 96, 1024}) {
        CAPTURE(block);
        const Positions b = run(block);
        bool same = true;
        for (size_t i = 0; i < a.size(); ++i) same = same && a[i] == b[i];
        CHECK(same);
    }
}

TEST_CASE("The GPU and the emulation run the same kernel bodies to round-off", "[CudaStep]") {
    requireDevice();
    const Law law = GENERATE(from_range(deviceLaws()));
    const Mesh mesh = GENERATE(Mesh::Tets, Mesh::Mixed);
    const std::string integrator = GENERATE(as<std::string>{}, "<SemiImplicitEuler damping=\"5\"/>", "<CentralDifference damping=\"5\"/>");
    const bool visco = GENERATE(false, true);
    CAPTURE(law.name, meshName(mesh), integrator, visco);
    const auto end = [&](const std::string& root) {
        auto sim = core::Simulation::fromString(scene(law, root, kLift + (visco ? prony() : ""), integrator, mesh));
        for (int s = 0; s < 300; ++s) sim->step();
        return sim->state("mo").x();
    };
    const Positions gpu = end("<CudaStep/>");
    const Positions emu = end("<CudaStep emulate=\"true\"/>");
    auto ref = core::Simulation::fromString(scene(law, ""));
    const double err = displacementError(gpu, emu, ref->state("mo").x0());
    CAPTURE(sci(err));
    CHECK(err <= 1e-11);
}

TEST_CASE("CudaStep on the GPU keeps the state on the device until it is read", "[CudaStep]") {
    requireDevice();
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    residency::stateStaysOnDevice(onGpu(precision), precision == "float" ? 1e-4 : 1e-11);
}

TEST_CASE("CudaStep on the GPU takes up what a program writes into the state it read", "[CudaStep]") {
    requireDevice();
    residency::writesAreTakenUp("<CudaStep/>");
}

TEST_CASE("CudaStep on the GPU names the first step whose state is not finite, whatever checkEvery", "[CudaStep]") {
    requireDevice();
    residency::firstBadStepFound("<CudaStep");
}

TEST_CASE("CudaStep on the GPU restarts from a checkpoint bitwise as the run that wrote it", "[CudaStep]") {
    requireDevice();
    residency::restartIsBitwise("<CudaStep/>");
}

TEST_CASE("CudaStep on the GPU gives the constraints' reactions as the CPU does", "[CudaStep]") {
    requireDevice();
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    CAPTURE(precision);
    residency::reactionsFollow(onGpu(precision), deviceTolerance(precision, 1e-9));
}

TEST_CASE("CudaStep on the GPU brings the Prony states back with the state: the relaxed stresses are the CPU's", "[CudaStep][ViscoelasticProny]") {
    requireDevice();
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    CAPTURE(precision);
    residency::relaxedStressesFollow(onGpu(precision), deviceTolerance(precision, 1e-9));
}

TEST_CASE("CudaStep on the GPU scales ConstantForce by its load curve as the CPU does", "[CudaStep]") {
    requireDevice();
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    CAPTURE(precision);
    loads::curvedForcesFollowTheCpu(onGpu(precision), deviceTolerance(precision));
}

TEST_CASE("CudaStep on the GPU applies SurfacePressure's follower load as the CPU does", "[CudaStep]") {
    requireDevice();
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    CAPTURE(precision);
    loads::pressuresFollowTheCpu(onGpu(precision), deviceTolerance(precision));
}

TEST_CASE("CudaStep on the GPU gives bitwise the same forces and trajectory with the corner forces in node order", "[CudaStep]") {
    requireDevice();
    loads::forceOrderIsBitwise(gpuRunner, "<CudaStep");
}

TEST_CASE("The GPU element kernels give TLED's forces with materials per group and fibres per element", "[CudaStep][groupMaterials]") {
    requireDevice();
    groups::forcesMatch(gpuRunner);
}

TEST_CASE("CudaStep on the GPU follows TLEDForceField with materials per group and fibres per element over 1000 steps",
          "[CudaStep][groupMaterials]") {
    requireDevice();
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    CAPTURE(precision);
    groups::trajectoriesFollow(onGpu(precision), deviceTolerance(precision));
}

TEST_CASE("CudaStep on the GPU relaxes materials per group with fibres per element as TLEDForceField does",
          "[CudaStep][groupMaterials][ViscoelasticProny]") {
    requireDevice();
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    CAPTURE(precision);
    groups::relaxedGroupsFollow(onGpu(precision), deviceTolerance(precision));
}

TEST_CASE("CudaStep on the GPU gives bitwise the same trajectory of groups with fibre arrays for any block size", "[CudaStep][groupMaterials]") {
    requireDevice();
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    CAPTURE(precision);
    const BodyParts parts = groups::groupParts(groups::groupCase("three groups with fibre arrays"), Mesh::Mixed);
    const auto run = [&](int block) {
        auto sim = core::Simulation::fromString(scene(parts, "<CudaStep precision=\"" + precision + "\" blockSize=\"" + std::to_string(block) + "\"/>"));
        for (int s = 0; s < 200; ++s) sim->step();
        return sim->state("mo").x();
    };
    const Positions a = run(256);
    for (int block : {32, 96, 1024}) {
        CAPTURE(block);
        CHECK(run(block) == a);
    }
}

TEST_CASE("The GPU edge-form kernel gives HEML's forces for every law and the springs", "[CudaStep][HEML]") {
    requireDevice();
    heml::forcesMatch(gpuRunner);
}

TEST_CASE("CudaStep on the GPU follows HEMLForceField over 1000 steps, every law and the springs", "[CudaStep][HEML]") {
    requireDevice();
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    CAPTURE(precision);
    heml::trajectoriesFollow(onGpu(precision), deviceTolerance(precision));
}

TEST_CASE("CudaStep on the GPU relaxes HEML as HEMLForceField does, either part or both, or refuses as it does", "[CudaStep][HEML][ViscoelasticProny]") {
    requireDevice();
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    CAPTURE(precision);
    heml::relaxedFollow(onGpu(precision), deviceTolerance(precision));
}

TEST_CASE("The GPU edge-form kernel gives HEML's forces with materials per group and fibre arrays", "[CudaStep][HEML][groupMaterials]") {
    requireDevice();
    heml::groupForcesMatch(gpuRunner);
}

TEST_CASE("CudaStep on the GPU follows HEMLForceField with materials per group and fibre arrays over 1000 steps",
          "[CudaStep][HEML][groupMaterials]") {
    requireDevice();
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    CAPTURE(precision);
    heml::groupsFollow(onGpu(precision), deviceTolerance(precision));
}

TEST_CASE("CudaStep on the GPU gives bitwise the same HEML trajectory for any block size", "[CudaStep][HEML]") {
    requireDevice();
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    CAPTURE(precision);
    const auto run = [&](int block) {
        auto sim = core::Simulation::fromString(scene(heml::parts(deviceLaw("TransverselyIsotropic")),
                                                      "<CudaStep precision=\"" + precision + "\" blockSize=\"" + std::to_string(block) + "\"/>", prony()));
        for (int s = 0; s < 200; ++s) sim->step();
        return sim->state("mo").x();
    };
    const Positions a = run(256);
    for (int block : {32, 96, 1024}) {
        CAPTURE(block);
        CHECK(run(block) == a);
    }
}
