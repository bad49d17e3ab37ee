// The vibration output of a dynamic run and its spectra (docs/dynamic.md "Spectra"):
//   BASE_vibration.csv        one line per output step as it is computed: time, carrier angle and
//                             every channel of dynamics::VibrationChannels with its unit;
//   BASE_spectrum.csv         at the end, one line per frequency bin: frequency [Hz], carrier
//                             order, order of the sun's speed relative to the carrier, and each
//                             channel's amplitude (Hann window, Welch average) in its unit;
//   BASE_spectrum_lines.csv   the stage's characteristic lines up to the Nyquist frequency
//                             (dynamics::CharacteristicLines) with whether a healthy stage shows
//                             each in a torsional and a housing-fixed signal;
//   BASE_spectrum_CHANNEL.svg log amplitude over mesh order f/f_m for te, ring_force_x,
//                             ring_torque and the sun's first channel, the lines a healthy stage
//                             shows marked
//                             (solid), the mesh harmonics the planet phasing keeps out of a
//                             torsional signal and the tooth-fault fundamentals dashed.
// Every line is written whole and checked (CsvFile); a value that is not finite is an empty cell.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "epicycle/dynamics/spectrum.hpp"
#include "epicycle/dynamics/vibration.hpp"
#include "epicycle/report/files.hpp"
#include "epicycle/report/svg_plot.hpp"

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

/// The amplitude spectrum `amplitude` (bin j at j·resolution [Hz], bin 0 left out) as a log plot,
/// `lines` marked: those `allowed` solid, the others dashed; `legend` names the curve. With
/// `mesh_hz` > 0 (f_m [Hz]) against mesh order f/f_m up to kSpectrumPlotOrders (the paper
/// stage's highest mode is 21 mesh orders at 1500 rpm), else against frequency [Hz], every bin.
inline constexpr double kSpectrumPlotOrders = 32;
LinePlot SpectrumPlot(const std::string& title, const std::string& y_label,
                      const std::vector<double>& amplitude, double resolution,
                      const std::vector<dynamics::SpectralLine>& lines,
                      const std::string& legend = "amplitude", double mesh_hz = 0);

}  // namespace epicycle::report
