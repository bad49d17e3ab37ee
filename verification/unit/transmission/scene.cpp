// Scene files: units in every key; unknown, missing, mistyped and out-of-range keys are errors
// naming the file, line, key, value and rule.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "epicycle/transmission/scene.hpp"
#include "stage_fixtures.hpp"

using Catch::Matchers::Contains;
using epicycle::test::Replace;
using epicycle::test::SceneText;
using epicycle::transmission::ParseScene;

namespace {

auto Parse(const std::string& text) { return ParseScene(text, "s.toml"); }

}  // namespace

TEST_CASE("the paper's scenes load with SI values", "[unit][transmission]") {
  const auto s = Parse(SceneText("paper_stage.toml"));
  CHECK(s.stage.sun.module == Approx(4.23e-3));
  CHECK(s.stage.sun.pressure_angle == Approx(25.0 * 3.14159265358979 / 180));
  CHECK(s.stage.ring.hub_radius == Approx(156.4e-3));
  CHECK(s.material.youngs_modulus == Approx(207e9));
  CHECK(s.loads.sun_torque == -600.0);
  CHECK(s.stage.load_sign == -1);
  CHECK(s.stage.carrier_radius == Approx(86.715e-3));
  // Tip radius from the addendum coefficient: r + (x + 1) m.
  CHECK(s.stage.sun.tip_radius == Approx((8 + 0.3 + 1.0) * 4.23e-3));
  REQUIRE(s.fits.size() == 2);
  CHECK(s.stage.planet.profile_shift == s.fits[0].profile_shift);
  CHECK(s.stage.ring.profile_shift == s.fits[1].profile_shift);
  const auto s4 = Parse(SceneText("paper_stage_4planets.toml"));
  CHECK(s4.stage.planets == 4);
  CHECK(s4.stage.ring.shaper.has_value());
  CHECK_NOTHROW(epicycle::geometry::Stage(s4.stage));
}

TEST_CASE("unknown, missing, mistyped and out-of-range keys", "[unit][transmission]") {
  const std::string base = SceneText("paper_stage.toml");
  CHECK_THROWS_WITH(
      Parse(Replace(
          base,
          "module_mm = 4.23\nface_width_mm = 25.0\npressure_angle_deg = 25.0\nprofile_shift = 0.30",
          "modul_mm = 4.23\nface_width_mm = 25.0\npressure_angle_deg = 25.0\nprofile_shift = "
          "0.30")),
      Contains("sun.module_mm is missing"));
  CHECK_THROWS_WITH(
      Parse(Replace(base, "radius_mm = 86.715", "radius_mm = 86.715\nradius_in = 3.4")),
      Contains("carrier.radius_in: unknown key") && Contains("known keys here:") &&
          Contains("radius_mm"));
  // The message carries the line of the offending key.
  const auto line = 1 + std::count(base.begin(), base.begin() + base.find("teeth = 16"), '\n');
  CHECK_THROWS_WITH(Parse(Replace(base, "teeth = 16", "teeth = \"16\"")),
                    Contains("s.toml:" + std::to_string(line) +
                             ": sun.teeth = \"16\": must be an integer, not a string"));
  CHECK_THROWS_WITH(Parse(Replace(base, "face_width_mm = 25.0", "face_width_mm = -25.0")),
                    Contains("sun.face_width_mm = -25: must be in [2.115, 423]"));  // 0.5 m, 100 m
  CHECK_THROWS_WITH(Parse(Replace(base, "poisson_ratio = 0.3", "poisson_ratio = 0.5")),
                    Contains("material.poisson_ratio = 0.5: must be in [0, 0.5)"));
  CHECK_THROWS_WITH(Parse(Replace(base, "sun_torque_Nm = -600.0", "sun_torque_Nm = 0.0")),
                    Contains("load.sun_torque_Nm = 0: must be non-zero"));
  CHECK_THROWS_WITH(Parse(Replace(base, "type = \"direct\"", "type = \"hob\"")),
                    Contains("ring.cutter.type = \"hob\": must be one of \"shaper\", \"direct\""));
  CHECK_THROWS_WITH(Parse(Replace(base, "[scene]", "[scene\n")),
                    Contains("s.toml:") && Contains("TOML syntax error"));
  CHECK_THROWS_WITH(Parse(Replace(base, "gear = \"ring\"", "gear = \"planet\"")),
                    Contains("fit[1].gear = \"planet\": each gear can be fitted once"));
}

TEST_CASE("errors section", "[unit][transmission]") {
  const std::string base =
      SceneText("paper_stage.toml") +
      "\n[[errors.pin]]\ngear = \"planet1\"\ntangential_um = 20.0\n"
      "\n[[errors.runout]]\ngear = \"planet1\"\namplitude_um = 20.0\nphase_deg = 90.0\n"
      "\n[[errors.thickness]]\ngear = \"sun\"\nerror_um = -10.0\n";
  const auto s = Parse(base);
  REQUIRE(s.stage.pin_errors.size() == 3);
  CHECK(s.stage.pin_errors[0].tangential == Approx(20e-6));
  CHECK(s.stage.pin_errors[1].tangential == 0.0);
  CHECK(s.stage.planet_runouts[0].amplitude == Approx(20e-6));
  CHECK(s.stage.planet_runouts[0].phase == Approx(3.14159265358979 / 2));
  CHECK(s.stage.sun.thickness_error == Approx(-10e-6));
  CHECK_THROWS_WITH(Parse(Replace(base, "gear = \"planet1\"\ntangential_um",
                                  "gear = \"planet7\"\ntangential_um")),
                    Contains("errors.pin[0].gear = \"planet7\": must be \"sun\", \"ring\" or "
                             "\"planet1\"..\"planet3\""));
  CHECK_THROWS_WITH(
      Parse(Replace(base, "amplitude_um = 20.0", "amplitude_um = -2.0")),
      Contains("errors.runout[0].amplitude_um = -2: must be in [0, 1057.5]"));  // m/4 [um]
}

TEST_CASE("model and supports tables: values in SI, errors name key, value and rule",
          "[unit][transmission]") {
  const std::string base = SceneText("paper_stage.toml");
  const auto defaults = Parse(base);
  CHECK(defaults.model.plane == epicycle::solvers::PlaneAssumption::kPlaneStrain);
  CHECK(defaults.model.join_depth == 0.0);
  CHECK(defaults.supports.sun == epicycle::transmission::SunSupport::kFixed);
  CHECK(defaults.supports.planet_stiffness == 0.0);
  const auto s = Parse(base +
                       "\n[model]\nplane = \"stress\"\njoin_depth_mm = 0.5\nmesh_refinement = 2\n"
                       "\n[supports]\nsun = \"elastic\"\nsun_stiffness_N_per_um = 300.0\n"
                       "planet_stiffness_N_per_um = 500.0\n");
  CHECK(s.model.plane == epicycle::solvers::PlaneAssumption::kPlaneStress);
  CHECK(s.model.join_depth == Approx(0.5e-3));
  CHECK(s.model.mesh_refinement == 2);
  CHECK(s.supports.sun == epicycle::transmission::SunSupport::kElastic);
  CHECK(s.supports.sun_stiffness == Approx(3e8));  // 300 N/µm
  CHECK(s.supports.planet_stiffness == Approx(5e8));
  CHECK(Parse(base + "\n[supports]\nsun = \"floating\"\n").supports.sun ==
        epicycle::transmission::SunSupport::kFloating);
  CHECK_THROWS_WITH(Parse(base + "\n[model]\nplane = \"shell\"\n"),
                    Contains("model.plane = \"shell\"") && Contains("strain"));
  CHECK_THROWS_WITH(Parse(base + "\n[model]\nmesh_refinement = 9\n"),
                    Contains("model.mesh_refinement = 9"));
  CHECK_THROWS_WITH(Parse(base + "\n[model]\njoin_depth_mm = -1.0\n"),
                    Contains("model.join_depth_mm = -1"));
  CHECK(defaults.model.join_depth_factor == 1.0);
  CHECK(Parse(base + "\n[model]\njoin_depth_factor = 1.5\n").model.join_depth_factor == 1.5);
  // The factor scales h = 0.6 min d; h must stay below min d, so the factor below 1/0.6.
  CHECK_THROWS_WITH(Parse(base + "\n[model]\njoin_depth_factor = 1.7\n"),
                    Contains("model.join_depth_factor = 1.7") && Contains("centre line"));
  CHECK_THROWS_WITH(Parse(base + "\n[model]\njoin_depth_factor = 0.0\n"),
                    Contains("model.join_depth_factor = 0"));
  CHECK_THROWS_WITH(Parse(base + "\n[model]\njoin_depth_mm = 0.5\njoin_depth_factor = 1.2\n"),
                    Contains("model.join_depth_factor = given") && Contains("not both"));
  CHECK_THROWS_WITH(Parse(base + "\n[supports]\nsun = \"elastic\"\n"),
                    Contains("supports.sun_stiffness_N_per_um is missing"));
  // Bearings (docs/scenes.md): 1 .. 1e6 N/um; a planet's 0 is a rigid pin.
  CHECK_THROWS_WITH(Parse(base + "\n[supports]\nsun = \"elastic\"\nsun_stiffness_N_per_um = 0.0\n"),
                    Contains("supports.sun_stiffness_N_per_um = 0: must be in [1, 1000000]"));
  CHECK_THROWS_WITH(Parse(base + "\n[supports]\nsun = \"elastic\"\nsun_stiffness_N_per_um = 1e9\n"),
                    Contains("supports.sun_stiffness_N_per_um = 1000000000: must be in [1, 1000000]"));
  CHECK_THROWS_WITH(Parse(base + "\n[supports]\nplanet_stiffness_N_per_um = -2.0\n"),
                    Contains("supports.planet_stiffness_N_per_um = -2"));
  CHECK_THROWS_WITH(Parse(base + "\n[supports]\nplanet_stiffness_N_per_um = 1e-30\n"),
                    Contains("supports.planet_stiffness_N_per_um = 1e-30: must be in [1, 1000000]") &&
                        Contains("floats"));
  CHECK(Parse(base + "\n[supports]\nplanet_stiffness_N_per_um = 0.0\n").supports.planet_stiffness ==
        0.0);
  // The gap window: 1 um .. m/4 = 1057.5 um on the paper's stage (m = 4.23 mm).
  auto window = [&](const std::string& v) {
    std::string text = base;
    const std::string key = "gap_window_um = 100.0";
    REQUIRE(text.find(key) != std::string::npos);
    return Parse(text.replace(text.find(key), key.size(), "gap_window_um = " + v));
  };
  CHECK_THROWS_WITH(window("1e-300"),
                    Contains("contact.gap_window_um = 1e-300: must be in [1, 1057.5]"));
  CHECK_THROWS_WITH(window("2000.0"), Contains("contact.gap_window_um = 2000: must be in [1, 1057.5]"));
  CHECK(window("1057.5").gap_window == Approx(1057.5e-6));
  // A stiffness given to a sun that is not elastic is an unknown key there, not silently ignored.
  CHECK_THROWS_WITH(
      Parse(base + "\n[supports]\nsun = \"floating\"\nsun_stiffness_N_per_um = 300.0\n"),
      Contains("supports.sun_stiffness_N_per_um"));
}

TEST_CASE("dynamics and lubricant tables: typed SI settings, cross-key rules named at the key",
          "[unit][transmission]") {
  using epicycle::transmission::FrictionLaw;
  const std::string base = SceneText("paper_stage.toml");
  const auto s = Parse(base);
  CHECK(s.dynamics.sun_speed == Approx(1500 * 3.14159265358979 / 30));
  CHECK(s.dynamics.friction.law == FrictionLaw::kXuKahraman);
  CHECK(s.dynamics.friction.lubricant.dynamic_viscosity == Approx(0.05));
  CHECK(s.dynamics.friction.lubricant.composite_roughness == Approx(0.8e-6));
  CHECK_NOTHROW(s.dynamics.Validate());
  // Dry flanks: the constant law takes any μ in [0, 1], the same range the reader documents.
  const auto dry = Parse(Replace(base, "friction = \"xu-kahraman\"",
                                 "friction = \"constant\"\nfriction_coefficient = 0.4"));
  CHECK(dry.dynamics.friction.law == FrictionLaw::kConstant);
  CHECK(dry.dynamics.friction.coefficient == 0.4);
  CHECK_NOTHROW(dry.dynamics.Validate());
  CHECK_THROWS_WITH(
      Parse(Replace(base, "friction = \"xu-kahraman\"", "friction_coefficient = 1.5")),
      Contains("dynamics.friction_coefficient = 1.5: must be in [0, 1]"));
  // The scene's speed has the command line's range (--speed-rpm): 1e12 rpm used to run.
  CHECK_THROWS_WITH(Parse(Replace(base, "sun_speed_rpm = 1500.0", "sun_speed_rpm = 1e12")),
                    Contains("dynamics.sun_speed_rpm = 1e+12: must be in [1, 100000]"));
  // Cross-key rules carry the file and line of the key the user wrote.
  const auto line = 1 + std::count(base.begin(), base.begin() + base.find("sun_speed_rpm"), '\n');
  CHECK_THROWS_WITH(Parse(Replace(base, "sun_speed_rpm = 1500.0", "sun = \"speed\"")),
                    Contains("s.toml:" + std::to_string(line) + ": dynamics.sun = \"speed\"") &&
                        Contains("carrier = \"torque\""));
  CHECK_NOTHROW(
      Parse(Replace(base, "sun_speed_rpm = 1500.0", "sun = \"speed\"\ncarrier = \"torque\"")));
  const std::string bk =
      Replace(base, "friction = \"xu-kahraman\"", "friction = \"benedict-kelley\"");
  CHECK_NOTHROW(Parse(bk));
  CHECK_THROWS_WITH(Parse(Replace(bk, "roughness_um = 0.8", "roughness_um = 1.5")),
                    Contains("lubricant.roughness_um = 1.5") && Contains("benedict-kelley"));
}

TEST_CASE("a gear's mass or inertia far from its steel disc is a warning naming the key",
          "[unit][transmission]") {
  // The reference: the solid steel disc of the planet's pitch circle, computed here (z = 24,
  // m = 4.23 mm, b = 25 mm: r = 50.76 mm, m_d = 7850 π r² b = 1.589 kg, J_d = m_d r²/2).
  const std::string base = SceneText("paper_stage.toml");
  const double r = 0.5 * 4.23e-3 * 24, md = 7850 * 3.14159265358979 * r * r * 0.025;
  const double jd = 0.5 * md * r * r;
  auto number = [](double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.6g", v);
    return std::string(b);
  };
  for (const std::string& w : Parse(base).warnings)
    CHECK(w.find("steel disc") == std::string::npos);  // the paper's gears: within 0.8-6.2
  auto warned = [&](const std::string& text, const std::string& key) {
    for (const std::string& w : Parse(text).warnings)
      if (w.find(key) != std::string::npos && w.find("steel disc") != std::string::npos) return w;
    return std::string();
  };
  const std::string light =
      warned(Replace(base, "inertia_kgm2 = 24e-4", "inertia_kgm2 = " + number(jd * 0.005)),
             "planet.inertia_kgm2");
  CHECK_THAT(light, Contains("planet.inertia_kgm2 = " + number(jd * 0.005)));
  CHECK(warned(Replace(base, "inertia_kgm2 = 24e-4", "inertia_kgm2 = " + number(jd * 0.011)),
               "planet.inertia_kgm2")
            .empty());
  CHECK_FALSE(warned(Replace(base, "inertia_kgm2 = 24e-4", "inertia_kgm2 = " + number(jd * 0.009)),
                     "planet.inertia_kgm2")
                  .empty());
  CHECK_FALSE(
      warned(Replace(base, "mass_kg = 1.23", "mass_kg = " + number(md * 101)), "planet.mass_kg")
          .empty());
}

TEST_CASE(
    "a gear lighter than the model represents (half a tooth of steel) is refused naming the key",
    "[unit][transmission]") {
  // docs/scenes.md, "Ranges and validity": M >= 0.98 rho b m^2 (the member on one mesh, c_gamma b,
  // no faster than its teeth's first bending mode), J >= that times r_b^2. The planet of the
  // paper's stage: m = 4.23 mm, b = 25 mm, z = 24, 25 deg: 0.98 * 7850 * 0.025 * 4.23e-3^2 =
  // 3.44e-3 kg, r_b = 50.76 cos 25 = 46.00 mm, J >= 7.28e-6 kg m^2 (a planet of 1e-30 kg m^2
  // would have modes at 2.4e17 Hz).
  const std::string base = SceneText("paper_stage.toml");
  const double m_min = 0.98 * 7850 * 0.025 * 4.23e-3 * 4.23e-3;
  const double rb = 0.5 * 4.23e-3 * 24 * std::cos(25 * 3.14159265358979 / 180);
  const double j_min = m_min * rb * rb;
  auto with = [&](const std::string& from, const std::string& to) {
    return Replace(base, from, to);
  };
  auto text = [](double v) { return std::to_string(v); };
  CHECK_THROWS_WITH(Parse(with("inertia_kgm2 = 24e-4", "inertia_kgm2 = 1e-30")),
                    Contains("planet.inertia_kgm2 = 1e-30: must be 0 (not given) or >= 7.2") &&
                        Contains("lightest gear the model represents") &&
                        Contains("teeth as massless springs"));
  CHECK_THROWS_WITH(Parse(with("inertia_kgm2 = 24e-4", "inertia_kgm2 = " + text(0.9 * j_min))),
                    Contains("planet.inertia_kgm2"));
  CHECK_NOTHROW(Parse(with("inertia_kgm2 = 24e-4", "inertia_kgm2 = " + text(1.1 * j_min))));
  CHECK_THROWS_WITH(Parse(with("mass_kg = 1.23", "mass_kg = " + text(0.9 * m_min))),
                    Contains("planet.mass_kg = " + text(0.9 * m_min)) &&
                        Contains("must be 0 (not given) or >= 0.0034"));
  CHECK_NOTHROW(Parse(with("mass_kg = 1.23", "mass_kg = " + text(1.1 * m_min))));
}

// A pair's centre distance, as the stage's carrier radius: within 2 modules of m (z1 ± z2)/2,
// the ISO 20/40 pair's 4 (20 + 40)/2 = 120 mm (docs/scenes.md); 1e9 mm used to give an empty
// contact list and exit 0.
TEST_CASE("a gear pair's centre distance is checked against its gears", "[unit][transmission]") {
  const std::string base = SceneText("iso_pair_20_40.toml");
  const std::string key = "centre_distance_mm = 120.0";
  REQUIRE(base.find(key) != std::string::npos);
  auto with = [&](const std::string& v) {
    std::string text = base;
    return Parse(text.replace(text.find(key), key.size(), "centre_distance_mm = " + v));
  };
  CHECK(with("121.0").pair.centre_distance == Approx(0.121));
  CHECK_THROWS_WITH(with("1e9"), Contains("pair.centre_distance_mm = 1000000000: must be in [112, 128]") &&
                                     Contains("m (z1 + z2)/2 = 120"));
  CHECK_THROWS_WITH(with("111.9"), Contains("pair.centre_distance_mm = 111.9: must be in [112, 128]"));
}
