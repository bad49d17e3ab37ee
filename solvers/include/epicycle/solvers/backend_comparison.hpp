// Back ends judged against a reference on a collection of problem files: what `epicycle contact
// compare` and `contact stability` print, and what a study of one's own solver can call.
//
// The reference of a problem is the active-set Newton at kReferenceTolerance (best effort where
// round-off stops it: its status says so, and the errors are then against its last iterate).
// Every run is judged by the driver's residual (ContactReport::residual) and by its difference
// from the reference (CompareSolutions: relative force and rigid-displacement differences).
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "epicycle/solvers/contact_problem.hpp"
#include "epicycle/solvers/contact_solver.hpp"

namespace epicycle::solvers {

/// Tolerance of the reference solve on the nondimensional residual [-].
inline constexpr double kReferenceTolerance = 1e-12;

/// `repeats` solves (at least one) of one problem by one back end.
struct TimedSolve {
  ContactReport report;         ///< of the last solve
  ContactSolution solution;     ///< of the last solve
  double median_seconds = 0.0;  ///< median of the solves' total times [s]
};
TimedSolve SolveRepeated(Backend backend, const ContactProblem& problem,
                         const ContactOptions& options, int repeats);

/// The active-set Newton at kReferenceTolerance, at most 500 iterations.
TimedSolve SolveReference(const ContactProblem& problem);

/// One (back end, problem) run of a comparison. Errors are NaN where not computed (a back end
/// that threw has no solution to compare).
struct ComparisonRun {
  std::string backend;    ///< BackendName
  std::string problem;    ///< the problem's name
  std::string category;   ///< the problem file's category
  std::string status;     ///< StatusName, or "exception" when the back end threw
  std::string message;    ///< the back end's message (the exception's text when it threw)
  double residual = 0.0;  ///< driver residual, nondimensional [-]
  double force_error = std::numeric_limits<double>::quiet_NaN();         ///< [-]
  double multiplier_error = std::numeric_limits<double>::quiet_NaN();    ///< [-]
  double displacement_error = std::numeric_limits<double>::quiet_NaN();  ///< [-]
  double median_seconds = 0.0;                                           ///< [s]
  int iterations = 0;
  bool solved = false;  ///< converged and did not throw
  bool finite = false;  ///< the answer's forces and multipliers are all finite
  /// max(force_error, displacement_error), NaN unless both are finite [-].
  double error() const;
};

/// Solves `problem` `repeats` times with `backend` and compares the last answer with
/// `reference`. A back end that throws (it should not) gives a failed run carrying the
/// exception's text, so a comparison of many runs goes on.
ComparisonRun CompareBackend(Backend backend, const ContactProblem& problem,
                             const std::string& category, const ContactOptions& options,
                             int repeats, const ContactSolution& reference);

/// "status: message", without repeating the status where the message starts with it.
std::string StatusWithMessage(const std::string& status, const std::string& message);

/// One back end over every problem of a comparison.
struct BackendSummary {
  std::string backend;
  int solved = 0;                   ///< runs that converged
  int runs = 0;                     ///< runs in all
  double median_seconds = 0.0;      ///< median run time, 0 when there are no runs [s]
  double worst_error = 0.0;         ///< largest error() over solved runs, 0 if none [-]
  double worst_residual = 0.0;      ///< largest residual over solved runs, 0 if none [-]
  std::vector<std::string> failed;  ///< "problem (status)" of each run not solved
};

/// The summary of each of `backends` (in that order) over `runs`.
std::vector<BackendSummary> SummarizeByBackend(const std::vector<ComparisonRun>& runs,
                                               const std::vector<std::string>& backends);

/// Solves per (back end, problem) of a comparison unless a request says otherwise [-].
inline constexpr int kDefaultComparisonRepeats = 5;

/// A comparison of back ends over problem files (`epicycle contact compare`, Python's
/// compare_backends): every problem's reference, then every back end of `backends` on it.
struct ComparisonRequest {
  std::vector<std::string> inputs;                  ///< problem files or folders of them
  std::vector<Backend> backends = AvailableBackends();  ///< in the order of the runs
  ContactOptions options;  ///< of every back end's run (its tolerance is the verdict's)
  int repeats = kDefaultComparisonRepeats;  ///< solves per (back end, problem); the median time [-]
};

/// Receives each run as it is computed (a table written row by row keeps what came before a
/// later failure).
class ComparisonSink {
 public:
  virtual ~ComparisonSink() = default;
  /// A failed reference or back-end run, with where it happened (the problem's file).
  virtual void Failure(const std::string& what) = 0;
  virtual void Run(const ComparisonRun& run) = 0;
};

/// What a comparison found (its fields named once by transmission::VisitRecord).
struct ComparisonRecord {
  double tolerance = 0.0;                  ///< of every back end's run, nondimensional [-]
  int repeats = 0;                         ///< solves per (back end, problem) [-]
  std::vector<std::string> files;          ///< the problem files, in the runs' order
  std::vector<std::string> problem_names;  ///< each file's problem name
  std::vector<std::string> backends;       ///< BackendName of each requested back end
  std::vector<ComparisonRun> runs;         ///< per problem, per back end
  std::vector<std::string> failures;       ///< each failed run, as the sink was told
  std::vector<BackendSummary> summaries;   ///< SummarizeByBackend of the runs, per back end
  /// Every run counted in the failures: the reference and each back end on every problem.
  std::size_t RunsInAll() const { return files.size() * (backends.size() + 1); }
};

/// Runs `request`, streaming every run to `sink`.
/// @throws std::invalid_argument for a file that is not a problem file (naming it).
ComparisonRecord RunComparison(const ComparisonRequest& request, ComparisonSink& sink);

/// One row of the stability table (`epicycle contact stability`): each back end once on a
/// problem of the "stiff" category, against its reference.
struct StabilityRow {
  std::string problem;
  int contacts = 0, equalities = 0;  ///< N, m [-]
  std::vector<ComparisonRun> runs;   ///< per back end of AllBackends()
};

/// The "stiff" problems of the folder `dir`, each back end once at `tolerance`.
std::vector<StabilityRow> RunStability(const std::string& dir, double tolerance);

}  // namespace epicycle::solvers
