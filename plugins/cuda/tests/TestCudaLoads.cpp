// ConstantForce with load curves on the emulated device step, against the CPU (LoadCases.h), and
// the limit on their number.
#include "LoadCases.h"

using namespace cudatest;

TEST_CASE("CudaStep emulated scales ConstantForce by its load curve as the CPU does", "[CudaStep]") {
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    CAPTURE(precision);
    loads::curvedForcesFollowTheCpu(emulated(precision), deviceTolerance(precision));
}

TEST_CASE("CudaStep emulated applies SurfacePressure's follower load as the CPU does", "[CudaStep]") {
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    CAPTURE(precision);
    loads::pressuresFollowTheCpu(emulated(precision), deviceTolerance(precision));
}

TEST_CASE("More ConstantForce components with a load curve than the device step takes is a located error", "[CudaStep]") {
    std::string body;
    for (int k = 0; k <= cuda::kMaxLoads; ++k)
        body += "<ConstantForce name=\"f" + std::to_string(k) + "\" indices=\"30\" force=\"0 0 0.001\" curve=\"ramp 0.01\"/>";
    const std::string e = initError(scene(deviceLaw("NeoHookean"), "<CudaStep emulate=\"true\"/>", body));
    CAPTURE(e);
    CHECK(e.find("ConstantForce 'f" + std::to_string(cuda::kMaxLoads) + "'") != std::string::npos);
    CHECK(e.find("beyond the first " + std::to_string(cuda::kMaxLoads)) != std::string::npos);
}

TEST_CASE("CudaStep emulated gives bitwise the same forces and trajectory with the corner forces in node order", "[CudaStep]") {
    loads::forceOrderIsBitwise(cuda::makeEmulatedRunner, "<CudaStep emulate=\"true\"");
}
