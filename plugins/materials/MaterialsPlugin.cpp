#include "fascia/materials/CompressibleMooneyRivlin.h"
#include "fascia/materials/CompressibleNeoHookean.h"
#include "fascia/materials/IncompressibleMooneyRivlin.h"
#include "fascia/materials/IncompressibleNeoHookean.h"
#include "fascia/materials/NeoHookean.h"
#include "fascia/materials/Orthotropic.h"
#include "fascia/materials/StVenantKirchhoff.h"
#include "fascia/materials/TransverselyIsotropic.h"
#include "fascia/plugin/Plugin.h"

using namespace fascia::materials;

static void registerAll(fascia::core::Registry& r) {
    r.add<StVenantKirchhoff>("StVenantKirchhoff", "Saint Venant-Kirchhoff material, lambda/2 (tr E)^2 + mu tr(E^2) (HEML Table 3)");
    r.add<IncompressibleNeoHookean>("IncompressibleNeoHookean", "HEML's neo-Hookean C1 (I1 - 3), no volumetric term (HEML Table 3)");
    r.add<IncompressibleMooneyRivlin>("IncompressibleMooneyRivlin", "HEML's Mooney-Rivlin C1 (I1 - 3) + C2 (I2 - 3), no volumetric term (HEML Table 3)");
    r.add<CompressibleNeoHookean>("CompressibleNeoHookean", "compressible neo-Hookean C1 (I1 - 3) - mu ln J + lambda/2 (ln J)^2 (HEML eq. (26))");
    r.add<CompressibleMooneyRivlin>("CompressibleMooneyRivlin", "Mooney-Rivlin C1 (I1bar - 3) + C2 (I2bar - 3) + kappa/2 (J - 1)^2");
    r.add<NeoHookean>("NeoHookean", "neo-Hookean mu/2 (I1bar - 3) + kappa/2 (J - 1)^2 (TLED eq. (31)-(32), no fibres)");
    r.add<TransverselyIsotropic>("TransverselyIsotropic", "neo-Hookean plus fibres eta/4 (I4bar - 1)^2 (TLED eq. (33) convention)");
    r.add<Orthotropic>("Orthotropic", "neo-Hookean plus two fibre families eta/4 (I4bar - 1)^2 + eta2/4 (I6bar - 1)^2");
}

FASCIA_PLUGIN("fascia.materials", "0.1.0", "invariant-based hyperelastic materials shared by HEML and TLED", registerAll)
