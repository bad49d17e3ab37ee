// `epicycle dynamic SCENE --speed-sweep FROM:TO:N --periodic` and `--continue NAME:FROM:TO:N`: the
// stage's periodic orbits continued over the sun speed or another of its parameters
// (dynamics/stage_branch.hpp, docs/periodic.md §3), both branches through the folds with their
// stability, one CSV line per point as it is computed, a JSON record and SVG plots (stable solid,
// unstable dashed, folds marked).
#pragma once

#include <string>

#include "epicycle/dynamics/branch_run.hpp"

namespace epicycle::app {

struct BranchArgs {
  std::string option;  ///< "--speed-sweep" or "--continue": the option that gave the range
  std::string spec;    ///< its value as the user gave it
  std::string out;
  bool quiet = false;
};

/// Parses `--speed-sweep FROM:TO:N` with --periodic (the sun speed) or `--continue NAME:FROM:TO:N`
/// into the request's parameter, range and steps: bad input before any table is built.
/// @throws std::invalid_argument naming the option, its value and the rule (an unknown NAME, a
///         range of zero width, N < 1).
void ParseBranch(const std::string& option, const std::string& spec,
                 dynamics::BranchRequest* request);

/// Runs the branch (dynamics::RunBranch); writes OUT/periodic_branch.csv (lines as computed),
/// _summary.json and the SVG plots.
/// @throws ComputationFailed saying where the continuation stopped (after writing the branch so
///         far).
void RunBranch(const BranchArgs& args, const dynamics::BranchRequest& request);

}  // namespace epicycle::app
