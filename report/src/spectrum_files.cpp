#include "epicycle/report/spectrum_files.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "epicycle/geometry/stage.hpp"
#include "epicycle/report/provenance.hpp"

namespace epicycle::report {

namespace {

// Amplitudes below this fraction of a plot's largest are drawn at it: the plot shows 8 decades
// (the integrator's and the contact solve's errors sit far below the lines of interest).
constexpr double kPlotFloor = 1e-8;

std::string UnitSuffix(const std::string& unit) {
  if (unit == "N m") return "Nm";
  if (unit == "m/s2") return "m_per_s2";
  return unit;
}

// Local maxima of a (bins 1.. size−1), largest first, at most `count`.
std::vector<int> Peaks(const std::vector<double>& a, std::size_t count) {
  std::vector<int> p;
  for (std::size_t j = 1; j < a.size(); ++j) {
    const bool left = a[j] > a[j - 1] || j == 1;
    const bool right = j + 1 == a.size() || a[j] >= a[j + 1];
    if (left && right && a[j] > 0) p.push_back(static_cast<int>(j));
  }
  std::sort(p.begin(), p.end(), [&](int x, int y) {
    return a[static_cast<std::size_t>(x)] > a[static_cast<std::size_t>(y)];
  });
  if (p.size() > count) p.resize(count);
  return p;
}

}  // namespace

std::string ChannelColumn(const dynamics::VibrationChannel& channel, const std::string& infix) {
  std::string column = channel.name;
  return column.append(infix).append("_").append(UnitSuffix(channel.unit));
}

VibrationFiles::VibrationFiles(std::string base, const nlohmann::json& provenance,
                               const dynamics::DynamicModel& model,
                               const dynamics::SpectrumOptions& options)
    : base_(std::move(base)),
      provenance_(provenance),
      model_(model),
      channels_(dynamics::VibrationChannels(model)),
      frequencies_(
          dynamics::CharacteristicFrequencies(model.stage_model().stage(), model.sun_speed())),
      spectrum_(static_cast<int>(channels_.size()), options),
      csv_(base_ + "_vibration.csv", [&] {
        std::string head = ProvenanceCsvLine(provenance) + "time_s,carrier_deg";
        for (const auto& c : channels_) head.append(",").append(ChannelColumn(c));
        return head + "\n";
      }()) {}

void VibrationFiles::Write(const dynamics::DynamicSample& s) {
  dynamics::VibrationValues(model_, s, &values_);
  std::string line = fmt::format("{:.9g},{:.6f}", s.time, geometry::Deg(s.carrier_angle));
  for (double v : values_) line.append(",").append(Num(v, "{:.10g}"));
  csv_.WriteLine(line);
  spectrum_.Add(s.time, values_);
}

std::string VibrationFiles::Close(const std::string& title) {
  csv_.Close();
  const dynamics::WelchSpectrum& sp = spectrum_;
  if (sp.segments() == 0)
    return fmt::format("  spectrum: none, the run ended after {} of the {} samples of a segment\n",
                       sp.samples(), sp.options().segment);
  const int nb = sp.bins();
  const double df = sp.resolution(), fc = frequencies_.carrier, fr = frequencies_.sun_relative;
  std::vector<std::vector<double>> amp;
  for (int c = 0; c < sp.channels(); ++c) amp.push_back(sp.Amplitudes(c));

  std::string head = ProvenanceCsvLine(provenance_) + "frequency_Hz,carrier_order,sun_order";
  for (const auto& c : channels_) head.append(",").append(ChannelColumn(c, "_amplitude"));
  CsvFile csv(base_ + "_spectrum.csv", head + "\n");
  for (int j = 0; j < nb; ++j) {
    const double f = sp.Frequency(j);
    std::string line = fmt::format("{:.9g},{:.9g},{:.9g}", f, f / fc, f / fr);
    for (const auto& a : amp)
      line.append(",").append(Num(a[static_cast<std::size_t>(j)], "{:.6g}"));
    csv.WriteLine(line);
  }
  csv.Close();

  const double nyquist = sp.Frequency(nb - 1);
  const auto torsional =
      dynamics::CharacteristicLines(frequencies_, dynamics::SignalKind::kTorsional, nyquist);
  const auto housing =
      dynamics::CharacteristicLines(frequencies_, dynamics::SignalKind::kHousing, nyquist);
  CsvFile lines(base_ + "_spectrum_lines.csv",
                ProvenanceCsvLine(provenance_) +
                    "name,kind,frequency_Hz,carrier_order,sun_order,harmonic,sideband,multiple,"
                    "healthy_torsional,healthy_housing\n");
  for (std::size_t k = 0; k < torsional.size(); ++k) {
    const dynamics::SpectralLine& x = torsional[k];
    lines.WriteLine(fmt::format("{},{},{:.9g},{:.9g},{:.9g},{},{},{},{},{}", CsvText(x.name),
                                CsvText(dynamics::LineKindName(x.kind)), x.frequency,
                                x.carrier_order, x.sun_order, x.harmonic, x.sideband, x.multiple,
                                x.allowed ? 1 : 0, housing[k].allowed ? 1 : 0));
  }
  lines.Close();

  std::string text = fmt::format(
      "  spectrum: {} segments of {} samples ({:.4g} s, Hann, half-overlapping) from t = {:.4g} "
      "s, resolution {:.4g} Hz = {:.4g} carrier orders; f_c {:.4f} Hz, f_m {:.3f} Hz; largest "
      "peaks (the nearest characteristic line within one bin):\n",
      sp.segments(), sp.options().segment, sp.options().segment * sp.options().sample_interval,
      sp.first_time(), df, df / fc, fc, frequencies_.mesh);
  std::vector<std::string> written;
  for (std::size_t c = 0; c < channels_.size(); ++c) {
    const dynamics::VibrationChannel& ch = channels_[c];
    const auto& all = ch.kind == dynamics::SignalKind::kTorsional ? torsional : housing;
    text += fmt::format("    {:<22}", ch.name);
    for (int j : Peaks(amp[c], 4)) {
      // The nearest characteristic line within one bin (the resolution), "-" if none.
      std::string near = "-";
      double best = df * (1 + 1e-9);
      for (const auto& x : all) {
        const double d = std::abs(x.frequency - sp.Frequency(j));
        if (d < best || (d == best && x.allowed)) {
          best = d;
          near = x.name;
        }
      }
      text += fmt::format(" {:.1f} Hz ({}) {:.3g} {};", sp.Frequency(j), near,
                          amp[c][static_cast<std::size_t>(j)], ch.unit);
    }
    text += "\n";
    const bool plot = ch.name == "te" || ch.name == "ring_force_x" || ch.name == "ring_torque" ||
                      ch.name == "sun_force_x" || ch.name == "sun_x" ||
                      ch.name == "ring_acceleration_x";
    if (!plot) continue;
    // Marked: what a healthy stage shows, the mesh harmonics the phasing removes from a torsional
    // signal, and the tooth-fault fundamentals.
    std::vector<dynamics::SpectralLine> marked;
    for (const auto& x : all) {
      const bool fault = x.multiple == 1 && x.harmonic == 0;
      if (x.allowed || fault ||
          (x.kind == dynamics::LineKind::kMesh && ch.kind == dynamics::SignalKind::kTorsional))
        marked.push_back(x);
    }
    const std::string path = base_ + "_spectrum_" + ch.name + ".svg";
    WriteTextFile(path, RenderSvg(SpectrumPlot(
                            fmt::format("{}: {}", title, ch.name),
                            fmt::format("{} amplitude [{}]", ch.name, ch.unit), amp[c], df, marked,
                            fmt::format("{} segments, {:.3g} Hz", sp.segments(), df),
                            frequencies_.mesh)));
  }
  return text;
}

LinePlot SpectrumPlot(const std::string& title, const std::string& y_label,
                      const std::vector<double>& amplitude, double resolution,
                      const std::vector<dynamics::SpectralLine>& lines, const std::string& legend,
                      double mesh_hz) {
  LinePlot p;
  p.title = title;
  const bool orders = mesh_hz > 0 && std::isfinite(mesh_hz);
  const double unit = orders ? mesh_hz : 1.0;  // x = frequency / unit
  p.x_label = (orders ? fmt::format("mesh order f/f_m (f_m = {:.4g} Hz)", mesh_hz)
                      : std::string("frequency [Hz]")) +
              " (solid: lines of a healthy stage; dashed: phasing-cancelled or fault)";
  p.y_label = y_label;
  p.log_y = true;
  PlotSeries s{legend, {}, {}};
  double top = 0;
  for (std::size_t j = 1; j < amplitude.size(); ++j) top = std::max(top, amplitude[j]);
  // Against mesh order: up to kSpectrumPlotOrders (the CSV holds every bin).
  for (std::size_t j = 1; j < amplitude.size(); ++j) {
    if (orders && static_cast<double>(j) * resolution > kSpectrumPlotOrders * mesh_hz) break;
    s.x.push_back(static_cast<double>(j) * resolution / unit);
    s.y.push_back(std::max(amplitude[j], kPlotFloor * top));
  }
  p.series.push_back(std::move(s));
  for (const auto& x : lines) p.x_markers.push_back({x.frequency / unit, x.name, !x.allowed});
  return p;
}

}  // namespace epicycle::report
