#include "fascia/sim/LayoutBytes.h"

namespace fascia::core {

// the key function: LayoutReport's type information lives in fascia_core, so that dynamic_cast
// finds it across the plugins' shared libraries
LayoutReport::~LayoutReport() = default;

} // namespace fascia::core
