// The dynamic model on the paper's stage with the hybrid FE compliance (tables from a cache
// written before the timing), planet 1 with 20 µm run-out, -600 N·m, 1500 rpm, Xu & Kahraman
// friction, mesh damping ζ = 0.05: one right-hand-side evaluation (contact search, compliance,
// local terms, contact solve warm-started from a neighbouring state, damping, friction, bearings)
// and one carrier revolution with CVODE BDF at rtol 1e-6 (fixed sun). Checks after the loop: the
// sun's balance of the evaluation (Σ sun-mesh torques + T − J θ̈ = 0 to round-off) and whether
// the revolution completed; counters give the time split of the run.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <string>

#include "epicycle/dynamics/simulation.hpp"
#include "epicycle/dynamics/dynamic_summary.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "recording_reporter.hpp"
#include "epicycle/io/units.hpp"

namespace {

using namespace epicycle;

transmission::Scene RunoutScene(transmission::SunSupport sun) {
  auto s = transmission::ReadScene(std::string(EPICYCLE_SCENES_DIR) + "/paper_stage_runout.toml");
  s.supports.sun = sun;
  s.dynamics.sun_speed = io::RpmToRadPerSecond(1500);
  return s;
}

// The stage's dynamic model with the benchmarks' table cache.
struct Case : dynamics::StageDynamics {
  explicit Case(transmission::SunSupport sun) : StageDynamics(RunoutScene(sun), Cache()) {}
  static transmission::FeComplianceOptions Cache() {
    transmission::FeComplianceOptions o;
    o.cache_directory = (std::filesystem::temp_directory_path() / "epicycle-bench-ilt").string();
    return o;
  }
};

// One evaluation's timing loop and its counters (BM_DynamicEvaluation, BM_DamagedEvaluation).
void TimeEvaluations(benchmark::State& state, const dynamics::StageDynamics& c);

// Arg 0: fixed sun; 1: floating sun.
void BM_DynamicEvaluation(benchmark::State& state) {
  const Case c(state.range(0) == 0 ? transmission::SunSupport::kFixed
                                   : transmission::SunSupport::kFloating);
  TimeEvaluations(state, c);
}
BENCHMARK(BM_DynamicEvaluation)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

// The cost of a damaged tooth (docs/damage.md): the paper stage without errors (Arg 0), with
// scenes/paper_stage_spall.toml's spall on planet 1's tooth 13 (Arg 1), and with
// scenes/paper_stage_runout_crack.toml's root crack in sun tooth 0 alone (Arg 2), fixed sun, at
// t = 0, where the damaged tooth meshes (the spall's contact split into two strips; the cracked
// tooth's rows read from its damaged rows).
void BM_DamagedEvaluation(benchmark::State& state) {
  const std::string dir = EPICYCLE_SCENES_DIR;
  auto scene = transmission::ReadScene(
      dir + (state.range(0) == 1 ? "/paper_stage_spall.toml" : "/paper_stage.toml"));
  if (state.range(0) == 2) {
    const auto cracked = transmission::ReadScene(dir + "/paper_stage_runout_crack.toml");
    scene.damage.cracks = cracked.damage.cracks;
  }
  scene.dynamics.sun_speed = io::RpmToRadPerSecond(1500);
  const dynamics::StageDynamics c(std::move(scene), Case::Cache());
  TimeEvaluations(state, c);
}
BENCHMARK(BM_DamagedEvaluation)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);

// The cost of slices of the face width (docs/face_width.md, "Cost"): scenes/
// paper_stage_pin_tilt.toml (planet 1's pin tilted radially by 20 µm over the face), fixed sun,
// 1500 rpm, with S = 1, 2, 5, 10, 20 slices.
void BM_FaceWidthEvaluation(benchmark::State& state) {
  auto scene =
      transmission::ReadScene(std::string(EPICYCLE_SCENES_DIR) + "/paper_stage_pin_tilt.toml");
  scene.face_width.slices = static_cast<int>(state.range(0));
  scene.dynamics.sun_speed = io::RpmToRadPerSecond(1500);
  const dynamics::StageDynamics c(std::move(scene), Case::Cache());
  TimeEvaluations(state, c);
}
BENCHMARK(BM_FaceWidthEvaluation)
    ->Arg(1)
    ->Arg(2)
    ->Arg(5)
    ->Arg(10)
    ->Arg(20)
    ->Unit(benchmark::kMicrosecond);

// The helical paper stage against the spur one at the same S (docs/face_width.md, "Helical
// meshes", Cost): scenes/paper_stage_helical.toml (β = 15°, the paper stage's transverse
// section) and scenes/paper_stage_pin_tilt.toml, fixed sun, 1500 rpm, S = 5, 10, 20 slices; the
// second argument 1 for helical, 0 for spur.
void BM_FaceWidthHelicalEvaluation(benchmark::State& state) {
  const bool helical = state.range(1) != 0;
  auto scene = transmission::ReadScene(std::string(EPICYCLE_SCENES_DIR) +
                                       (helical ? "/paper_stage_helical.toml"
                                                : "/paper_stage_pin_tilt.toml"));
  scene.face_width.slices = static_cast<int>(state.range(0));
  scene.dynamics.sun_speed = io::RpmToRadPerSecond(1500);
  transmission::FeComplianceOptions fe = Case::Cache();
  fe.helical_slices = true;  // as `epicycle dynamic`
  const dynamics::StageDynamics c(std::move(scene), fe);
  TimeEvaluations(state, c);
}
BENCHMARK(BM_FaceWidthHelicalEvaluation)
    ->ArgsProduct({{5, 10, 20}, {0, 1}})
    ->Unit(benchmark::kMicrosecond);

void TimeEvaluations(benchmark::State& state, const dynamics::StageDynamics& c) {
  const Eigen::VectorXd d = c.model.QuasiStaticStart({}, solvers::Backend::kActiveSetNewton);
  const Eigen::VectorXd v = Eigen::VectorXd::Zero(c.model.size());
  auto solver = solvers::MakeContactSolver(solvers::Backend::kActiveSetNewton);
  // Two neighbouring times (one step of ~3 µs apart), evaluated in turn, each warm-started from
  // the other: every evaluation starts from a neighbour's forces and finds in the solver what the
  // neighbour's solve left there (as in an integration), never its own answer.
  dynamics::Evaluation pair[2];
  const double times[2] = {0.0, 3e-6};
  c.model.Evaluate(times[0], d, v, *solver, {}, nullptr, &pair[0]);
  c.model.Evaluate(times[1], d, v, *solver, {}, &pair[0], &pair[1]);
  int k = 0;
  for (auto _ : state) {  // as the integrator calls it: without the energies
    c.model.Evaluate(times[k], d, v, *solver, {}, &pair[1 - k], &pair[k], /*energies=*/false);
    benchmark::DoNotOptimize(pair[k].acceleration.data());
    k = 1 - k;
  }
  const dynamics::Evaluation& e = pair[1];
  const int ks = c.model.Find(dynamics::MotionDof::kSun, dynamics::MotionDof::kRotation);
  double mesh = 0;
  for (double m : e.sun_mesh_torque) mesh += m;
  state.counters["sun_balance_error_Nm"] =
      std::abs(mesh + c.scene.loads.sun_torque - c.model.mass()(ks) * e.acceleration(ks));
  state.counters["contacts"] = e.terms.size();
  state.counters["ok"] = e.ok ? 1 : 0;
}

// The parts of one evaluation at the same state (fixed sun), for the time split:
//   0 poses of the members;  1 contact search of the stage;  2 the contact terms (search, FE
//   compliance matrix, local terms);  3 the contact problem's construction (its validation);
//   4 the warm contact solve: this state's and the neighbouring state's problems in turn, each
//     from the other's forces and after the other's solve (the average of the two);
//   5 the cold solve;
//   6 one factorisation of the final active set, Cholesky of C_AA + diag(u'_A), as the Newton does.
void BM_EvaluationPart(benchmark::State& state) {
  Case c(transmission::SunSupport::kFixed);
  const Eigen::VectorXd d = c.model.QuasiStaticStart({}, solvers::Backend::kActiveSetNewton);
  const Eigen::VectorXd v = Eigen::VectorXd::Zero(c.model.size());
  auto solver = solvers::MakeContactSolver(solvers::Backend::kActiveSetNewton);
  dynamics::Evaluation warm;
  c.model.Evaluate(0.0, d, v, *solver, {}, nullptr, &warm);
  const double t = 3e-6;
  const geometry::StagePoses poses = c.model.Poses(t, d);
  const transmission::ContactTerms terms = c.stage_model.Terms(poses);
  const auto problem_of = [](const transmission::ContactTerms& tm) {
    solvers::ContactProblemData pd;
    pd.compliance = tm.compliance;
    pd.overlap = tm.overlap;
    pd.local = tm.local;
    pd.equality_matrix.resize(0, tm.size());
    pd.equality_rhs.resize(0);
    return pd;
  };
  const solvers::ContactProblemData data = problem_of(terms);
  const solvers::ContactProblem problem(data);
  solvers::ContactSolution answer;
  solver->Solve(problem, {}, &answer);
  // The neighbouring state's problem (t = 0, the forces `warm` came from), for part 4.
  const solvers::ContactProblem neighbour(problem_of(warm.terms));
  solvers::ContactSolution answers[2];
  answers[0].force = warm.force;
  answers[1] = answer;
  const solvers::ContactProblem* problems[2] = {&neighbour, &problem};
  int turn = 1;
  std::vector<int> active;
  for (int j = 0; j < terms.size(); ++j)
    if (answer.force(j) > 0) active.push_back(j);
  Eigen::MatrixXd h(active.size(), active.size());
  for (std::size_t a = 0; a < active.size(); ++a)
    for (std::size_t b = 0; b < active.size(); ++b)
      h(a, b) = problem.compliance()(active[a], active[b]);
  for (std::size_t a = 0; a < active.size(); ++a)
    h(a, a) += solvers::LocalApproachDerivative(terms.local[active[a]], answer.force(active[a]));
  const int part = static_cast<int>(state.range(0));
  solvers::ContactReport last;
  solvers::ContactOptions warm_options;
  warm_options.warm_start = true;
  for (auto _ : state) {
    switch (part) {
      case 0:
        benchmark::DoNotOptimize(c.model.Poses(t, d));
        break;
      case 1:
        benchmark::DoNotOptimize(transmission::SearchStage(c.stage, poses, c.scene.gap_window));
        break;
      case 2:
        benchmark::DoNotOptimize(c.stage_model.Terms(poses));
        break;
      case 3:
        benchmark::DoNotOptimize(solvers::ContactProblem(data));
        break;
      case 4: {
        solvers::ContactSolution& s = answers[turn];
        s.force = answers[1 - turn].force;
        last = solver->Solve(*problems[turn], warm_options, &s);
        benchmark::DoNotOptimize(s.force.data());
        turn = 1 - turn;
        break;
      }
      case 5: {
        solvers::ContactSolution s;
        last = solver->Solve(problem, {}, &s);
        benchmark::DoNotOptimize(s.force.data());
        break;
      }
      case 6:
        benchmark::DoNotOptimize(h.llt().matrixL().rows());
        break;
    }
  }
  state.counters["contacts"] = terms.size();
  state.counters["active"] = static_cast<double>(active.size());
  if (part == 4 || part == 5) state.counters["iterations"] = last.iterations;
}
BENCHMARK(BM_EvaluationPart)->DenseRange(0, 6)->Unit(benchmark::kMicrosecond);

// One carrier revolution (65 mesh cycles, 0.2025 s) at 1500 rpm, 20 outputs per mesh cycle.
// Arg 0: the default tolerances; 1: the rates' tolerance at the stage's highest linearised
// frequency (rate_scale = 0: fewer steps, a larger error; docs/dynamic.md).
void BM_CarrierRevolution(benchmark::State& state) {
  Case c(transmission::SunSupport::kFixed);
  const double duration = 2 * std::numbers::pi / std::abs(c.model.carrier_speed());
  std::vector<double> times;
  const int outputs = 65 * 20;
  for (int i = 1; i <= outputs; ++i) times.push_back(duration * i / outputs);
  dynamics::SimulationOptions o;
  if (state.range(0) == 1) o.rate_scale = 0;
  const Eigen::VectorXd d0 = c.model.QuasiStaticStart(o.contact, o.backend);
  dynamics::SimulationResult r;
  for (auto _ : state) {
    r = dynamics::Simulate(c.model, o, d0, Eigen::VectorXd::Zero(c.model.size()), times);
    benchmark::DoNotOptimize(r.samples.data());
  }
  state.counters["completed"] = r.completed() ? 1 : 0;
  state.counters["steps"] = static_cast<double>(r.stats.steps);
  state.counters["evaluations"] = static_cast<double>(r.stats.rhs_evaluations);
  state.counters["jacobians"] = static_cast<double>(r.stats.jacobian_evaluations);
  state.counters["failed_solves"] = static_cast<double>(r.stats.failed_solves);
  state.counters["evaluation_s"] = r.stats.rhs_seconds;
  state.counters["jacobian_s"] = r.stats.jacobian_seconds;
  state.counters["wall_s"] = r.stats.wall_seconds;
  state.counters["rate_scale_rad_s"] = r.stats.rate_scale;
  state.counters["error_test_failures"] = static_cast<double>(r.stats.error_test_failures);
  state.counters["K_gamma"] = dynamics::Summarise(r.samples).k_gamma;
}
BENCHMARK(BM_CarrierRevolution)->Arg(0)->Arg(1)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace

// After the runs, the targets of the performance work as the ratios they are stated in (CPU time,
// the least of the repetitions: `--benchmark_repetitions=3` gives the best of 3; measured and
// reported, not asserted). The in-run evaluation is the revolution's evaluation time over its
// evaluations: SimulationStats::rhs_seconds is wall time, equal to CPU time on a quiet machine
// only.
int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  epicycle::bench::RecordingReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  const auto us = [&](const char* name) { return 1e6 * reporter.seconds(name); };
  const char* revolution = "BM_CarrierRevolution/0/iterations:1";
  const double fact = us("BM_EvaluationPart/6");
  const double in_run = 1e6 * reporter.counter(revolution, "evaluation_s") /
                        reporter.counter(revolution, "evaluations");
  std::printf("\nTargets (CPU; NaN where a benchmark was filtered out)\n");
  std::printf("  one evaluation, fixed sun        %8.2f us   (target <= 8 us)\n",
              us("BM_DynamicEvaluation/0"));
  std::printf("  in-run evaluation / one          %8.2f      (target <= 1.3; %.2f us wall)\n",
              in_run / us("BM_DynamicEvaluation/0"), in_run);
  std::printf("  carrier revolution               %8.2f s    (target <= 1 s)\n",
              1e-6 * us(revolution));
  std::printf("  warm solve / one factorisation   %8.2f      (target <= 3)\n",
              us("BM_EvaluationPart/4") / fact);
  std::printf("  cold solve / one factorisation   %8.2f      (target <= 20)\n",
              us("BM_EvaluationPart/5") / fact);
  std::printf("  validation / warm solve          %8.2f      (target <= 1)\n",
              us("BM_EvaluationPart/3") / us("BM_EvaluationPart/4"));
  benchmark::Shutdown();
  return 0;
}
