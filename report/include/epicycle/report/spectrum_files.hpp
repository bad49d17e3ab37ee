// The vibration output of a dynamic run and its spectra (docs/spectra.md):
//   BASE_vibration.csv        one line per output step as it is computed: time, carrier angle and
//                             every channel of dynamics::VibrationChannels with its unit;
//   BASE_spectrum.csv         at the end, one line per frequency bin: frequency [Hz], carrier
//                             order, order of the sun's speed relative to the carrier, and each
//                             channel's amplitude (Hann window, Welch average) in its unit;
//   BASE_spectrum_lines.csv   the stage's characteristic lines up to the Nyquist frequency
//                             (dynamics::CharacteristicLines), a row per kind of signal
//                             (torsional, housing) and line, with whether a healthy stage shows
//                             it in that kind of signal; every tooth fault's lines are listed,
//                             whatever the scene's damage;
//   BASE_spectrum_CHANNEL.svg for te, ring_force_x, ring_torque and the sun's first channel
//                             (SpectrumSvg): log amplitude over mesh order with the lines of a
//                             healthy stage, and with damage or a run-out a panel over its
//                             lines.
// Every line is written whole and checked (CsvFile); a value that is not finite is an empty cell.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "epicycle/dynamics/spectrum.hpp"
#include "epicycle/dynamics/vibration.hpp"
#include "epicycle/report/files.hpp"

namespace epicycle::report {

/// A column name with its unit: "ring_force_x_N", "ring_torque_Nm", "te_rad".
std::string ChannelColumn(const dynamics::VibrationChannel& channel, const std::string& infix = "");

class VibrationFiles {
 public:
  /// Creates BASE_vibration.csv (its head at once) and the spectrum's accumulator.
  /// @throws std::runtime_error naming a file that cannot be written; std::invalid_argument
  ///         for bad spectrum options.
  VibrationFiles(std::string base, const nlohmann::json& provenance,
                 const dynamics::DynamicModel& model, const dynamics::SpectrumOptions& options);
  /// One output step: its line, and its values into the spectrum.
  void Write(const dynamics::DynamicSample& s);
  /// Closes BASE_vibration.csv and, if at least one segment is complete, writes the spectrum's
  /// CSV files and SVGs (`title`: the scene's name). Returns a console summary (the resolution,
  /// segments, the largest lines of each channel), or why there is no spectrum.
  std::string Close(const std::string& title);
  const dynamics::WelchSpectrum& spectrum() const { return spectrum_; }

 private:
  std::string base_;
  nlohmann::json provenance_;
  const dynamics::DynamicModel& model_;
  std::vector<dynamics::VibrationChannel> channels_;
  dynamics::StageFrequencies frequencies_;
  dynamics::WelchSpectrum spectrum_;
  CsvFile csv_;
  std::vector<double> values_;
};

/// One channel's spectrum figure (BASE_spectrum_CHANNEL.svg).
struct SpectrumFigure {
  std::string title;    ///< "paper stage, 3 planets: te"
  std::string y_label;  ///< "te amplitude [rad]"
  std::string legend;   ///< names the curve: "5 segments, 4.94 Hz"
  dynamics::SignalKind kind = dynamics::SignalKind::kTorsional;
  dynamics::StageFrequencies frequencies;
  /// The scene's damaged or run-out gears (dynamics::FaultKinds): only their lines are marked.
  std::vector<dynamics::LineKind> faults;
};

/// The amplitude spectrum `amplitude` (bin j at j·resolution [Hz], bin 0 left out) as an SVG: a
/// log plot over mesh order f/f_m up to kSpectrumPlotOrders (the paper stage's highest mode is
/// 21 mesh orders at 1500 rpm) with the lines a healthy stage shows in this kind of signal
/// marked solid and the mesh harmonics the phasing keeps out of a torsional signal dashed; with
/// faults, under it a panel over frequency [Hz] from 0 past the faults' lowest lines
/// (their multiples 0 … 3) with those marked dashed. Each label starts at its line;
/// a curve denser than the pixels is drawn light under its upper envelope.
inline constexpr double kSpectrumPlotOrders = 32;
std::string SpectrumSvg(const SpectrumFigure& figure, const std::vector<double>& amplitude,
                        double resolution);

}  // namespace epicycle::report
