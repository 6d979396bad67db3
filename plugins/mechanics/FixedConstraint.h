#pragma once
#include "AxisConstraint.h"

namespace fascia::mechanics {

/// Holds nodes at their rest positions, in all directions or along a per-axis mask (rollers,
/// symmetry planes). The reaction force (the force the support exerts) is recorded on each node.
class FixedConstraint : public AxisConstraint {};

} // namespace fascia::mechanics
