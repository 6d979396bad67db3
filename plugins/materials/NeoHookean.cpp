#include "fascia/materials/NeoHookean.h"
#include "fascia/materials/Moduli.h"

namespace fascia::materials {

void NeoHookean::init() { resolveMuKappa(*this, m_mu, m_kappa, m_E, m_nu, m_law.mu, m_law.kappa); }

} // namespace fascia::materials
