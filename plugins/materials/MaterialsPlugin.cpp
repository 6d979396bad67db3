#include "fascia/materials/BuiltinMaterials.h"
#include "fascia/plugin/Plugin.h"

#include <string>

using namespace fascia::materials;

static void registerAll(fascia::core::Registry& r) {
    // every built-in material, from the one list (BuiltinMaterials.h): the one-line description
    // (--list), then the energy in full (--describe prints every line), both built from the law's
    // parts (ComposedLaw.h)
    forEachBuiltinMaterial([&](auto* tag) {
        using M = std::decay_t<decltype(*tag)>;
        r.add<M>(M::kName, materialDescription<M>());
    });
}

FASCIA_PLUGIN("fascia.materials", "0.1.0", "invariant-based hyperelastic materials shared by HEML and TLED", registerAll)
