#include "fascia/elements/DeviceForm.h"

namespace fascia::elements {

// the key function: DeviceFormSource's type information lives in fascia_elements, so that the step
// backend's dynamic_cast finds it across the plugins' shared libraries (as core::LayoutReport's)
DeviceFormSource::~DeviceFormSource() = default;

} // namespace fascia::elements
