// The unit conversions every layer shares (io/units.hpp) against their definitions: 60 rpm is one
// revolution per second, 2π rad/s; 30 rpm is π rad/s. Tolerances: each conversion is one
// multiplication and one division of correctly rounded values (π itself rounded), so each result
// is within 3 units in the last place of the exact value, 3 ε relative; a round trip within 6 ε.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <numbers>

#include "epicycle/io/units.hpp"

using epicycle::io::RadPerSecondToRpm;
using epicycle::io::RpmToRadPerSecond;

TEST_CASE("rpm and rad/s: one revolution per second is 60 rpm", "[unit][io]") {
  const double eps = std::numeric_limits<double>::epsilon();
  CHECK(std::abs(RpmToRadPerSecond(60.0) - 2.0 * std::numbers::pi) <=
        3 * eps * 2.0 * std::numbers::pi);
  CHECK(std::abs(RpmToRadPerSecond(30.0) - std::numbers::pi) <= 3 * eps * std::numbers::pi);
  CHECK(std::abs(RadPerSecondToRpm(std::numbers::pi) - 30.0) <= 3 * eps * 30.0);
  CHECK(RpmToRadPerSecond(0.0) == 0.0);
  CHECK(RpmToRadPerSecond(-1500.0) == -RpmToRadPerSecond(1500.0));
  for (double n : {1.0, 7.5, 1500.0, 2763.265306122449, 1e5}) {
    INFO("n = " << n << " rpm");
    CHECK(std::abs(RadPerSecondToRpm(RpmToRadPerSecond(n)) - n) <= 6 * eps * n);
  }
  // Usable in constant expressions (a default member value of a public struct).
  static_assert(RpmToRadPerSecond(30.0) > 3.14 && RpmToRadPerSecond(30.0) < 3.15);
}
