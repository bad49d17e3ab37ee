// `epicycle dynamic SCENE --speed-sweep FROM:TO:N`: the dynamic model at N sun speeds
// (dynamics/speed_sweep.hpp), one CSV row per speed written as it is computed, a JSON summary and
// SVG plots against speed with the coincidences of mesh harmonics and natural frequencies marked.
#pragma once

#include <string>
#include <vector>

#include "epicycle/dynamics/speed_sweep_run.hpp"

namespace epicycle::app {

struct SpeedSweepArgs {
  std::string spec;     ///< "FROM:TO:N" as the user gave it
  std::string out;      ///< output folder
  std::string backend;  ///< as the user named it (the provenance)
  bool quiet = false;
};

/// Runs the sweep of `request` at the speeds of args.spec; writes OUT/speed_sweep.csv (rows as
/// computed), _summary.json and the SVG plots.
/// @throws ComputationFailed naming the failed speeds (after writing everything).
void RunSpeedSweep(const SpeedSweepArgs& args, dynamics::SpeedSweepRequest request);

}  // namespace epicycle::app
