// Invalid gears and stages are refused with a message that names the key, the value and the rule.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "epicycle/geometry/argument_range.hpp"
#include "epicycle/geometry/stage.hpp"
#include "geometry_fixtures.hpp"

using namespace epicycle::geometry;
using Catch::Matchers::Contains;

namespace {

GearSpec Sun() { return epicycle::test::PaperStage().stage.sun; }
StageSpec Paper() { return epicycle::test::PaperStage().stage; }

}  // namespace

TEST_CASE("teeth, module and width out of range", "[unit][geometry]") {
  GearSpec g = Sun();
  g.teeth = 2;
  CHECK_THROWS_WITH(Gear(g), Contains("sun.teeth = 2: must be >= 3"));
  g = Sun();
  g.module = -4.23e-3;
  CHECK_THROWS_WITH(Gear(g), Contains("sun.module_mm = -4.23: must be > 0"));
  g = Sun();
  g.face_width = 0;
  CHECK_THROWS_WITH(Gear(g), Contains("sun.face_width_mm = 0: must be > 0"));
}

TEST_CASE("pointed tooth", "[unit][geometry]") {
  GearSpec g = Sun();
  // The tool's full dedendum as addendum: s_a = 0.11 m, below the 0.2 m limit.
  g.tip_radius = 0;
  CHECK_THROWS_WITH(Gear(g), Contains("sun.tip_radius_mm = 39.9735: pointed tooth") &&
                                 Contains("below the limit 0.846 mm"));
}

TEST_CASE("undercut is generated and reported, not refused", "[unit][geometry]") {
  GearSpec g = Sun();
  g.profile_shift = -0.2;
  g.tip_radius = 36.0e-3;
  const Gear cut(g);  // below x_min = -0.107: undercut
  CHECK(cut.undercut());
  CHECK(cut.MinimumShiftWithoutUndercut() == Approx(-0.1077).margin(1e-4));
  // The involute starts where the trochoid crosses it, above the base circle.
  CHECK(cut.undercut_radius() > cut.base_radius());
  CHECK(cut.form_radius() == cut.undercut_radius());
  CHECK_FALSE(Gear(Sun()).undercut());
  // The closed-form limit: x_min = h_a0/m − ρ(1 − sin α)/m − z sin²α/2.
  const Gear ok(Sun());
  const double a = Rad(25.0);
  CHECK(
      ok.MinimumShiftWithoutUndercut() ==
      Approx(1.35 - 0.05 * (1 - std::sin(a)) - 16 * std::sin(a) * std::sin(a) / 2).epsilon(1e-12));
}

TEST_CASE("tip-fillet interference and tip-root clearance", "[unit][geometry]") {
  StageSpec s = Paper();
  // A deep ring tooth reaches the planet's flank below its form circle.
  s.ring.tip_radius = 132.9e-3;
  CHECK_THROWS_WITH(Stage(s),
                    Contains("tip-fillet interference: the ring's tip reaches the planet's flank"));
  s = Paper();
  s.carrier_radius = 85.0e-3;  // planets pulled in: the sun's tip meets the planet's root circle
  CHECK_THROWS_WITH(Stage(s),
                    Contains("the sun's tip hits the planet's root (radial clearance -0.1"));
}

TEST_CASE("planets that clash and planet counts that cannot be equally spaced",
          "[unit][geometry]") {
  StageSpec s = Paper();
  s.planets = 9;
  s.ring.teeth = 65;
  CHECK_THROWS_WITH(Stage(s), Contains("stage.planets = 9: neighbouring planets clash"));
  s = Paper();
  s.planets = 4;
  CHECK_THROWS_WITH(Stage(s), Contains("stage.planets = 4: cannot be equally spaced: (z_sun + "
                                       "z_ring)/n = 81/4 is not whole"));
  s = Paper();
  s.planet_angles = {0.0, Rad(120.0), Rad(250.0)};
  CHECK_THROWS_WITH(Stage(s), Contains("stage.planet_angles_deg[2] = 250: the planet cannot be "
                                       "assembled") &&
                                  Contains("nearest angle that is: 248.889"));
  // A small departure is shown, not rounded away: 81 · 240.0001/360 = 54.0000225.
  s.planet_angles = {0.0, Rad(120.0), Rad(240.0001)};
  CHECK_THROWS_WITH(Stage(s), Contains("stage.planet_angles_deg[2] = 240.0001: the planet cannot "
                                       "be assembled") &&
                                  Contains("= 54.0000225 is not whole") &&
                                  Contains("nearest angle that is: 240°"));
  s = Paper();
  s.pin_errors.resize(2);
  CHECK_THROWS_WITH(Stage(s), Contains("errors.pin = 2 entries: needs one entry per planet (3)"));
}

TEST_CASE("cutters that cannot make the tooth", "[unit][geometry]") {
  GearSpec g = Sun();
  g.rack->tip_radius = 1.5 * g.rack->addendum;
  CHECK_THROWS_WITH(Gear(g), Contains("sun.cutter.tip_radius_per_module = 2.025: must be >= 0 and "
                                      "below the tool addendum"));
  g = Sun();
  g.tip_round_radius = 3e-3;
  CHECK_THROWS_WITH(Gear(g), Contains("sun.tip_") && Contains("3"));
  g = Sun();
  g.rack.reset();
  CHECK_THROWS_WITH(Gear(g), Contains("sun.cutter = none: an external gear needs its rack cutter"));
}

TEST_CASE("an outline or profile of a bad point count is refused, naming the argument",
          "[unit][geometry]") {
  // A count below 1 samples nothing (0 divided by zero, a negative count read before the start
  // of an empty profile); the front ends' rule, geometry::kPointsPerSegment ([1, 1000]: 1e7
  // points a segment fill the memory), is checked where a user gives the count (Python's
  // test_bad_calls.py), the meshers and tests sampling finer.
  const Gear sun(Sun());
  for (int n : {0, -5})
    CHECK_THROWS_WITH(sun.Outline(n), Contains("points_per_segment = " + std::to_string(n) +
                                               ": must be >= 1"));
  CHECK_THROWS_WITH(sun.half_profile().Sample(0), Contains("points_per_segment = 0"));
  CHECK_THROWS_WITH(CheckArgument("points_per_segment", 1001, kPointsPerSegment),
                    "points_per_segment = 1001: must be a whole number in [1, 1000]");
  const std::vector<Vec2> one = sun.Outline(1), two = sun.Outline(2);
  CHECK(two.size() > one.size());
  for (const Vec2& p : two) CHECK(std::isfinite(p.x() + p.y()));
}
