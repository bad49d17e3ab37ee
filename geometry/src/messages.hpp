// Error messages of the geometry layer: they name the scene key, its value and the rule.
#pragma once

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "epicycle/io/number_format.hpp"

namespace epicycle::geometry::internal {

/// A number printed compactly (up to 6 significant digits): io's message format.
using io::Num;
/// A number printed with 10 significant digits: a value whose fault is a small departure (an
/// angle 1e-4 deg off a whole assembly) shows it.
inline std::string Precise(double v) { return Num(v, 10); }
/// A length [m] printed in millimetres.
inline std::string Mm(double metres) { return Num(metres * 1e3); }

[[noreturn]] inline void Fail(const std::string& owner, const std::string& key,
                              const std::string& value, const std::string& rule) {
  throw std::invalid_argument(owner + "." + key + " = " + value + ": " + rule);
}

/// Lengths are checked in SI and reported in mm, as their scene keys are.
inline void RequirePositive(const std::string& owner, const std::string& key, double v) {
  if (!(v > 0) || !std::isfinite(v)) {
    const bool mm = key.size() > 3 && key.compare(key.size() - 3, 3, "_mm") == 0;
    Fail(owner, key, mm ? Mm(v) : Num(v), "must be > 0");
  }
}

}  // namespace epicycle::geometry::internal

namespace epicycle::geometry {
using internal::Fail;
using internal::Mm;
using internal::Num;
using internal::Precise;
using internal::RequirePositive;
}  // namespace epicycle::geometry
