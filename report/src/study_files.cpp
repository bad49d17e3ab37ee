#include "epicycle/report/study_files.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include <fmt/format.h>

#include "epicycle/report/files.hpp"
#include "epicycle/report/provenance.hpp"
#include "epicycle/report/record_json.hpp"
#include "epicycle/report/sobol_files.hpp"
#include "epicycle/report/svg_plot.hpp"

namespace epicycle::report {

std::string ExceedanceText(const studies::Exceedance& e) {
  const char* f = "{:.4f}";
  return fmt::format("  P(K_gamma > {}) = {} [{}, {}] ({} of {} cases; {:g} % Clopper-Pearson)\n",
                     e.threshold, Figure(e.p, f, "-"), Figure(e.lower, f, "-"),
                     Figure(e.upper, f, "-"), e.above, e.count, 100.0 * e.level);
}

std::string SampleSummaryText(const std::string& name, const studies::SampleSummary& s,
                              const std::string& unit) {
  const char* f = "{:.6g}";
  std::string out =
      fmt::format("  {:<22} mean {} [{}, {}], std {}, max {}{}\n", name, Figure(s.mean, f, "-"),
                  Figure(s.mean_lower, f, "-"), Figure(s.mean_upper, f, "-"),
                  Figure(s.standard_deviation, f, "-"), Figure(s.max, f, "-"), unit);
  for (const auto& q : s.percentiles)
    out += fmt::format("  {:<22} P{:<5} {} [{}, {}]\n", "", 100.0 * q.p, Figure(q.value, f, "-"),
                       Figure(q.lower, f, "-"), Figure(q.upper, f, "-"));
  return out;
}

std::string StudyRootStressText(const std::vector<studies::GearStressStatistics>& gears) {
  if (gears.empty()) return "";
  // The P95 of each (kStudyPercentiles' second level) with its interval.
  auto cell = [](const studies::SampleSummary& s) {
    const char* f = "{:.1f}";
    for (const auto& q : s.percentiles)
      if (q.p == 0.95)
        return fmt::format("{:>7} {:>7} [{}, {}]", Figure(s.mean, f, "-"), Figure(q.value, f, "-"),
                           Figure(q.lower, f, "-"), Figure(q.upper, f, "-"));
    return fmt::format("{:>7}", Figure(s.mean, f, "-"));
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
        return fmt::format("{:>6} {:>6} [{}, {}] {:>6}", Figure(s.mean, f, "-"),
                           Figure(q.value, f, "-"), Figure(q.lower, f, "-"),
                           Figure(q.upper, f, "-"), Figure(s.min, f, "-"));
    return fmt::format("{:>6}", Figure(s.mean, f, "-"));
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

void WriteStudySummaryFiles(const std::string& base, const std::string& study_name,
                            const studies::StudyRecord& record, const nlohmann::json& provenance) {
  const studies::StudySummary& s = record.summary;
  if (s.sobol)
    WriteTextFile(base + "_sobol.svg",
                  RenderSvg(SobolBarPlot(study_name, *s.sobol, s.sobol->outputs.front())));
  WriteTextFile(base + "_summary.json", SummaryJson(record, provenance).dump(2) + "\n");

  // Histogram as a step outline; the empirical CDF F(x_(i)) = i/n as steps.
  const auto& h = s.k_gamma_histogram;
  LinePlot hist{study_name + ": K_gamma histogram", "K_gamma [-]", "cases [-]", {}, false, {}};
  hist.series.push_back(HistogramOutline("K_gamma", h.lo, h.width, h.counts));
  LinePlot cdf{
      study_name + ": K_gamma empirical CDF", "K_gamma [-]", "F [-]", {}, false, {0.95, 0.99}};
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
    throw std::invalid_argument(m.study_path + ": not the study of " + head.path +
                                " (its hash is " + m.study.hash + "; the part's line is '" +
                                head.study_line +
                                "'): the file changed since the shards ran, or give the study "
                                "file they ran with --study FILE");
  studies::MergedRows merged = studies::MergeParts(m.study, m.parts);
  m.rows = std::move(merged.rows);
  std::filesystem::create_directories(out_dir);
  const std::string base = (std::filesystem::path(out_dir) / "study").string();
  studies::WriteRowsFile(base + "_rows.csv", m.study, merged.comment, m.rows);
  m.record = studies::MakeStudyRecord(m.study, m.study_path, m.rows, 0.0);
  WriteStudySummaryFiles(base, m.study.name, m.record,
                         Provenance(m.study.backend_name, &m.study.scene));
  return m;
}

std::string StudySummaryText(const studies::StudySpec& study, const studies::StudySummary& s) {
  std::string t =
      fmt::format("\n  {} of {} cases in the file, {} failed (left out of the statistics)\n",
                  s.cases, study.Cases(), s.failed);
  if (s.failed > 0)
    t += fmt::format("    by status: {} contact-failure, {} geometry, {} bad-sampled-value\n",
                     s.failed_contact, s.failed_geometry, s.failed_bad_sampled_value);
  t += SampleSummaryText("K_gamma", s.k_gamma, "") +
       SampleSummaryText("K_gamma (sweep mean)", s.k_gamma_mean, "") +
       SampleSummaryText("TE peak-to-peak", s.te_peak_to_peak, " urad") +
       SampleSummaryText("sun orbit", s.sun_orbit, " um") + StudyRootStressText(s.root_stress);
  for (const studies::MeshFaceStatistics& m : s.face_width)
    t += SampleSummaryText("K_gamma K_Hbeta " + m.mesh, m.k_gamma_k_h_beta, "") +
         SampleSummaryText("K_Hbeta " + m.mesh, m.k_h_beta, "");
  for (const studies::ColumnStatistics& c : s.helical)  // a helical stage's axial loads
    t += SampleSummaryText(c.column, c.values, "");
  for (const studies::Exceedance& e : s.k_gamma_exceedance) t += ExceedanceText(e);
  t += "  Spearman rank correlation of K_gamma with\n";
  for (std::size_t j = 0; j < s.columns.size(); ++j)
    t += fmt::format("    {:<36} {}\n", s.columns[j],
                     Figure(s.spearman[j], "{:+.3f}", "- (constant)"));
  if (s.sobol) t += SobolText(*s.sobol);
  return t;
}

}  // namespace epicycle::report
