// The TLED element loops in double (precision "double"), and the choice of a group's loop.
#include "TLEDKernelLaws.h"

namespace fascia::tled {

template TLEDForceField::Impl::KernelFn kernelFor<double>(const TLEDForceField::Impl::Group&, const void*&);
// (instantiated in TLEDKernelFloat.cpp)
extern template TLEDForceField::Impl::KernelFn kernelFor<float>(const TLEDForceField::Impl::Group&, const void*&);

void chooseKernel(TLEDForceField::Impl::Group& g, bool mixed) {
    g.fn = mixed ? kernelFor<float>(g, g.law) : kernelFor<double>(g, g.law);
}

} // namespace fascia::tled
