// The element layer is a library that element force fields link (HEML, TLED, out-of-tree ones);
// it registers no component of its own, but sits in the plugin folder like materials.
#include "fascia/plugin/Plugin.h"

static void registerAll(fascia::core::Registry&) {}

FASCIA_PLUGIN("fascia.elements", "0.1.0", "the element layer shared by HEML, TLED and plugins (no components)", registerAll)
