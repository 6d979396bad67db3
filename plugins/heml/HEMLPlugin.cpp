#include "fascia/heml/HEMLForceField.h"
#include "fascia/plugin/Plugin.h"

static void registerAll(fascia::core::Registry& r) {
    r.add<fascia::heml::HEMLForceField>(
        "HEMLForceField", "Hyper-Elastic Mass Links on tetrahedra, any material of fascia.materials (Goulette and Chen 2015)");
}

FASCIA_PLUGIN("fascia.heml", "0.1.0", "HEMLForceField: the Hyper-Elastic Mass Links method", registerAll)
