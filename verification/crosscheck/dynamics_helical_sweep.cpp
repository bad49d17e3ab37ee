// The speed sweep on a helical stage (docs/speed_sweeps.md; docs/model.md §10, "Helical meshes in
// slices"): one speed's window read-outs of the axial forces and tilting moments against the
// dynamic driver's steps over the same window, and at low speed against the quasi-static driver
// and the closed form F_a = F_t tan β_b per mesh.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "dynamics_fixtures.hpp"
#include "epicycle/dynamics/speed_sweep.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "figures.hpp"

using namespace epicycle;

namespace {

// The helical paper stage (β = 15°, scenes/paper_stage_helical.toml) with 5 slices (the dynamic
// crosscheck's, dynamics_helical.cpp: the comparisons are between drivers on one model), FE
// compliance without the local term, friction off, sun fixed, the sun at `rpm`.
test::DynamicRig HelicalRig(double rpm) {
  return test::MakeRig(
      test::Replace(test::SceneText("paper_stage_helical.toml"), "slices = 20", "slices = 5"),
      "helical paper stage", test::QuasiStaticLimitOptions(rpm));
}

// Mean and largest magnitude of `value` over `samples`, by hand (the reference of the sweep's
// HelicalLoadRange).
template <typename F>
std::pair<double, double> MeanMaxAbs(const std::vector<dynamics::DynamicSample>& samples, F value) {
  double sum = 0, largest = 0;
  for (const dynamics::DynamicSample& s : samples) {
    sum += value(s);
    largest = std::max(largest, std::abs(value(s)));
  }
  return {sum / static_cast<double>(samples.size()), largest};
}

}  // namespace

TEST_CASE(
    "helical speed sweep: one speed's axial forces and tilting moments are the dynamic run's over "
    "the same window, and at low speed the quasi-static driver's",
    "[crosscheck][slow][dynamics][helical]") {
  const double rpm = 60;
  const auto rig = HelicalRig(rpm);
  const dynamics::DynamicModel& base = *rig.model;
  const geometry::Stage& st = *rig.stage;
  const double tc = st.mesh_cycle() / std::abs(base.carrier_speed());  // a mesh cycle [s]
  const int per_cycle = 4;

  // The sweep: one speed, one mesh cycle skipped (the start transient decays in 5.9 ms at σ_min,
  // docs/periodic.md §4, far less than the 78 ms cycle at 60 rpm), one mesh cycle measured.
  dynamics::SpeedSweepOptions o;
  o.sun_speeds_rpm = {rpm};
  o.window_cycles = 1;
  o.outputs_per_cycle = per_cycle;
  o.skip_time = tc;
  o.simulation.rtol = 1e-8;
  const dynamics::SpeedSweepResult sweep = dynamics::SweepSpeeds(base, o);
  REQUIRE(sweep.speeds.size() == 1);
  const dynamics::SpeedResult& r = sweep.speeds.front();
  INFO(r.message);
  REQUIRE(r.ok());
  REQUIRE(r.helical.count == per_cycle);
  REQUIRE(r.helical.mean.planets.size() == 3);

  // The dynamic driver's run (Simulate at the run's uniform output times, as RunDynamic) from the
  // same start angle (the window's start less the skip) and the same quasi-static start, over
  // the skip and the window; its window is the last `per_cycle` steps.
  dynamics::DynamicModel at = dynamics::ModelAtSpeed(base, rpm);
  at.SetStartAngle(o.window_start - at.carrier_speed() * o.skip_time);
  dynamics::SimulationOptions so;
  so.rtol = o.simulation.rtol;
  const Eigen::VectorXd d0 = at.QuasiStaticStart(so.contact, so.backend);
  const dynamics::SimulationResult run =
      dynamics::Simulate(at, so, d0, Eigen::VectorXd::Zero(at.size()), test::Times(at, st, 2, 4));
  REQUIRE(run.completed());
  REQUIRE(run.samples.size() == 2 * per_cycle);
  const std::vector<dynamics::DynamicSample> window(run.samples.end() - per_cycle,
                                                    run.samples.end());
  for (std::size_t k = 0; k < window.size(); ++k)
    CHECK(window[k].carrier_angle ==
          Approx(sweep.plan.window_angles[k]).margin(1e-12 * std::abs(window[k].carrier_angle)));

  // F_a = |T_s| tan β_b / (n r_b,sun) per sun mesh (helical_slices.hpp: the axial part of the
  // transverse force F_t on the base plane); the tilting moments against F_a times the planet's
  // two working pitch radii.
  const double tan_bb =
      std::tan(st.sun().spec().helix.angle) * std::cos(st.sun().spec().pressure_angle);
  const double fa = std::abs(rig.scene.loads.sun_torque) * tan_bb / (3 * st.sun().base_radius());
  const double rbp = st.planet(0).base_radius();
  const double arm = rbp / std::cos(st.meshes()[0].pressure_angle) +
                     rbp / std::cos(st.meshes()[1].pressure_angle);

  // (1) Sweep against the dynamic run. Both integrate the same equations from the same state under
  // the same error control (rtol 1e-8); they differ only in CVODE's first step (estimated from
  // the first output time: 1.25 cycles in the sweep, 0.25 in the run), so their states differ by
  // the integrator's global error. Over the run's ~1e3 steps, each within rtol of the state, that
  // is ≤ 1e3 × 1e-8 = 1e-5 of the state; the axial forces and moments are linear in the contact
  // forces, which follow the deflections: ≤ 1e-5 F_a and 1e-5 F_a·d.
  const double tol_force = 1e-5 * fa, tol_moment = 1e-5 * fa * arm;
  double worst_force = 0, worst_moment = 0;
  auto compare = [&](std::pair<double, double> ref, double mean, double max_abs, double tol,
                     double* worst) {
    CHECK(std::abs(mean - ref.first) <= tol);
    CHECK(std::abs(max_abs - ref.second) <= tol);
    *worst = std::max({*worst, std::abs(mean - ref.first), std::abs(max_abs - ref.second)});
  };
  compare(MeanMaxAbs(window, [](const auto& s) { return s.helical.sun_axial_force; }),
          r.helical.mean.sun_axial_force, r.helical.max_abs.sun_axial_force, 3 * tol_force,
          &worst_force);
  compare(MeanMaxAbs(window, [](const auto& s) { return s.helical.ring_axial_force; }),
          r.helical.mean.ring_axial_force, r.helical.max_abs.ring_axial_force, 3 * tol_force,
          &worst_force);
  compare(MeanMaxAbs(window, [](const auto& s) { return s.helical.carrier_axial_force; }),
          r.helical.mean.carrier_axial_force, r.helical.max_abs.carrier_axial_force,
          3 * tol_force, &worst_force);
  for (std::size_t i = 0; i < 3; ++i) {
    const auto& m = r.helical.mean.planets[i];
    const auto& x = r.helical.max_abs.planets[i];
    compare(MeanMaxAbs(window, [i](const auto& s) { return s.helical.planets[i].sun_mesh_axial; }),
            m.sun_mesh_axial, x.sun_mesh_axial, tol_force, &worst_force);
    compare(MeanMaxAbs(window, [i](const auto& s) { return s.helical.planets[i].ring_mesh_axial; }),
            m.ring_mesh_axial, x.ring_mesh_axial, tol_force, &worst_force);
    compare(MeanMaxAbs(window, [i](const auto& s) { return s.helical.planets[i].moment_radial; }),
            m.moment_radial, x.moment_radial, tol_moment, &worst_moment);
    compare(
        MeanMaxAbs(window, [i](const auto& s) { return s.helical.planets[i].moment_tangential; }),
        m.moment_tangential, x.moment_tangential, tol_moment, &worst_moment);
  }
  test::VerifyRow("helical speed sweep at 60 rpm: window axial forces, tilting moments (mean, max)",
                  "dynamic run over the same window",
                  "largest gaps " + test::Sci(worst_force / fa) + " F_a, " +
                      test::Sci(worst_moment / (fa * arm)) + " F_a d",
                  "", "1e-5 (integrator global error)",
                  worst_force <= 3 * tol_force && worst_moment <= tol_moment);

  // (2) Low speed against the quasi-static driver at the window's carrier angles and the closed
  // form. The dynamic step's axial forces differ from the quasi-static ones by the dynamic load,
  // O(speed) at low speed; dynamics_helical.cpp measures the largest gap per step at 60 rpm as
  // 3.8e-4 F_a on this stage with a 20 µm run-out, which drives the dynamic load; without the
  // run-out the load varies less, so 1e-3 F_a (the measured gap × 2.6 for the margin of that
  // test's halving rule, 1.25, and the mix of the two orders) bounds each window mean.
  double qs_sun[3] = {0, 0, 0}, qs_total = 0;
  for (double angle : sweep.plan.window_angles) {
    const auto q = transmission::SolvePosition(*rig.stage_model, angle, rig.scene.loads,
                                               transmission::QuasiStaticOptions{});
    REQUIRE(q.converged);
    for (std::size_t i = 0; i < 3; ++i)
      qs_sun[i] += q.helical.planets[i].sun_mesh_axial / per_cycle;
    qs_total += q.helical.sun_axial_force / per_cycle;
  }
  double worst_qs = 0;
  for (std::size_t i = 0; i < 3; ++i) {
    CHECK(std::abs(r.helical.mean.planets[i].sun_mesh_axial - qs_sun[i]) <= 1e-3 * fa);
    worst_qs = std::max(worst_qs, std::abs(r.helical.mean.planets[i].sun_mesh_axial - qs_sun[i]));
  }
  // The sun's axial force is Σ F_t tan β_b over its contacts, and Σ F_t r_b,sun = |T_s| in
  // equilibrium (friction off): n F_a exactly for the quasi-static driver (to its contact
  // tolerance, 1e-10 relative), within the dynamic load's 1e-3 n F_a for the sweep.
  CHECK(std::abs(std::abs(qs_total) - 3 * fa) <= 1e-8 * 3 * fa);
  CHECK(std::abs(std::abs(r.helical.mean.sun_axial_force) - 3 * fa) <= 1e-3 * 3 * fa);
  test::VerifyRow("helical speed sweep at 60 rpm: mean sun-mesh axial force per planet",
                  "quasi-static driver at the window's angles; n F_a = |T_s| tan b_b / r_b",
                  "largest gap " + test::Sci(worst_qs / fa) + " F_a; sun " +
                      test::Sci(std::abs(r.helical.mean.sun_axial_force) / (3 * fa) - 1) +
                      " of n F_a",
                  "", "1e-3 F_a", worst_qs <= 1e-3 * fa);
}
