// HEMLForceField on the device step, through the CPU emulation of its kernel bodies (CudaStep
// emulate="true", or a runner from makeEmulatedRunner), against HEMLForceField on the CPU: the cases
// of HEMLCases.h, which TestCudaDevice.cpp runs through real launches.
#include "HEMLCases.h"

using namespace cudatest;

TEST_CASE("The emulated edge-form kernel gives HEML's forces for every law and the springs", "[CudaStep][HEML]") {
    heml::forcesMatch(cuda::makeEmulatedRunner);
}

TEST_CASE("CudaStep emulated follows HEMLForceField over 1000 steps, every law and the springs", "[CudaStep][HEML]") {
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    CAPTURE(precision);
    heml::trajectoriesFollow(emulated(precision), deviceTolerance(precision));
}

TEST_CASE("CudaStep emulated follows HEMLForceField with CentralDifference and PrescribedDisplacement over 1000 steps", "[CudaStep][HEML]") {
    const std::string integrator = GENERATE(as<std::string>{}, "<CentralDifference/>", "<CentralDifference damping=\"5\"/>");
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    CAPTURE(integrator, precision);
    const Pair r = runBoth(heml::parts(deviceLaw("NeoHookean")), kLift, integrator, emulated(precision), 1000);
    CAPTURE(sci(r.err));
    // (CentralDifference in double: the CPU's own rounding in x, TestCudaEmulation.cpp)
    CHECK(r.err <= (precision == "float" ? 1e-4 : 5e-9));
    CHECK(r.moved > 1e-4);
}

TEST_CASE("CudaStep emulated relaxes HEML as HEMLForceField does, either part or both, or refuses as it does", "[CudaStep][HEML][ViscoelasticProny]") {
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    CAPTURE(precision);
    heml::relaxedFollow(emulated(precision), deviceTolerance(precision));
}

TEST_CASE("CudaStep emulated relaxes HEML: the viscous trajectory leaves the elastic one by far more than its error", "[CudaStep][HEML][ViscoelasticProny]") {
    const BodyParts body = heml::parts(deviceLaw("NeoHookean"));
    const Pair visco = runBoth(body, prony(), "<SemiImplicitEuler damping=\"5\"/>", emulated("double"), 1000);
    const Pair elastic = runBoth(body, "", "<SemiImplicitEuler damping=\"5\"/>", emulated("double"), 1000);
    const double apart = displacementError(visco.device, elastic.device, visco.rest);
    CAPTURE(sci(apart), sci(visco.err));
    CHECK(apart >= 0.05);
    CHECK(visco.err <= 1e-11);
}

TEST_CASE("The emulated edge-form kernel gives HEML's forces with materials per group and fibre arrays", "[CudaStep][HEML][groupMaterials]") {
    heml::groupForcesMatch(cuda::makeEmulatedRunner);
}

TEST_CASE("CudaStep emulated follows HEMLForceField with materials per group and fibre arrays over 1000 steps",
          "[CudaStep][HEML][groupMaterials]") {
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    CAPTURE(precision);
    heml::groupsFollow(emulated(precision), deviceTolerance(precision));
}

TEST_CASE("The device step refuses a second element force field or a second series beside HEML, located", "[CudaStep][HEML]") {
    const BodyParts body = heml::parts(deviceLaw("NeoHookean"));
    // two series: HEMLForceField takes one (the CPU refuses it too)
    const std::string two = initError(scene(body, emulated("double"), kTwoSeries));
    CAPTURE(two);
    CHECK(two.find("ViscoelasticProny 'bulk'") != std::string::npos);
    CHECK(two.find("one") != std::string::npos);
    // HEML and TLED on one state
    const std::string both = initError(scene(body, emulated("double"), "<TLEDForceField name=\"tled\"/>"));
    CAPTURE(both);
    CHECK(both.find("TLEDForceField 'tled'") != std::string::npos);
    CHECK(both.find("a second element force field") != std::string::npos);
}
