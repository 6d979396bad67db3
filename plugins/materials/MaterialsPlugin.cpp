#include "fascia/materials/ArrudaBoyce.h"
#include "fascia/materials/CompressibleMooneyRivlin.h"
#include "fascia/materials/CompressibleNeoHookean.h"
#include "fascia/materials/HolzapfelGasserOgden.h"
#include "fascia/materials/IncompressibleMooneyRivlin.h"
#include "fascia/materials/IncompressibleNeoHookean.h"
#include "fascia/materials/NeoHookean.h"
#include "fascia/materials/Orthotropic.h"
#include "fascia/materials/StVenantKirchhoff.h"
#include "fascia/materials/TransverselyIsotropic.h"
#include "fascia/materials/UncoupledMooneyRivlin.h"
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
    r.add<HolzapfelGasserOgden>("HolzapfelGasserOgden", "Holzapfel-Gasser-Ogden mu/2 (I1bar - 3) + k1/(2 k2) sum_{i=4,6} [exp(k2 <E_i>^2) - 1] + K/2 (ln J)^2, E_i = kappa (I1bar - 3) + (1 - 3 kappa)(I_ibar - 1), fibres in tension only (<E> = max(E, 0)), one or two families, kappa = dispersion, K = bulkModulus (Gasser 2006)");
    r.add<ArrudaBoyce>("ArrudaBoyce", "Arruda-Boyce eight-chain mu sum_{i=1}^{5} C_i/lambdaM^(2i-2) (I1bar^i - 3^i) + kappa/2 (J - 1)^2, C = 1/2, 1/20, 11/1050, 19/7000, 519/673750 (Arruda-Boyce 1993, NiftySim)");
    r.add<UncoupledMooneyRivlin>("UncoupledMooneyRivlin", "FEBio's uncoupled Mooney-Rivlin c1 (I1bar - 3) + c2 (I2bar - 3) + k/2 (ln J)^2");
}

FASCIA_PLUGIN("fascia.materials", "0.1.0", "invariant-based hyperelastic materials shared by HEML and TLED", registerAll)
