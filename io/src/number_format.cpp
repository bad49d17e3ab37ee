#include "epicycle/io/number_format.hpp"

#include <algorithm>
#include <cstdio>

namespace epicycle::io {

std::string Num(double v, int significant_digits) {
  // "%.Ng" takes at most N + 8 characters ("-", ".", "e-308"); beyond 17 digits a double has no
  // more to show, and 40 keeps the buffer bounded.
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", std::clamp(significant_digits, 1, 40), v);
  return buf;
}

}  // namespace epicycle::io
