// Formatting of numbers in the messages of std::invalid_argument (private to the transmission
// layer).
#pragma once

#include <sstream>
#include <string>

namespace epicycle::transmission::internal {

inline std::string Num(double v) {
  std::ostringstream os;
  os.precision(6);
  os << v;
  return os.str();
}

}  // namespace epicycle::transmission::internal
