// The HEML element loops in double (precision "double"), and the choice of a material's loops.
#include "HEMLKernelLaws.h"

namespace fascia::heml {

template Impl::Loops loopsIn<double>(const materials::BaseMaterial*);
// (instantiated in HEMLKernelFloat.cpp)
extern template Impl::Loops loopsIn<float>(const materials::BaseMaterial*);

Impl::Loops loopsFor(const materials::BaseMaterial* m, bool mixed) { return mixed ? loopsIn<float>(m) : loopsIn<double>(m); }

} // namespace fascia::heml
