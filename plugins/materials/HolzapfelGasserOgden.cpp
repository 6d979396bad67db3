#include "fascia/materials/HolzapfelGasserOgden.h"
#include "fascia/materials/Moduli.h"

#include <cmath>

namespace fascia::materials {

void HolzapfelGasserOgden::init() {
    m_law.mu = m_mu.get();
    m_law.k1 = m_k1.get();
    m_law.k2 = m_k2.get();
    m_law.dispersion = m_dispersion.get();
    m_law.K = m_bulk.get();
    m_a0 = unitDirection(*this, m_dir);
    m_law.twoFamilies = m_dir2.isSet();
    m_b0 = m_a0;
    if (m_law.twoFamilies) {
        m_b0 = unitDirection(*this, m_dir2);
        if (std::abs(m_a0.dot(m_b0)) > 1.0 - 1e-9)
            fail(m_dir2, "'direction2' is parallel to 'direction': give two distinct fibre families, or leave "
                         "'direction2' unset for one family");
    }
}

double HolzapfelGasserOgden::waveSpeed(double rho) const {
    const double b = 1.0 - 3.0 * m_law.dispersion;
    const double eta = 2.0 * m_law.k1 * b * b * (m_law.twoFamilies ? 2.0 : 1.0);
    return std::sqrt((m_law.K + 4.0 / 3.0 * m_law.mu + eta) / rho);
}

} // namespace fascia::materials
