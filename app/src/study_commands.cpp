// `epicycle study FILE`: a tolerance study (docs/studies.md). The rows are written by the studies
// library as they are computed (resumed on a re-run); this command prints progress and writes the
// summary (JSON), K_γ's histogram and empirical CDF (SVG). Under mpirun (built with
// EPICYCLE_WITH_MPI) rank 0 writes every file.
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "console.hpp"
#include "epicycle/io/spec_fields.hpp"
#include "epicycle/report/sobol_files.hpp"
#include "epicycle/report/study_files.hpp"
#include "epicycle/studies/runner.hpp"
#include "epicycle/studies/sobol.hpp"
#include "epicycle/studies/study_run.hpp"
#include "epicycle/studies/study_summary.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "options.hpp"

namespace epicycle::app {

namespace {

using json = nlohmann::json;

struct StudyArgs {
  std::string study, out = "study-out", cases, shard;
  int threads = 0;  // 0: every core
  long max_cases = -1;
  TableArgs tables;
  bool quiet = false, stresses = false;
};

// "I:J" (--cases) or "K/N" (--shard): two whole numbers as CLI11 would read them.
std::array<long, 2> TwoWholeNumbers(const std::string& text, char separator,
                                    const std::string& message) {
  const std::vector<std::string> f = io::Fields(text, separator);
  try {
    if (f.size() != 2) throw std::invalid_argument(text);
    return {io::Whole(f[0]), io::Whole(f[1])};
  } catch (const std::logic_error&) {
    throw std::invalid_argument(message);
  }
}

std::string DesignText(const studies::StudySpec& study) {
  if (study.design == studies::Design::kSobol)
    return fmt::format("Sobol design: N (d + 2) = {} x {}", study.samples,
                       study.variables.size() + 2);
  return fmt::format("{} grid points x {} samples", study.GridPoints(), study.samples);
}

// The program's study sink: a failed case on stderr (or counted in the progress bar).
class StudyConsole final : public studies::StudySink {
 public:
  explicit StudyConsole(bool quiet) : bar_(quiet) {}
  void Row(const studies::CaseRow& r, long rows, long total) override {
    if (!r.ok()) {
      ++failed_;
      if (!bar_.tty()) std::fprintf(stderr, "  case %ld FAILED: %s\n", r.id, r.message.c_str());
    }
    bar_.Show(static_cast<int>(rows), static_cast<int>(total), static_cast<int>(failed_), "cases");
  }

 private:
  ProgressBar bar_;
  long failed_ = 0;
};

// The summary on the console after its files (BASE_rows.csv, ...) are written.
void PrintSummary(const studies::StudySpec& study, const studies::StudySummary& s,
                  const std::string& base) {
  Print(report::StudySummaryText(study, s));
  PrintWarnings(study.warnings);
  std::printf("\nwrote %s_rows.csv, _summary.json, _kgamma_hist.svg, _kgamma_cdf.svg%s\n",
              base.c_str(), s.sobol ? ", _sobol.svg" : "");
  if (s.failed > 0)
    throw ComputationFailed(
        fmt::format("{} of {} cases failed (their rows say why)", s.failed, s.cases));
}

void RunStudyCommand(const StudyArgs& a) {
  const studies::MpiSession mpi;
  studies::StudyRequest request;
  request.study = studies::ReadStudy(a.study);
  request.study_path = a.study;
  request.stresses = a.stresses;
  request.threads = a.threads;
  request.max_cases = a.max_cases;
  request.rank = mpi.rank();
  const studies::StudySpec& study = request.study;
  const bool root = mpi.rank() == 0;
  std::filesystem::create_directories(a.out);
  const std::string base = a.out + "/study";
  if (!a.cases.empty() && !a.shard.empty())
    throw std::invalid_argument("--cases = " + a.cases + " and --shard = " + a.shard +
                                ": give one of them (both select the cases of a part)");
  if (!a.cases.empty()) {
    const auto [first, last] = TwoWholeNumbers(
        a.cases, ':',
        "--cases = " + a.cases + ": must be I:J, two whole numbers (the case ids I <= k < J)");
    request.part = studies::CaseRange{first, last};
    studies::CheckCaseRange(*request.part, study.Cases(), "--cases");
  }
  if (!a.shard.empty()) {
    const auto [k, n] = TwoWholeNumbers(
        a.shard, '/',
        "--shard = " + a.shard + ": must be K/N, two whole numbers (shard K of N, K from 0)");
    request.part = studies::ShardRange(study.Cases(), k, n, "--shard");
  }
  request.rows_file =
      request.part ? a.out + "/" + studies::PartFileName(*request.part) : base + "_rows.csv";
  const json provenance = Provenance(study.backend_name, &study.scene);
  request.comment = report::StudyComment(provenance, a.study);
  request.cache_directory = a.tables.Options().cache_directory;
  const int threads = a.threads > 0
                          ? a.threads
                          : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (root)
    std::printf("%s: %ld cases (%s), %zu variables, seed %llu, %s\n", study.name.c_str(),
                study.Cases(), DesignText(study).c_str(), study.variables.size(),
                static_cast<unsigned long long>(study.seed),
                mpi.active() ? fmt::format("{} MPI ranks x {} threads", mpi.size(), threads).c_str()
                             : fmt::format("{} threads", threads).c_str());
  StudyConsole console(!root || a.quiet);
  const studies::StudyRun run = studies::RunStudy(request, console);
  if (!root) return;
  const studies::RunReport& report = run.report;
  for (const std::string& m : report.table_messages) std::printf("  %s\n", m.c_str());
  if (report.dropped_partial)
    std::printf("  dropped a truncated last row of %s (a run killed while writing it)\n",
                request.rows_file.c_str());
  std::printf("  %ld rows resumed, %ld computed in %.3f s (%.1f cases/s; tables %.2f s)\n",
              report.resumed, report.computed, report.seconds,
              report.seconds > 0 ? static_cast<double>(report.computed) / report.seconds : 0.0,
              report.table_seconds);
  if (request.part) {
    // A part: its rows only; the summary is the merge's (over every case).
    long failed_rows = 0;
    for (const studies::CaseRow& r : report.rows) failed_rows += r.ok() ? 0 : 1;
    std::printf(
        "\nwrote %s: cases %ld:%ld, %zu of %ld rows (join the parts with `epicycle "
        "study merge %s`)\n",
        request.rows_file.c_str(), request.part->first, request.part->last, report.rows.size(),
        request.part->Size(), a.out.c_str());
    if (failed_rows > 0)
      throw ComputationFailed(fmt::format("{} of {} cases failed (their rows say why)", failed_rows,
                                          report.rows.size()));
    return;
  }

  report::WriteStudySummaryFiles(base, study.name, *run.record, provenance);
  PrintSummary(study, run.record->summary, base);
}

struct MergeArgs {
  std::vector<std::string> parts;
  std::string out = "study-out", study;
};

void MergeStudyCommand(const MergeArgs& a) {
  const report::MergedStudy m = report::MergeStudy(a.parts, a.out, a.study);
  std::printf("%s: %zu parts of %s merged, %ld cases\n", m.study.name.c_str(), m.parts.size(),
              m.study_path.c_str(), m.study.Cases());
  PrintSummary(m.study, m.record.summary, a.out + "/study");
}

}  // namespace

void RegisterStudyCommands(CLI::App& app) {
  using A = transmission::StudyArguments;
  static StudyArgs a;
  auto* cmd = app.add_subcommand(
      "study",
      "Tolerance study: Monte-Carlo and parameter sweeps of the quasi-static load sharing");
  static MergeArgs m;
  cmd->add_option("study", a.study, "Study file (TOML, docs/studies.md)")->check(CLI::ExistingFile);
  cmd->add_option("--out", a.out, "Output folder (rows CSV, summary JSON, SVG); a re-run resumes");
  Add(cmd, A::kThreads, a.threads);
  Add(cmd, A::kMaxCases, a.max_cases);
  AddTables(cmd, a.tables);
  cmd->add_flag("--quiet", a.quiet, "No progress bar");
  Add(cmd, A::kStresses, a.stresses);
  Add(cmd, A::kCases, a.cases);
  Add(cmd, A::kShard, a.shard);
  auto* merge = cmd->add_subcommand(
      "merge",
      "Join the parts of a study (--cases/--shard runs) into the files a single run writes");
  merge->add_option("parts", m.parts, "Part files (study_cases_*.csv) or folders of them")
      ->required();
  merge->add_option("--out", m.out, "Output folder (rows CSV, summary JSON, SVG)");
  merge->add_option("--study", m.study, "The study file (default: the one the first part names)")
      ->check(CLI::ExistingFile);
  merge->callback([] { MergeStudyCommand(m); });
  cmd->callback([cmd] {
    if (cmd->got_subcommand("merge")) return;
    if (a.study.empty()) throw CLI::RequiredError("study");
    RunStudyCommand(a);
  });
}

}  // namespace epicycle::app
