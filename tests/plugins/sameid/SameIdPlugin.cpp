/// Uses the id of the good test plugin ("fascia.test") with a component of its own.
#include "fascia/plugin/Plugin.h"

namespace fascia::testsameid {

class SameIdOnly : public core::Component {};

static void registerAll(core::Registry& r) { r.add<SameIdOnly>("TestSameIdOnly", "never registered"); }

} // namespace fascia::testsameid

FASCIA_PLUGIN("fascia.test", "0.0.2", "same id as the good test plugin", fascia::testsameid::registerAll)
