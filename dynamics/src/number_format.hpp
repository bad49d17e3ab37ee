// Formatting of numbers in the messages of std::invalid_argument (private to the dynamics layer).
#pragma once

#include <sstream>
#include <string>

namespace epicycle::dynamics::internal {

inline std::string Num(double v) {
  std::ostringstream os;
  os.precision(6);
  os << v;
  return os.str();
}

}  // namespace epicycle::dynamics::internal
