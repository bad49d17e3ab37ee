// The speed sweep's files (docs/speed_sweeps.md): the CSV written a speed at a time and the
// figures against sun speed (its summary JSON is the record's: speed_sweep_run_files.hpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "epicycle/dynamics/load_sharing_parts.hpp"
#include "epicycle/report/provenance.hpp"
#include "epicycle/report/run_files.hpp"
#include "epicycle/report/svg_plot.hpp"
#include "helical_columns.hpp"

namespace epicycle::report {

namespace {

// "dev_sun_rotation,dev_sun_translation,…," : the parts of the largest |LSR_i − 1/n|.
std::string DeviationPartColumns() {
  std::string out;
  for (const char* name : dynamics::kLoadSharingPartNames) out += fmt::format("dev_{},", name);
  return out;
}

}  // namespace

SpeedSweepFile::SpeedSweepFile(const std::string& path, const nlohmann::json& provenance,
                               int helical_planets)
    : csv_(path), helical_planets_(helical_planets) {
  csv_.Write(ProvenanceCsvLine(provenance) +
             "index,sun_speed_rpm,mesh_frequency_Hz,status,K_gamma,dynamic_factor,"
             "dynamic_factor_mesh,peak_mesh_force_N,te_amplitude_urad,sun_orbit_radius_um,lsr_min,"
             "lsr_max,lsr_deviation," +
             DeviationPartColumns() + "largest_residual" + HelicalRangeColumns(helical_planets) +
             ",steps,evaluations,failed_contact_solves,cpu_s,wall_s,message\n");
}

void SpeedSweepFile::Write(const dynamics::SpeedResult& r, const dynamics::SpeedSweepPlan& plan) {
  // A failed speed keeps its speed, status and message; its figures are empty (not zeros).
  auto v = [&](double x) { return r.ok() ? Cell(x) : std::string(); };
  std::string parts;
  for (double x : r.deviation_parts) parts += v(x) + ",";
  csv_.WriteLine(fmt::format(
      "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}", r.index, Cell(r.sun_speed_rpm),
      Cell(r.mesh_frequency), r.ok() ? "ok" : transmission::RunStatusName(r.status), v(r.k_gamma),
      v(r.dynamic_factor), CsvText(r.ok() && r.factor_mesh >= 0 ? plan.meshes[r.factor_mesh] : ""),
      v(r.peak_mesh_force), v(r.te_amplitude * 1e6), v(r.orbit_radius * 1e6), v(r.lsr_min),
      v(r.lsr_max),
      v(r.lsr_deviation) + "," + parts + v(r.largest_residual) +
          HelicalRangeCells(helical_planets_, r.helical, r.ok() && r.helical.count > 0),
      r.stats.steps, r.stats.rhs_evaluations, r.stats.failed_solves, Cell(r.cpu_seconds),
      Cell(r.wall_seconds), CsvText(r.message)));
}

void SpeedSweepFile::Close() { csv_.Close(); }

void WriteSpeedSweepPlots(const std::string& path, const std::string& scene_name,
                          const dynamics::SpeedSweepPlan& plan,
                          const std::vector<dynamics::SpeedResult>& speeds) {
  std::vector<XMarker> markers;
  for (const dynamics::Coincidence& c : plan.coincidences) {
    // A degenerate pair split by an error (e.g. 4941.95 and 4942.25 Hz): one marker "m2,3 h4".
    const std::string tail = fmt::format(" h{}", c.harmonic);
    if (!markers.empty() &&
        std::abs(markers.back().x - c.sun_speed_rpm) <= 1e-3 * c.sun_speed_rpm &&
        markers.back().label.ends_with(tail)) {
      XMarker& m = markers.back();
      m.label.insert(m.label.size() - tail.size(), fmt::format(",{}", c.mode + 1));
      m.dashed = m.dashed && !c.phasing_excited;
      m.rank = std::min(m.rank, c.harmonic + (c.phasing_excited ? 0 : 1000));
      continue;
    }
    // Labels go first to the phasing's excited lines, then to the lower harmonics.
    markers.push_back({c.sun_speed_rpm, fmt::format("m{}", c.mode + 1) + tail, !c.phasing_excited,
                       c.harmonic + (c.phasing_excited ? 0 : 1000)});
  }
  auto plot = [&](const std::string& what, const std::string& unit, const std::string& file,
                  double scale, auto field, std::vector<double> refs) {
    LinePlot p{scene_name + ": " + what + " against sun speed",
               "sun speed [rpm]",
               what + " [" + unit + "]",
               {},
               false,
               std::move(refs)};
    PlotSeries s{what, {}, {}, false};
    for (const dynamics::SpeedResult& r : speeds) {
      if (!r.ok()) continue;
      s.x.push_back(r.sun_speed_rpm);
      s.y.push_back(field(r) * scale);
    }
    p.series.push_back(s);
    p.x_markers = markers;
    WriteTextFile(path + "_" + file + ".svg", RenderSvg(p));
  };
  plot("K_gamma", "-", "k_gamma", 1.0, [](const auto& r) { return r.k_gamma; }, {plan.qs_k_gamma});
  plot("dynamic factor", "-", "dynamic_factor", 1.0, [](const auto& r) { return r.dynamic_factor; },
       {1.0});
  plot("TE amplitude", "urad", "te_amplitude", 1e6, [](const auto& r) { return r.te_amplitude; },
       {plan.qs_te_amplitude * 1e6});
  plot("sun orbit radius", "um", "orbit", 1e6, [](const auto& r) { return r.orbit_radius; }, {});
  // The largest |LSR_i − 1/n| and its parts at that sample and planet (signed: the parts sum to
  // the signed deviation there; the curve is its magnitude).
  LinePlot dev{scene_name + ": largest |LSR - 1/n| and its parts against sun speed",
               "sun speed [rpm]",
               "LSR - 1/n [-]",
               {},
               false,
               {0.0}};
  PlotSeries total{"largest |LSR - 1/n|", {}, {}, false};
  std::vector<PlotSeries> parts;
  for (const char* name : dynamics::kLoadSharingPartNames) parts.push_back({name, {}, {}, false});
  for (const dynamics::SpeedResult& r : speeds) {
    if (!r.ok()) continue;
    total.x.push_back(r.sun_speed_rpm);
    total.y.push_back(r.lsr_deviation);
    // Oriented so that the parts sum to +|LSR − 1/n|.
    double sum = 0;
    for (double x : r.deviation_parts) sum += x;
    const double sign = sum < 0 ? -1.0 : 1.0;
    for (std::size_t k = 0; k < parts.size(); ++k) {
      parts[k].x.push_back(r.sun_speed_rpm);
      parts[k].y.push_back(sign * r.deviation_parts[k]);
    }
  }
  dev.series.push_back(total);
  for (PlotSeries& p : parts) dev.series.push_back(std::move(p));
  dev.x_markers = markers;
  WriteTextFile(path + "_lsr_deviation.svg", RenderSvg(dev));
}

}  // namespace epicycle::report
