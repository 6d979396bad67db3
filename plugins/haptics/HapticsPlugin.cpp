// The haptics library is linked by embedding programs (examples/haptics); it registers no
// component of its own, but sits in the plugin folder like the element layer.
#include "fascia/plugin/Plugin.h"

static void registerAll(fascia::core::Registry&) {}

FASCIA_PLUGIN("fascia.haptics", "0.1.0", "virtual coupling for haptic devices (no components)", registerAll)
