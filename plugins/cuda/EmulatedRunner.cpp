#include "EmulatedRunner.h"

namespace fascia::cuda {

std::unique_ptr<StepRunner> makeEmulatedRunner(const StepSetup& s, Precision p) {
    if (p == Precision::Float) return std::make_unique<EmulatedRunner<float>>(s);
    return std::make_unique<EmulatedRunner<double>>(s);
}

} // namespace fascia::cuda
