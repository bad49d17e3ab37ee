// A contact solve's report as console text (contact_text.hpp).
#include "epicycle/report/contact_text.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "epicycle/config.h"
#include "epicycle/report/files.hpp"
#include "epicycle/solvers/backend_comparison.hpp"

namespace epicycle::report {

using solvers::ContactStatus;

std::string ContactSolveText(const solvers::ContactProblem& problem,
                             const solvers::ContactProblemFile& file, const std::string& input_hash,
                             solvers::Backend backend, const solvers::ContactOptions& options,
                             const solvers::ContactReport& r, const solvers::ContactSolution& sol) {
  const bool converged = r.status == ContactStatus::kConverged;
  std::string t;
  t += fmt::format("problem      {} (N = {}, m = {}, {})\n", problem.name(), problem.num_contacts(),
                   problem.num_equalities(), file.category);
  t += fmt::format("program      epicycle {}, input {}\n", EPICYCLE_VERSION, input_hash);
  t += fmt::format("back end     {}\n", solvers::BackendName(backend));
  t += fmt::format("status       {}\n", solvers::StatusName(r.status));
  t += fmt::format("message      {}\n", r.message);
  t += fmt::format("iterations   {} (back-end code {})\n", r.iterations, r.backend_code);
  t += fmt::format("time         {:.3e} s in the back end, {:.3e} s in total\n", r.solve_seconds,
                   r.total_seconds);
  t += fmt::format("residual     complementarity {}, equilibrium {}, total {} (tolerance {:.1e})\n",
                   Figure(r.residual.complementarity, "{:.3e}", "not finite"),
                   Figure(r.residual.equilibrium, "{:.3e}", "not finite"),
                   Figure(r.residual.total, "{:.3e}", "not finite"), options.tolerance);
  t += fmt::format("active       {} of {} contacts{}\n", r.active_contacts, problem.num_contacts(),
                   r.polished ? " (POLISHED)" : "");
  // A failed solve still shows its last iterate (what the back end stopped at), marked as such;
  // components that are not finite are named, never printed as nan/inf.
  const char* what = converged ? "" : " -- last iterate of a FAILED solve, not a solution";
  const auto& labels = problem.data().contact_labels;
  t += fmt::format("forces [N]{}:\n", what);
  for (int j = 0; j < sol.force.size() && j < problem.num_contacts(); ++j)
    t += fmt::format("  {:4d} {:>16}  {}\n", j, Figure(sol.force(j), "{:.9e}", "not finite"),
                     labels.empty() ? "" : labels[j]);
  if (problem.num_equalities() > 0) {
    const auto& ml = problem.data().multiplier_labels;
    t += fmt::format("multipliers (rigid displacements){}:\n", what);
    for (int i = 0; i < sol.multiplier.size() && i < problem.num_equalities(); ++i)
      t += fmt::format("  {:4d} {:>16}  {}\n", i, Figure(sol.multiplier(i), "{:.9e}", "not finite"),
                       ml.empty() ? "" : ml[i]);
  }
  if (file.expected && converged) {
    const auto d = solvers::CompareSolutions(problem, sol, *file.expected);
    t += fmt::format("against the file's expected solution ({}): force {:.2e}, multiplier {:.2e}\n",
                     file.expected_note, d.force, d.multiplier);
  }
  return t;
}

ComparisonTables ComparisonSummaryText(const std::vector<solvers::ComparisonRun>& rows,
                                       const std::vector<std::string>& names, std::size_t problems,
                                       double tol, int repeats) {
  ComparisonTables t;
  t.console = fmt::format(
      "{} problems, tolerance {:.1e}, reference: newton at {:.0e}, {} repeat(s); error = max of "
      "the "
      "relative force and rigid-displacement (G^T lambda) differences, over converged runs\n\n",
      problems, tol, solvers::kReferenceTolerance, repeats);
  t.console += fmt::format("{:<14} {:>8} {:>14} {:>14} {:>16}  {}\n", "back end", "solved",
                           "median time", "worst error", "worst residual", "failures");
  t.markdown = fmt::format(
      "{} problems, tolerance {:.0e}, median of {} solve(s) per problem.\n\n"
      "| back end | solved | median time [s] | worst error | worst residual | not converged |\n"
      "|---|---|---|---|---|---|\n",
      problems, tol, repeats);
  for (const solvers::BackendSummary& b : solvers::SummarizeByBackend(rows, names)) {
    std::string failed;
    for (const std::string& f : b.failed) failed += (failed.empty() ? "" : ", ") + f;
    t.console += fmt::format("{:<14} {:>4}/{:<3} {:>12.3e} s {:>14.2e} {:>16.2e}  {}\n", b.backend,
                             b.solved, b.runs, b.median_seconds, b.worst_error, b.worst_residual,
                             failed.empty() ? "-" : failed);
    t.markdown +=
        fmt::format("| {} | {}/{} | {:.2e} | {:.1e} | {:.1e} | {} |\n", b.backend, b.solved, b.runs,
                    b.median_seconds, b.worst_error, b.worst_residual, b.runs - b.solved);
  }
  return t;
}

std::string ComparisonCsvHeader() {
  return "backend,problem,category,status,residual,force_error,multiplier_error,"
         "displacement_error,median_seconds,iterations,message";
}

std::string ComparisonCsvRow(const solvers::ComparisonRun& row) {
  return fmt::format("{},{},{},{},{},{},{},{},{},{},{}", CsvText(row.backend), CsvText(row.problem),
                     CsvText(row.category), CsvText(row.status), Figure(row.residual, "{:.6e}"),
                     Figure(row.force_error, "{:.6e}"), Figure(row.multiplier_error, "{:.6e}"),
                     Figure(row.displacement_error, "{:.6e}"), Figure(row.median_seconds, "{:.6e}"),
                     row.iterations, CsvText(row.message));
}

std::string StabilityTableText(const std::vector<solvers::StabilityRow>& rows, double tol) {
  std::string table = "| case | N | m |";
  std::string rule = "|---|---|---|";
  // Appended piece by piece (GCC 12's -Wrestrict misfires on "text" + string).
  for (solvers::Backend b : solvers::AllBackends()) {
    table += fmt::format(" {} |", solvers::BackendName(b));
    rule += "---|";
  }
  table += fmt::format("\n{}\n", rule);
  for (const solvers::StabilityRow& row : rows) {
    table += fmt::format("| {} | {} | {} |", row.problem, row.contacts, row.equalities);
    for (const solvers::ComparisonRun& run : row.runs) {
      std::string cell = "n/a";
      if (run.status != solvers::StatusName(solvers::ContactStatus::kBackendUnavailable)) {
        cell = fmt::format("{}, res {:.0e}, err {:.0e}", run.status, run.residual,
                           std::max(run.force_error, run.displacement_error));
        if (!run.finite) cell += ", NaN!";
        if (run.solved && run.residual > tol) cell += ", BAD";
      }
      table += " " + cell + " |";
    }
    table += "\n";
  }
  table += fmt::format(
      "\nTolerance {:.0e}; err = max relative force / rigid-displacement difference from the "
      "active-set Newton at {:.0e} (see CompareSolutions). Written by `epicycle contact "
      "stability` ({}).\n",
      tol, solvers::kReferenceTolerance, EPICYCLE_VERSION);
  return table;
}

}  // namespace epicycle::report
