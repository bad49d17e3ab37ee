// Scene keys of profile modifications and pitch deviations ([<gear>.modification],
// [<gear>.pitch]): values in SI, and invalid values refused with key, value and rule.
#include <catch2/catch.hpp>

#include <cmath>

#include "epicycle/geometry/stage.hpp"
#include "epicycle/transmission/scene.hpp"
#include "stage_fixtures.hpp"

using Catch::Matchers::Contains;
using epicycle::test::Replace;
using epicycle::test::SceneText;
using epicycle::transmission::ParseScene;

namespace {

// The paper's stage with extra keys in the sun's sub-tables.
std::string WithSun(const std::string& tables) {
  return Replace(SceneText("paper_stage.toml"), "[sun.cutter]", tables + "\n[sun.cutter]");
}
epicycle::geometry::Stage Build(const std::string& text) {
  return epicycle::geometry::Stage(ParseScene(text, "s.toml").stage);
}

}  // namespace

TEST_CASE("relief and pitch keys load in SI", "[unit][transmission]") {
  const auto s = ParseScene(WithSun("[sun.modification]\ntip_relief_um = 12.0\n"
                                    "tip_relief_start_mm = 37.0\ntip_relief_shape = \"parabolic\"\n"
                                    "[sun.pitch]\niso1328_grade = 6\nseed = 3\n"),
                            "s.toml");
  const auto& tip = s.stage.sun.modification.tip;
  CHECK(tip.amount == Approx(12e-6));
  CHECK(tip.start_radius == Approx(37e-3));
  CHECK(tip.shape == epicycle::geometry::ReliefShape::kParabolic);
  CHECK(s.stage.sun.pitch_deviations.size() == 16);
  CHECK_NOTHROW(epicycle::geometry::Stage(s.stage));
  // A start given as a roll angle u: r = r_b √(1 + u²).
  const auto r = ParseScene(WithSun("[sun.modification]\nroot_relief_um = 5.0\n"
                                    "root_relief_start_roll_deg = 20.0\n"),
                            "s.toml");
  const double rb = 0.5 * 4.23e-3 * 16 * std::cos(25.0 * M_PI / 180);
  CHECK(r.stage.sun.modification.root.start_radius ==
        Approx(rb * std::hypot(1.0, 20.0 * M_PI / 180)).epsilon(1e-12));
  // Single pitch deviations become cumulative ones: F_p,k = Σ_{j≤k} f_pt,j, F_p,0 = 0.
  const auto p = ParseScene(
      WithSun("[sun.pitch]\nsingle_um = [1.0, 2.0, -3.0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0]\n"),
      "s.toml");
  CHECK(p.stage.sun.pitch_deviations[0] == 0.0);
  CHECK(p.stage.sun.pitch_deviations[1] == Approx(2e-6));
  CHECK(p.stage.sun.pitch_deviations[2] == Approx(-1e-6));
  CHECK(p.stage.sun.pitch_deviations[3] == Approx(-1e-6));
}

TEST_CASE("invalid modifications name key, value and rule", "[unit][transmission]") {
  // Relief larger than the tooth can take.
  CHECK_THROWS_WITH(
      Build(WithSun("[sun.modification]\ntip_relief_um = 300.0\ntip_relief_start_mm = 37.0\n")),
      Contains("sun.modification.tip_relief_um = 300: too large for its zone") &&
          Contains("exceeds 0.05 rad"));
  // A start radius outside the active flank.
  CHECK_THROWS_WITH(
      Build(WithSun("[sun.modification]\ntip_relief_um = 10.0\ntip_relief_start_mm = 45.0\n")),
      Contains("sun.modification.tip_relief_start_mm = 45: must lie on the active involute"));
  CHECK_THROWS_WITH(
      Build(WithSun("[sun.modification]\ntip_relief_um = 10.0\n")),
      Contains("sun.modification.tip_relief_start_mm is missing") ||
          Contains("give exactly one of tip_relief_start_mm or tip_relief_start_roll_deg"));
  CHECK_THROWS_WITH(Build(WithSun("[sun.modification]\ntip_relief_um = -1.0\n"
                                  "tip_relief_start_mm = 37.0\n")),
                    Contains("sun.modification.tip_relief_um = -1: must be >= 0"));
  CHECK_THROWS_WITH(Build(WithSun("[sun.modification]\ntip_relief_um = 5.0\n"
                                  "tip_relief_start_mm = 37.0\ntip_relief_shape = \"cubic\"\n")),
                    Contains("sun.modification.tip_relief_shape = \"cubic\""));
  // A pitch list of the wrong length, not closing, or a class outside ISO 1328-1's 1..11.
  CHECK_THROWS_WITH(Build(WithSun("[sun.pitch]\nsingle_um = [1.0, -1.0]\n")),
                    Contains("sun.pitch.single_um = 2 entries: needs one entry per tooth (16)"));
  CHECK_THROWS_WITH(
      Build(WithSun("[sun.pitch]\nsingle_um = [1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1]\n")),
      Contains("sun.pitch.single_um = [16 entries]: single pitch deviations must sum to zero") &&
          Contains("their sum is 16 um"));
  CHECK_THROWS_WITH(Build(WithSun("[sun.pitch]\niso1328_grade = 12\n")),
                    Contains("sun.pitch.iso1328_grade = 12"));
  CHECK_THROWS_WITH(Build(WithSun("[sun.pitch]\niso1328_grade = 0\n")),
                    Contains("sun.pitch.iso1328_grade = 0"));
  CHECK_THROWS_WITH(Build(WithSun("[sun.pitch]\niso1328_grade = 6\ncumulative_um = [0]\n")),
                    Contains("give exactly one of single_um, cumulative_um or iso1328_grade"));
}
