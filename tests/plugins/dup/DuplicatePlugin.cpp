/// Registers a component of its own, then "TestCounter", which the good test plugin registers too.
#include "fascia/plugin/Plugin.h"

namespace fascia::testdup {

class DupOnly : public core::Component {};
class DupCounter : public core::Component {};

static void registerAll(core::Registry& r) {
    r.add<DupOnly>("TestDupOnly", "registered before the clash; must vanish when the load fails");
    r.add<DupCounter>("TestCounter", "clashes with fascia.test");
}

} // namespace fascia::testdup

FASCIA_PLUGIN("fascia.testdup", "0.0.1", "clashes with fascia.test", fascia::testdup::registerAll)
