// The vibration output of a dynamic run (docs/spectra.md): per output step the signals
// a test rig would measure, from what the step's evaluation holds, and the spectrum settings of a
// run.
//
// Channels (SignalKind: torsional or housing-fixed, dynamics/spectrum.hpp):
//   te [rad]                    torsional  the dynamic transmission error at the sun
//   ring_force_x, _y [N]        housing    the force the ring puts on its mounting, inertial frame:
//                                          a held ring passes its meshes' net force
//                                          (Evaluation::ring_mesh_force); an elastic ring its
//                                          springs' and dampers' k_r d + c_r ḋ
//   ring_torque [N·m]           torsional  the ring's moment on its mounting (held: the meshes'
//                                          moment; elastic: k_rt θ + c_rt θ̇)
//   ring_acceleration_x, _y [m/s²]  housing  an elastic ring only: its centre's acceleration
//   sun_force_x, _y [N]         housing    a fixed or elastic sun: the force the sun puts on its
//                                          bearing (held: the meshes' net force on it; elastic:
//                                          −Evaluation::sun_bearing_force)
//   sun_x, _y [m]               housing    a floating sun instead: its centre from nominal (orbit)
#pragma once

#include <string>
#include <vector>

#include "epicycle/dynamics/dynamic_model.hpp"
#include "epicycle/dynamics/run_span.hpp"
#include "epicycle/dynamics/simulation.hpp"
#include "epicycle/dynamics/spectrum.hpp"

namespace epicycle::dynamics {

struct VibrationChannel {
  std::string name;  ///< "te", "ring_force_x", ...
  std::string unit;  ///< "rad", "N", "N m", "m/s2", "m"
  SignalKind kind = SignalKind::kTorsional;
};

/// The channels of `model`'s vibration output, in the order VibrationValues fills them.
std::vector<VibrationChannel> VibrationChannels(const DynamicModel& model);

/// The channels' values at output step `s` of a run of `model` (resized to the channels).
void VibrationValues(const DynamicModel& model, const DynamicSample& s, std::vector<double>* out);

/// What the caller's user gave for a spectrum's settings, for the messages of
/// RunSpectrumOptions: each option's name, whether it was given (a default is said to be one, so
/// that a message never blames an option the user did not give), and what set the run's length.
struct SpectrumInputs {
  std::string resolution_option = "resolution";  ///< e.g. "--spectrum-resolution"
  bool resolution_given = true;
  std::string skip_option = "skip_cycles";  ///< e.g. "--spectrum-skip-cycles"
  bool skip_given = true;
  std::string run = "the run";  ///< what set the run's length: "--range cycle", "--time = 0.1 s"
};

/// Mesh cycles a spectrum leaves out at the start of a run unless told otherwise.
inline constexpr double kDefaultSpectrumSkipCycles = 4;

/// Spectrum settings of a run over `span` (uniform output times T k/N):
///   - the first `skip_cycles` mesh cycles are left out (the start transient, docs/dynamic.md
///     "Start": it decays within a few mesh cycles);
///   - segments 1/`resolution` long [Hz]; resolution 0: one carrier revolution if the rest of
///     the run holds one (every kinematic line is then on a bin: all are whole carrier orders),
///     else the rest of the run in whole mesh cycles (mesh harmonics on bins);
///   - half-overlapping segments (Welch).
/// A segment has 8 samples at least and at most the R output steps after the skip: a resolution
/// given must lie in [1/(R Δt), 1/(8 Δt)] (checked before the segment's length is made a count).
/// @throws std::invalid_argument naming what the user gave (`inputs`) when a value is out of
/// range or the rest of the run is shorter than a segment.
SpectrumOptions RunSpectrumOptions(const RunSpan& span, const StageFrequencies& frequencies,
                                   double resolution, double skip_cycles,
                                   const SpectrumInputs& inputs = {});

}  // namespace epicycle::dynamics
