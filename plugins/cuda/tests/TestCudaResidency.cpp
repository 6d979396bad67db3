// The device step keeps the state on the device (CudaStep.h): nothing comes back until something
// reads it, what a program writes after a read is taken up, a state that is not finite is found
// and named with its first step however rarely the host checks, and a checkpoint restarts the
// device's history. Through the emulation (CudaStep emulate="true"), which runs the same
// host-side code as the GPU; test_cuda_device runs the same cases through real launches.
#include "CudaTestSupport.h"
#include "ResidencyCases.h"

using namespace cudatest;

TEST_CASE("CudaStep emulated keeps the state on the device until it is read", "[CudaStep]") {
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    residency::stateStaysOnDevice(emulated(precision), precision == "float" ? 1e-4 : 1e-11);
}

TEST_CASE("CudaStep emulated takes up what a program writes into the state it read", "[CudaStep]") {
    residency::writesAreTakenUp("<CudaStep emulate=\"true\"/>");
}

TEST_CASE("CudaStep emulated names the first step whose state is not finite, whatever checkEvery", "[CudaStep]") {
    residency::firstBadStepFound("<CudaStep emulate=\"true\"");
}

TEST_CASE("CudaStep emulated restarts from a checkpoint bitwise as the run that wrote it", "[CudaStep]") {
    residency::restartIsBitwise("<CudaStep emulate=\"true\"/>");
}

TEST_CASE("CudaStep emulated gives the constraints' reactions as the CPU does", "[CudaStep]") {
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    CAPTURE(precision);
    residency::reactionsFollow(emulated(precision), deviceTolerance(precision, 1e-9));
}

TEST_CASE("CudaStep emulated brings the Prony states back with the state: the relaxed stresses are the CPU's", "[CudaStep][ViscoelasticProny]") {
    const std::string precision = GENERATE(as<std::string>{}, "double", "float");
    CAPTURE(precision);
    residency::relaxedStressesFollow(emulated(precision), deviceTolerance(precision, 1e-9));
}
