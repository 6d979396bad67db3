#include "fascia/materials/ArrudaBoyce.h"

namespace fascia::materials {

void ArrudaBoyce::init() {
    m_law.mu = m_mu.get();
    m_law.lambdaM = m_lambdaM.get();
    m_law.kappa = m_kappa.get();
}

} // namespace fascia::materials
