#include "fascia/viscoelastic/ViscoelasticProny.h"

#include "fascia/plugin/Plugin.h"

static void registerAll(fascia::core::Registry& r) {
    r.add<fascia::viscoelastic::ViscoelasticProny>(
        "ViscoelasticProny", "Prony-series relaxation (TLED eq. (5)-(30), HEML eq. (14)-(20)) for the force field in its node");
}

FASCIA_PLUGIN("fascia.viscoelastic", "0.1.0", "Prony-series viscoelasticity for TLED and HEML force fields", registerAll)
