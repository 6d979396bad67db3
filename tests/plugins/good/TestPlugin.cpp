/// fascia.test: trivial components for the core tests (never in the built-in plugin folder).
#include "TestCounter.h"
#include "TestMechanics.h"
#include "TestNaN.h"

#include "fascia/plugin/Plugin.h"

namespace fascia::test {

int nextInitIndex() {
    static int next = 0;
    return next++;
}

static void registerAll(core::Registry& r) {
    r.add<TestCounter>("TestCounter", "counts beginStep and observe calls; a parameter of every type");
    r.add<TestNaN>("TestNaN", "constant force that turns NaN at a chosen step");
    r.add<TestState>("TestState", "minimal mechanical state");
    r.add<TestMass>("TestMass", "same mass on every node");
    r.add<TestEuler>("TestEuler", "semi-implicit Euler without damping");
}

} // namespace fascia::test

FASCIA_PLUGIN("fascia.test", "0.0.1", "components for the core tests", fascia::test::registerAll)
