#include "fascia/base/Format.h"

#include <sstream>

namespace fascia::core {

std::string formatNumber(double v, int significantDigits) {
    std::ostringstream os;
    os.precision(significantDigits);
    os << v;
    return os.str();
}

} // namespace fascia::core
