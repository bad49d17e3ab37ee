// The quasi-static planetary solver on the paper's stage with the hybrid FE compliance (tables
// from a cache written before the timing): one whole-stage position (contact search, compliance
// matrix, contact problem, solve, geometric iterations until the members stop moving), and a
// 360-position sweep over one planet revolution with planet 1's 20 µm run-out. Checks after the
// loop: Σ LSR_i = 1 (the input torque is carried), failed positions.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <numbers>
#include <string>

#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/quasistatic.hpp"

namespace {

using namespace epicycle;

transmission::Scene Scene(const std::string& file) {
  return transmission::ReadScene(std::string(EPICYCLE_SCENES_DIR) + "/" + file);
}

transmission::FeComplianceOptions Cache() {
  transmission::FeComplianceOptions o;
  o.cache_directory = (std::filesystem::temp_directory_path() / "epicycle-bench-ilt").string();
  return o;
}

// A scene's stage with its cached FE compliance and the quasi-static options of its supports,
// the sun fixed (arg 0) or floating (arg 1).
struct StageCase {
  transmission::Scene scene;
  geometry::Stage stage;
  transmission::FeStageCompliance compliance;
  transmission::QuasiStaticOptions options;
  StageCase(const std::string& file, std::int64_t floating)
      : scene(Scene(file)), stage(scene.stage), compliance(scene, stage, Cache()) {
    options.setup = transmission::SetupFromScene(scene);
    options.setup.sun =
        floating == 0 ? transmission::SunSupport::kFixed : transmission::SunSupport::kFloating;
  }
};

// Arg 0: fixed sun; 1: floating sun.
void BM_StagePosition(benchmark::State& state) {
  const StageCase c("paper_stage.toml", state.range(0));
  const auto& [scene, stage, compliance, o] = c;
  const double angle = 0.3 * stage.mesh_cycle();
  transmission::PositionResult r;
  for (auto _ : state) {
    r = transmission::SolvePosition(scene, stage, compliance, angle, o);
    benchmark::DoNotOptimize(r.load_sharing.data());
  }
  double sum = 0.0;
  for (double v : r.load_sharing) sum += v;
  state.counters["lsr_sum_error"] = std::abs(sum - 1.0);
  state.counters["geometric_iterations"] = r.geometric_iterations;
  state.counters["contacts"] = static_cast<double>(r.problem.contacts.size());
  state.counters["converged"] = r.converged ? 1 : 0;
}
BENCHMARK(BM_StagePosition)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

// Arg 0: fixed sun; 1: floating sun.
void BM_StageSweep360(benchmark::State& state) {
  const StageCase c("paper_stage_runout.toml", state.range(0));
  const auto& [scene, stage, compliance, o] = c;
  const double period = 2.0 * std::numbers::pi * stage.planet(0).teeth() / stage.ring().teeth();
  const auto angles = transmission::SweepAngles(0.0, period, 360);
  std::vector<transmission::PositionResult> results;
  for (auto _ : state) {
    results = transmission::Sweep(scene, stage, compliance, angles, o);
    benchmark::DoNotOptimize(results.data());
  }
  int failed = 0;
  double worst = 0.0;
  for (const auto& r : results) {
    failed += r.converged ? 0 : 1;
    double sum = 0.0;
    for (double v : r.load_sharing) sum += v;
    if (r.converged) worst = std::max(worst, std::abs(sum - 1.0));
  }
  state.counters["failed"] = failed;
  state.counters["lsr_sum_error"] = worst;
}
BENCHMARK(BM_StageSweep360)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
