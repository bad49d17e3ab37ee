// Result warnings of a dynamic run (dynamics::DynamicWarnings) on output steps made up here,
// whose values are known: a negative share, a transmission error past the small-rotation bound,
// a contact force twice the local term's validity limit (closed form L = h: F = h² π b E* /
// (4 R_eq)), and a step whose contact solve failed, which is not looked at.
#include <catch2/catch.hpp>

#include <cmath>

#include "epicycle/dynamics/dynamic_summary.hpp"
#include "local_term_fixtures.hpp"
#include "stage_fixtures.hpp"

using Catch::Matchers::Contains;
using namespace epicycle;

namespace {

dynamics::DynamicSample Step(const std::vector<double>& lsr, double carrier_angle = 0.0) {
  dynamics::DynamicSample s;
  s.carrier_angle = carrier_angle;
  s.load_sharing = lsr;
  s.evaluation.ok = true;
  return s;
}

}  // namespace

TEST_CASE("dynamic result warnings: jammed planet, large rotation, load past the local term",
          "[unit][dynamics]") {
  const auto scene = test::PaperScene();
  const geometry::Stage stage(scene.stage);
  CHECK(dynamics::DynamicWarnings(stage, {Step({0.3, 0.3, 0.4})}).empty());
  CHECK(dynamics::DynamicWarnings(stage, {}).empty());

  // Planet 3 below zero at two steps, the worst at carrier −2°; a failed step is not looked at.
  const double deg = geometry::kPi / 180.0;
  auto failed = Step({0.0, 0.0, -7.0});
  failed.evaluation.ok = false;
  auto w = dynamics::DynamicWarnings(
      stage, {Step({0.6, 0.5, -0.1}, -1 * deg), Step({0.6, 0.7, -0.3}, -2 * deg), failed});
  REQUIRE(w.size() == 1);
  CHECK_THAT(w[0], Contains("planet 3: load-sharing ratio LSR = -0.3 < 0 at carrier -2 deg") &&
                       Contains("(2 output step(s))") && Contains("jammed"));

  // The bound: 0.1 m / r_b,sun = 0.1 · 4.23 mm / (4.23·16/2 · cos 25° mm) = 0.1/(8 cos 25°) rad.
  const double bound = 0.1 / (8.0 * std::cos(25.0 * deg));
  auto small = Step({0.3, 0.3, 0.4}), large = small;
  small.transmission_error = 0.99 * bound;
  large.transmission_error = -1.01 * bound;
  CHECK(dynamics::DynamicWarnings(stage, {small}).empty());
  w = dynamics::DynamicWarnings(stage, {small, large});
  REQUIRE(w.size() == 1);
  CHECK_THAT(w[0], Contains("transmission error") && Contains("at 1 output step(s)") &&
                       Contains("a tenth of the module along the sun's line of action"));

  // One contact at twice its validity limit (docs in local_term_fixtures.hpp).
  const test::LocalTermWithLimit t = test::SteelLocalTerm();
  auto loaded = Step({0.3, 0.3, 0.4});
  loaded.evaluation.terms.local = {t.parameters, t.parameters};
  loaded.evaluation.force = Eigen::Vector2d(0.5 * t.limit_force, 2.0 * t.limit_force);
  w = dynamics::DynamicWarnings(stage, {loaded});
  REQUIRE(w.size() == 1);
  CHECK_THAT(
      w[0], Contains(" is 2 times the local term's validity limit") && Contains("on 1 contact(s)"));
}
