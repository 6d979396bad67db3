#include "fascia/materials/StVenantKirchhoff.h"
#include "fascia/materials/Moduli.h"

namespace fascia::materials {

void StVenantKirchhoff::init() {
    if (useYoungPoisson(*this, {&m_lambda, &m_mu}, m_E, m_nu)) {
        m_law.lambda = lameLambda(m_E.get(), m_nu.get());
        m_law.mu = lameMu(m_E.get(), m_nu.get());
    } else {
        m_law.lambda = m_lambda.get();
        m_law.mu = m_mu.get();
        if (m_law.lambda + 2.0 / 3.0 * m_law.mu <= 0)
            fail(m_lambda, "lambda = " + std::to_string(m_law.lambda) +
                               " gives a non-positive bulk modulus lambda + 2 mu/3; use lambda > -2 mu/3");
    }
}

} // namespace fascia::materials
