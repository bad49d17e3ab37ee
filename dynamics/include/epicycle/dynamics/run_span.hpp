// The duration and output times of a dynamic run: a range of carrier rotation
// (transmission/run_range.hpp) at the carrier speed, or a given time, with a number of outputs
// per mesh cycle.
#pragma once

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

/// Mesh frequency per sun speed, f_m/n_s = z_r/(60 (1 + z_r/z_s)) [Hz/rpm] (ring fixed).
double MeshHzPerSunRpm(const geometry::Stage& stage);

/// The sun speeds at which mesh harmonics h = 1..`harmonics` meet a natural frequency f [Hz]:
/// n_s = f/(h · `hz_per_rpm`) [rpm]; none for f ≤ 0 (a rigid-body mode).
std::vector<double> HarmonicSunSpeeds(double frequency, double hz_per_rpm, int harmonics);

}  // namespace epicycle::dynamics
