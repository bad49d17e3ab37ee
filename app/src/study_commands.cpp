// `epicycle study FILE`: a tolerance study (docs/studies.md). The rows are written by the studies
// library as they are computed (resumed on a re-run); this command prints progress and writes the
// summary (JSON), K_γ's histogram and empirical CDF (SVG). Under mpirun (built with
// EPICYCLE_WITH_MPI) rank 0 writes every file.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "console.hpp"
#include "epicycle/report/study_files.hpp"
#include "epicycle/studies/runner.hpp"
#include "epicycle/studies/study_summary.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "options.hpp"

namespace epicycle::app {

namespace {

using json = nlohmann::json;

struct StudyArgs {
  std::string study, out = "study-out", cache;
  int threads = 0;  // 0: every core
  long max_cases = -1;
  bool no_cache = false, quiet = false, stresses = false;
};

json Stat(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

void RunStudyCommand(const StudyArgs& a) {
  const studies::MpiSession mpi;
  studies::StudySpec study = studies::ReadStudy(a.study);
  study.scene.model.stresses = study.scene.model.stresses || a.stresses;
  const bool root = mpi.rank() == 0;
  std::filesystem::create_directories(a.out);
  const std::string base = a.out + "/study";
  studies::RunOptions opt;
  opt.rows_file = base + "_rows.csv";
  const json provenance = Provenance(study.backend_name, &study.scene);
  std::string comment = ProvenanceCsvLine(provenance);
  while (!comment.empty() && (comment.back() == '\n')) comment.pop_back();
  if (comment.rfind("# ", 0) == 0) comment = comment.substr(2);
  opt.comment = comment + "; study " + a.study;
  if (!a.no_cache)
    opt.cache_directory = a.cache.empty() ? transmission::DefaultCacheDirectory() : a.cache;
  opt.threads = a.threads > 0 ? a.threads
                              : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  opt.max_new_cases = a.max_cases;
  const bool tty = root && !a.quiet && isatty(fileno(stderr));
  long failed = 0;
  const auto t0 = std::chrono::steady_clock::now();
  opt.on_row = [&](const studies::CaseRow& r, long rows, long total) {
    if (!r.ok) {
      ++failed;
      if (!tty) std::fprintf(stderr, "  case %ld FAILED: %s\n", r.id, r.message.c_str());
    }
    if (tty)
      Progress(static_cast<int>(rows), static_cast<int>(total), static_cast<int>(failed),
               std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
               "cases");
  };
  if (root)
    std::printf("%s: %ld cases (%ld grid points x %ld samples), %zu variables, seed %llu, %s\n",
                study.name.c_str(), study.Cases(), study.GridPoints(), study.samples,
                study.variables.size(), static_cast<unsigned long long>(study.seed),
                mpi.active()
                    ? fmt::format("{} MPI ranks x {} threads", mpi.size(), opt.threads).c_str()
                    : fmt::format("{} threads", opt.threads).c_str());
  const studies::RunReport report = studies::RunStudyMpi(study, opt);
  if (!root) return;
  for (const std::string& m : report.table_messages) std::printf("  %s\n", m.c_str());
  if (report.dropped_partial)
    std::printf("  dropped a truncated last row of %s (a run killed while writing it)\n",
                opt.rows_file.c_str());
  std::printf("  %ld rows resumed, %ld computed in %.3f s (%.1f cases/s; tables %.2f s)\n",
              report.resumed, report.computed, report.seconds,
              report.seconds > 0 ? static_cast<double>(report.computed) / report.seconds : 0.0,
              report.table_seconds);

  const studies::StudySummary s = studies::SummariseStudy(study, report.rows);
  std::printf("\n  %ld of %ld cases in the file, %ld failed (left out of the statistics)\n",
              s.cases, study.Cases(), s.failed);
  std::printf("%s%s%s%s%s", report::SampleSummaryText("K_gamma", s.k_gamma, "").c_str(),
              report::SampleSummaryText("K_gamma (sweep mean)", s.k_gamma_mean, "").c_str(),
              report::SampleSummaryText("TE peak-to-peak", s.te_peak_to_peak, " urad").c_str(),
              report::SampleSummaryText("sun orbit", s.sun_orbit, " um").c_str(),
              report::StudyRootStressText(s.root_stress).c_str());
  std::printf("  Spearman rank correlation of K_gamma with\n");
  for (std::size_t j = 0; j < s.columns.size(); ++j)
    std::printf("    %-36s %s\n", s.columns[j].c_str(),
                Num(s.spearman[j], "{:+.3f}", "- (constant)").c_str());
  PrintWarnings(study.warnings);

  json j;
  j["provenance"] = provenance;
  j["study"] = a.study;
  j["study_hash"] = study.hash;
  j["seed"] = study.seed;
  j["cases_total"] = study.Cases();
  j["cases_in_file"] = s.cases;
  j["cases_failed"] = s.failed;
  j["statistics_note"] =
      "mean CI: normal approximation x +- z s/sqrt(n); percentile CIs: exact binomial order "
      "statistics (distribution-free), null where n is too small for the bound";
  j["K_gamma"] = report::SampleSummaryJson(s.k_gamma);
  j["K_gamma_sweep_mean"] = report::SampleSummaryJson(s.k_gamma_mean);
  j["TE_peak_to_peak_urad"] = report::SampleSummaryJson(s.te_peak_to_peak);
  j["sun_orbit_um"] = report::SampleSummaryJson(s.sun_orbit);
  if (!s.root_stress.empty()) j["root_stress"] = report::StudyRootStressJson(s.root_stress);
  json rho = json::object();
  for (std::size_t k = 0; k < s.columns.size(); ++k) rho[s.columns[k]] = Stat(s.spearman[k]);
  j["spearman_K_gamma"] = rho;
  j["warnings"] = study.warnings;
  j["computed_seconds"] = report.seconds;
  WriteTextFile(base + "_summary.json", j.dump(2) + "\n");

  // Histogram as a step outline; the empirical CDF F(x_(i)) = i/n as steps.
  const auto& h = s.k_gamma_histogram;
  LinePlot hist{study.name + ": K_gamma histogram", "K_gamma [-]", "cases [-]", {}, false, {}};
  hist.series.push_back(report::HistogramOutline("K_gamma", h.lo, h.width, h.counts));
  LinePlot cdf{
      study.name + ": K_gamma empirical CDF", "K_gamma [-]", "F [-]", {}, false, {0.95, 0.99}};
  cdf.series.push_back(report::EmpiricalCdfSteps("empirical CDF", s.k_gamma_sorted));
  WriteTextFile(base + "_kgamma_hist.svg", RenderSvg(hist));
  WriteTextFile(base + "_kgamma_cdf.svg", RenderSvg(cdf));
  std::printf("\nwrote %s_rows.csv, _summary.json, _kgamma_hist.svg, _kgamma_cdf.svg\n",
              base.c_str());
  if (s.failed > 0)
    throw ComputationFailed(
        fmt::format("{} of {} cases failed (their rows say why)", s.failed, s.cases));
}

}  // namespace

void RegisterStudyCommands(CLI::App& app) {
  static StudyArgs a;
  auto* cmd = app.add_subcommand(
      "study",
      "Tolerance study: Monte-Carlo and parameter sweeps of the quasi-static load sharing");
  cmd->add_option("study", a.study, "Study file (TOML, docs/studies.md)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", a.out, "Output folder (rows CSV, summary JSON, SVG); a re-run resumes");
  AddNumber(cmd, "--threads", a.threads, "Worker threads (default: every core)", kThreads);
  AddNumber(cmd, "--max-cases", a.max_cases,
            "Compute at most this many new cases, then summarise (a partial run)",
            transmission::kStudyCases);
  cmd->add_option("--cache", a.cache, "Influence-table cache folder (default: ~/.cache/epicycle)");
  cmd->add_flag("--no-cache", a.no_cache, "Build the influence tables in memory only");
  cmd->add_flag("--quiet", a.quiet, "No progress bar");
  cmd->add_flag("--stresses", a.stresses,
                "Also each gear's root stress per case (the study's or scene's stresses)");
  cmd->callback([] { RunStudyCommand(a); });
}

}  // namespace epicycle::app
