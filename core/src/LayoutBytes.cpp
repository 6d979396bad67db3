#include "fascia/sim/LayoutBytes.h"
#include "fascia/sim/LoadTerms.h"
#include "fascia/sim/StepTerms.h"

namespace fascia::core {

// the key function: LayoutReport's type information lives in fascia_core, so that dynamic_cast
// finds it across the plugins' shared libraries
LayoutReport::~LayoutReport() = default;
// (the same for the load terms of fascia/sim/LoadTerms.h)
NodalLoad::~NodalLoad() = default;
PressureLoad::~PressureLoad() = default;
// (and for the integrators' and constraints' terms of fascia/sim/StepTerms.h)
ExplicitScheme::~ExplicitScheme() = default;
AxisHold::~AxisHold() = default;

} // namespace fascia::core
