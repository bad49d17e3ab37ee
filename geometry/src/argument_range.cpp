#include "epicycle/geometry/argument_range.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include <fmt/format.h>

namespace epicycle::geometry {

bool ArgumentRange::Holds(double v) const {
  if (!std::isfinite(v)) return false;
  if (lo_open ? !(v > lo) : !(v >= lo)) return false;
  if (!(v <= hi)) return false;
  return !whole || v == std::floor(v);
}

std::string ArgumentRange::Describe() const {
  std::string text =
      fmt::format("must be {} {}{}, {}]", whole ? "a whole number in" : "finite and in",
                  lo_open ? "(" : "[", lo, hi);
  if (*unit != '\0') text += fmt::format(" {}", unit);
  if (*why != '\0') text += fmt::format(" ({})", why);
  return text;
}

double CheckArgument(const std::string& name, double value, const ArgumentRange& range) {
  if (!range.Holds(value))
    throw std::invalid_argument(fmt::format("{} = {}: {}", name, value, range.Describe()));
  return value;
}

double CheckArgumentText(const std::string& name, const std::string& text,
                         const ArgumentRange& range) {
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(begin, &end);
  if (text.empty() || end != begin + text.size() || !range.Holds(v))
    throw std::invalid_argument(name + " = " + text + ": " + range.Describe());
  return v;
}

}  // namespace epicycle::geometry
