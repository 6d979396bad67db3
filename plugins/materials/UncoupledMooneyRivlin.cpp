#include "fascia/materials/UncoupledMooneyRivlin.h"

#include <sstream>

namespace fascia::materials {

void UncoupledMooneyRivlin::init() {
    m_law.c1 = m_c1.get();
    m_law.c2 = m_c2.get();
    m_law.k = m_k.get();
    if (!(m_law.c1 + m_law.c2 > 0)) {
        std::ostringstream os;
        os << "c1 + c2 = " << m_law.c1 + m_law.c2 << " must be positive (it is half the shear modulus)";
        fail(m_c1, os.str());
    }
}

} // namespace fascia::materials
