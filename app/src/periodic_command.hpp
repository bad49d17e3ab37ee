// `epicycle dynamic SCENE --speed-sweep FROM:TO:N --periodic` and `--continue NAME:FROM:TO:N`: the
// stage's periodic orbits continued over the sun speed or another of its parameters
// (dynamics/stage_branch.hpp, docs/periodic.md §3), both branches through the folds with their
// stability, one CSV line per point as it is computed, a JSON record and SVG plots (stable solid,
// unstable dashed, folds marked).
#pragma once

#include <string>

#include "epicycle/dynamics/dynamic_model.hpp"
#include "epicycle/dynamics/simulation.hpp"
#include "epicycle/dynamics/stage_branch.hpp"
#include "epicycle/transmission/scene.hpp"

namespace epicycle::app {

struct BranchArgs {
  std::string option;  ///< "--speed-sweep" or "--continue": the option that gave the range
  std::string spec;    ///< its value as the user gave it
  std::string parameter;
  double from = 0, to = 0;
  int steps = 0;       ///< N: the largest arclength step is 1/N [-]
  int max_points = 0;  ///< 0: the library's default
  std::string out, backend;
  bool quiet = false;
};

/// Parses `--speed-sweep FROM:TO:N` with --periodic (the sun speed) or `--continue NAME:FROM:TO:N`
/// into a branch's range, and checks the scene's period against the branch's limit: bad input
/// before any table is built.
/// @throws std::invalid_argument naming the option, its value and the rule (an unknown NAME, a
///         range of zero width, a period of too many mesh cycles).
BranchArgs ParseBranch(const std::string& option, const std::string& spec,
                       const transmission::Scene& scene);

/// Runs the branch on the rig's model with `simulation`'s tolerances and back end; writes
/// OUT/periodic_branch.csv (lines as computed), _summary.json and the SVG plots.
/// @throws ComputationFailed saying where the continuation stopped (after writing the branch so
///         far).
void RunBranch(const BranchArgs& args, const dynamics::StageDynamics& rig,
               const dynamics::SimulationOptions& simulation);

}  // namespace epicycle::app
