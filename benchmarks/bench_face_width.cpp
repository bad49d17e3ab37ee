// The cost of slices of the face width (docs/face_width.md, "Cost"): the paper stage with planet
// 1's pin tilted radially by 20 µm over the face (scenes/paper_stage_pin_tilt.toml, the carrier
// rigid), fixed sun, at S = 1, 2, 5, 10, 20 slices: one quasi-static position (search, compliance,
// slices, contact solve, geometric iterations) and one dynamic right-hand-side evaluation
// warm-started from a neighbouring state, both against the plane model (S = 1). Counters: the
// contacts of the problem; after the loop, Σ LSR_i = 1 of the position (the torque carried).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>

#include "epicycle/dynamics/simulation.hpp"
#include "epicycle/io/units.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/quasistatic.hpp"

namespace {

using namespace epicycle;

transmission::FeComplianceOptions Cache() {
  transmission::FeComplianceOptions o;
  o.cache_directory = (std::filesystem::temp_directory_path() / "epicycle-bench-ilt").string();
  return o;
}

// The pin-tilt scene with S slices and the carrier rigid (its wind-up needs no slices' cost).
transmission::Scene TiltScene(std::int64_t slices) {
  auto s = transmission::ReadScene(std::string(EPICYCLE_SCENES_DIR) + "/paper_stage_pin_tilt.toml");
  s.face_width.slices = static_cast<int>(slices);
  s.face_width.carrier_torsional_stiffness = 0;
  s.dynamics.sun_speed = io::RpmToRadPerSecond(1500);
  return s;
}

void BM_FaceWidthPosition(benchmark::State& state) {
  const transmission::Scene scene = TiltScene(state.range(0));
  const geometry::Stage stage(scene.stage);
  const transmission::FeStageCompliance compliance(scene, stage, Cache());
  const transmission::StageModel model(stage, compliance, transmission::SetupFromScene(scene));
  const double angle = 0.3 * stage.mesh_cycle();
  transmission::PositionResult r;
  for (auto _ : state) {
    r = transmission::SolvePosition(model, angle, scene.loads, {});
    benchmark::DoNotOptimize(r.solution.force.data());
  }
  double sum = 0;
  for (double v : r.load_sharing) sum += v;
  state.counters["lsr_sum_error"] = std::abs(sum - 1);
  state.counters["contacts"] = static_cast<double>(r.problem.contacts.size());
  state.counters["converged"] = r.converged ? 1 : 0;
}
BENCHMARK(BM_FaceWidthPosition)->Arg(1)->Arg(2)->Arg(5)->Arg(10)->Arg(20)->Unit(benchmark::kMillisecond);

void BM_FaceWidthEvaluation(benchmark::State& state) {
  const dynamics::StageDynamics c(TiltScene(state.range(0)), Cache());
  const Eigen::VectorXd d = c.model.QuasiStaticStart({}, solvers::Backend::kActiveSetNewton);
  const Eigen::VectorXd v = Eigen::VectorXd::Zero(c.model.size());
  auto solver = solvers::MakeContactSolver(solvers::Backend::kActiveSetNewton);
  // Two neighbouring times evaluated in turn, each warm-started from the other (bench_dynamics's
  // BM_DynamicEvaluation).
  dynamics::Evaluation pair[2];
  const double times[2] = {0.0, 3e-6};
  c.model.Evaluate(times[0], d, v, *solver, {}, nullptr, &pair[0]);
  c.model.Evaluate(times[1], d, v, *solver, {}, &pair[0], &pair[1]);
  int k = 0;
  for (auto _ : state) {
    c.model.Evaluate(times[k], d, v, *solver, {}, &pair[1 - k], &pair[k], /*energies=*/false);
    benchmark::DoNotOptimize(pair[k].acceleration.data());
    k = 1 - k;
  }
  state.counters["contacts"] = pair[1].terms.size();
  state.counters["ok"] = pair[1].ok ? 1 : 0;
}
BENCHMARK(BM_FaceWidthEvaluation)->Arg(1)->Arg(2)->Arg(5)->Arg(10)->Arg(20)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
