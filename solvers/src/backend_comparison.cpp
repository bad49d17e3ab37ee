#include "epicycle/solvers/backend_comparison.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>

#include "epicycle/solvers/contact_io.hpp"

namespace epicycle::solvers {

TimedSolve SolveRepeated(Backend backend, const ContactProblem& problem,
                         const ContactOptions& options, int repeats) {
  auto solver = MakeContactSolver(backend);
  TimedSolve run;
  std::vector<double> times;
  for (int r = 0; r < std::max(1, repeats); ++r) {
    ContactSolution s;
    run.report = solver->Solve(problem, options, &s);
    run.solution = s;
    times.push_back(run.report.total_seconds);
  }
  std::sort(times.begin(), times.end());
  run.median_seconds = times[times.size() / 2];
  return run;
}

TimedSolve SolveReference(const ContactProblem& problem) {
  ContactOptions o;
  o.tolerance = kReferenceTolerance;
  o.max_iterations = 500;
  return SolveRepeated(Backend::kActiveSetNewton, problem, o, 1);
}

double ComparisonRun::error() const {
  return std::isfinite(force_error) && std::isfinite(displacement_error)
             ? std::max(force_error, displacement_error)
             : std::numeric_limits<double>::quiet_NaN();
}

ComparisonRun CompareBackend(Backend backend, const ContactProblem& problem,
                             const std::string& category, const ContactOptions& options,
                             int repeats, const ContactSolution& reference) {
  ComparisonRun row;
  row.backend = BackendName(backend);
  row.problem = problem.name();
  row.category = category;
  TimedSolve run;
  try {
    run = SolveRepeated(backend, problem, options, repeats);
  } catch (const std::exception& e) {
    row.status = "exception";
    row.message = e.what();
    return row;
  }
  row.status = StatusName(run.report.status);
  row.message = run.report.message;
  row.residual = run.report.residual.total;
  const SolutionDifference d = CompareSolutions(problem, run.solution, reference);
  row.force_error = d.force;
  row.multiplier_error = d.multiplier;
  row.displacement_error = d.displacement;
  row.median_seconds = run.median_seconds;
  row.iterations = run.report.iterations;
  row.solved = run.report.status == ContactStatus::kConverged;
  row.finite = run.solution.force.allFinite() && run.solution.multiplier.allFinite();
  return row;
}

std::string StatusWithMessage(const std::string& status, const std::string& message) {
  if (message.empty()) return status;
  return message.rfind(status, 0) == 0 ? message : status + ": " + message;
}

std::vector<BackendSummary> SummarizeByBackend(const std::vector<ComparisonRun>& runs,
                                               const std::vector<std::string>& backends) {
  std::vector<BackendSummary> out;
  for (const std::string& b : backends) {
    BackendSummary s;
    s.backend = b;
    std::vector<double> t;
    for (const ComparisonRun& r : runs) {
      if (r.backend != b) continue;
      ++s.runs;
      t.push_back(r.median_seconds);
      if (r.solved) {
        ++s.solved;
        s.worst_error = std::max(s.worst_error, std::max(r.force_error, r.displacement_error));
        s.worst_residual = std::max(s.worst_residual, r.residual);
      } else {
        s.failed.push_back(r.problem + " (" + r.status + ")");
      }
    }
    std::sort(t.begin(), t.end());
    s.median_seconds = t.empty() ? 0.0 : t[t.size() / 2];
    out.push_back(std::move(s));
  }
  return out;
}

ComparisonRecord RunComparison(const ComparisonRequest& request, ComparisonSink& sink) {
  ComparisonRecord record;
  record.tolerance = request.options.tolerance;
  record.repeats = request.repeats;
  record.files = ListProblemFiles(request.inputs);
  for (Backend b : request.backends) record.backends.push_back(BackendName(b));
  auto fail = [&](const std::string& what) {
    record.failures.push_back(what);
    sink.Failure(what);
  };
  for (const std::string& path : record.files) {
    const ContactProblemFile file = ReadContactProblemFile(path);
    const ContactProblem problem(file.data);
    record.problem_names.push_back(problem.name());
    const TimedSolve ref = SolveReference(problem);
    if (ref.report.status != ContactStatus::kConverged) {
      char tol[16];
      std::snprintf(tol, sizeof tol, "%.0e", kReferenceTolerance);
      fail("reference (newton at " + std::string(tol) + ") on " + problem.name() + " (" + path +
           "): " + StatusWithMessage(StatusName(ref.report.status), ref.report.message) +
           "; errors of this problem are against its last iterate");
    }
    for (Backend b : request.backends) {
      const ComparisonRun run =
          CompareBackend(b, problem, file.category, request.options, request.repeats, ref.solution);
      if (!run.solved)
        fail(run.backend + " on " + run.problem + " (" + path +
             "): " + StatusWithMessage(run.status, run.message));
      sink.Run(run);
      record.runs.push_back(run);
    }
  }
  record.summaries = SummarizeByBackend(record.runs, record.backends);
  return record;
}

std::vector<StabilityRow> RunStability(const std::string& dir, double tolerance) {
  ContactOptions options;
  options.tolerance = tolerance;
  std::vector<StabilityRow> rows;
  for (const std::string& path : ListProblemFiles({dir})) {
    const ContactProblemFile file = ReadContactProblemFile(path);
    if (file.category != "stiff") continue;
    const ContactProblem problem(file.data);
    const TimedSolve ref = SolveReference(problem);
    StabilityRow row{problem.name(), problem.num_contacts(), problem.num_equalities(), {}};
    for (Backend b : AllBackends())
      row.runs.push_back(CompareBackend(b, problem, file.category, options, 1, ref.solution));
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace epicycle::solvers
