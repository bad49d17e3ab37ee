// The geometry suite builds the shipped scenes' gears through geometry's API alone
// (support/geometry_fixtures.hpp); reading the scene files must give exactly those specs, field by
// field and bit for bit, so that the geometry suite tests the stages the scenes describe.
#include <catch2/catch.hpp>

#include <string>

#include "epicycle/transmission/scene.hpp"
#include "geometry_fixtures.hpp"
#include "stage_fixtures.hpp"

using namespace epicycle::geometry;

namespace {

void CheckSame(const Relief& scene, const Relief& fixture) {
  CHECK(scene.amount == fixture.amount);
  CHECK(scene.start_radius == fixture.start_radius);
  CHECK(scene.shape == fixture.shape);
}

void CheckSame(const GearSpec& scene, const GearSpec& fixture) {
  INFO(scene.name);
  CHECK(scene.name == fixture.name);
  CHECK(scene.kind == fixture.kind);
  CHECK(scene.teeth == fixture.teeth);
  CHECK(scene.module == fixture.module);
  CHECK(scene.face_width == fixture.face_width);
  CHECK(scene.pressure_angle == fixture.pressure_angle);
  CHECK(scene.profile_shift == fixture.profile_shift);
  CHECK(scene.tip_radius == fixture.tip_radius);
  CHECK(scene.tip_round_radius == fixture.tip_round_radius);
  CHECK(scene.root_radius == fixture.root_radius);
  CHECK(scene.root_round_radius == fixture.root_round_radius);
  CHECK(scene.hub_radius == fixture.hub_radius);
  REQUIRE(scene.rack.has_value() == fixture.rack.has_value());
  if (scene.rack) {
    CHECK(scene.rack->addendum == fixture.rack->addendum);
    CHECK(scene.rack->dedendum == fixture.rack->dedendum);
    CHECK(scene.rack->tip_radius == fixture.rack->tip_radius);
  }
  REQUIRE(scene.shaper.has_value() == fixture.shaper.has_value());
  if (scene.shaper) {
    CHECK(scene.shaper->teeth == fixture.shaper->teeth);
    CHECK(scene.shaper->profile_shift == fixture.shaper->profile_shift);
    CHECK(scene.shaper->tip_radius == fixture.shaper->tip_radius);
    CHECK(scene.shaper->tip_round_radius == fixture.shaper->tip_round_radius);
  }
  CHECK(scene.thickness_error == fixture.thickness_error);
  CHECK(scene.min_tip_thickness == fixture.min_tip_thickness);
  CheckSame(scene.modification.tip, fixture.modification.tip);
  CheckSame(scene.modification.root, fixture.modification.root);
  CHECK(scene.pitch_deviations == fixture.pitch_deviations);
}

void CheckSame(const StageSpec& scene, const StageSpec& fixture) {
  CheckSame(scene.sun, fixture.sun);
  CheckSame(scene.planet, fixture.planet);
  CheckSame(scene.ring, fixture.ring);
  CHECK(scene.planets == fixture.planets);
  CHECK(scene.carrier_radius == fixture.carrier_radius);
  CHECK(scene.planet_angles == fixture.planet_angles);
  CHECK(scene.pin_errors.size() == fixture.pin_errors.size());
  CHECK(scene.planet_runouts.size() == fixture.planet_runouts.size());
  CHECK(scene.planet_thickness_errors == fixture.planet_thickness_errors);
  CHECK(scene.sun_runout.amplitude == fixture.sun_runout.amplitude);
  CHECK(scene.ring_runout.amplitude == fixture.ring_runout.amplitude);
  CHECK(scene.load_sign == fixture.load_sign);
  CHECK(scene.min_planet_gap == fixture.min_planet_gap);
}

}  // namespace

TEST_CASE("the geometry suite's paper stage is scenes/paper_stage.toml as read",
          "[unit][transmission][scene]") {
  for (const double backlash_um : {150.0, 0.0}) {
    INFO("backlash " << backlash_um << " um");
    const epicycle::transmission::Scene scene = backlash_um == 150.0
                                                    ? epicycle::test::PaperScene()
                                                    : epicycle::test::ZeroBacklashPaperScene();
    const epicycle::test::PaperStageFixture fixture = epicycle::test::PaperStage(backlash_um);
    CheckSame(scene.stage, fixture.stage);
    REQUIRE(scene.fits.size() == fixture.fits.size());
    for (std::size_t k = 0; k < scene.fits.size(); ++k) {
      CHECK(scene.fits[k].profile_shift == fixture.fits[k].profile_shift);
      CHECK(scene.fits[k].normal_backlash == fixture.fits[k].normal_backlash);
    }
  }
}

TEST_CASE("the geometry suite's ISO 20/40 pair is scenes/iso_pair_20_40.toml as read",
          "[unit][transmission][scene]") {
  const auto scene = epicycle::transmission::ParseScene(
      epicycle::test::SceneText("iso_pair_20_40.toml"), "iso_pair_20_40.toml");
  REQUIRE(scene.kind == epicycle::transmission::SceneKind::kPair);
  const PairSpec fixture = epicycle::test::IsoPair2040();
  CheckSame(scene.pair.gear1, fixture.gear1);
  CheckSame(scene.pair.gear2, fixture.gear2);
  CHECK(scene.pair.centre_distance == fixture.centre_distance);
  CHECK(scene.pair.load_sign == fixture.load_sign);
}

TEST_CASE("a relief's start given by roll angle is the geometry suite's ReliefStartRadius",
          "[unit][transmission][scene]") {
  const auto scene = epicycle::transmission::ParseScene(
      epicycle::test::Replace(epicycle::test::SceneText("paper_stage.toml"), "[sun.cutter]",
                              "[sun.modification]\ntip_relief_um = 8.0\n"
                              "tip_relief_start_roll_deg = 30.0\n[sun.cutter]"),
      "paper_stage.toml + sun relief");
  CHECK(scene.stage.sun.modification.tip.start_radius ==
        epicycle::test::ReliefStartRadius(scene.stage.sun, 30.0));
}
