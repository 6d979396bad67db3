#include "fascia/tled/TLEDForceField.h"

#include "fascia/plugin/Plugin.h"

static void registerAll(fascia::core::Registry& r) {
    r.add<fascia::tled::TLEDForceField>(
        "TLEDForceField", "total Lagrangian explicit dynamics forces on tetrahedra and hexahedra (Taylor et al. 2009)");
}

FASCIA_PLUGIN("fascia.tled", "0.1.0", "TLED element forces (T4, H8 with hourglass control), anisotropic viscoelastic", registerAll)
