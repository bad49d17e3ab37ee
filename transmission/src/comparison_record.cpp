// The fields of a comparison of contact back ends (record.hpp), in the order of its JSON summary.
#include "epicycle/solvers/backend_comparison.hpp"
#include "epicycle/transmission/record.hpp"

namespace epicycle::transmission {

namespace {

void VisitSummary(const solvers::BackendSummary& s, RecordVisitor& visit) {
  visit.Text("backend", s.backend);
  visit.Integer("solved", s.solved);
  visit.Integer("runs", s.runs);
  visit.Number("median_seconds", s.median_seconds);
  visit.Number("worst_error", s.worst_error);
  visit.Number("worst_residual", s.worst_residual);
  visit.Texts("failed", s.failed);
}

void VisitRun(const solvers::ComparisonRun& r, RecordVisitor& visit) {
  visit.Text("backend", r.backend);
  visit.Text("problem", r.problem);
  visit.Text("category", r.category);
  visit.Text("status", r.status);
  visit.Text("message", r.message);
  visit.Flag("solved", r.solved);
  visit.Flag("finite", r.finite);
  visit.Integer("iterations", r.iterations);
  visit.Number("residual", r.residual);
  visit.Number("force_error", r.force_error);
  visit.Number("multiplier_error", r.multiplier_error);
  visit.Number("displacement_error", r.displacement_error);
  visit.Number("error", r.error());
  visit.Number("median_seconds", r.median_seconds);
}

}  // namespace

void VisitRecord(const solvers::ComparisonRecord& record, RecordVisitor& visit) {
  visit.Number("tolerance", record.tolerance);
  visit.Number("reference_tolerance", solvers::kReferenceTolerance);
  visit.Integer("repeats", record.repeats);
  visit.Texts("files", record.files);
  visit.Texts("problems", record.problem_names);
  visit.Integer("runs_in_all", static_cast<long>(record.RunsInAll()));
  visit.Texts("failures", record.failures);
  visit.BeginList("backends");
  for (const solvers::BackendSummary& s : record.summaries) {
    visit.Item();
    VisitSummary(s, visit);
  }
  visit.EndList();
  visit.BeginList("runs");
  for (const solvers::ComparisonRun& r : record.runs) {
    visit.Item();
    VisitRun(r, visit);
  }
  visit.EndList();
}

}  // namespace epicycle::transmission
