#include "fascia/materials/TransverselyIsotropic.h"
#include "fascia/materials/Moduli.h"

#include <cmath>

namespace fascia::materials {

void TransverselyIsotropic::init() {
    resolveMuKappa(*this, m_mu, m_kappa, m_E, m_nu, m_law.mu, m_law.kappa);
    m_law.eta = m_eta.get();
    m_a0 = unitDirection(*this, m_dir);
}

double TransverselyIsotropic::waveSpeed(double rho) const {
    return std::sqrt((m_law.kappa + 4.0 / 3.0 * m_law.mu + m_law.eta) / rho);
}

} // namespace fascia::materials
