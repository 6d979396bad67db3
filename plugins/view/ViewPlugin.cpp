// fascia.view: pictures of a run (the renderer of fascia-view, offscreen).
#include "fascia/plugin/Plugin.h"

#include "PngSnapshot.h"

static void registerView(fascia::core::Registry& r) {
    r.add<fascia::view::PngSnapshot>("PngSnapshot", "PNG pictures of the bodies' surfaces coloured by a field, with the tools, every N steps or at the end of the run");
}

FASCIA_PLUGIN("fascia.view", "0.1.0", "pictures of a run: PngSnapshot (VTK rendering, offscreen)", registerView)
