// An out-of-tree plugin: registered through the one entry point.
#include "fascia/plugin/Plugin.h"

#include "CorotationalTetForceField.h"
#include "Yeoh.h"

static void registerExample(fascia::core::Registry& r) {
    r.add<example::CorotationalTetForceField>("CorotationalTetForceField", "corotational linear elasticity on tetrahedra (example plugin)");
    r.add<example::Yeoh>("Yeoh", fascia::materials::materialDescription<example::Yeoh>());
}

FASCIA_PLUGIN("example.plugin", "1.0.0", "an out-of-tree plugin: a force field and a material", registerExample)
