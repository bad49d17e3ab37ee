// The duration and output times of a dynamic run: a range of carrier rotation
// (transmission/run_range.hpp) at the carrier speed, or a given time, with a number of outputs
// per mesh cycle.
#pragma once

#include <string>
#include <vector>

#include "epicycle/geometry/stage.hpp"
#include "epicycle/transmission/run_range.hpp"

namespace epicycle::dynamics {

struct RunSpan {
  double duration = 0;        ///< simulated time T [s]
  double cycle_time = 0;      ///< one mesh cycle at the carrier speed, (2π/z_r)/|ω_c| [s]
  double mesh_frequency = 0;  ///< f_m = z_r |ω_c|/2π [Hz]
  /// N = max(1, ⌈T/cycle_time · outputs per cycle · (1 − 1e-12)⌉) [-] (a whole number of
  /// output intervals within round-off is whole)
  int outputs = 0;
  /// t_k = T k/N, k = 1..N [s] (t = 0 is the start, not an output).
  std::vector<double> OutputTimes() const;
};

/// The run over `range` at carrier speed ω_c = `carrier_speed` [rad/s] (its sign is ignored), or
/// over `time` [s] instead when time > 0, with `outputs_per_cycle` outputs per mesh cycle.
/// @throws std::invalid_argument if ω_c is 0 or not finite, time < 0 or not finite,
/// outputs_per_cycle < 1, or the run would have more than kMaxRunOutputs output steps.
/// The most output steps a run may have (1e6: at ~10 kB a kept sample, 10 GB).
inline constexpr int kMaxRunOutputs = 1000000;
RunSpan MakeRunSpan(const geometry::Stage& stage, double carrier_speed,
                    transmission::RunRange range, double time, int outputs_per_cycle);

/// Integrator steps a run of `duration` [s] at sun speed n_s = `sun_rpm` [rpm] is expected to take
/// (CVODE BDF at its defaults): duration × kStepsPerSecondAtOneRpm · √(n_s/rpm), the rate
/// measured on the paper's stage without friction (3.3k, 29k, 92k and 378k steps per simulated
/// second at 1, 10, 100 and 1500 rpm, docs/dynamic_cost.md, "Cost of a long run"); with friction it was
/// up to 7 times more (10 rpm). An estimate of the order of magnitude, for a warning.
inline constexpr double kStepsPerSecondAtOneRpm = 1e4;
double ExpectedSteps(double duration, double sun_rpm);

/// Expected steps past which a run is warned about before it starts (at 20–130 µs a step, 3 to
/// 22 minutes and more; docs/dynamic_cost.md, "Cost of a long run").
inline constexpr double kStepsWarning = 1e7;

/// The warning of a run over `span` at `sun_rpm` [rpm] expected to take more than kStepsWarning
/// steps, "" otherwise: it names what set the duration (`duration_source`, e.g. "--time = 3600 s")
/// and the speed (`speed_source`, e.g. "--speed-rpm = 1"), the estimate and its rule.
std::string RunCostWarning(const RunSpan& span, double sun_rpm, const std::string& duration_source,
                           const std::string& speed_source);

/// The default outputs per mesh cycle of a run (docs/dynamic.md "Outputs"): enough to draw the
/// vibration the run excites, taken as every elastic mode of the model linearised at its
/// operating point up to the kMaxResolvedHarmonic-th mesh harmonic (above that the mesh drives a
/// mode only through the ringing after each change of the contact set, which decays within the
/// cycle): N = min(max(⌈kOutputsPerModePeriod · f_max/f_m⌉, 20), kOutputsPerModePeriod ·
/// kMaxResolvedHarmonic), f_max the highest elastic natural frequency [Hz], f_m the mesh
/// frequency [Hz]. Every mode below the cap then has at least kOutputsPerModePeriod outputs per
/// period; 20 is the floor for a stage whose modes lie near its mesh frequency.
inline constexpr int kOutputsPerModePeriod = 10;
inline constexpr int kMaxResolvedHarmonic = 50;
/// @throws std::invalid_argument if f_m is not positive and finite.
int DefaultOutputsPerCycle(double highest_mode_hz, double mesh_hz);

class DynamicModel;
/// f_max for DefaultOutputsPerCycle: the highest natural frequency of `model` linearised at
/// carrier angle 0 with its own (secant) mesh stiffnesses (DynamicModel::Linearise, SolveModes)
/// [Hz]; 0 if it has no elastic mode.
double HighestModeFrequency(const DynamicModel& model);
/// DefaultOutputsPerCycle at `model`'s own mesh frequency (its sun speed, MeshHzPerSunRpm).
int DefaultOutputsPerCycle(const DynamicModel& model, double highest_mode_hz);

/// Mesh frequency per sun speed, f_m/n_s = z_r/(60 (1 + z_r/z_s)) [Hz/rpm] (ring fixed).
double MeshHzPerSunRpm(const geometry::Stage& stage);

/// The sun speeds at which mesh harmonics h = 1..`harmonics` meet a natural frequency f [Hz]:
/// n_s = f/(h · `hz_per_rpm`) [rpm]; none for f ≤ 0 (a rigid-body mode).
std::vector<double> HarmonicSunSpeeds(double frequency, double hz_per_rpm, int harmonics);

}  // namespace epicycle::dynamics
