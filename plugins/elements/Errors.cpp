#include "fascia/elements/Errors.h"

#include "fascia/base/Error.h"

namespace fascia::elements {

void runtimeError(const core::Component& owner, const std::string& message) {
    core::throwSimulationError("[" + owner.path() + "] " + message);
}

} // namespace fascia::elements
