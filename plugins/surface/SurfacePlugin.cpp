// The triangle-surface library is linked by leaf plugins (meshio, contact); it registers no
// component of its own, but sits in the plugin folder like the element layer.
#include "fascia/plugin/Plugin.h"

static void registerAll(fascia::core::Registry&) {}

FASCIA_PLUGIN("fascia.surface", "0.1.0", "triangle surfaces: STL and OBJ reader, closed-surface check, volume-mesh boundary (no components)", registerAll)
