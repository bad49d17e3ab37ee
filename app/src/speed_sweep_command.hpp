// `epicycle dynamic SCENE --speed-sweep FROM:TO:N`: the dynamic model at N sun speeds
// (dynamics/speed_sweep.hpp), one CSV row per speed written as it is computed, a JSON summary and
// SVG plots against speed with the coincidences of mesh harmonics and natural frequencies marked.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "epicycle/dynamics/dynamic_model.hpp"
#include "epicycle/dynamics/simulation.hpp"

namespace epicycle::app {

struct SpeedSweepArgs {
  std::string spec;   ///< "FROM:TO:N" as the user gave it
  std::string out;    ///< output folder
  std::string range;  ///< cycle | planet | revolution: the measured window
  std::string backend, integrator;
  double window_cycles = 0;  ///< > 0 replaces the range [mesh cycles]
  double start_deg = 0;      ///< carrier angle where the window begins [deg]
  int outputs_per_cycle = 64;
  int harmonics = 6;  ///< mesh harmonics 1..harmonics for the coincidences
  int threads = 0;    ///< 0: every core
  bool quiet = false;
};

/// The integrator's tolerances and contact back end as a summary JSON's keys (rtol,
/// atol_length_m, atol_angle_rad, rate_tolerance_scale_rad_per_s, contact_tolerance, backend).
void AddTolerances(const dynamics::SimulationOptions& simulation, const std::string& backend,
                   nlohmann::json* j);

/// Parses "FROM:TO:N" (sun speeds [rpm], N speeds, ends included).
/// @throws std::invalid_argument naming --speed-sweep, the value and the rule.
std::vector<double> ParseSpeedSweep(const std::string& spec);

/// Runs the sweep on the rig's stage with `simulation`'s integrator settings; writes
/// OUT/speed_sweep.csv (rows as computed), _summary.json and the SVG plots.
/// @throws ComputationFailed naming the failed speeds (after writing everything).
void RunSpeedSweep(const SpeedSweepArgs& args, const dynamics::StageDynamics& rig,
                   const dynamics::SimulationOptions& simulation);

}  // namespace epicycle::app
