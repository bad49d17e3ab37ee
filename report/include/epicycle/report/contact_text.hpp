// `epicycle contact solve`'s report and `contact compare`'s summary as console text. The solve: the
// problem and program, the back end's status, iterations, times and residuals, the forces and
// multipliers (a failed solve's last iterate marked as such, components that are not finite named),
// and the distance to the file's expected solution.
#pragma once

#include <string>
#include <vector>

#include "epicycle/solvers/backend_comparison.hpp"
#include "epicycle/solvers/contact_io.hpp"
#include "epicycle/solvers/contact_problem.hpp"
#include "epicycle/solvers/contact_solver.hpp"

namespace epicycle::report {

/// The report of solving `problem` (read from `file`, whose content hash is `input_hash`) with
/// `backend` at `options`: `r` and `sol` as the solve returned them.
std::string ContactSolveText(const solvers::ContactProblem& problem,
                             const solvers::ContactProblemFile& file, const std::string& input_hash,
                             solvers::Backend backend, const solvers::ContactOptions& options,
                             const solvers::ContactReport& r, const solvers::ContactSolution& sol);

/// `epicycle contact compare`'s summary per back end (solved, median time, worst error and
/// residual, failures) as a console table and as the Markdown table of docs/solvers.md.
struct ComparisonTables {
  std::string console, markdown;
};
/// The tables of `rows` (every back end of `names` on `problems` problems at tolerance `tol`,
/// the median of `repeats` solves each).
ComparisonTables ComparisonSummaryText(const std::vector<solvers::ComparisonRun>& rows,
                                       const std::vector<std::string>& names, std::size_t problems,
                                       double tol, int repeats);

/// The comparison CSV's column line and one run's row (without '\n'; numbers as %.6e, text
/// quoted where it must be).
std::string ComparisonCsvHeader();
std::string ComparisonCsvRow(const solvers::ComparisonRun& run);

/// `epicycle contact stability`'s Markdown table: a row per problem, a cell per back end
/// ("status, res R, err E", marked NaN! or BAD), with its note on the tolerance `tol`.
std::string StabilityTableText(const std::vector<solvers::StabilityRow>& rows, double tol);

}  // namespace epicycle::report
