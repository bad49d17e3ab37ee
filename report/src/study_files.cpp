#include "epicycle/report/study_files.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include <fmt/format.h>

#include "epicycle/report/files.hpp"
#include "epicycle/report/provenance.hpp"
#include "epicycle/report/sobol_files.hpp"
#include "epicycle/report/svg_plot.hpp"

namespace epicycle::report {

namespace {

nlohmann::json Stat(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }

}  // namespace

nlohmann::json SampleSummaryJson(const studies::SampleSummary& s) {
  nlohmann::json j = {{"count", s.count},
                      {"mean", Stat(s.mean)},
                      {"mean_ci", {Stat(s.mean_lower), Stat(s.mean_upper)}},
                      {"std", Stat(s.standard_deviation)},
                      {"min", Stat(s.min)},
                      {"max", Stat(s.max)},
                      {"confidence_level", s.level}};
  nlohmann::json p = nlohmann::json::array();
  for (const auto& q : s.percentiles)
    p.push_back({{"p", q.p}, {"value", Stat(q.value)}, {"ci", {Stat(q.lower), Stat(q.upper)}}});
  j["percentiles"] = p;
  return j;
}

nlohmann::json ExceedanceJson(const studies::Exceedance& e) {
  return {{"k_gamma_limit", e.threshold},
          {"cases", e.count},
          {"above", e.above},
          {"probability", Stat(e.p)},
          {"ci", {Stat(e.lower), Stat(e.upper)}},
          {"interval", "Clopper-Pearson (exact binomial)"},
          {"confidence_level", e.level}};
}

std::string ExceedanceText(const studies::Exceedance& e) {
  const char* f = "{:.4f}";
  return fmt::format("  P(K_gamma > {}) = {} [{}, {}] ({} of {} cases; {:g} % Clopper-Pearson)\n",
                     e.threshold, Num(e.p, f, "-"), Num(e.lower, f, "-"), Num(e.upper, f, "-"),
                     e.above, e.count, 100.0 * e.level);
}

std::string SampleSummaryText(const std::string& name, const studies::SampleSummary& s,
                              const std::string& unit) {
  const char* f = "{:.6g}";
  std::string out =
      fmt::format("  {:<22} mean {} [{}, {}], std {}, max {}{}\n", name, Num(s.mean, f, "-"),
                  Num(s.mean_lower, f, "-"), Num(s.mean_upper, f, "-"),
                  Num(s.standard_deviation, f, "-"), Num(s.max, f, "-"), unit);
  for (const auto& q : s.percentiles)
    out += fmt::format("  {:<22} P{:<5} {} [{}, {}]\n", "", 100.0 * q.p, Num(q.value, f, "-"),
                       Num(q.lower, f, "-"), Num(q.upper, f, "-"));
  return out;
}

nlohmann::json StudyRootStressJson(const std::vector<studies::GearStressStatistics>& gears) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& g : gears) {
    nlohmann::json e = {{"gear", g.gear},
                        {"tension_MPa", SampleSummaryJson(g.tension)},
                        {"compression_magnitude_MPa", SampleSummaryJson(g.compression)},
                        {"largest_range_MPa", SampleSummaryJson(g.range)}};
    if (g.s_f.count > 0) e["S_F"] = SampleSummaryJson(g.s_f);
    if (g.s_h.count > 0) e["S_H"] = SampleSummaryJson(g.s_h);
    list.push_back(e);
  }
  return list;
}

std::string StudyRootStressText(const std::vector<studies::GearStressStatistics>& gears) {
  if (gears.empty()) return "";
  // The P95 of each (kStudyPercentiles' second level) with its interval.
  auto cell = [](const studies::SampleSummary& s) {
    const char* f = "{:.1f}";
    for (const auto& q : s.percentiles)
      if (q.p == 0.95)
        return fmt::format("{:>7} {:>7} [{}, {}]", Num(s.mean, f, "-"), Num(q.value, f, "-"),
                           Num(q.lower, f, "-"), Num(q.upper, f, "-"));
    return fmt::format("{:>7}", Num(s.mean, f, "-"));
  };
  std::string out = fmt::format(
      "  root stress [MPa], each case's largest: mean, P95 [CI]\n    {:<8}  {:<30} {:<30} {}\n",
      "gear", "tension", "|compression|", "range");
  for (const auto& g : gears)
    out += fmt::format("    {:<8}  {:<30} {:<30} {}\n", g.gear, cell(g.tension),
                       cell(g.compression), cell(g.range));
  if (std::none_of(gears.begin(), gears.end(), [](const auto& g) { return g.s_f.count > 0; }))
    return out;
  // The safety factors' low tail: the P5 (kSafetyPercentiles' second level) and the smallest.
  auto low = [](const studies::SampleSummary& s) {
    const char* f = "{:.2f}";
    for (const auto& q : s.percentiles)
      if (q.p == 0.05)
        return fmt::format("{:>6} {:>6} [{}, {}] {:>6}", Num(s.mean, f, "-"), Num(q.value, f, "-"),
                           Num(q.lower, f, "-"), Num(q.upper, f, "-"), Num(s.min, f, "-"));
    return fmt::format("{:>6}", Num(s.mean, f, "-"));
  };
  out += fmt::format(
      "  safety factors from each case's own stresses: mean, P5 [CI], smallest\n    {:<8}  {:<34} "
      "{}\n",
      "gear", "S_F (root tension)", "S_H (contact pressure)");
  for (const auto& g : gears)
    out += fmt::format("    {:<8}  {:<34} {}\n", g.gear, low(g.s_f), low(g.s_h));
  return out;
}

std::string StudyComment(const nlohmann::json& provenance, const std::string& study_path) {
  std::string comment = ProvenanceCsvLine(provenance);
  while (!comment.empty() && comment.back() == '\n') comment.pop_back();
  if (comment.rfind("# ", 0) == 0) comment = comment.substr(2);
  return comment + "; study " + study_path;
}

void WriteStudySummaryFiles(const std::string& base, const studies::StudySpec& study,
                            const studies::StudySummary& s, const nlohmann::json& provenance,
                            const std::string& study_path, double computed_seconds) {
  nlohmann::json j;
  j["provenance"] = provenance;
  j["study"] = study_path;
  j["study_hash"] = study.hash;
  j["seed"] = study.seed;
  j["cases_total"] = study.Cases();
  j["cases_in_file"] = s.cases;
  j["cases_failed"] = s.failed;
  j["statistics_note"] =
      "mean CI: normal approximation x +- z s/sqrt(n); percentile CIs: exact binomial order "
      "statistics (distribution-free), null where n is too small for the bound";
  j["K_gamma"] = SampleSummaryJson(s.k_gamma);
  j["K_gamma_sweep_mean"] = SampleSummaryJson(s.k_gamma_mean);
  j["TE_peak_to_peak_urad"] = SampleSummaryJson(s.te_peak_to_peak);
  j["sun_orbit_um"] = SampleSummaryJson(s.sun_orbit);
  if (!s.k_gamma_exceedance.empty()) {
    nlohmann::json ex = nlohmann::json::array();
    for (const studies::Exceedance& e : s.k_gamma_exceedance) ex.push_back(ExceedanceJson(e));
    j["K_gamma_exceedance"] = ex;
  }
  if (!s.root_stress.empty()) j["root_stress"] = StudyRootStressJson(s.root_stress);
  nlohmann::json rho = nlohmann::json::object();
  for (std::size_t k = 0; k < s.columns.size(); ++k) rho[s.columns[k]] = Stat(s.spearman[k]);
  j["spearman_K_gamma"] = rho;
  if (s.sobol) {
    j["sobol"] = SobolJson(*s.sobol);
    WriteTextFile(base + "_sobol.svg",
                  RenderSvg(SobolBarPlot(study.name, *s.sobol, s.sobol->outputs.front())));
  }
  j["warnings"] = study.warnings;
  j["computed_seconds"] = computed_seconds;
  WriteTextFile(base + "_summary.json", j.dump(2) + "\n");

  // Histogram as a step outline; the empirical CDF F(x_(i)) = i/n as steps.
  const auto& h = s.k_gamma_histogram;
  LinePlot hist{study.name + ": K_gamma histogram", "K_gamma [-]", "cases [-]", {}, false, {}};
  hist.series.push_back(HistogramOutline("K_gamma", h.lo, h.width, h.counts));
  LinePlot cdf{
      study.name + ": K_gamma empirical CDF", "K_gamma [-]", "F [-]", {}, false, {0.95, 0.99}};
  cdf.series.push_back(EmpiricalCdfSteps("empirical CDF", s.k_gamma_sorted));
  WriteTextFile(base + "_kgamma_hist.svg", RenderSvg(hist));
  WriteTextFile(base + "_kgamma_cdf.svg", RenderSvg(cdf));
}

MergedStudy MergeStudy(const std::vector<std::string>& paths, const std::string& out_dir,
                       const std::string& study_path) {
  MergedStudy m;
  m.parts = studies::FindParts(paths);
  const studies::PartHead head = studies::ReadPartHead(m.parts.front());
  m.study_path = study_path.empty() ? head.study_file : study_path;
  if (m.study_path.empty())
    throw std::invalid_argument(head.path +
                                ": the part names no study file; give it with --study FILE");
  try {
    m.study = studies::ReadStudy(m.study_path);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string(e.what()) + " (the study file of " + head.path +
                                (study_path.empty() ? "; give another with --study FILE)" : ")"));
  }
  // The shard's `--stresses` (its part line says so) is part of what it computed.
  m.study.scene.model.stresses = m.study.scene.model.stresses || head.stresses;
  if (head.study_line.find("; study_hash " + m.study.hash + ";") == std::string::npos)
    throw std::invalid_argument(m.study_path + ": not the study of " + head.path + " (its hash is " +
                                m.study.hash + "; the part's line is '" + head.study_line +
                                "'): the file changed since the shards ran, or give the study "
                                "file they ran with --study FILE");
  studies::MergedRows merged = studies::MergeParts(m.study, m.parts);
  m.rows = std::move(merged.rows);
  std::filesystem::create_directories(out_dir);
  const std::string base = (std::filesystem::path(out_dir) / "study").string();
  studies::WriteRowsFile(base + "_rows.csv", m.study, merged.comment, m.rows);
  m.summary = studies::SummariseStudy(m.study, m.rows);
  WriteStudySummaryFiles(base, m.study, m.summary, Provenance(m.study.backend_name, &m.study.scene),
                         m.study_path, 0.0);
  return m;
}

}  // namespace epicycle::report
