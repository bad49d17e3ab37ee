// `epicycle contact solve|compare|stability`: the contact core on problem files.
#include <cstdio>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "console.hpp"
#include "epicycle/report/contact_plots.hpp"
#include "epicycle/report/contact_text.hpp"
#include "epicycle/report/record_json.hpp"
#include "epicycle/solvers/backend_comparison.hpp"
#include "epicycle/solvers/contact_io.hpp"
#include "epicycle/solvers/contact_solver.hpp"
#include "epicycle/transmission/scene.hpp"
#include "options.hpp"

namespace epicycle::app {
namespace {

namespace fs = std::filesystem;
using solvers::Backend;
using solvers::ComparisonRun;
using solvers::ContactOptions;
using solvers::ContactProblem;
using solvers::ContactProblemFile;
using solvers::ContactReport;
using solvers::ContactSolution;
using solvers::ContactStatus;

void SolveCommand(const std::string& path, const std::string& backend_name, double tol, bool polish,
                  const std::vector<std::string>& kv) {
  const ContactProblemFile file = solvers::ReadContactProblemFile(path);
  const ContactProblem problem(file.data);
  ContactOptions options;
  options.tolerance = tol;
  options.polish = polish;
  for (const std::string& item : kv) {
    const auto eq = item.find('=');
    if (eq == std::string::npos)
      throw std::invalid_argument("--option '" + item + "': must be KEY=VALUE");
    options.backend_options[item.substr(0, eq)] = item.substr(eq + 1);
  }
  const Backend backend = solvers::BackendFromName(backend_name);
  auto solver = solvers::MakeContactSolver(backend);
  ContactSolution sol;
  const ContactReport r = solver->Solve(problem, options, &sol);
  const bool converged = r.status == ContactStatus::kConverged;
  Print(report::ContactSolveText(problem, file, FileHash(path), backend, options, r, sol));
  if (!converged)
    throw ComputationFailed(fmt::format("{}: the {} back end did not converge: {} ({})", path,
                                        solvers::BackendName(backend),
                                        solvers::StatusName(r.status), r.message));
}

// The program's comparison sink: a failed run on stderr as it happens, every run a flushed row
// of the CSV (a later bad file or an interrupted run keeps every row computed before it).
class CompareConsole final : public solvers::ComparisonSink {
 public:
  explicit CompareConsole(std::optional<CsvFile>* csv) : csv_(csv) {}
  void Failure(const std::string& what) override {
    std::fprintf(stderr, "contact compare: FAILED %s\n", what.c_str());
  }
  void Run(const ComparisonRun& run) override {
    if (*csv_) (*csv_)->WriteLine(report::ComparisonCsvRow(run));
  }

 private:
  std::optional<CsvFile>* csv_;
};

struct CompareArgs {
  std::vector<std::string> inputs;
  std::string csv, svg_prefix, markdown, json;
  double tol = ContactOptions().tolerance;
  int repeats = solvers::kDefaultComparisonRepeats;
};

void CompareCommand(const CompareArgs& a) {
  solvers::ComparisonRequest request;
  request.inputs = a.inputs;
  request.options.tolerance = a.tol;
  request.repeats = a.repeats;
  nlohmann::json provenance;
  if (!a.csv.empty() || !a.json.empty()) provenance = report::ComparisonProvenance(request);
  std::optional<CsvFile> out;
  if (!a.csv.empty()) {
    const fs::path parent = fs::path(a.csv).parent_path();
    if (!parent.empty()) fs::create_directories(parent);
    out.emplace(a.csv);
    out->Write(ProvenanceCsvLine(provenance));
    out->WriteLine(report::ComparisonCsvHeader());
  }
  CompareConsole console(&out);
  const solvers::ComparisonRecord record = solvers::RunComparison(request, console);
  const report::ComparisonTables tables = report::ComparisonSummaryText(
      record.runs, record.backends, record.files.size(), a.tol, a.repeats);
  Print(tables.console);
  if (out) out->Close();
  if (!a.csv.empty()) fmt::print("\nCSV written to {}\n", a.csv);
  if (!a.markdown.empty()) WriteTextFile(a.markdown, tables.markdown);
  if (!a.json.empty())
    WriteTextFile(a.json, report::SummaryJson(record, provenance).dump(2) + "\n");
  if (!a.svg_prefix.empty()) {
    report::WriteComparisonPlots(a.svg_prefix, record);
    fmt::print("SVG written to {0}_profile.svg and {0}_error_vs_time.svg\n", a.svg_prefix);
  }
  if (!record.failures.empty())
    throw ComputationFailed(fmt::format(
        "{} of {} runs (the reference and every back end on every problem) did not converge: "
        "listed above as FAILED; every run's row is in the table{}",
        record.failures.size(), record.RunsInAll(), a.csv.empty() ? "" : " and the CSV"));
}

void StabilityCommand(const std::string& dir, double tol) {
  Print(report::StabilityTableText(solvers::RunStability(dir, tol), tol));
}

}  // namespace

void RegisterContactCommands(CLI::App& app) {
  using A = transmission::ContactArguments;
  CLI::App* contact = app.add_subcommand("contact", "the contact problem and its back ends");
  contact->require_subcommand(1);

  auto* solve =
      contact->add_subcommand("solve", "solve one problem file, print solution and residuals");
  static std::string s_file, s_backend = "newton";
  static double s_tol = 1e-10;
  static bool s_polish = false;
  static std::vector<std::string> s_kv;
  solve->add_option("file", s_file, "problem file (JSON)")->required();
  solve->add_option("--backend", s_backend,
                    "newton, ipopt, nlopt-slsqp, nlopt-lbfgs, nlopt-auglag");
  Add(solve, A::kTolerance, s_tol);
  solve->add_flag("--polish", s_polish, "labelled active-set polish step after the raw solve");
  solve->add_option("--option", s_kv, "back-end option KEY=VALUE (e.g. newton.ls_beta=0.5)");
  solve->callback([] { SolveCommand(s_file, s_backend, s_tol, s_polish, s_kv); });

  auto* compare = contact->add_subcommand("compare", "every available back end on every problem");
  static CompareArgs c;
  compare->add_option("inputs", c.inputs, "problem files or directories")->required();
  compare->add_option("--csv", c.csv, "write one row per (back end, problem)");
  compare->add_option("--svg-prefix", c.svg_prefix,
                      "write PREFIX_profile.svg and PREFIX_error_vs_time.svg");
  Add(compare, A::kTolerance, c.tol);
  Add(compare, A::kRepeats, c.repeats);
  compare->add_option("--markdown", c.markdown,
                      "write the summary table as markdown (tools/update_solver_docs.sh puts it "
                      "into docs/solvers.md)");
  compare->add_option("--json", c.json,
                      "write the comparison's record as JSON (keys: docs/records.md)");
  compare->callback([] { CompareCommand(c); });

  auto* stability =
      contact->add_subcommand("stability", "the stiff/extreme (back end x case) table");
  static std::string st_dir;
  static double st_tol = 1e-10;
  stability->add_option("dir", st_dir, "collection directory (verification/data/contact)")
      ->required();
  Add(stability, A::kTolerance, st_tol);
  stability->callback([] { StabilityCommand(st_dir, st_tol); });
}

}  // namespace epicycle::app
