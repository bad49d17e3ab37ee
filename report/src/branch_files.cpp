#include "epicycle/report/branch_files.hpp"

#include <stdexcept>

#include <fmt/format.h>

#include "epicycle/report/provenance.hpp"
#include "helical_columns.hpp"

namespace epicycle::report {

namespace {
const std::string kSunSpeed = dynamics::StagePeriodicSystem::kSunSpeed;

// The provenance line and the columns: the parameter's, the sun speed's when it is another, a
// helical stage's axial loads over the period after the figures.
std::string BranchHead(const nlohmann::json& provenance, const std::string& parameter,
                       int helical_planets) {
  std::string head = ProvenanceCsvLine(provenance);
  head += "index,";
  head += parameter;
  if (parameter != kSunSpeed) head += ",sun_speed_rpm";
  head +=
      ",period_s,stability,spectral_radius,real_multipliers_above_1,"
      "real_multipliers_below_minus_1,complex_multipliers_outside,K_gamma,te_amplitude_urad,"
      "sun_orbit_radius_um";
  if (helical_planets > 0) head += HelicalRangeColumns(helical_planets);
  head += ",arclength,corrector_iterations,bifurcations_before,bifurcation_parameters\n";
  return head;
}
}  // namespace


std::vector<PlotSeries> StabilitySegments(const std::string& name, const std::vector<double>& x,
                                          const std::vector<double>& y,
                                          const std::vector<bool>& stable, int colour) {
  if (x.size() != y.size() || x.size() != stable.size())
    throw std::invalid_argument("stability segments: x, y and stable must have one size (" +
                                std::to_string(x.size()) + ", " + std::to_string(y.size()) +
                                ", " + std::to_string(stable.size()) + ")");
  std::vector<PlotSeries> out;
  bool named_stable = false, named_unstable = false;
  for (std::size_t k = 0; k < x.size();) {
    PlotSeries seg;
    seg.colour = colour;
    seg.dashed = !stable[k];
    if (stable[k] && !named_stable) seg.name = name + ", stable", named_stable = true;
    if (!stable[k] && !named_unstable) seg.name = name + ", unstable", named_unstable = true;
    std::size_t j = k;
    for (; j < x.size() && stable[j] == stable[k]; ++j) {
      seg.x.push_back(x[j]);
      seg.y.push_back(y[j]);
    }
    if (j < x.size()) {
      seg.x.push_back(x[j]);
      seg.y.push_back(y[j]);
    }
    out.push_back(std::move(seg));
    k = j;
  }
  return out;
}

BranchFile::BranchFile(const std::string& path, const nlohmann::json& provenance,
                       const std::string& parameter, int helical_planets)
    : csv_(path, BranchHead(provenance, parameter, helical_planets)),
      speed_column_(parameter != kSunSpeed),
      helical_planets_(helical_planets) {}

void BranchFile::Update(const dynamics::StageBranchRecord& r) {
  for (; written_ < r.points.size(); ++written_) {
    const dynamics::StageBranchPoint& p = r.points[written_];
    std::string kinds, where;
    for (const dynamics::StageBranchBifurcation& b : r.bifurcations)
      if (b.after_point == p.index) {
        if (!kinds.empty()) kinds += ';', where += ';';
        kinds += dynamics::BifurcationKindName(b.kind);
        where += Cell(b.parameter);
      }
    std::string speed;
    if (speed_column_) speed = ',', speed += Cell(p.sun_speed_rpm);
    csv_.WriteLine(fmt::format(
        "{},{}{},{},{},{},{},{},{},{},{},{}{},{},{},{},{}", p.index, Cell(p.parameter), speed,
        Cell(p.period), dynamics::StabilityName(p.stability), Cell(p.spectral_radius),
        p.real_above_one, p.real_below_minus_one, p.complex_outside, Cell(p.k_gamma),
        Cell(p.te_amplitude * 1e6), Cell(p.orbit_radius * 1e6),
        helical_planets_ > 0 ? HelicalRangeCells(helical_planets_, p.helical, p.helical.count > 0)
                             : std::string(),
        Cell(p.arclength), p.corrector_iterations, CsvText(kinds), CsvText(where)));
  }
}

void BranchFile::Close() { csv_.Close(); }

std::string BranchPlanText(const dynamics::BranchPlan& plan, const std::string& given) {
  const dynamics::StageBranchOptions& o = *plan.options;
  const dynamics::StageDynamics& rig = *plan.rig;
  std::string t = fmt::format(
      "{}: periodic orbits continued over {} from {} to {} ({}), sun {}, period {} mesh "
      "cycle(s), rtol {:.1e}, {}\n",
      rig.scene.name, o.parameter, Cell(o.start), Cell(o.end), given,
      transmission::SunSupportName(rig.stage_model.setup().sun), o.period.mesh_cycles,
      o.simulation.rtol,
      o.method == dynamics::PeriodicMethod::kHarmonicBalance
          ? fmt::format("harmonic balance with {} harmonics", o.harmonics)
          : std::string("shooting"));
  for (const std::string& m : rig.compliance.tables().messages()) t += "  " + m + "\n";
  t += fmt::format("  {:<6} {:<14} {:<10} {:<11} {:<10} {:<12} {}\n", "point", o.parameter,
                   "stability", "max |mu|", "K_gamma", "TE amp urad", "bifurcations before");
  return t;
}

std::string BranchPointsText(const dynamics::StageBranchRecord& r, std::size_t from) {
  std::string t;
  for (std::size_t k = from; k < r.points.size(); ++k) {
    const dynamics::StageBranchPoint& p = r.points[k];
    std::string before;
    for (const dynamics::StageBranchBifurcation& b : r.bifurcations)
      if (b.after_point == p.index)
        before += fmt::format("{} at {} ", dynamics::BifurcationKindName(b.kind), Cell(b.parameter));
    t += fmt::format("  {:<6} {:<14} {:<10} {:<11.6f} {:<10.5f} {:<12.4f} {}\n", p.index,
                     Cell(p.parameter), dynamics::StabilityName(p.stability), p.spectral_radius,
                     p.k_gamma, p.te_amplitude * 1e6, before);
  }
  return t;
}

std::string BranchRecordText(const dynamics::BranchRecord& record) {
  const dynamics::StageBranchRecord& r = record.branch;
  int unstable = 0;
  for (const dynamics::StageBranchPoint& p : r.points)
    unstable += p.stability == dynamics::Stability::kUnstable;
  if (r.method == dynamics::PeriodicMethod::kHarmonicBalance)
    return fmt::format(
        "\n  {} points ({} unstable), {} bifurcations; {} linearisations and {} residuals of "
        "the harmonic balance ({} evaluations); {:.2f} s CPU, {:.2f} s wall\n",
        r.points.size(), unstable, r.bifurcations.size(), r.integrations, r.plain_integrations,
        r.steps, r.cpu_seconds, r.wall_seconds);
  const std::string rebuilt =
      r.rebuilds > 0 ? fmt::format("; {} stages rebuilt with the error's values", r.rebuilds)
                     : std::string();
  return fmt::format(
      "\n  {} points ({} unstable), {} bifurcations; {} periods integrated with the "
      "variational equations and {} without ({} steps){}; {:.2f} s CPU, {:.2f} s wall\n",
      r.points.size(), unstable, r.bifurcations.size(), r.integrations, r.plain_integrations,
      r.steps, rebuilt, r.cpu_seconds, r.wall_seconds);
}

void WriteBranchPlots(const std::string& path, const std::string& scene_name,
                      const dynamics::StageBranchRecord& r) {
  std::vector<double> x;
  std::vector<bool> stable;
  for (const dynamics::StageBranchPoint& p : r.points) {
    x.push_back(p.parameter);
    stable.push_back(p.stability != dynamics::Stability::kUnstable);
  }
  std::vector<XMarker> folds;
  for (const dynamics::StageBranchBifurcation& b : r.bifurcations)
    folds.push_back({b.parameter,
                     fmt::format("{} {:.5g}", dynamics::BifurcationKindName(b.kind), b.parameter),
                     false, b.kind == dynamics::BifurcationKind::kFold ? 0 : 1});
  const std::string x_label = r.parameter + " (periodic orbits: stable solid, unstable dashed)";
  auto plot = [&](const std::string& what, const std::string& unit, const std::string& file,
                  double scale, auto field, std::vector<double> refs) {
    std::vector<double> y;
    for (const dynamics::StageBranchPoint& p : r.points) y.push_back(field(p) * scale);
    LinePlot figure{scene_name + ": " + what + " along the branch", x_label,
                    what + " [" + unit + "]", StabilitySegments(what, x, y, stable), false,
                    std::move(refs)};
    figure.x_markers = folds;
    WriteTextFile(path + "_" + file + ".svg", RenderSvg(figure));
  };
  plot("K_gamma", "-", "k_gamma", 1.0, [](const auto& p) { return p.k_gamma; }, {});
  plot("TE amplitude", "urad", "te_amplitude", 1e6, [](const auto& p) { return p.te_amplitude; },
       {});
  plot("Floquet spectral radius", "-", "spectral_radius", 1.0,
       [](const auto& p) { return p.spectral_radius; }, {1.0});
  bool moves = false;
  for (const dynamics::StageBranchPoint& p : r.points) moves = moves || p.orbit_radius > 0;
  if (moves)
    plot("sun orbit radius", "um", "orbit", 1e6, [](const auto& p) { return p.orbit_radius; }, {});
}

}  // namespace epicycle::report
