// The HEML element loops in float (precision "mixed": HEMLKernel.h).
#include "HEMLKernelLaws.h"

namespace fascia::heml {

template Impl::Loops loopsIn<float>(const materials::BaseMaterial*);

} // namespace fascia::heml
