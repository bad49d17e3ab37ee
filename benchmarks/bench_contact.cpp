// Contact back ends on stage-sized problems (issue 3, "must show" 4).
//
// For every stage-sized gear-like problem (the collection's generator, MakeGearLikeProblem, or the
// "gear-like" files of verification/data/contact/ when present) this times
//   solve/<back end>/<case>        one cold solve at a 1e-9 residual, per available back end;
//   newton_warm_step/<case>        the active-set Newton warm-started from the answer of the same
//                                  problem under 99 % of its load and back, in turn (a load-sweep
//                                  step each way, after the other step's solve);
//   newton_warm_same/<case>        the same, started from its own answer (the floor: one check);
//   factorise_kkt/<case>           one factorisation of the final active set as the Newton does it:
//                                  Cholesky of H_AA = C_AA + diag(u'_A), the Schur complement
//                                  G_A H_AA⁻¹ G_Aᵀ + S and its Cholesky;
//   factorise_llt/<case>           the Cholesky of H_AA alone.
// After each timing loop the answer is compared with a tight Newton reference (tolerance 1e-12)
// and the difference published as counters (error_F, error_lambda: relative, CompareSolutions),
// with the driver's residual and whether it converged. At the end a table of the ratios the issue
// targets is printed (Newton vs Ipopt ≥ 50×, Newton vs SLSQP ≥ 10×, warm solve ≤ 3× one
// factorisation). They are measured and reported, not asserted.
//
//   build-backends/benchmarks/bench_contact --benchmark_min_time=0.5
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <Eigen/Cholesky>

#include "contact_collection.hpp"
#include "epicycle/solvers/contact_io.hpp"
#include "epicycle/solvers/contact_problem.hpp"
#include "epicycle/solvers/contact_solver.hpp"
#include "recording_reporter.hpp"

namespace {

using epicycle::solvers::Backend;
using epicycle::solvers::BackendName;
using epicycle::solvers::CompareSolutions;
using epicycle::solvers::ContactOptions;
using epicycle::solvers::ContactProblem;
using epicycle::solvers::ContactProblemData;
using epicycle::solvers::ContactProblemFile;
using epicycle::solvers::ContactReport;
using epicycle::solvers::ContactSolution;
using epicycle::solvers::ContactStatus;
using epicycle::solvers::MakeContactSolver;

constexpr double kSolveTolerance = 1e-9;       // the "at a 1e-9 residual"
constexpr double kReferenceTolerance = 1e-12;  // tight Newton reference

struct Case {
  std::string name;
  std::unique_ptr<ContactProblem> problem;
  ContactSolution reference;
  std::unique_ptr<ContactProblem> lighter;  // the same under 99 % of its load
  ContactSolution previous_step;            // Newton answer at 99 % load
  std::string reference_backend;            // which back end gave the reference
};

std::vector<ContactProblemFile> StageSizedProblems() {
  std::vector<ContactProblemFile> files;
  const std::filesystem::path dir = std::filesystem::path(EPICYCLE_TEST_DATA_DIR) / "contact";
  if (std::filesystem::is_directory(dir)) {
    std::vector<std::filesystem::path> paths;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
      if (entry.path().extension() == ".json") paths.push_back(entry.path());
    }
    std::sort(paths.begin(), paths.end());
    for (const auto& path : paths) {
      ContactProblemFile file;
      try {
        file = epicycle::solvers::ReadContactProblemFile(path.string());
      } catch (const std::invalid_argument&) {
        continue;  // not a problem file (e.g. expected_failures.json)
      }
      const auto n = file.data.overlap.size();
      if (file.category == "gear-like" && n >= 30 && n <= 60) files.push_back(std::move(file));
    }
  }
  if (files.empty()) {
    // Sized like the paper's stage: 3 planets × 2 meshes × 5 pairs = 30 contacts, m = 6;
    // 4 planets × 2 meshes × 7 pairs = 56 contacts, m = 7.
    epicycle::solvers::GearLikeSpec three;
    three.planets = 3;
    three.drive_pairs = 3;
    three.coast_pairs = 2;
    three.seed = 11;
    files.push_back(epicycle::solvers::MakeGearLikeProblem(three, "bench-stage-3p-30c"));
    epicycle::solvers::GearLikeSpec four;
    four.planets = 4;
    four.drive_pairs = 4;
    four.coast_pairs = 3;
    four.seed = 12;
    files.push_back(epicycle::solvers::MakeGearLikeProblem(four, "bench-stage-4p-56c"));
  }
  return files;
}

ContactReport SolveOnce(Backend backend, const ContactProblem& problem, double tolerance,
                        ContactSolution* solution, bool warm = false) {
  ContactOptions options;
  options.tolerance = tolerance;
  options.warm_start = warm;
  return MakeContactSolver(backend)->Solve(problem, options, solution);
}

// The tight reference: the active-set Newton at 1e-12, or, should it not converge there, Ipopt at
// 1e-12 (an independent method); reported on stdout either way.
std::string TightReference(const ContactProblem& problem, ContactSolution* reference) {
  for (Backend backend : {Backend::kActiveSetNewton, Backend::kIpopt}) {
    if (!MakeContactSolver(backend)->available()) continue;
    const ContactReport report = SolveOnce(backend, problem, kReferenceTolerance, reference);
    std::printf("reference for %s: %s, %s (residual %.2e)\n", problem.name().c_str(),
                BackendName(backend).c_str(), epicycle::solvers::StatusName(report.status).c_str(),
                report.residual.total);
    if (report.status == ContactStatus::kConverged) return BackendName(backend);
  }
  return "none (no back end converged at 1e-12)";
}

std::vector<Case> BuildCases() {
  std::vector<Case> cases;
  for (ContactProblemFile& file : StageSizedProblems()) {
    Case c;
    c.name = file.data.name;
    ContactProblemData lighter = file.data;
    if (lighter.equality_rhs.size() > 0) {
      lighter.equality_rhs *= 0.99;
    } else {
      lighter.overlap *= 0.99;
    }
    c.problem = std::make_unique<ContactProblem>(file.data);
    c.reference_backend = TightReference(*c.problem, &c.reference);
    c.lighter = std::make_unique<ContactProblem>(lighter);
    SolveOnce(Backend::kActiveSetNewton, *c.lighter, kReferenceTolerance, &c.previous_step);
    cases.push_back(std::move(c));
  }
  return cases;
}

void PublishAnswer(benchmark::State& state, const Case& c, const ContactReport& report,
                   const ContactSolution& solution) {
  const auto diff = CompareSolutions(*c.problem, solution, c.reference);
  state.counters["error_F"] = diff.force;
  state.counters["error_lambda"] = diff.multiplier;
  state.counters["residual"] = report.residual.total;
  state.counters["converged"] = report.status == ContactStatus::kConverged ? 1 : 0;
  state.counters["iterations"] = report.iterations;
  state.counters["N"] = c.problem->num_contacts();
  state.counters["m"] = c.problem->num_equalities();
  state.SetLabel(epicycle::solvers::StatusName(report.status) + ", ref " + c.reference_backend);
}

void BenchSolve(benchmark::State& state, const Case* c, Backend backend) {
  auto solver = MakeContactSolver(backend);
  ContactOptions options;
  options.tolerance = kSolveTolerance;
  ContactSolution solution;
  ContactReport report;
  for (auto _ : state) {
    report = solver->Solve(*c->problem, options, &solution);
    benchmark::DoNotOptimize(solution.force.data());
  }
  PublishAnswer(state, *c, report, solution);
}

void BenchWarm(benchmark::State& state, const Case* c, const ContactSolution* start) {
  auto solver = MakeContactSolver(Backend::kActiveSetNewton);
  ContactOptions options;
  options.tolerance = kSolveTolerance;
  options.warm_start = true;
  ContactSolution solution;
  ContactReport report;
  for (auto _ : state) {
    solution = *start;
    report = solver->Solve(*c->problem, options, &solution);
    benchmark::DoNotOptimize(solution.force.data());
  }
  PublishAnswer(state, *c, report, solution);
}

// A load-sweep step in both directions in turn: the problem from the answer at 99 % load, then the
// 99 % problem from the full answer, and so on. Each solve starts from the other problem's answer
// and finds in the solver what the other solve left there (its factorisation), as in a sweep,
// never its own; the time is the average of the two directions.
void BenchWarmStep(benchmark::State& state, const Case* c) {
  auto solver = MakeContactSolver(Backend::kActiveSetNewton);
  ContactOptions options;
  options.tolerance = kSolveTolerance;
  options.warm_start = true;
  const ContactProblem* problems[2] = {c->lighter.get(), c->problem.get()};
  ContactSolution answers[2] = {c->previous_step, c->reference};
  ContactSolution solution;
  ContactReport report, full_report;
  int turn = 1;
  for (auto _ : state) {
    solution = answers[1 - turn];
    report = solver->Solve(*problems[turn], options, &solution);
    benchmark::DoNotOptimize(solution.force.data());
    if (turn == 1) full_report = report;
    answers[turn] = solution;
    turn = 1 - turn;
  }
  PublishAnswer(state, *c, full_report, answers[1]);
}

// The final active set's KKT data in SI units (the cost does not depend on the scaling).
struct ActiveSetKkt {
  Eigen::MatrixXd h;  // C_AA + diag(u'_A)
  Eigen::MatrixXd g;  // G_A (m×|A|)
  Eigen::MatrixXd s;  // S
};

ActiveSetKkt BuildActiveSetKkt(const Case& c) {
  const ContactProblem& p = *c.problem;
  const Eigen::VectorXd& f = c.reference.force;
  std::vector<int> active;
  for (int j = 0; j < f.size(); ++j) {
    if (f(j) > 0) active.push_back(j);
  }
  const int a = static_cast<int>(active.size());
  const int m = p.num_equalities();
  // u'(F_j) by a central difference of the problem's own local approach.
  Eigen::VectorXd slope = Eigen::VectorXd::Zero(f.size());
  if (p.has_local()) {
    for (int j : active) {
      const double h = 1e-6 * f(j);
      Eigen::VectorXd up = f, down = f;
      up(j) += h;
      down(j) -= h;
      slope(j) = (p.LocalApproach(up)(j) - p.LocalApproach(down)(j)) / (2 * h);
    }
  }
  ActiveSetKkt kkt;
  kkt.h.resize(a, a);
  kkt.g.resize(m, a);
  for (int k = 0; k < a; ++k) {
    for (int l = 0; l < a; ++l) kkt.h(k, l) = p.compliance()(active[k], active[l]);
    kkt.h(k, k) += slope(active[k]);
    for (int i = 0; i < m; ++i) kkt.g(i, k) = p.equality_matrix()(i, active[k]);
  }
  kkt.s = p.support_stiffness();
  if (kkt.s.size() == 0) kkt.s = Eigen::MatrixXd::Zero(m, m);
  return kkt;
}

void BenchFactoriseKkt(benchmark::State& state, const Case* c) {
  const ActiveSetKkt kkt = BuildActiveSetKkt(*c);
  bool ok = true;
  for (auto _ : state) {
    Eigen::LLT<Eigen::MatrixXd> h_llt(kkt.h);
    const Eigen::MatrixXd half = h_llt.matrixL().solve(kkt.g.transpose());
    const Eigen::MatrixXd schur = half.transpose() * half + kkt.s;
    Eigen::LLT<Eigen::MatrixXd> s_llt(schur);
    ok = ok && h_llt.info() == Eigen::Success && s_llt.info() == Eigen::Success;
    benchmark::DoNotOptimize(s_llt.matrixLLT().data());
  }
  state.counters["active"] = static_cast<double>(kkt.h.rows());
  state.counters["m"] = static_cast<double>(kkt.g.rows());
  if (!ok) state.SkipWithError("active-set KKT factorisation failed");
}

void BenchFactoriseLlt(benchmark::State& state, const Case* c) {
  const ActiveSetKkt kkt = BuildActiveSetKkt(*c);
  for (auto _ : state) {
    Eigen::LLT<Eigen::MatrixXd> h_llt(kkt.h);
    benchmark::DoNotOptimize(h_llt.matrixLLT().data());
  }
  state.counters["active"] = static_cast<double>(kkt.h.rows());
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  const std::vector<Case> cases = BuildCases();
  const std::vector<Backend> backends = epicycle::solvers::AvailableBackends();
  for (const Case& c : cases) {
    for (Backend backend : backends) {
      if (backend == Backend::kNloptLbfgs && c.problem->num_equalities() > 0) continue;
      const std::string name = "solve/" + BackendName(backend) + "/" + c.name;
      benchmark::RegisterBenchmark(name.c_str(), BenchSolve, &c, backend)
          ->Unit(benchmark::kMicrosecond);
    }
    benchmark::RegisterBenchmark(("newton_warm_step/" + c.name).c_str(), BenchWarmStep, &c)
        ->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark(("newton_warm_same/" + c.name).c_str(), BenchWarm, &c,
                                 &c.reference)
        ->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark(("factorise_kkt/" + c.name).c_str(), BenchFactoriseKkt, &c)
        ->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark(("factorise_llt/" + c.name).c_str(), BenchFactoriseLlt, &c)
        ->Unit(benchmark::kMicrosecond);
  }
  epicycle::bench::RecordingReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);

  std::printf("\nRatios of CPU time per solve (issue 3 targets; measured, not asserted)\n");
  std::printf("%-24s %12s %12s %12s %14s %14s\n", "case", "ipopt/newton", "slsqp/newton",
              "auglag/newton", "warm_step/fact", "warm_same/fact");
  for (const Case& c : cases) {
    const double newton = reporter.seconds("solve/newton/" + c.name);
    const double fact = reporter.seconds("factorise_kkt/" + c.name);
    const auto ratio = [&](const std::string& name) {
      return reporter.seconds(name + c.name) / newton;
    };
    std::printf("%-24s %12.1f %12.1f %12.1f %14.2f %14.2f\n", c.name.c_str(), ratio("solve/ipopt/"),
                ratio("solve/nlopt-slsqp/"), ratio("solve/nlopt-auglag/"),
                reporter.seconds("newton_warm_step/" + c.name) / fact,
                reporter.seconds("newton_warm_same/" + c.name) / fact);
    for (Backend backend : backends) {
      const std::string name = "solve/" + BackendName(backend) + "/" + c.name;
      if (!std::isnan(reporter.seconds(name)) && !reporter.converged(name)) {
        std::printf("  note: %s did not reach the %g residual\n", name.c_str(), kSolveTolerance);
      }
    }
  }
  benchmark::Shutdown();
  return 0;
}
