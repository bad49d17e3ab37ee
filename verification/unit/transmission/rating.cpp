// The ratings' composition (transmission/rating.hpp) on a hand-made run summary: each load factor
// scales σ_F linearly and σ_H as its square root, the safety factors are the permissible stress
// over the stress (Y_ST = 2, Y_M = 0.7 for planets), the model's own columns come from the run's
// root stresses and line-of-action pressures, and missing inputs are named.
#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>

#include "epicycle/transmission/rating.hpp"
#include "stage_fixtures.hpp"

using namespace epicycle;
using namespace epicycle::transmission;

namespace {

Scene RatedScene() {
  Scene s = test::PaperScene();
  s.material.bending_limit = 430e6;
  s.material.contact_limit = 1500e6;
  return s;
}

// Three planets with L_i = 1.2, 1.05, 0.75 at their worst positions.
SweepSummary Summary() {
  SweepSummary s;
  s.converged = 10;
  s.lsr_max = {0.4, 0.35, 0.25};
  return s;
}

}  // namespace

TEST_CASE("The standard's table of K_gamma", "[unit][transmission][rating]") {
  const double expected[] = {1.0, 1.0, 1.0, 1.2, 1.3, 1.4, 1.4, 1.4};
  for (int n = 1; n <= 8; ++n) CHECK(TableMeshLoadFactor(n) == expected[n - 1]);
  CHECK_THROWS_AS(TableMeshLoadFactor(0), std::invalid_argument);
}

TEST_CASE("Ratings scale with the load factors", "[unit][transmission][rating]") {
  Scene scene = RatedScene();
  const geometry::Stage stage(scene.stage);
  const StageRating base = RateStage(scene, stage, Summary());
  scene.rating.application_factor = 1.5;
  const StageRating ka = RateStage(scene, stage, Summary(), 1.1, "a dynamic run");
  REQUIRE(base.gears.size() == 5);  // sun, 3 planets, ring
  const double k_model[] = {1.2, 1.2, 1.05, 0.75, 1.2};  // sun and ring meet the worst planet
  for (std::size_t i = 0; i < base.gears.size(); ++i) {
    const GearRating &g = base.gears[i], &h = ka.gears[i];
    INFO(g.gear);
    CHECK(g.k_gamma_table == 1.0);
    CHECK(g.k_gamma_model == Approx(k_model[i]).epsilon(1e-15));
    const double ym = g.gear.rfind("planet", 0) == 0 ? 0.7 : 1.0;
    CHECK(g.reversed_bending == ym);
    // Bending: linear in K_γ and K_A K_v; S_F σ_F = σ_Flim Y_ST Y_M.
    if (g.gear != "ring") {
      CHECK(g.sigma_f_table == Approx(g.sigma_f0).epsilon(1e-15));
      CHECK(g.sigma_f_model == Approx(g.sigma_f0 * k_model[i]).epsilon(1e-15));
      CHECK(h.sigma_f_model == Approx(g.sigma_f_model * 1.5 * 1.1).epsilon(1e-15));
      CHECK(g.s_f_model * g.sigma_f_model == Approx(430e6 * 2 * ym).epsilon(1e-15));
    } else {  // not rated by method B: NaN with the reason
      CHECK(std::isnan(g.sigma_f0));
      CHECK_THAT(g.note, Catch::Matchers::Contains("bending not rated"));
    }
    // Contact: as the square root; S_H σ_H = σ_Hlim.
    CHECK(g.sigma_h_model ==
          Approx(g.z_bd * g.sigma_h0 * std::sqrt(k_model[i])).epsilon(1e-15));
    CHECK(h.sigma_h_model == Approx(g.sigma_h_model * std::sqrt(1.5 * 1.1)).epsilon(1e-15));
    CHECK(g.s_h_model * g.sigma_h_model == Approx(1500e6).epsilon(1e-15));
    // Without the run's stresses the model's own columns are missing, and say why.
    CHECK(std::isnan(g.root_stress));
    CHECK(std::isnan(g.s_h_pressure));
    CHECK_THAT(g.note, Catch::Matchers::Contains("[model] stresses"));
  }
  // The planets' contact rating is governed by the sun mesh (Z_D = 1 there, the larger σ_H0).
  CHECK(base.gears[1].contact_mesh == "sun-planet1");
  CHECK(base.gears[2].contact_mesh == "sun-planet2");
}

TEST_CASE("Ratings from the run's own stresses", "[unit][transmission][rating]") {
  const Scene scene = RatedScene();
  const geometry::Stage stage(scene.stage);
  SweepSummary s = Summary();
  RootStressSummary sun;
  sun.extremes.body = kSunBody;
  sun.extremes.tension = 200e6;
  sun.extremes.compression = -250e6;
  s.root_stress.push_back(sun);
  auto flank = [](bool drive, double pressure, bool tip) {
    FlankPressure f;
    f.body = kSunBody;
    f.drive = drive;
    f.pressure = pressure;
    f.tip = tip;
    return f;
  };
  const FlankPressure drive_loa = flank(true, 1000e6, false);
  const FlankPressure drive_tip = flank(true, 4000e6, true);  // a corner: reported, not rated
  const FlankPressure coast = flank(false, 3000e6, false);
  s.contact_pressure = {drive_loa, drive_tip, coast};
  const GearRating g = RateStage(scene, stage, s).gears.front();
  CHECK(g.root_stress == 200e6);
  CHECK(g.s_f_stress == Approx(430e6 * 2 / 200e6).epsilon(1e-15));
  CHECK(g.contact_pressure == 1000e6);
  CHECK(g.s_h_pressure == Approx(1.5).epsilon(1e-15));
}

TEST_CASE("A dynamic rating: the ISO columns take K_v, the stresses in motion do not",
          "[unit][transmission][rating]") {
  const Scene scene = RatedScene();
  const geometry::Stage stage(scene.stage);
  SweepSummary at_rest = Summary();  // the quasi-static reference: its own stresses are not used
  RootStressSummary rest;
  rest.extremes.body = kSunBody;
  rest.extremes.tension = 150e6;
  at_rest.root_stress.push_back(rest);
  MotionStresses motion;
  motion.source = "a run in motion";
  RootStressSummary moving = rest;
  moving.extremes.tension = 240e6;
  motion.root_stress.push_back(moving);
  FlankPressure p;
  p.body = kSunBody;
  p.pressure = 1200e6;
  motion.contact_pressure.push_back(p);
  const double kv = 1.25;
  const StageRating still = RateStage(scene, stage, at_rest);
  const StageRating dynamic = RateStage(scene, stage, at_rest, kv, "the run", &motion);
  const GearRating &g = still.gears.front(), &h = dynamic.gears.front();
  // ISO 6336: σ_F ∝ K_v, σ_H ∝ √K_v, with K_γ of the reference.
  CHECK(h.sigma_f_model == Approx(g.sigma_f_model * kv).epsilon(1e-15));
  CHECK(h.sigma_h_model == Approx(g.sigma_h_model * std::sqrt(kv)).epsilon(1e-15));
  CHECK(h.k_gamma_model == g.k_gamma_model);
  // The model's own: the stresses in motion, K_A = 1 and no K_v (they carry the dynamics).
  CHECK(h.root_stress == 240e6);
  CHECK(h.s_f_stress == Approx(430e6 * 2 / 240e6).epsilon(1e-15));
  CHECK(h.contact_pressure == 1200e6);
  CHECK(h.s_h_pressure == Approx(1500.0 / 1200.0).epsilon(1e-15));
  bool listed = false;
  for (const RatingFactor& f : dynamic.factors)
    listed = listed || f.source.find("a run in motion") != std::string::npos;
  CHECK(listed);
}

TEST_CASE("A rating without its inputs is refused by name", "[unit][transmission][rating]") {
  Scene scene = test::PaperScene();
  const geometry::Stage stage(scene.stage);
  try {
    CheckRatingInputs(scene, "--rating");
    FAIL("no error");
  } catch (const std::invalid_argument& e) {
    CHECK_THAT(std::string(e.what()),
               Catch::Matchers::Contains("--rating needs the scene's [material] "
                                         "bending_limit_MPa (ISO 6336-5's sigma_Flim)"));
  }
  scene.material.bending_limit = 430e6;
  CHECK_THROWS_WITH(RateStage(scene, stage, Summary()),
                    Catch::Matchers::Contains("[material] contact_limit_MPa"));
  scene.material.contact_limit = 1500e6;
  SweepSummary none = Summary();
  none.converged = 0;
  CHECK_THROWS_AS(RateStage(scene, stage, none), std::runtime_error);
  CHECK_THROWS_AS(RateStage(scene, stage, Summary(), 0.9), std::invalid_argument);
}
