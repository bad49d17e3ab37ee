// The jumps of a stage with two coexisting periodic orbits near a resonance (docs/periodic.md §3,
// "Jumps"): the periodic orbits continued over the sun speed from both sides (their folds), and
// carried time-integration sweeps up and down at several speed steps (speed_sweep.hpp, "Carried
// state"), with the speed where each sweep leaves the orbit it started on.
#pragma once

#include <vector>

#include "epicycle/dynamics/branch_run.hpp"
#include "epicycle/dynamics/speed_sweep_run.hpp"

namespace epicycle::dynamics {

/// What a jump study is asked for (speeds in rpm).
struct JumpRequest {
  DynamicRequest run;              ///< the scene and its run settings
  double below_rpm = 0;            ///< where the branch from below starts [rpm]
  double above_rpm = 0;            ///< where the branch from above starts [rpm], > below_rpm
  int branch_steps = 12;           ///< the branches' largest step, 1/N of the range [-]
  int branch_points = 300;         ///< the most points of each branch [-]
  double sweep_from_rpm = 0;       ///< the sweeps' lowest speed [rpm]
  double sweep_to_rpm = 0;         ///< the sweeps' highest speed [rpm]
  std::vector<double> steps_rpm;   ///< one up- and one down-sweep per speed step [rpm]
  double window_cycles = 4;        ///< mesh cycles measured per speed [-]
};

/// One pair of carried sweeps.
struct JumpSweeps {
  double step_rpm = 0;                ///< [rpm]
  SpeedSweepRecord up, down;          ///< the run-up and the run-down
  double up_jump_rpm = 0;             ///< the first speed of the run-up off its orbit [rpm]
  double down_jump_rpm = 0;           ///< the first speed of the run-down off its orbit [rpm]
  double dwell_s = 0;                 ///< skip and window per speed at the run-up's jump [s]
  double rate_rpm_per_s() const { return step_rpm / dwell_s; }  ///< the sweep rate [rpm/s]
};

struct JumpStudy {
  StageBranchRecord from_below, from_above;  ///< each to its first fold and a little past it
  double lower_fold_rpm = 0, upper_fold_rpm = 0;  ///< [rpm]
  double te_threshold = 0;  ///< between the two orbits' TE amplitudes (SeparatingTeAmplitude) [rad]
  std::vector<JumpSweeps> sweeps;  ///< in the order of steps_rpm
};

/// Runs the study. @throws std::invalid_argument for a bad request (from the branch and sweep
/// requests' rules, or above_rpm ≤ below_rpm); std::runtime_error when a branch finds no fold, a
/// sweep's speed fails or a sweep does not jump (naming which).
JumpStudy RunJumps(const JumpRequest& request);

}  // namespace epicycle::dynamics
