// Helical scenes (docs/scenes.md, "Helical gears"): module, pressure angle and profile shift read
// in the normal section and brought to the transverse section; the stage's [helix] table and the
// gears' own keys give the same stage; β = 0 is the spur scene bit for bit; a [[fit]] and every
// driver of the planar model refuse a helical scene, naming its key.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <string>

#include "epicycle/geometry/helical.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/scene.hpp"
#include "stage_fixtures.hpp"
#include "thrown_message.hpp"

using Catch::Matchers::Contains;
using epicycle::test::Replace;
using epicycle::test::SceneText;
using namespace epicycle;

namespace {

transmission::Scene Grc(const std::string& text = SceneText("grc_helical_stage.toml")) {
  return transmission::ParseScene(text, "grc_helical_stage.toml");
}

// The GRC scene with the hands in the gears' tables instead of [helix].
std::string PerGearText() {
  std::string t = Replace(SceneText("grc_helical_stage.toml"),
                          "[helix]\nhelix_angle_deg = 7.5\nsun_hand = \"right\"\n", "");
  t = Replace(t, "[sun]\nteeth = 21\n", "[sun]\nteeth = 21\nhelix_angle_deg = 7.5\nhand = \"right\"\n");
  t = Replace(t, "[planet]\nteeth = 39\n",
              "[planet]\nteeth = 39\nhelix_angle_deg = 7.5\nhand = \"left\"\n");
  return Replace(t, "[ring]\nteeth = 99\n", "[ring]\nteeth = 99\nhelix_angle_deg = 7.5\nhand = \"left\"\n");
}

}  // namespace

TEST_CASE("a helical scene is read in the normal section", "[unit][transmission]") {
  const transmission::Scene s = Grc();
  REQUIRE(transmission::IsHelical(s));
  const double beta = 7.5 * std::numbers::pi / 180, mt = 10e-3 / std::cos(beta);
  const geometry::StageSpec& st = s.stage;
  for (const geometry::GearSpec* g : {&st.sun, &st.planet, &st.ring}) {
    CHECK(g->helix.angle == Approx(beta).epsilon(1e-15));
    CHECK(g->module == Approx(mt).epsilon(1e-15));
    CHECK(g->pressure_angle ==
          Approx(std::atan(std::tan(20 * std::numbers::pi / 180) / std::cos(beta))).epsilon(1e-15));
    // The rack's heights in normal modules: h_a0 = 1.25 m_n.
    if (g->rack) CHECK(g->rack->addendum == Approx(12.5e-3).epsilon(1e-15));
  }
  CHECK(st.sun.helix.hand == geometry::Hand::kRight);
  CHECK(st.planet.helix.hand == geometry::Hand::kLeft);
  CHECK(st.ring.helix.hand == geometry::Hand::kLeft);
  // x_t m_t = x_n m_n; the tip from addendum_per_module in normal modules: r + x_n m_n ∓ 1.0 m_n.
  CHECK(st.ring.profile_shift * mt == Approx(0.04 * 10e-3).epsilon(1e-14));
  CHECK(st.sun.tip_radius == Approx(21 * mt / 2 + 10e-3).epsilon(1e-14));
  CHECK(st.ring.tip_radius == Approx(99 * mt / 2 + 0.4e-3 - 10e-3).epsilon(1e-14));
  CHECK(s.warnings.empty());
  // The gears' own keys give the same stage as [helix].
  const transmission::Scene per_gear = Grc(PerGearText());
  for (auto [a, b] : {std::pair{&st.sun, &per_gear.stage.sun}, {&st.planet, &per_gear.stage.planet},
                      {&st.ring, &per_gear.stage.ring}}) {
    CHECK(a->module == b->module);
    CHECK(a->pressure_angle == b->pressure_angle);
    CHECK(a->helix.hand == b->helix.hand);
    CHECK(a->tip_radius == b->tip_radius);
  }
  const geometry::Stage stage = transmission::MakeStage(s);
  CHECK(stage.planets() == 3);
}

TEST_CASE("helix angle 0 is the spur scene, bit for bit", "[unit][transmission]") {
  const transmission::Scene spur = epicycle::test::PaperScene();
  const std::string text = SceneText("paper_stage.toml") +
                           "\n[helix]\nhelix_angle_deg = 0.0\nsun_hand = \"left\"\n";
  const transmission::Scene zero = transmission::ParseScene(text, "paper_stage.toml");
  CHECK_FALSE(transmission::IsHelical(zero));
  for (auto [a, b] : {std::pair{&spur.stage.sun, &zero.stage.sun},
                      {&spur.stage.planet, &zero.stage.planet},
                      {&spur.stage.ring, &zero.stage.ring}}) {
    CHECK(a->module == b->module);
    CHECK(a->pressure_angle == b->pressure_angle);
    CHECK(a->profile_shift == b->profile_shift);
    CHECK(a->tip_radius == b->tip_radius);
    CHECK(a->root_radius == b->root_radius);
  }
  CHECK(spur.stage.carrier_radius == zero.stage.carrier_radius);
  CHECK_NOTHROW(transmission::RequireSpur(zero, "a driver"));
}

TEST_CASE("the planar model's drivers refuse a helical scene, naming its key",
          "[unit][transmission]") {
  const transmission::Scene s = Grc();
  const std::string m =
      test::ThrownMessage([&] { transmission::RequireSpur(s, "`epicycle quasistatic`"); });
  CHECK_THAT(m, Contains("grc_helical_stage.toml:") && Contains("helix.helix_angle_deg = 7.5") &&
                    Contains("`epicycle quasistatic` computes the planar (spur) model") &&
                    Contains("`epicycle geometry`"));
  // Through the FE compliance every driver builds: refused before any table is built.
  const geometry::Stage stage = transmission::MakeStage(s);
  CHECK_THROWS_WITH(transmission::FeStageCompliance(s, stage, {}),
                    Contains("helix.helix_angle_deg = 7.5") && Contains("planar (spur) model"));
  // A [[fit]] solves a spur stage's shift: a helical stage gives its shifts.
  const std::string fit = SceneText("grc_helical_stage.toml") +
                          "\n[[fit]]\ngear = \"ring\"\nnormal_backlash_um = 150.0\n";
  CHECK_THROWS_WITH(Grc(Replace(fit, "profile_shift = 0.04 ", "# ")),
                    Contains("fit[0].gear = \"ring\"") && Contains("a helical stage"));
}
