#include "fascia/materials/CompressibleMooneyRivlin.h"

namespace fascia::materials {

void CompressibleMooneyRivlin::init() {
    m_law.C1 = m_C1.get();
    m_law.C2 = m_C2.get();
    m_law.kappa = m_kappa.get();
    if (m_law.C1 + m_law.C2 <= 0) fail(m_C1, "C1 + C2 must be positive (it is half the shear modulus)");
}

} // namespace fascia::materials
