// The ratings' composition (transmission/rating.hpp) on a hand-made run summary: each load factor
// scales σ_F linearly and σ_H as its square root, the safety factors are the permissible stress
// over the stress (Y_ST = 2, Y_M = 0.7 for planets), the model's own columns come from the run's
// root stresses and line-of-action pressures, and missing inputs are named.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>

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
  const StageRating base = RateStage(RatingInputsOf(scene), stage, Summary());
  scene.rating.application_factor = 1.5;
  const StageRating ka = RateStage(RatingInputsOf(scene), stage, Summary(), 1.1, "a dynamic run");
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
  const GearRating g = RateStage(RatingInputsOf(scene), stage, s).gears.front();
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
  const StageRating still = RateStage(RatingInputsOf(scene), stage, at_rest);
  const StageRating dynamic =
      RateStage(RatingInputsOf(scene), stage, at_rest, kv, "the run", &motion);
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
    CheckRatingInputs(RatingInputsOf(scene), "--rating");
    FAIL("no error");
  } catch (const std::invalid_argument& e) {
    CHECK_THAT(std::string(e.what()),
               Catch::Matchers::Contains("--rating needs the scene's [material] "
                                         "bending_limit_MPa (ISO 6336-5's sigma_Flim)"));
  }
  scene.material.bending_limit = 430e6;
  CHECK_THROWS_WITH(RateStage(RatingInputsOf(scene), stage, Summary()),
                    Catch::Matchers::Contains("[material] contact_limit_MPa"));
  scene.material.contact_limit = 1500e6;
  SweepSummary none = Summary();
  none.converged = 0;
  CHECK_THROWS_AS(RateStage(RatingInputsOf(scene), stage, none), std::runtime_error);
  CHECK_THROWS_AS(RateStage(RatingInputsOf(scene), stage, Summary(), 0.9), std::invalid_argument);
}

// The rating inputs are resolved once from the scene; a scene made in code with a value the
// reader would refuse is refused there, naming the scene's key.
TEST_CASE("The rating inputs of a scene name its keys", "[unit][transmission][rating]") {
  Scene scene = RatedScene();
  const RatingInputs in = RatingInputsOf(scene);
  CHECK(in.bending_limit == 430e6);
  CHECK(in.contact_limit == 1500e6);
  CHECK(in.sun_torque == scene.loads.sun_torque);
  CHECK(in.application_factor == 1.0);
  CHECK(in.youngs_modulus == scene.material.youngs_modulus);
  scene.rating.application_factor = 0.5;
  CHECK_THROWS_WITH(RatingInputsOf(scene),
                    Catch::Contains("[rating] application_factor = 0.5: must be in [1, 4]"));
  scene = RatedScene();
  scene.material.poisson_ratio = 0.5;
  CHECK_THROWS_WITH(RatingInputsOf(scene),
                    Catch::Contains("[material] poisson_ratio = 0.5: must be in [0, 0.5)"));
}

// ISO 6336-1 clause 7.5, K_Hβ by method C (docs/model.md §10 "Ratings across the face": the
// sources), in the standard's own units (µm, N/mm, N/(mm·µm)) worked by hand here:
// F_βx = 1.33 B1 f_sh + B2 f_ma, at least F_βx,min = max(0.005 F_m/b, 0.5 f_Hβ); y_β = 0.15 F_βx,
// at most 6 µm (case-hardened); F_βy = F_βx − y_β; c_γβ = 0.85 c_γα;
// K_Hβ = 1 + F_βy c_γβ/(2 F_m/b) up to 2, else √(2 F_βy c_γβ/(F_m/b)); K_Fβ = K_Hβ^N_F with
// N_F = (b/h)²/(1 + b/h + (b/h)²), b/h at least 3. The function works in SI: the conversions are
// exact up to round-off, so 1e-12 relative.
TEST_CASE("ISO 6336-1 method C: K_Hbeta and K_Fbeta from the misalignment and c_gamma",
          "[unit][transmission][rating][face_width]") {
  const double tol = 1e-12;
  FaceLoadFactorInputs in;
  in.face_width = 25e-3;        // b = 25 mm
  in.mean_force = 6000;         // F_m/b = 240 N/mm
  in.mesh_stiffness = 17.56e9;  // c_γα = 17.56 N/(mm·µm)
  in.tooth_depth = 5e-3;        // b/h = 5
  SECTION("the whole face carries: a pin's tilt of 9.34 um across the mesh") {
    in.assembly = 9.34e-6;
    const FaceLoadFactorC c = IsoFaceLoadFactorC(in);
    // F_βx = 9.34, y_β = 1.401, F_βy = 7.939 µm; c_γβ = 14.926; x = 7.939·14.926/480.
    const double f_beta_y = 9.34 * 0.85, x = f_beta_y * 0.85 * 17.56 / (2 * 240.0);
    CHECK(c.f_beta_x == Approx(9.34e-6).epsilon(tol));
    CHECK(c.y_beta == Approx(0.15 * 9.34e-6).epsilon(tol));
    CHECK(c.f_beta_y == Approx(f_beta_y * 1e-6).epsilon(tol));
    CHECK(c.c_gamma_beta == Approx(0.85 * 17.56e9).epsilon(tol));
    CHECK_FALSE(c.lifted);
    CHECK(c.k_h_beta == Approx(1 + x).epsilon(tol));
    CHECK(c.k_h_beta == Approx(1.24687).epsilon(1e-5));  // the same by a calculator
    CHECK(c.n_f == Approx(25.0 / 31.0).epsilon(tol));    // 25/(1 + 5 + 25)
    CHECK(c.k_f_beta == Approx(std::pow(1 + x, 25.0 / 31.0)).epsilon(tol));
  }
  SECTION("part of the face lifts: the square-root branch, continuous at K_Hbeta = 2") {
    in.assembly = 50e-6;  // F_βx = 50 µm: y_β = 7.5 µm capped at 6 µm, F_βy = 44 µm
    const FaceLoadFactorC c = IsoFaceLoadFactorC(in);
    CHECK(c.y_beta == Approx(6e-6).epsilon(tol));
    CHECK(c.f_beta_y == Approx(44e-6).epsilon(tol));
    CHECK(c.lifted);
    CHECK(c.k_h_beta == Approx(std::sqrt(2 * 44 * 0.85 * 17.56 / 240.0)).epsilon(tol));
    // At x = 1 both branches give 2: F_βy = 2 F_m/b / c_γβ, i.e. F_βx = F_βy/0.85.
    in.assembly = 2 * 240.0 / (0.85 * 17.56) / 0.85 * 1e-6;
    CHECK(IsoFaceLoadFactorC(in).k_h_beta == Approx(2.0).epsilon(1e-9));
  }
  SECTION("deformation counts 1.33 times, and F_betax has its minimum") {
    in.deflection = 3e-6;
    in.assembly = 1e-6;
    CHECK(IsoFaceLoadFactorC(in).f_beta_x == Approx((1.33 * 3 + 1) * 1e-6).epsilon(tol));
    in.deflection = in.assembly = 0;
    in.lead_slope = 2e-6;  // 0.5 f_Hβ = 1 µm < 0.005 F_m/b = 1.2 µm: the load's term binds
    const FaceLoadFactorC c = IsoFaceLoadFactorC(in);
    CHECK(c.f_beta_x_min == Approx(0.005 * 240 * 1e-6).epsilon(tol));  // 1.2 µm
    CHECK(c.f_beta_x == c.f_beta_x_min);
    CHECK(c.at_minimum);
    CHECK(c.k_h_beta == Approx(1 + 1.2 * 0.85 * 0.85 * 17.56 / 480.0).epsilon(tol));
  }
  SECTION("a lead slope with little misalignment: F_betax,min = 0.5 f_Hbeta binds") {
    // f_Hβ = 12 µm, f_ma = 1 µm (say a pin tilt that cancels most of the slope), f_sh = 0:
    // 1.33·1·0 + 1·1 = 1 µm < F_βx,min = max(0.005·240, 0.5·12) = max(1.2, 6) = 6 µm.
    // y_β = 0.15·6 = 0.9 µm, F_βy = 5.1 µm; c_γβ = 0.85·17.56 = 14.926 N/(mm·µm);
    // x = 5.1·14.926/(2·240) = 76.1226/480 = 0.15858875 ≤ 1: K_Hβ = 1.15858875.
    in.assembly = 1e-6;
    in.lead_slope = 12e-6;
    const FaceLoadFactorC c = IsoFaceLoadFactorC(in);
    CHECK(c.f_beta_x_min == Approx(6e-6).epsilon(tol));
    CHECK(c.at_minimum);
    CHECK(c.f_beta_x == Approx(6e-6).epsilon(tol));
    CHECK(c.y_beta == Approx(0.9e-6).epsilon(tol));
    CHECK(c.f_beta_y == Approx(5.1e-6).epsilon(tol));
    CHECK_FALSE(c.lifted);
    CHECK(c.k_h_beta == Approx(1.15858875).epsilon(tol));
    // Without the minimum (f_Hβ = 0) the same mesh would take F_βx = 1.2 µm: K_Hβ = 1 +
    // 1.02·14.926/480 = 1 + 15.22452/480 = 1.03171775, the understatement the minimum prevents.
    in.lead_slope = 0;
    CHECK(IsoFaceLoadFactorC(in).k_h_beta == Approx(1.03171775).epsilon(tol));
    in.lead_slope = -1e-6;
    CHECK_THROWS_WITH(IsoFaceLoadFactorC(in), Catch::Contains("f_Hbeta [m] = -1e-06"));
  }
  SECTION("B1 and B2 of each helix modification weigh f_sh and f_ma") {
    // ISO 6336-1 method C's table (docs/model.md §10): with f_ma = 8 µm, f_sh = 3 µm,
    // 0.5 (f_ma + f_sh) = 5.5 µm:
    const double fma = 8e-6, fsh = 3e-6;
    using B = std::array<double, 2>;
    CHECK(MethodCModification(0, false, fma, fsh) == B{1.0, 1.0});       // none
    CHECK(MethodCModification(6e-6, false, fma, fsh) == B{0.5, 0.5});    // C_β = 6 ≥ 5.5
    CHECK(MethodCModification(5.5e-6, false, fma, fsh) == B{0.5, 0.5});  // the row's own C_β
    CHECK(MethodCModification(4e-6, false, fma, fsh) == B{1.0, 0.5});    // C_β = 4 < 5.5
    CHECK(MethodCModification(0, true, fma, fsh) == B{0.7, 0.7});        // end relief
    CHECK(MethodCModification(6e-6, true, fma, fsh) == B{0.5, 0.5});     // crowning taken
    CHECK_THROWS_WITH(MethodCModification(-1e-6, false, fma, fsh),
                      Catch::Contains("C_beta [m] = -1e-06: must be finite and >= 0"));
    in.deflection = fsh;
    in.assembly = fma;
    // F_βx of each row: none 1.33·3 + 8 = 11.99; crowned for both 0.5·3.99 + 0.5·8 = 5.995;
    // crowned for f_ma 3.99 + 4 = 7.99; end relief 0.7·3.99 + 0.7·8 = 8.393 µm.
    const std::pair<B, double> rows[] = {
        {{1.0, 1.0}, 11.99}, {{0.5, 0.5}, 5.995}, {{1.0, 0.5}, 7.99}, {{0.7, 0.7}, 8.393}};
    for (const auto& [b, f_beta_x] : rows) {
      in.b1 = b[0];
      in.b2 = b[1];
      CHECK(IsoFaceLoadFactorC(in).f_beta_x == Approx(f_beta_x * 1e-6).epsilon(tol));
    }
    in.b1 = 1.5;
    CHECK_THROWS_WITH(IsoFaceLoadFactorC(in), Catch::Contains("B1 = 1.5: must be in (0, 1]"));
    in.b1 = 1;
    in.b2 = 0;
    CHECK_THROWS_WITH(IsoFaceLoadFactorC(in), Catch::Contains("B2 = 0: must be finite and > 0"));
  }
  SECTION("b/h below 3 counts as 3") {
    in.tooth_depth = 10e-3;  // b/h = 2.5
    CHECK(IsoFaceLoadFactorC(in).n_f == Approx(9.0 / 13.0).epsilon(tol));
  }
  SECTION("bad inputs are named") {
    in.mean_force = 0;
    CHECK_THROWS_WITH(IsoFaceLoadFactorC(in), Catch::Contains("F_m [N] = 0"));
    in.mean_force = 6000;
    in.assembly = -1e-6;
    CHECK_THROWS_WITH(IsoFaceLoadFactorC(in), Catch::Contains("f_ma [m]"));
  }
}

TEST_CASE("A rating across the face width: the model's K_Hbeta beside method C's, the safety "
          "factors of the stresses per slice",
          "[unit][transmission][rating][face_width]") {
  const Scene scene = RatedScene();
  const geometry::Stage stage(scene.stage);
  SweepSummary s = Summary();
  MeshFaceSummary sun_mesh;
  sun_mesh.mesh = "sun-planet1";
  sun_mesh.k_h_beta_max = 1.4;
  sun_mesh.k_gamma_k_h_beta_max = 1.5;
  sun_mesh.misalignment_assembly = -9.34e-6;  // a sign: the end it opens; ISO takes |f_ma|
  sun_mesh.stresses = true;
  sun_mesh.root_stress_max = 250e6;
  sun_mesh.root_stress_gear = "planet1";
  sun_mesh.hertz_pressure_max = 1200e6;
  s.face_width = {sun_mesh};
  const std::array<double, 2> c{17.56e9, 23.61e9};
  // Without the meshes' stiffness no face-width rating; with it, one per mesh.
  CHECK(RateStage(RatingInputsOf(scene), stage, s).face_width.empty());
  const StageRating rating =
      RateStage(RatingInputsOf(scene), stage, s, 1.0, "quasi-static", nullptr, &c);
  REQUIRE(rating.face_width.size() == 1);
  const MeshFaceRating& m = rating.face_width.front();
  CHECK(m.k_gamma_model == Approx(1.2).epsilon(1e-15));  // 3 × 0.4
  CHECK(m.k_h_beta_model == 1.4);
  CHECK(m.iso_inputs.assembly == Approx(9.34e-6).epsilon(1e-15));
  // F_m = F_t K_A K_γ(table) K_v = T_s/(3 r_s) with K_A = K_γ = K_v = 1 for three planets.
  const double ft = std::abs(scene.loads.sun_torque) / (3 * stage.sun().reference_radius());
  CHECK(m.iso_inputs.mean_force == Approx(ft).epsilon(1e-15));
  CHECK(m.iso_inputs.mesh_stiffness == 17.56e9);
  const double x = 0.85 * 9.34e-6 * 0.85 * 17.56e9 * 25e-3 / (2 * ft);
  CHECK(m.iso.k_h_beta == Approx(1 + x).epsilon(1e-12));
  CHECK(m.k_gamma_k_h_beta_iso == Approx(1 + x).epsilon(1e-12));  // K_γ table = 1
  CHECK(m.k_gamma_k_h_beta_model == 1.5);
  // A planet's fillet: Y_M = 0.7, Y_ST = 2.
  CHECK(m.s_f_stress == Approx(430e6 * 2 * 0.7 / 250e6).epsilon(1e-15));
  CHECK(m.s_h_pressure == Approx(1500.0 / 1200.0).epsilon(1e-15));
  CHECK(m.iso_inputs.b1 == 1);  // no lead modification
  CHECK(m.iso_inputs.b2 == 1);
  // A crowned planet: method C's B1 = B2 = 0.5 halve the misalignment it takes, and the
  // factors list says so.
  Scene crowned = scene;
  LeadSpec lead;
  lead.gear = "planet1";
  lead.crowning = 5e-6;
  crowned.face_width.leads = {lead};
  const StageRating c_rating =
      RateStage(RatingInputsOf(crowned), stage, s, 1.0, "quasi-static", nullptr, &c);
  const MeshFaceRating& mc = c_rating.face_width.front();
  CHECK(mc.iso_inputs.b1 == 0.5);
  CHECK(mc.iso_inputs.b2 == 0.5);
  const double xc = 0.85 * 0.5 * 9.34e-6 * 0.85 * 17.56e9 * 25e-3 / (2 * ft);
  CHECK(mc.iso.k_h_beta == Approx(1 + xc).epsilon(1e-12));
  bool listed = false;
  for (const RatingFactor& f : c_rating.factors) listed = listed || f.symbol == "B1 = B2 sun-planet1";
  CHECK(listed);
  // A lead slope of the sun, f_Hβ = 12 µm, with a mesh misalignment of 0.5 µm (the rest taken
  // up): method C's F_βx is its minimum 0.5 f_Hβ = 6 µm (0.005 µm per N/mm of F_m/b = 236 N/mm
  // is 1.18 µm here), so x = 0.85·6e-6·0.85 c_γα b/(2 F_m).
  Scene sloped = scene;
  LeadSpec slope;
  slope.gear = "sun";
  slope.slope = -12e-6;  // the sign says which way; the standard takes |f_Hβ|
  sloped.face_width.leads = {slope};
  SweepSummary little = s;
  little.face_width.front().misalignment_assembly = 0.5e-6;
  const MeshFaceRating& ms =
      RateStage(RatingInputsOf(sloped), stage, little, 1.0, "quasi-static", nullptr, &c)
          .face_width.front();
  CHECK(0.005 * ft / 25.0 < 6.0);  // 0.005 µm × F_m/b [N/mm] below 0.5 f_Hβ [µm]
  CHECK(ms.iso_inputs.lead_slope == 12e-6);
  CHECK(ms.iso.at_minimum);
  CHECK(ms.iso.f_beta_x == Approx(6e-6).epsilon(1e-15));
  const double xs = 0.85 * 6e-6 * 0.85 * 17.56e9 * 25e-3 / (2 * ft);
  CHECK(ms.iso.k_h_beta == Approx(1 + xs).epsilon(1e-12));
}
