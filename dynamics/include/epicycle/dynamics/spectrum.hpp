// Amplitude spectra of uniformly sampled signals and the characteristic frequencies of a planetary
// stage (docs/spectra.md, docs/model.md §9 "Fault frequencies").
//
// WelchSpectrum: Welch's averaged, windowed periodogram, accumulated as the samples arrive. Each
// segment of N samples has its mean removed, is weighted by the periodic Hann window
// w_k = ½(1 − cos 2πk/N), k = 0..N−1, and transformed (Eigen's FFT); the squared amplitudes are
// averaged over the segments, which start every `hop` samples (default N/2: half-overlapping).
// Memory: one segment per channel and the accumulated spectrum (N/2 + 1 values per channel),
// whatever the length of the run.
//
// Scaling (a sinusoid A cos(2π f t + φ) with f on a bin reads A at that bin):
//   a_j = c_j |X_j| / Σ_k w_k,   X_j = Σ_k w_k x_k e^{−2πi jk/N},   Σ_k w_k = N/2,
// c_j = 2 for 0 < j < N/2 (the negative frequency's half), 1 at j = N/2; the window's coherent
// gain Σw/N = 1/2 is what the division corrects. Averaged: a_j = √(mean over segments of a_j²).
// Bin j is the frequency j Δf, Δf = 1/(N Δt) (the resolution). What the window does:
//   - a line between bins reads less: at δ bins off, |W(δ)|/W(0) = |sinc δ|/(1 − δ²) (N ≫ 1),
//     least half a bin off: 8/(3π) = 0.8488 (−1.42 dB, kHannScallopLoss); its peak lies on the
//     nearest bin, so a line's frequency is known to ±Δf/2;
//   - a line on a bin spreads to its two neighbours at A/2 and nowhere else; two lines are
//     resolved when at least two bins apart;
//   - removing each segment's mean changes only bins 0 and 1 (the window's transform of a
//     constant is nonzero at bins 0 and ±1 only): a mean would otherwise read as a line at Δf.
//     Bin 0 reports the mean over the segments of the segment means, |mean|.
// Noise: white noise of variance σ² reads a_j² = 6σ²/N on average per bin (the Hann window's
// Σw²/(Σw)² = 3/(2N), times c² = 4).
//
// The samples must be uniformly spaced: the first sample accepted (at or after `start_time`) sets
// t_0, the m-th after it must be at t_0 + m Δt within `time_tolerance` Δt; anything else (a
// missing, repeated or late sample) is refused, naming the time, the expected one and the rule.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "epicycle/geometry/stage.hpp"
#include "epicycle/transmission/damage.hpp"

namespace epicycle::dynamics {

/// Σw/N of the periodic Hann window [-] (the amplitude scaling divides by it).
inline constexpr double kHannCoherentGain = 0.5;
/// Amplitude of a line half a bin off its nearest bin relative to its true amplitude, 8/(3π) [-]
/// (N → ∞; for N ≥ 64 the finite-N value differs by < 1e-3 of it).
inline constexpr double kHannScallopLoss = 0.848826363156775;

struct SpectrumOptions {
  double sample_interval = 0;    ///< Δt [s], > 0, finite
  int segment = 0;               ///< N, samples per segment [-], ≥ 8
  int hop = 0;                   ///< samples between segment starts [-], in [1, N]; 0: N/2
  double start_time = 0;         ///< samples before this time are not used [s] (start transient)
  double time_tolerance = 1e-6;  ///< allowed |t − expected| in units of Δt [-], in (0, 0.5)
  /// @throws std::invalid_argument naming the field, its value and the rule.
  void Validate() const;
  double resolution() const { return 1.0 / (segment * sample_interval); }  ///< Δf [Hz]
};

class WelchSpectrum {
 public:
  /// `channels` signals sampled together (≥ 1). @throws std::invalid_argument for bad options.
  WelchSpectrum(int channels, const SpectrumOptions& options);

  /// One sample of every channel at time `time` [s]; samples before options.start_time are
  /// skipped. @throws std::invalid_argument for a time off the uniform grid (see above), a
  /// number of values other than channels(), or a value that is not finite.
  void Add(double time, std::span<const double> values);

  int channels() const { return channels_; }
  int segments() const { return segments_; }  ///< segments averaged so far
  long samples() const { return samples_; }   ///< samples used (after start_time)
  int bins() const { return options_.segment / 2 + 1; }
  double resolution() const { return options_.resolution(); }  ///< Δf [Hz]
  double Frequency(int bin) const { return bin * resolution(); }
  const SpectrumOptions& options() const { return options_; }
  /// Time of the first sample used [s] (NaN before it).
  double first_time() const { return t0_; }

  /// The averaged amplitude spectrum of `channel`, bins() values in the channel's unit (scaling
  /// above). @throws std::logic_error before the first segment is complete;
  /// std::out_of_range for a bad channel.
  std::vector<double> Amplitudes(int channel) const;

 private:
  void Segment();
  int channels_;
  SpectrumOptions options_;
  std::vector<double> window_;  // w_k
  std::vector<double> buffer_;  // channels × N, the current segment
  std::vector<double> power_;   // channels × bins, Σ over segments of a_j²
  std::vector<double> mean_;    // channels, Σ over segments of the segment means
  int fill_ = 0, segments_ = 0;
  long samples_ = 0;
  double t0_;
};

/// The reading of a line at `frequency` [Hz] in an amplitude spectrum (WelchSpectrum::Amplitudes,
/// bin j at j·`resolution`): the largest amplitude of the bins within one bin of it,
/// |j Δf − f| ≤ Δf. For a line of amplitude A with no other line within three bins it lies in
/// [8/(3π) A, A] (kHannScallopLoss; the exact A on a bin). 0 for a frequency outside the bins.
double LineAmplitude(const std::vector<double>& amplitude, double resolution, double frequency);

/// Rotation frequencies of a stage with the ring fixed (docs/model.md §9 "Fault frequencies").
struct StageFrequencies {
  int sun_teeth = 0, planet_teeth = 0, ring_teeth = 0, planets = 0;
  /// Equally spaced planets with (z_s + z_r)/n whole: the planet-phasing rule decides which lines
  /// a healthy stage shows (otherwise every line may appear).
  bool symmetric = false;
  /// No planet carries an error of its own (pin-hole position, run-out, tooth thickness). With
  /// `symmetric`, a sun or ring tooth's lines follow the phasing as well (docs/damage.md "Which
  /// lines a tooth fault puts into which signal"); a planet with an error of its own lets every
  /// order of the fault through.
  bool identical_planets = true;
  double sun = 0;              ///< f_s, the sun's speed [Hz]
  double carrier = 0;          ///< f_c = f_s z_s/(z_s + z_r) [Hz]
  double mesh = 0;             ///< f_m = z_r f_c = z_s (f_s − f_c) [Hz]
  double sun_relative = 0;     ///< f_s − f_c, the sun's speed relative to the carrier [Hz]
  double planet_relative = 0;  ///< f_m/z_p, a planet's speed relative to the carrier [Hz]
};

/// The frequencies of `stage` at sun speed `sun_speed` [rad/s] (its sign is ignored).
/// @throws std::invalid_argument for a speed that is zero or not finite.
StageFrequencies CharacteristicFrequencies(const geometry::Stage& stage, double sun_speed);

/// How a signal sees the stage: a torsional quantity (the sun's rotation, the TE, a member's
/// torque: a scalar, the same in every frame), or a force or displacement component in a fixed
/// direction of the housing (the ring's mounting, the sun's bearing, the sun's orbit), which sees
/// the planets' forces turn with the carrier.
enum class SignalKind { kTorsional, kHousing };
std::string SignalKindName(SignalKind kind);  ///< "torsional", "housing"

enum class LineKind {
  kMesh,             ///< h f_m
  kCarrierSideband,  ///< h f_m ± k f_c
  kSunTooth,         ///< a sun tooth meets the n planets: k n (f_s − f_c) (torsional),
                     ///< k n (f_s − f_c) ± f_s (housing)
  kPlanetTooth,      ///< a planet tooth (one flank or both) meets its mates once a turn of the
                     ///< planet: k f_m/z_p (torsional), k f_m/z_p ± f_c (housing)
  kRingTooth,        ///< the n planets pass one ring tooth: k n f_c (either kind)
};
std::string LineKindName(LineKind kind);  ///< "mesh", "carrier sideband", "sun tooth", ...

/// The tooth-fault lines a scene puts into a spectrum: kSunTooth, kPlanetTooth, kRingTooth for
/// each gear that carries a pit or a crack, or a run-out (`errors`: it repeats with its gear's
/// turn as a damaged tooth does), in that order, each once.
std::vector<LineKind> FaultKinds(const transmission::Damage& damage,
                                 const geometry::StageSpec& errors);

struct SpectralLine {
  std::string name;  ///< "3 f_m", "2 f_m - f_c", "n (f_s - f_c) + f_s", "2 x f_m/z_p", ...
  LineKind kind = LineKind::kMesh;
  double frequency = 0;      ///< [Hz]
  double carrier_order = 0;  ///< f/f_c [-]
  double sun_order = 0;      ///< f/(f_s − f_c) [-]
  /// h of the mesh harmonic the line sits on or beside (0: none; a fault line beside h f_m is
  /// the fault's line nearest to it on that side).
  int harmonic = 0;
  /// Carrier sidebands: the signed k of ± k f_c. Fault lines: the sign s of the housing frame's
  /// shift, the line being |k F + s g| (F the fault's spacing, g = f_s for a sun tooth, f_c for a
  /// planet tooth; s = 0 in a torsional signal and for a ring tooth).
  int sideband = 0;
  int multiple = 1;  ///< fault lines: k of k F + s g [-] (≥ 0); others 1
  /// The line appears in this kind of signal of a healthy stage with identical planets: for a
  /// symmetric stage by the planet phasing (docs/model.md §9): torsional, h f_m when
  /// h z_s ≡ 0 (mod n); housing, h f_m + f_c when h z_s ≡ 1 and h f_m − f_c when
  /// h z_s ≡ −1 (mod n) (dynamics::PhasingFamily), nothing else. Fault lines: false. A stage
  /// that is not symmetric: every mesh and carrier line true.
  bool allowed = false;
};

/// The characteristic lines of `f` in (0, max_frequency] [Hz] for `kind` of signal, sorted by
/// frequency: every mesh harmonic h f_m, their carrier sidebands h f_m ± k f_c for k ≤
/// `carrier_sidebands`, and for each tooth fault its lines in this kind of signal
/// (docs/damage.md "Which lines a tooth fault puts into which signal"): with F its spacing and
/// s g the housing frame's shift, |k F + s g| for k = 0 … `fault_multiples`, and beside every
/// mesh harmonic its nearest line on either side that is not a healthy stage's line. With
/// identical planets on a symmetric stage (f.symmetric, f.identical_planets):
///   sun tooth   torsional k n (f_s − f_c)        housing k n (f_s − f_c) ± f_s
///   planet      torsional k f_m/z_p              housing k f_m/z_p ± f_c
///   ring tooth  either    k n f_c
/// otherwise the sun's and ring's lines are those of n = 1 with the shift f_c: every
/// k (f_s − f_c) (± f_c), every k f_c.
/// @throws std::invalid_argument for max_frequency ≤ 0 or not finite, negative counts.
std::vector<SpectralLine> CharacteristicLines(const StageFrequencies& f, SignalKind kind,
                                              double max_frequency, int carrier_sidebands = 3,
                                              int fault_multiples = 3);

}  // namespace epicycle::dynamics
