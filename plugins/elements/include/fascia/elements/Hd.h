#pragma once
/// The host/device macros FASCIA_HD and FASCIA_INLINE of the element layer's functions (3x3
/// vocabulary, geometry, stress). They are defined in the core (fascia/base/Hd.h, with the rules for
/// code that must compile for the GPU), since the laws in fascia/materials use them too.
#include "fascia/base/Hd.h"
