/// A plugin built at -O0 (tests/plugins/CMakeLists.txt), as an out-of-tree build without a build
/// type used to be: loading it works, with a warning that names it.
#include "fascia/plugin/Plugin.h"

namespace {
void registerNothing(fascia::core::Registry&) {}
} // namespace

FASCIA_PLUGIN("fascia.test.unoptimised", "0.0.1", "built without optimisation", registerNothing)
