#include "epicycle/report/spectrum_files.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "epicycle/geometry/stage.hpp"
#include "epicycle/report/provenance.hpp"
#include "epicycle/report/svg_plot.hpp"

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
  for (double v : values_) line.append(",").append(Figure(v, "{:.10g}"));
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
      line.append(",").append(Figure(a[static_cast<std::size_t>(j)], "{:.6g}"));
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
                    "signal,name,kind,frequency_Hz,carrier_order,sun_order,harmonic,sideband,"
                    "multiple,healthy\n");
  for (const auto kind : {dynamics::SignalKind::kTorsional, dynamics::SignalKind::kHousing})
    for (const dynamics::SpectralLine& x :
         kind == dynamics::SignalKind::kTorsional ? torsional : housing)
      lines.WriteLine(fmt::format(
          "{},{},{},{:.9g},{:.9g},{:.9g},{},{},{},{}", CsvText(dynamics::SignalKindName(kind)),
          CsvText(x.name), CsvText(dynamics::LineKindName(x.kind)), x.frequency, x.carrier_order,
          x.sun_order, x.harmonic, x.sideband, x.multiple, x.allowed ? 1 : 0));
  lines.Close();
  const std::vector<dynamics::LineKind> faults = dynamics::FaultKinds(
      model_.stage_model().setup().damage, model_.stage_model().stage().spec());
  // The console names the healthy lines and the scene's own faults' only.
  auto own = [&](const dynamics::SpectralLine& x) {
    return x.kind == dynamics::LineKind::kMesh || x.kind == dynamics::LineKind::kCarrierSideband ||
           std::find(faults.begin(), faults.end(), x.kind) != faults.end();
  };

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
        if (own(x) && (d < best || (d == best && x.allowed))) {
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
    SpectrumFigure figure;
    figure.title = fmt::format("{}: {}", title, ch.name);
    figure.y_label = fmt::format("{} amplitude [{}]", ch.name, ch.unit);
    figure.legend = fmt::format("{} segments, {:.3g} Hz", sp.segments(), df);
    figure.kind = ch.kind;
    figure.frequencies = frequencies_;
    figure.faults = faults;
    WriteTextFile(base_ + "_spectrum_" + ch.name + ".svg", SpectrumSvg(figure, amp[c], df));
  }
  return text;
}

std::string SpectrumSvg(const SpectrumFigure& figure, const std::vector<double>& amplitude,
                        double resolution) {
  const dynamics::StageFrequencies& f = figure.frequencies;
  const bool torsional = figure.kind == dynamics::SignalKind::kTorsional;
  const double nyquist = resolution * static_cast<double>(amplitude.size() - 1);
  double top = 0;
  for (std::size_t j = 1; j < amplitude.size(); ++j) top = std::max(top, amplitude[j]);
  // The curve over [0, upto] Hz in units of `unit` Hz.
  auto curve = [&](double upto, double unit) {
    PlotSeries s{figure.legend, {}, {}};
    s.envelope = true;
    for (std::size_t j = 1; j < amplitude.size(); ++j) {
      const double hz = static_cast<double>(j) * resolution;
      if (hz > upto * (1 + 1e-12)) break;
      s.x.push_back(hz / unit);
      s.y.push_back(std::max(amplitude[j], kPlotFloor * top));
    }
    return s;
  };
  auto panel = [&](const std::string& title, const std::string& x_label) {
    LinePlot p;
    p.title = title;
    p.x_label = x_label;
    p.y_label = figure.y_label;
    p.log_y = true;
    p.labels_right = true;
    return p;
  };

  // The whole spectrum over mesh order, up to kSpectrumPlotOrders (the CSV holds every bin): the
  // lines a healthy stage shows (solid) and the mesh harmonics the phasing cancels (dashed).
  const double orders_to = std::min(nyquist, kSpectrumPlotOrders * f.mesh);
  LinePlot whole =
      panel(figure.faults.empty() ? figure.title : "the whole spectrum",
            fmt::format("mesh order f/f_m (f_m = {:.4g} Hz); solid: lines of a healthy stage{}",
                        f.mesh, torsional ? ", dashed: mesh harmonics the phasing cancels" : ""));
  whole.series.push_back(curve(orders_to, f.mesh));
  for (const auto& x : dynamics::CharacteristicLines(f, figure.kind, orders_to, 1, 0))
    if (x.allowed || (torsional && x.kind == dynamics::LineKind::kMesh))
      whole.x_markers.push_back({x.frequency / f.mesh, x.name, !x.allowed, x.allowed ? 0 : 1});
  if (figure.faults.empty()) return RenderSvg(whole);

  // The faults' lowest lines (multiples 0 … 3 of their spacing) over frequency, from 0 to a
  // quarter past the highest of them, at least 12 bins.
  const int multiples = 3;
  double highest = 0;
  for (const auto& x : dynamics::CharacteristicLines(f, figure.kind, nyquist, 1, multiples))
    if (x.harmonic == 0 &&
        std::find(figure.faults.begin(), figure.faults.end(), x.kind) != figure.faults.end())
      highest = std::max(highest, x.frequency);
  const double zoom_to = std::min(nyquist, std::max(1.25 * highest, 12 * resolution));
  std::string gears;
  for (auto k : figure.faults)
    gears +=
        std::string(gears.empty() ? "" : ", ") + (k == dynamics::LineKind::kSunTooth      ? "sun"
                                                  : k == dynamics::LineKind::kPlanetTooth ? "planet"
                                                                                          : "ring");
  LinePlot zoom =
      panel(fmt::format("the lines of the scene's damaged or run-out gears ({}), {} signal", gears,
                        dynamics::SignalKindName(figure.kind)),
            "frequency [Hz]; dashed: those lines (docs/damage.md), solid: a healthy stage's");
  zoom.height = 400;
  zoom.x_min = 0;
  zoom.x_max = zoom_to;
  zoom.series.push_back(curve(zoom_to, 1.0));
  for (const auto& x : dynamics::CharacteristicLines(f, figure.kind, zoom_to, 1, multiples)) {
    const bool fault = x.harmonic == 0 && std::find(figure.faults.begin(), figure.faults.end(),
                                                    x.kind) != figure.faults.end();
    if (fault || x.allowed)
      zoom.x_markers.push_back({x.frequency, x.name, fault, fault ? std::max(1, x.multiple) : 0});
  }
  whole.height = 400;
  return RenderSvgStack(figure.title, {whole, zoom});
}

}  // namespace epicycle::report
