// The dynamic factor K_v of a run (dynamics/dynamic_factor.hpp, docs/stresses.md "Ratings in
// motion") against the quasi-static driver: its reference peaks are the quasi-static mesh forces
// solved here position by position at the run's carrier angles, and K_v tends to 1 with the speed.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "dynamics_fixtures.hpp"
#include "epicycle/dynamics/dynamic_factor.hpp"
#include "epicycle/dynamics/simulation.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "figures.hpp"

using namespace epicycle;
using test::kRpm;

TEST_CASE("dynamic factor: the quasi-static reference at the run's angles, K_v -> 1 with the speed",
          "[crosscheck][slow][dynamics][rating]") {
  // The setting of "root stress: the dynamic root stress tends to the quasi-static one" (FE
  // compliance without the local term, friction off, planet 1 with 20 µm run-out, sun fixed,
  // 24 mesh cycles with 2 outputs each, rtol 1e-8). The mesh forces are what the root stress is
  // linear in, so the same argument holds: what separates the peaks in motion from those at rest
  // are the velocity and inertial terms, and halving the speed must at least halve K_v − 1
  // (ratio ≥ 2/1.25), down to the tolerances' floor (1e-6).
  double excess[2];
  const double speeds[2] = {120.0, 60.0};
  for (int k = 0; k < 2; ++k) {
    test::RigOptions o;
    o.local_terms = false;
    o.edit = [&](transmission::DynamicSettings& s) {
      s.sun_speed = speeds[k] * kRpm;
      s.friction.law = transmission::FrictionLaw::kOff;
    };
    const auto rig =
        test::MakeRig(test::WithRunout(test::SceneText("paper_stage.toml")), "runout", o);
    dynamics::SimulationOptions so;
    so.rtol = 1e-8;
    const std::vector<double> times = test::Times(*rig.model, *rig.stage, 24, 2);
    const auto r = test::Run(rig, times, so);
    REQUIRE(r.completed);
    dynamics::MotionLoads loads(*rig.stage);
    for (const dynamics::DynamicSample& s : r.samples) loads.Add(s);
    const dynamics::DynamicFactor kv = dynamics::DynamicLoadFactor(*rig.model, so, times, loads);
    // The reference: each position solved on its own (cold), Σ F per mesh, largest per mesh.
    std::vector<double> rest(rig.stage->meshes().size(), 0.0);
    for (const double t : times) {
      const auto q =
          transmission::SolvePosition(*rig.stage_model, rig.model->CarrierAngle(t), rig.scene.loads,
                                      transmission::QuasiStaticOptions{});
      REQUIRE(q.converged);
      std::vector<double> mesh(rest.size(), 0.0);
      for (std::size_t j = 0; j < q.problem.contacts.size(); ++j)
        mesh[static_cast<std::size_t>(
            geometry::MeshIndex(q.problem.contacts[j].planet, q.problem.contacts[j].mesh))] +=
            std::max(0.0, q.solution.force(static_cast<Eigen::Index>(j)));
      for (std::size_t m = 0; m < mesh.size(); ++m) rest[m] = std::max(rest[m], mesh[m]);
    }
    REQUIRE(kv.mesh >= 0);
    // Warm against cold starts: the same solution to the contact solve's tolerance (relative
    // 1e-10 on the forces), far inside 1e-8.
    CHECK(kv.peak_quasi_static == Approx(rest[static_cast<std::size_t>(kv.mesh)]).epsilon(1e-8));
    double largest = 0;
    for (std::size_t m = 0; m < rest.size(); ++m)
      largest = std::max(largest, loads.peak_mesh_force()[m] / rest[m]);
    CHECK(kv.value == Approx(largest).epsilon(1e-8));
    CHECK(kv.quasi_static.converged == static_cast<int>(times.size()));
    excess[k] = std::abs(kv.value - 1);
    test::Figure("K_v at " + std::to_string(speeds[k]) + " rpm (run-out, 24 mesh cycles): " +
                 test::Sci(kv.value, 8) + " on " + kv.mesh_name);
  }
  const bool pass = excess[1] <= excess[0] / 2 * 1.25 + 1e-6;
  test::VerifyRow(
      "dynamic factor K_v -> 1 linearly in speed (120, 60 rpm; run-out)",
      "quasi-static solver at the same carrier angles",
      "|K_v - 1| " + test::Sci(excess[0]) + " at 120 rpm, " + test::Sci(excess[1]) + " at 60 rpm",
      "ratio " + test::Sci(excess[0] / excess[1], 2), "ratio >= 2/1.25 (1e-6 floor)", pass);
  CHECK(pass);
}
