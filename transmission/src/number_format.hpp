// Formatting of numbers in the messages of std::invalid_argument (private to the transmission
// layer).
#pragma once

#include <sstream>
#include <string>

namespace epicycle::transmission::internal {

/// `v` with `digits` significant digits.
inline std::string Num(double v, int digits = 6) {
  std::ostringstream os;
  os.precision(digits);
  os << v;
  return os.str();
}

}  // namespace epicycle::transmission::internal
