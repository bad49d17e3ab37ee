// ISO 6336-2 factors of the ratings (docs/model.md §9, docs/stresses.md "Ratings") against
// references outside the code: the standard's tabulated Z_E (steel on steel) and Z_H (20°, no
// shift), its printed M_1 and M_2 formulas (tip pressure angles, 2π/z and ε_α, where the code uses
// radii of curvature), and σ_H0 against Hertz's line contact at the pitch point computed from the
// pitch point's radii of curvature (solvers::HertzPressure), for the external sun mesh and the
// internal ring mesh of the paper stage.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "epicycle/geometry/iso.hpp"
#include "epicycle/geometry/pair.hpp"
#include "epicycle/solvers/local_term.hpp"
#include "epicycle/transmission/rating.hpp"
#include "epicycle/transmission/scene.hpp"
#include "stage_fixtures.hpp"

using namespace epicycle;

namespace {
constexpr double kPi = 3.14159265358979323846;
}  // namespace

TEST_CASE("ISO 6336-2 elasticity and zone factors against the standard's values",
          "[reference][transmission][rating]") {
  // ISO 6336-2 tabulates Z_E = 189.8 √(N/mm²) for steel on steel (E = 206000 N/mm², ν = 0.3):
  // agreement to the table's last digit (±0.05).
  CHECK(geometry::iso::ElasticityFactor(206e9, 0.3, 206e9, 0.3) / 1e3 ==
        Approx(189.8).margin(0.05));
  // Z_H = 2.495 for a spur pair at α_w = α = 20° (the standard's figure, to its 3 decimals).
  const double a20 = 20 * kPi / 180;
  const auto f = geometry::iso::ContactFactorsB(20, a20, a20, 0.12, 0.0375876, 0.042, 0.0751754,
                                                0.082, 1.55, false);
  CHECK(f.z_h == Approx(2.495).margin(5e-4));
  CHECK(f.z_eps == Approx(std::sqrt((4 - 1.55) / 3)).epsilon(1e-15));
}

TEST_CASE("ISO 6336-2 single pair contact factors against the standard's printed form",
          "[reference][transmission][rating]") {
  // M_1 = tan α_w / √{[√(d_a1²/d_b1² − 1) − 2π/z_1][√(d_a2²/d_b2² − 1) − (ε_α − 1) 2π/z_2]},
  // M_2 the same with 1 and 2 exchanged; ε_α from the tip circles (geometry::iso::ContactRatio).
  // The code writes them with radii of curvature: the two must agree to round-off.
  for (const char* file : {"iso_pair_17_43.toml", "iso_pair_20_40.toml", "iso_pair_30_30.toml"}) {
    INFO(file);
    const auto scene = transmission::ReadScene(std::string(EPICYCLE_SCENES_DIR) + "/" + file);
    const geometry::GearPair pair(scene.pair);
    const geometry::Gear &g1 = pair.gear1(), &g2 = pair.gear2();
    const double aw = pair.summary().pressure_angle, a = pair.summary().centre_distance;
    const double eps = geometry::iso::ContactRatio(
        g1.base_radius(), g1.tip_radius(), g2.base_radius(), g2.tip_radius(), a, aw,
        2 * kPi * g1.base_radius() / g1.teeth(), false);
    const auto f = geometry::iso::ContactFactorsB(g1.teeth(), g1.spec().pressure_angle, aw, a,
                                                  g1.base_radius(), g1.tip_radius(),
                                                  g2.base_radius(), g2.tip_radius(), eps, false);
    auto tan_tip = [](const geometry::Gear& g) {
      const double q = g.tip_radius() / g.base_radius();
      return std::sqrt(q * q - 1);
    };
    const double z1 = g1.teeth(), z2 = g2.teeth();
    const double m1 = std::tan(aw) / std::sqrt((tan_tip(g1) - 2 * kPi / z1) *
                                               (tan_tip(g2) - (eps - 1) * 2 * kPi / z2));
    const double m2 = std::tan(aw) / std::sqrt((tan_tip(g2) - 2 * kPi / z2) *
                                               (tan_tip(g1) - (eps - 1) * 2 * kPi / z1));
    CHECK(f.m1 == Approx(m1).epsilon(1e-12));
    CHECK(f.m2 == Approx(m2).epsilon(1e-12));
    CHECK(f.z_b == std::max(1.0, f.m1));  // Z_B = max(1, M_1), Z_D = max(1, M_2)
    CHECK(f.z_d == std::max(1.0, f.m2));
  }
}

TEST_CASE("The rating's nominal contact stress is Hertz's at the pitch point",
          "[reference][transmission][rating]") {
  // σ_H0/Z_ε = p_H of the nominal normal force F_n = F_t/cos α on the contact width b with the
  // pitch point's radii ρ_i = r_bi tan α_w (1/R = 1/ρ_1 ± 1/ρ_2, − internal), E* in plane strain:
  // ISO's u and (u + 1)/u carry the internal mesh's sign, Hertz's radii do it here.
  transmission::Scene scene = test::PaperScene();
  scene.material.bending_limit = 430e6;
  scene.material.contact_limit = 1500e6;
  const geometry::Stage stage(scene.stage);
  transmission::SweepSummary summary;
  summary.converged = 1;
  summary.lsr_max.assign(3, 1.0 / 3);
  const auto rating = transmission::RateStage(transmission::RatingInputsOf(scene), stage, summary);
  const double ft = std::abs(scene.loads.sun_torque) / (3 * stage.sun().reference_radius());
  CHECK(rating.tangential_force == Approx(ft).epsilon(1e-15));
  for (int k = 0; k < 2; ++k) {
    const geometry::MeshSummary& m = stage.meshes()[k];
    const bool internal = k == 1;
    const geometry::Gear& g1 = internal ? stage.planet(0) : stage.sun();
    const geometry::Gear& g2 = internal ? stage.ring() : stage.planet(0);
    solvers::LocalTermParameters p;
    p.face_width = geometry::ContactFaceWidth(g1, g2);
    const double rho1 = g1.base_radius() * std::tan(m.pressure_angle),
                 rho2 = g2.base_radius() * std::tan(m.pressure_angle);
    p.reduced_radius = internal ? rho1 * rho2 / (rho2 - rho1) : rho1 * rho2 / (rho1 + rho2);
    for (auto& b : p.body) b = {scene.material.youngs_modulus, scene.material.poisson_ratio, 1e-3};
    const double hertz = solvers::HertzPressure(p, ft / std::cos(g1.spec().pressure_angle));
    // The gear rated by this mesh alone: the sun (sun mesh), the ring (ring mesh).
    const transmission::GearRating& g = internal ? rating.gears.back() : rating.gears.front();
    const auto z = geometry::iso::ContactFactorsB(
        g1.teeth(), g1.spec().pressure_angle, m.pressure_angle, m.centre_distance,
        g1.base_radius(), g1.tip_radius(), g2.base_radius(), g2.tip_radius(), m.contact_ratio_iso,
        internal);
    INFO(m.name << ": sigma_H0 " << g.sigma_h0 / 1e6 << " MPa, Hertz " << hertz / 1e6 << " MPa");
    CHECK(g.sigma_h0 / z.z_eps == Approx(hertz).epsilon(1e-12));
  }
}
