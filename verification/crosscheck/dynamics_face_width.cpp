// The load across the face width in the dynamic driver (docs/model.md §10, docs/face_width.md)
// against the quasi-static driver at low speed: each output step's K_Hβ per mesh tends to the
// quasi-static K_Hβ at the same carrier angle with the speed, as the load sharing does; and the
// run's summary holds the steps' largest and mean.
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

// The paper stage, planet 1's pin tilted radially by 20 µm over the face, 5 uncoupled slices
// (a fifth of the scenes' default: the comparison is between two drivers on one model, not of the
// model against a closed form), FE compliance without the local term, friction off, sun fixed.
test::DynamicRig TiltedPinRig(double rpm) {
  test::RigOptions o;
  o.local_terms = false;
  o.edit = [rpm](transmission::DynamicSettings& s) {
    s.sun_speed = io::RpmToRadPerSecond(rpm);
    s.friction.law = transmission::FrictionLaw::kOff;
  };
  return test::MakeRig(test::SceneText("paper_stage.toml") +
                           "\n[face_width]\nslices = 5\n[[face_width.pin_tilt]]\nplanet = 1\n"
                           "radial_um = 20.0\n",
                       "paper stage, pin 1 tilted", o);
}

}  // namespace

TEST_CASE(
    "face width: the dynamic K_Hbeta tends to the quasi-static one with the speed, and the "
    "summary holds the steps' largest and mean",
    "[crosscheck][slow][dynamics][face_width]") {
  // What separates a dynamic step's contact forces from the quasi-static forces at its carrier
  // angle are the velocity and inertia terms (damping ∝ δ̇, inertia ∝ ω²), O(speed) at low speed;
  // K_Hβ = max_s w_s / mean_s w_s is Lipschitz in the forces while the mean load is away from 0.
  // So halving the speed must at least halve the largest |K_Hβ,dyn − K_Hβ,qs| over the steps
  // (ratio ≥ 2/1.25, the argument and margin of the root-stress and load-sharing limits), down to
  // the tolerances' floor (relative 1e-6 of K_Hβ).
  double gap[2];
  const double speeds[2] = {120.0, 60.0};
  for (int k = 0; k < 2; ++k) {
    const auto rig = TiltedPinRig(speeds[k]);
    dynamics::SimulationOptions so;
    so.rtol = 1e-8;
    const auto r = test::Run(rig, test::Times(*rig.model, *rig.stage, 4, 4), so);
    REQUIRE(r.completed());
    REQUIRE(r.samples.size() == 16);
    gap[k] = 0;
    for (const dynamics::DynamicSample& s : r.samples) {
      REQUIRE(s.face_loads.size() == 6);  // 3 sun meshes, 3 ring meshes
      const auto q = transmission::SolvePosition(*rig.stage_model, s.carrier_angle, rig.scene.loads,
                                                 transmission::QuasiStaticOptions{});
      REQUIRE(q.converged);
      REQUIRE(q.face_loads.size() == 6);
      for (std::size_t m = 0; m < 6; ++m) {
        gap[k] = std::max(gap[k], std::abs(s.face_loads[m].k_h_beta - q.face_loads[m].k_h_beta));
        // Planet 1's sun mesh carries at −z, its ring mesh at +z (the radial tilt's kinematics,
        // crosscheck/transmission_face_width.cpp): the end slices' centres, ∓10 mm of 25 in 5.
        if (s.face_loads[m].planet == 0)
          CHECK(s.face_loads[m].largest_z == Approx(s.face_loads[m].ring_mesh ? 0.010 : -0.010));
      }
    }
    // The summary: the largest over the steps and their mean, per mesh (FaceLoadTracker).
    const dynamics::DynamicSummary sum = dynamics::Summarise(r.samples);
    REQUIRE(sum.face_width.size() == 6);
    for (std::size_t m = 0; m < 6; ++m) {
      double largest = 0, total = 0;
      for (const dynamics::DynamicSample& s : r.samples) {
        largest = std::max(largest, s.face_loads[m].k_h_beta);
        total += s.face_loads[m].k_h_beta;
      }
      CHECK(sum.face_width[m].k_h_beta_max == largest);
      CHECK(sum.face_width[m].k_h_beta_mean == Approx(total / 16).epsilon(1e-14));
    }
    CHECK(sum.face_width[0].mesh == "sun-planet1");
    CHECK(sum.face_width[0].k_h_beta_max > 1.05);  // the tilt's, well above round-off
    test::Figure("K_Hbeta, quasi-static limit at " + std::to_string(speeds[k]) +
                 " rpm: largest |K_dyn - K_qs| " + test::Sci(gap[k]));
  }
  const double floor = 1e-6 * 2.0;
  const bool pass = gap[1] <= gap[0] / 2 * 1.25 + floor;
  test::VerifyRow(
      "dynamic K_Hbeta -> quasi-static linearly in speed (120, 60 rpm; pin tilt, 5 "
      "slices)",
      "quasi-static solver at the same carrier angles",
      "largest gap " + test::Sci(gap[0]) + " at 120 rpm, " + test::Sci(gap[1]) + " at 60 rpm",
      "ratio " + test::Sci(gap[0] / gap[1], 2), "ratio >= 2/1.25 (1e-6 floor)", pass);
  CHECK(pass);
}
