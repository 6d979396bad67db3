#pragma once
/// Numbers as the messages and output texts write them.
#include <string>

namespace fascia::core {

/// v as an ostream writes it with precision(significantDigits) and the default flags ("%.Ng":
/// 0.1, 1e-07, 12345.7): the one formatter of the core and of the plugins, each with its digits.
std::string formatNumber(double v, int significantDigits);

} // namespace fascia::core
