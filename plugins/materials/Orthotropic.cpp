#include "fascia/materials/Orthotropic.h"
#include "fascia/materials/Moduli.h"

#include <cmath>

namespace fascia::materials {

void Orthotropic::init() {
    resolveMuKappa(*this, m_mu, m_kappa, m_E, m_nu, m_law.mu, m_law.kappa);
    m_law.eta = m_eta.get();
    m_law.eta2 = m_eta2.get();
    m_a0 = unitDirection(*this, m_dir);
    m_b0 = unitDirection(*this, m_dir2);
    const double c = std::abs(m_a0.dot(m_b0));
    if (c > 1.0 - 1e-9) fail(m_dir2, "'direction2' is parallel to 'direction': an orthotropic material needs two distinct fibre directions");
    if (c > 1e-9) warn("'direction' and 'direction2' are not orthogonal (|a0.b0| = " + std::to_string(c) + ")");
}

double Orthotropic::waveSpeed(double rho) const {
    return std::sqrt((m_law.kappa + 4.0 / 3.0 * m_law.mu + m_law.eta + m_law.eta2) / rho);
}

} // namespace fascia::materials
