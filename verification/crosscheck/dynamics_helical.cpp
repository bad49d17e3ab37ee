// The dynamic driver on a helical stage (docs/model.md §10, "Helical meshes in slices"; the
// planar DOFs, the axial and tilting motions held) against the quasi-static driver at low speed:
// each output step's load sharing, axial forces and tilting moments tend to the quasi-static ones
// at the same carrier angle, as the spur stage's load sharing does (dynamics_model.cpp); and the
// run's summary holds the steps' means of the axial loads.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "dynamics_fixtures.hpp"
#include "epicycle/dynamics/dynamic_summary.hpp"
#include "epicycle/dynamics/simulation.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "figures.hpp"

using namespace epicycle;

namespace {

// The helical paper stage (β = 15°, scenes/paper_stage_helical.toml) with 5 uncoupled slices (a
// quarter of the scene's: the comparison is between two drivers on one model), planet 1 with a
// 20 µm run-out (so that the load sharing moves over the cycle), FE compliance without the local
// term, friction off, sun fixed, the sun at `rpm`.
test::DynamicRig HelicalRig(double rpm) {
  return test::MakeRig(
      test::WithRunout(test::Replace(test::SceneText("paper_stage_helical.toml"), "slices = 20",
                                     "slices = 5")),
      "helical paper stage, run-out", test::QuasiStaticLimitOptions(rpm));
}

// The largest differences between the steps and the quasi-static solutions at their carrier
// angles: load sharing [-], and the axial loads relative to the nominal axial force F_a of a sun
// mesh [N] (forces) and F_a times the planet's working diameter (moments).
struct Gaps {
  double lsr = 0, force = 0, moment = 0;
};

Gaps QuasiStaticGaps(const test::DynamicRig& rig, const std::vector<dynamics::DynamicSample>& steps,
                     double fa, double arm) {
  Gaps g;
  for (const dynamics::DynamicSample& s : steps) {
    const auto q = transmission::SolvePosition(*rig.stage_model, s.carrier_angle, rig.scene.loads,
                                               transmission::QuasiStaticOptions{});
    REQUIRE(q.converged);
    REQUIRE(s.helical.planets.size() == 3);
    REQUIRE(q.helical.planets.size() == 3);
    for (std::size_t i = 0; i < 3; ++i) {
      g.lsr = std::max(g.lsr, std::abs(s.load_sharing[i] - q.load_sharing[i]));
      const auto& a = s.helical.planets[i];
      const auto& b = q.helical.planets[i];
      g.force = std::max({g.force, std::abs(a.sun_mesh_axial - b.sun_mesh_axial) / fa,
                          std::abs(a.ring_mesh_axial - b.ring_mesh_axial) / fa});
      g.moment = std::max({g.moment, std::abs(a.moment_tangential - b.moment_tangential) / (fa * arm),
                           std::abs(a.moment_radial - b.moment_radial) / (fa * arm),
                           std::abs(a.axial_moment_tangential - b.axial_moment_tangential) /
                               (fa * arm)});
    }
    g.force = std::max({g.force,
                        std::abs(s.helical.sun_axial_force - q.helical.sun_axial_force) / (3 * fa),
                        std::abs(s.helical.ring_axial_force - q.helical.ring_axial_force) / (3 * fa)});
  }
  return g;
}

}  // namespace

TEST_CASE(
    "helical stage in motion: the dynamic load sharing, axial forces and tilting moments tend to "
    "the quasi-static ones with the speed",
    "[crosscheck][slow][dynamics][helical]") {
  // What separates a dynamic step's contact forces from the quasi-static forces at its carrier
  // angle are the velocity terms (mesh damping on overlaps that change under the rigid motion and
  // the run-out, ∝ speed) and the inertial terms (∝ speed²): the dynamic load. The axial forces
  // are F_t tan β_b per contact and the moments their lever arms times them, linear in the
  // forces, so every gap is O(speed) at low speed. Halving the speed must at least halve each gap
  // (ratio ≥ 2/1.25, the margin of the spur stage's test for the mix of the two terms and the
  // output sampling), down to the tolerances' floor (integrator rtol 1e-8 on deflections of
  // ~1e-3 rad, contact solver 1e-10: 1e-6 of the nominal values).
  const double speeds[2] = {120.0, 60.0};
  Gaps gap[2];
  for (int k = 0; k < 2; ++k) {
    const auto rig = HelicalRig(speeds[k]);
    const geometry::Stage& st = *rig.stage;
    // F_a = |T_s| tan β_b /(n r_b,sun) per sun mesh; the arm the planet's two working pitch radii.
    const double tan_bb =
        std::tan(st.sun().spec().helix.angle) * std::cos(st.sun().spec().pressure_angle);
    const double fa = std::abs(rig.scene.loads.sun_torque) * tan_bb / (3 * st.sun().base_radius());
    const double rbp = st.planet(0).base_radius();
    const double arm = rbp / std::cos(st.meshes()[0].pressure_angle) +
                       rbp / std::cos(st.meshes()[1].pressure_angle);
    dynamics::SimulationOptions so;
    so.rtol = 1e-8;
    const auto r = test::Run(rig, test::Times(*rig.model, st, 2, 4), so);
    REQUIRE(r.completed());
    REQUIRE(r.samples.size() == 8);
    gap[k] = QuasiStaticGaps(rig, r.samples, fa, arm);
    // The summary's helical object: the steps' means (DynamicAccumulator, in step order).
    const dynamics::DynamicSummary sum = dynamics::Summarise(r.samples);
    REQUIRE(sum.helical_mean.planets.size() == 3);
    double sun = 0, tilt = 0;
    for (const dynamics::DynamicSample& s : r.samples) {
      sun += s.helical.sun_axial_force / 8;
      tilt += s.helical.planets[0].moment_tangential / 8;
    }
    CHECK(sum.helical_mean.sun_axial_force == Approx(sun).epsilon(1e-14));
    CHECK(sum.helical_mean.planets[0].moment_tangential == Approx(tilt).epsilon(1e-14));
    // The sun takes the axial force of its three meshes, F_a n within the run-out's share.
    CHECK(std::abs(sum.helical_mean.sun_axial_force) == Approx(3 * fa).epsilon(0.01));
    test::Figure("helical stage at " + std::to_string(static_cast<int>(speeds[k])) +
                 " rpm: largest gaps to the quasi-static driver LSR " + test::Sci(gap[k].lsr) +
                 ", axial force/F_a " + test::Sci(gap[k].force) + ", tilting moment/(F_a d) " +
                 test::Sci(gap[k].moment) + "; " + std::to_string(r.stats.rhs_evaluations) +
                 " evaluations");
  }
  const double floor = 1e-6;
  auto halves = [&](double a, double b) { return b <= a / 2 * 1.25 + floor; };
  const bool pass = halves(gap[0].lsr, gap[1].lsr) && halves(gap[0].force, gap[1].force) &&
                    halves(gap[0].moment, gap[1].moment);
  test::VerifyRow(
      "helical stage: dynamic LSR, axial forces, tilting moments -> quasi-static linearly in "
      "speed (120, 60 rpm; run-out, 5 slices)",
      "quasi-static solver at the same carrier angles",
      "largest gaps LSR " + test::Sci(gap[0].lsr) + " -> " + test::Sci(gap[1].lsr) + ", force " +
          test::Sci(gap[0].force) + " -> " + test::Sci(gap[1].force) + ", moment " +
          test::Sci(gap[0].moment) + " -> " + test::Sci(gap[1].moment),
      "ratios " + test::Sci(gap[0].lsr / gap[1].lsr, 2) + ", " +
          test::Sci(gap[0].force / gap[1].force, 2) + ", " +
          test::Sci(gap[0].moment / gap[1].moment, 2),
      "ratio >= 2/1.25 (1e-6 floor)", pass);
  CHECK(pass);
}
