#include "EmulatedRunner.h"

#include "DeviceLaws.h"

namespace fascia::cuda {

std::unique_ptr<StepRunner> makeEmulatedRunner(const StepSetup& s, Precision p) {
    return selectDeviceLaw(s.material, [&](auto tag, const materials::BaseMaterial* m) -> std::unique_ptr<StepRunner> {
        using Law = typename decltype(tag)::type;
        if constexpr (std::is_same_v<Law, elements::GenericLaw>) {
            m->fail("the material " + m->className() + " is not on the GPU step (it runs " + deviceLawNames() + ")");
        } else {
            const Law& law = elements::lawOf<Law>(m);
            if (p == Precision::Float) return std::make_unique<EmulatedRunner<Law, float>>(s, law);
            return std::make_unique<EmulatedRunner<Law, double>>(s, law);
        }
    });
}

} // namespace fascia::cuda
