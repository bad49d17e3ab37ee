// The jumps of a stage whose teeth separate near a resonance (docs/periodic.md §3, "Jumps"):
// slow run-ups and run-downs by time integration, each speed from the previous speed's end state
// (SpeedSweepOptions::carry), against the folds of the periodic orbits' continuation (shooting
// with Floquet multipliers: another method, which finds the folds as the points where a
// multiplier passes +1, not by integrating through them).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "epicycle/dynamics/jumps.hpp"
#include "epicycle/transmission/scene.hpp"
#include "figures.hpp"

using namespace epicycle;

TEST_CASE(
    "jumps: carried up- and down-sweeps of the light-torque stage with a pin error jump at "
    "speeds that bracket the continuation's folds, closer as the steps get finer",
    "[crosscheck][dynamics][periodic][slow]") {
  // The continuation from below (the orbit in contact, up to the upper fold) and from above (the
  // separating orbit, down to the lower fold), then carried sweeps in steps of 200 and 100 rpm
  // (the same dwell per speed: half the rate).
  dynamics::JumpRequest request;
  request.run.scene = transmission::ReadScene(std::string(EPICYCLE_SCENES_DIR) +
                                              "/paper_stage_light_pin_error.toml");
  request.run.tables.cache_directory = EPICYCLE_TEST_CACHE_DIR;
  request.below_rpm = 10800;
  request.above_rpm = 13200;
  request.sweep_from_rpm = 11000;
  request.sweep_to_rpm = 12800;
  request.steps_rpm = {200, 100};
  const dynamics::JumpStudy study = dynamics::RunJumps(request);
  const double fold_lo = study.lower_fold_rpm, fold_hi = study.upper_fold_rpm;
  REQUIRE(fold_lo < fold_hi);  // a hysteresis: both stable orbits between the folds

  // Bracketing: the orbit a run-up follows ends at the upper fold, so it cannot leave it below
  // that fold unless a speed step kicks it across the unstable orbit (which the test would
  // catch); past the fold it needs time to leave, so the first speed off it is at or above the
  // fold. The same for the run-down and the lower fold. No tolerance: the sweeps' speeds are
  // exact and a fold is located where its multiplier is +1 (|mu - 1| within 1e-4,
  // dynamics_periodic.cpp), a shift far below the speed steps asserted here.
  REQUIRE(study.sweeps.size() == 2);
  for (const dynamics::JumpSweeps& j : study.sweeps) {
    test::VerifyRow("jumps: carried sweeps, steps of " + test::Sci(j.step_rpm, 3) + " rpm",
                    "folds of the continuation at " + test::Sci(fold_lo, 6) + " and " +
                        test::Sci(fold_hi, 6) + " rpm",
                    "up-sweep jumps at " + test::Sci(j.up_jump_rpm, 6) + ", down-sweep at " +
                        test::Sci(j.down_jump_rpm, 6) + " rpm",
                    "", "down jump <= lower fold < upper fold <= up jump",
                    j.down_jump_rpm <= fold_lo && j.up_jump_rpm >= fold_hi);
    CHECK(j.up_jump_rpm >= fold_hi);
    CHECK(j.down_jump_rpm <= fold_lo);
  }
  // The slower sweep jumps closer to the folds.
  CHECK(study.sweeps[1].up_jump_rpm - study.sweeps[1].down_jump_rpm <
        study.sweeps[0].up_jump_rpm - study.sweeps[0].down_jump_rpm);
}
