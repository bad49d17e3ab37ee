// The jumps of a stage whose teeth separate near a resonance (docs/periodic.md §3, "Jumps"):
// slow run-ups and run-downs by time integration, each speed from the previous speed's end state
// (SpeedSweepOptions::carry), against the folds of the periodic orbits' continuation (shooting
// with Floquet multipliers: another method, which finds the folds as the points where a
// multiplier passes +1, not by integrating through them).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "epicycle/dynamics/branch_run.hpp"
#include "epicycle/dynamics/speed_sweep_run.hpp"
#include "epicycle/transmission/scene.hpp"
#include "figures.hpp"

using namespace epicycle;

namespace {

dynamics::DynamicRequest LightPinErrorRun() {
  dynamics::DynamicRequest r;
  r.scene = transmission::ReadScene(std::string(EPICYCLE_SCENES_DIR) +
                                    "/paper_stage_light_pin_error.toml");
  r.tables.cache_directory = EPICYCLE_TEST_CACHE_DIR;
  return r;
}

dynamics::StageBranchRecord Branch(double from, double to) {
  dynamics::BranchRequest b;
  b.run = LightPinErrorRun();
  b.start = from;
  b.end = to;
  b.steps = 12;
  b.max_points = 300;
  dynamics::BranchSink sink;
  return dynamics::RunBranch(b, sink).branch;
}

std::vector<dynamics::SpeedResult> Sweep(double step_rpm, dynamics::CarryState carry) {
  dynamics::SpeedSweepRequest s;
  s.run = LightPinErrorRun();
  const double lo = 11000, hi = 12800;
  s.sun_speeds_rpm =
      dynamics::SpeedGrid(lo, hi, static_cast<int>(std::lround((hi - lo) / step_rpm)) + 1);
  s.window_cycles = 4;
  s.threads = 1;
  s.carry = carry;
  dynamics::SpeedSweepSink sink;
  return dynamics::RunSpeedSweep(s, sink).speeds;
}

}  // namespace

TEST_CASE(
    "jumps: carried up- and down-sweeps of the light-torque stage with a pin error jump at "
    "speeds that bracket the continuation's folds, closer as the steps get finer",
    "[crosscheck][dynamics][periodic][slow]") {
  // The continuation from below (the orbit in contact, up to the upper fold) and from above (the
  // separating orbit, down to the lower fold).
  const dynamics::StageBranchRecord from_below = Branch(10800, 13200);
  const dynamics::StageBranchRecord from_above = Branch(13200, 10800);
  REQUIRE_FALSE(from_below.bifurcations.empty());
  REQUIRE_FALSE(from_above.bifurcations.empty());
  REQUIRE(from_below.bifurcations.front().kind == dynamics::BifurcationKind::kFold);
  REQUIRE(from_above.bifurcations.front().kind == dynamics::BifurcationKind::kFold);
  const double fold_hi = from_below.bifurcations.front().parameter;
  const double fold_lo = from_above.bifurcations.front().parameter;
  REQUIRE(fold_lo < fold_hi);  // a hysteresis: both stable orbits between the folds
  const double threshold = dynamics::SeparatingTeAmplitude(from_below, from_above);

  // Bracketing: the orbit a run-up follows ends at the upper fold, so it cannot leave it below
  // that fold unless a speed step kicks it across the unstable orbit (which the test would
  // catch); past the fold it needs time to leave, so the first speed off it is at or above the
  // fold. The same for the run-down and the lower fold. No tolerance: the sweep's speeds are
  // exact and the folds are located to a multiplier of +1 within 1e-4 (dynamics_periodic.cpp), a
  // shift of far less than the speed steps' resolution asserted here.
  double gap[2] = {0, 0};
  const double steps[2] = {200, 100};
  for (int s = 0; s < 2; ++s) {
    const auto up = Sweep(steps[s], dynamics::CarryState::kUp);
    const auto down = Sweep(steps[s], dynamics::CarryState::kDown);
    const int ju = dynamics::JumpIndex(up, dynamics::CarryState::kUp, threshold);
    const int jd = dynamics::JumpIndex(down, dynamics::CarryState::kDown, threshold);
    REQUIRE(ju > 0);
    REQUIRE(jd >= 0);
    const double up_rpm = up[static_cast<std::size_t>(ju)].sun_speed_rpm;
    const double down_rpm = down[static_cast<std::size_t>(jd)].sun_speed_rpm;
    gap[s] = up_rpm - down_rpm;
    test::VerifyRow("jumps: carried sweeps, steps of " + std::to_string(steps[s]) + " rpm",
                    "folds of the continuation at " + test::Sci(fold_lo, 6) + " and " +
                        test::Sci(fold_hi, 6) + " rpm",
                    "up-sweep jumps at " + test::Sci(up_rpm, 6) + ", down-sweep at " +
                        test::Sci(down_rpm, 6) + " rpm",
                    "", "down jump <= lower fold < upper fold <= up jump",
                    down_rpm <= fold_lo && up_rpm >= fold_hi);
    CHECK(up_rpm >= fold_hi);
    CHECK(down_rpm <= fold_lo);
  }
  // A slower sweep (half the step, the same dwell per speed) jumps closer to the folds.
  CHECK(gap[1] < gap[0]);
}
