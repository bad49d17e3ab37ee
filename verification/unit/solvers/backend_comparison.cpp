// The comparison of back ends that `epicycle contact compare|stability` prints: its summary on a
// hand-made table, and one run against a problem whose answer is known in closed form.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "epicycle/solvers/backend_comparison.hpp"
#include "epicycle/solvers/contact_io.hpp"

using namespace epicycle::solvers;

namespace {

ComparisonRun Row(const std::string& backend, const std::string& problem, bool solved,
                  double error, double residual, double seconds) {
  ComparisonRun r;
  r.backend = backend;
  r.problem = problem;
  r.status = solved ? "converged" : "iteration-limit";
  r.solved = solved;
  r.force_error = error;
  r.displacement_error = error / 2;
  r.residual = residual;
  r.median_seconds = seconds;
  return r;
}

}  // namespace

TEST_CASE("back-end summary of a hand-made comparison", "[unit][solvers]") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<ComparisonRun> runs = {
      Row("A", "P1", true, 1e-9, 1e-11, 3.0),   Row("A", "P2", true, 4e-9, 2e-12, 1.0),
      Row("A", "P3", false, 1.0, 5.0, 2.0),     Row("B", "P1", true, 2e-8, 3e-11, 0.5),
      Row("B", "P2", false, nan, 0.0, 0.25),
  };
  const auto s = SummarizeByBackend(runs, {"B", "A", "C"});
  REQUIRE(s.size() == 3);
  // A: 2 of 3 solved; median of {1, 2, 3} s; the failed run's error and residual do not count.
  CHECK(s[1].backend == "A");
  CHECK(s[1].solved == 2);
  CHECK(s[1].runs == 3);
  CHECK(s[1].median_seconds == 2.0);
  CHECK(s[1].worst_error == 4e-9);
  CHECK(s[1].worst_residual == 1e-11);
  CHECK(s[1].failed == std::vector<std::string>{"P3 (iteration-limit)"});
  // B: two runs, the upper median of {0.25, 0.5} s.
  CHECK(s[0].solved == 1);
  CHECK(s[0].median_seconds == 0.5);
  CHECK(s[0].worst_error == 2e-8);
  // C ran nothing: zeros, not NaN.
  CHECK(s[2].runs == 0);
  CHECK(s[2].median_seconds == 0.0);
  CHECK(s[2].worst_error == 0.0);
}

TEST_CASE("status with message is not repeated", "[unit][solvers]") {
  CHECK(StatusWithMessage("converged", "") == "converged");
  CHECK(StatusWithMessage("iteration-limit", "iteration-limit after 50") ==
        "iteration-limit after 50");
  CHECK(StatusWithMessage("exception", "bad size") == "exception: bad size");
}

TEST_CASE("one back end against the reference on a closed-form problem", "[unit][solvers]") {
  // One contact with a local term carrying a given load: F = W (the file's closed-form answer).
  const ContactProblemFile file =
      ReadContactProblemFile(EPICYCLE_TEST_DATA_DIR "/contact/cf_one_contact_load.json");
  REQUIRE(file.expected);
  const ContactProblem problem(file.data);
  const TimedSolve ref = SolveReference(problem);
  REQUIRE(ref.report.status == ContactStatus::kConverged);
  ContactOptions o;
  o.tolerance = 1e-10;
  const ComparisonRun run =
      CompareBackend(Backend::kActiveSetNewton, problem, file.category, o, 3, ref.solution);
  CHECK(run.solved);
  CHECK(run.finite);
  CHECK(run.status == "converged");
  CHECK(run.residual <= 1e-10);
  // Against the reference, and against the file's closed-form answer: the force is fixed by the
  // equilibrium row F = W to its residual; λ by the gap row, to the residual times ℓ*/|λ|.
  CHECK(run.error() <= 1e-9);
  const ComparisonRun exact =
      CompareBackend(Backend::kActiveSetNewton, problem, file.category, o, 1, *file.expected);
  CHECK(exact.force_error <= 1e-10);
  CHECK(exact.displacement_error <= 1e-9);
}
