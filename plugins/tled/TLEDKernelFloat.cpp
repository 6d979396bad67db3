// The TLED element loops in float (precision "mixed": TLEDKernel.h).
#include "TLEDKernelLaws.h"

namespace fascia::tled {

template TLEDForceField::Impl::KernelFn kernelFor<float>(const TLEDForceField::Impl::Group&, const void*&);

} // namespace fascia::tled
