// The dynamic model on the paper's stage with the hybrid FE compliance (tables from a cache
// written before the timing), planet 1 with 20 µm run-out, -600 N·m, 1500 rpm, Xu & Kahraman
// friction, mesh damping ζ = 0.05: one right-hand-side evaluation (contact search, compliance,
// local terms, contact solve warm-started from a neighbouring state, damping, friction, bearings)
// and one carrier revolution with CVODE BDF at rtol 1e-6 (fixed sun). Checks after the loop: the
// sun's balance of the evaluation (Σ sun-mesh torques + T − J θ̈ = 0 to round-off) and whether
// the revolution completed; counters give the time split of the run.
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>

#include "epicycle/dynamics/simulation.hpp"
#include "epicycle/dynamics/summary.hpp"
#include "epicycle/transmission/fe_compliance.hpp"

namespace {

using namespace epicycle;

transmission::Scene RunoutScene(transmission::SunSupport sun) {
  auto s = transmission::ReadScene(std::string(EPICYCLE_SCENES_DIR) + "/paper_stage_runout.toml");
  s.supports.sun = sun;
  s.dynamics.sun_speed = 1500 * std::numbers::pi / 30;
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

// Arg 0: fixed sun; 1: floating sun.
void BM_DynamicEvaluation(benchmark::State& state) {
  Case c(state.range(0) == 0 ? transmission::SunSupport::kFixed
                             : transmission::SunSupport::kFloating);
  const Eigen::VectorXd d = c.model.QuasiStaticStart({}, solvers::Backend::kActiveSetNewton);
  const Eigen::VectorXd v = Eigen::VectorXd::Zero(c.model.size());
  auto solver = solvers::MakeContactSolver(solvers::Backend::kActiveSetNewton);
  dynamics::Evaluation warm, e;
  c.model.Evaluate(0.0, d, v, *solver, {}, nullptr, &warm);
  // A neighbouring time (one step of ~3 µs) so that the warm start is a warm start.
  const double t = 3e-6;
  for (auto _ : state) {
    c.model.Evaluate(t, d, v, *solver, {}, &warm, &e);
    benchmark::DoNotOptimize(e.acceleration.data());
  }
  const int ks = c.model.Find(dynamics::MotionDof::kSun, dynamics::MotionDof::kRotation);
  double mesh = 0;
  for (double m : e.sun_mesh_torque) mesh += m;
  state.counters["sun_balance_error_Nm"] =
      std::abs(mesh + c.scene.sun_torque - c.model.mass()(ks) * e.acceleration(ks));
  state.counters["contacts"] = e.terms.size();
  state.counters["ok"] = e.ok ? 1 : 0;
}
BENCHMARK(BM_DynamicEvaluation)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

// One carrier revolution (65 mesh cycles, 0.2025 s) at 1500 rpm, 20 outputs per mesh cycle.
void BM_CarrierRevolution(benchmark::State& state) {
  Case c(transmission::SunSupport::kFixed);
  const double duration = 2 * std::numbers::pi / std::abs(c.model.carrier_speed());
  std::vector<double> times;
  const int outputs = 65 * 20;
  for (int i = 1; i <= outputs; ++i) times.push_back(duration * i / outputs);
  dynamics::SimulationOptions o;
  const Eigen::VectorXd d0 = c.model.QuasiStaticStart(o.contact, o.backend);
  dynamics::SimulationResult r;
  for (auto _ : state) {
    r = dynamics::Simulate(c.model, o, d0, Eigen::VectorXd::Zero(c.model.size()), times);
    benchmark::DoNotOptimize(r.samples.data());
  }
  state.counters["completed"] = r.completed ? 1 : 0;
  state.counters["steps"] = static_cast<double>(r.stats.steps);
  state.counters["evaluations"] = static_cast<double>(r.stats.rhs_evaluations);
  state.counters["jacobians"] = static_cast<double>(r.stats.jacobian_evaluations);
  state.counters["failed_solves"] = static_cast<double>(r.stats.failed_solves);
  state.counters["evaluation_s"] = r.stats.rhs_seconds;
  state.counters["jacobian_s"] = r.stats.jacobian_seconds;
  state.counters["wall_s"] = r.stats.wall_seconds;
  state.counters["K_gamma"] = dynamics::Summarise(r.samples).k_gamma;
}
BENCHMARK(BM_CarrierRevolution)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
