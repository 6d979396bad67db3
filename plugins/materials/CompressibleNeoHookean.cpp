#include "fascia/materials/CompressibleNeoHookean.h"
#include "fascia/materials/Moduli.h"

#include <cmath>
#include <sstream>

namespace fascia::materials {

void CompressibleNeoHookean::init() {
    if (useYoungPoisson(*this, {&m_mu, &m_lambda}, m_E, m_nu)) {
        m_law.mu = lameMu(m_E.get(), m_nu.get());
        m_law.lambda = lameLambda(m_E.get(), m_nu.get());
    } else {
        m_law.mu = m_mu.get();
        m_law.lambda = m_lambda.get();
        if (m_law.lambda + 2.0 / 3.0 * m_law.mu <= 0)
            fail(m_lambda, "lambda gives a non-positive bulk modulus lambda + 2 mu/3; use lambda > -2 mu/3");
    }
    m_law.C1 = m_C1.isSet() ? m_C1.get() : 0.5 * m_law.mu;
    if (m_C1.isSet() && std::abs(m_law.C1 - 0.5 * m_law.mu) > 1e-12 * m_law.mu) {
        std::ostringstream os;
        os << "C1 = " << m_law.C1 << " differs from mu/2 = " << 0.5 * m_law.mu
           << ": the rest state is not stress-free (residual stress (2 C1 - mu) I, HEML eq. (26)); "
              "leave C1 unset for C1 = mu/2";
        warn(os.str());
    }
}

} // namespace fascia::materials
