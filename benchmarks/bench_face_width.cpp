// The cost of slices of the face width (docs/face_width.md, "Cost"): the paper stage with planet
// 1's pin tilted radially by 20 µm over the face (scenes/paper_stage_pin_tilt.toml), fixed sun,
// at S = 1, 2, 5, 10, 20 slices: one quasi-static position (search, compliance, slices, contact
// solve, geometric iterations) against the plane model (S = 1); bench_dynamics's
// BM_FaceWidthEvaluation times the dynamic evaluation of the same scenes. Counters: the contacts
// of the problem; after the loop, Σ LSR_i = 1 (the torque carried).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>

#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/quasistatic.hpp"

namespace {

using namespace epicycle;

transmission::FeComplianceOptions Cache() {
  transmission::FeComplianceOptions o;
  o.cache_directory = (std::filesystem::temp_directory_path() / "epicycle-bench-ilt").string();
  return o;
}

// The pin-tilt scene with S slices.
transmission::Scene TiltScene(std::int64_t slices) {
  auto s = transmission::ReadScene(std::string(EPICYCLE_SCENES_DIR) + "/paper_stage_pin_tilt.toml");
  s.face_width.slices = static_cast<int>(slices);
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

}  // namespace

BENCHMARK_MAIN();
