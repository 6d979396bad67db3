#pragma once
/// invCbrt and fastLog for the laws, as materials::invCbrt and materials::fastLog (the code is the
/// core's, fascia/base/FastMath.h).
#include "fascia/base/FastMath.h"

namespace fascia::materials {
using core::fastLog;
using core::invCbrt;
} // namespace fascia::materials
