#include "Yeoh.h"

namespace example {

void Yeoh::init() {
    m_law.C10 = m_C10.get();
    m_law.C20 = m_C20.get();
    m_law.C30 = m_C30.get();
    m_law.kappa = m_kappa.get();
}

} // namespace example
