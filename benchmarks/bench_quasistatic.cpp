// The quasi-static planetary solver on the paper's stage with the hybrid FE compliance (tables
// from a cache written before the timing): one whole-stage position (contact search, compliance
// matrix, contact problem, solve, geometric iterations until the members stop moving), and a
// 360-position sweep over one planet revolution with planet 1's 20 µm run-out: every position
// cold, warm-started from its neighbour, warm on 2 threads. Checks after the loop: Σ LSR_i = 1
// (the input torque is carried), failed positions; counters: geometric and contact (back-end)
// iterations per position, what the warm start saves.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <ctime>
#include <filesystem>
#include <numbers>
#include <string>

#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "epicycle/transmission/run_range.hpp"
#include "epicycle/transmission/sweep_summary.hpp"

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
  transmission::StageModel model;
  StageCase(const std::string& file, std::int64_t floating)
      : scene(Scene(file)),
        stage(scene.stage),
        compliance(scene, stage, Cache()),
        model(stage, compliance, Setup(scene, floating)) {}
  static transmission::StageSetup Setup(const transmission::Scene& scene, std::int64_t floating) {
    transmission::StageSetup setup = transmission::SetupFromScene(scene);
    setup.sun =
        floating == 0 ? transmission::SunSupport::kFixed : transmission::SunSupport::kFloating;
    return setup;
  }
};

// Arg 0: fixed sun; 1: floating sun.
void BM_StagePosition(benchmark::State& state) {
  const StageCase c("paper_stage.toml", state.range(0));
  const double angle = 0.3 * c.stage.mesh_cycle();
  transmission::PositionResult r;
  for (auto _ : state) {
    r = transmission::SolvePosition(c.model, angle, c.scene.loads, {});
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

// The 360-position sweep, args (sun, mode): sun 0 fixed, 1 floating; mode 0 every position cold
// on one thread, 1 warm-started from the neighbour on one thread, 2 warm on 2 threads (one
// contiguous chunk each). Timed in wall time (UseRealTime) with the process's CPU time beside it
// (MeasureProcessCPUTime): the machine is shared, so a parallel speed-up shows in wall time only
// when the other core is free, and the CPU time says what the run cost; mode 2 also reports the
// longest chunk's CPU time alone (counter longest_chunk_cpu_ms), the wall time on two free cores.
void BM_StageSweep360(benchmark::State& state) {
  const StageCase c("paper_stage_runout.toml", state.range(0));
  const geometry::Stage& stage = c.stage;
  transmission::QuasiStaticOptions o;
  o.warm_start = state.range(1) > 0;
  o.threads = state.range(1) == 2 ? 2 : 1;
  const double period = transmission::CarrierSpan(stage, transmission::RunRange::kPlanetRevolution);
  const auto angles = transmission::SweepAngles(0.0, period, 360);
  std::vector<transmission::PositionResult> results;
  for (auto _ : state) {
    results = transmission::Sweep(c.model, c.scene.loads, angles, o);
    benchmark::DoNotOptimize(results.data());
  }
  int failed = 0;
  double worst = 0.0, geometric = 0.0, contact = 0.0;
  for (const auto& r : results) {
    failed += r.converged ? 0 : 1;
    geometric += r.geometric_iterations;
    contact += r.contact_iterations;
    double sum = 0.0;
    for (double v : r.load_sharing) sum += v;
    if (r.converged) worst = std::max(worst, std::abs(sum - 1.0));
  }
  const double n = static_cast<double>(results.size());
  if (state.range(1) == 2) {
    // What the wall time would be with both cores free: the larger of the two chunks' CPU times,
    // each chunk run alone on one thread (the same work as the parallel run's workers).
    double longest = 0.0;
    for (int half = 0; half < 2; ++half) {
      const std::vector<double> chunk(angles.begin() + half * 180,
                                      angles.begin() + half * 180 + 180);
      transmission::QuasiStaticOptions one = o;
      one.threads = 1;
      const std::clock_t c0 = std::clock();
      benchmark::DoNotOptimize(transmission::Sweep(c.model, c.scene.loads, chunk, one).data());
      longest = std::max(longest, static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC);
    }
    state.counters["longest_chunk_cpu_ms"] = 1e3 * longest;
  }
  state.counters["failed"] = failed;
  state.counters["lsr_sum_error"] = worst;
  state.counters["geometric_per_position"] = geometric / n;
  state.counters["contact_per_position"] = contact / n;
}
BENCHMARK(BM_StageSweep360)
    ->ArgsProduct({{0, 1}, {0, 1, 2}})
    ->ArgNames({"floating", "mode"})
    ->MeasureProcessCPUTime()
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// The reference of the Python bindings' cost (benchmarks/python_quasistatic.py, docs/python.md):
// 1000 positions over one planet revolution of the run-out case, sun fixed, warm-started on one
// thread, as epicycle.quasistatic(scene, range="planet", positions=1000, threads=1) runs them.
void BM_StageSweep1000(benchmark::State& state) {
  const StageCase c("paper_stage_runout.toml", 0);
  transmission::QuasiStaticOptions o;
  o.threads = 1;
  const auto angles = transmission::SweepAngles(
      0.0, transmission::CarrierSpan(c.stage, transmission::RunRange::kPlanetRevolution), 1000);
  std::vector<transmission::PositionResult> results;
  for (auto _ : state) {
    results = transmission::Sweep(c.model, c.scene.loads, angles, o);
    benchmark::DoNotOptimize(results.data());
  }
  int failed = 0;
  for (const auto& r : results) failed += r.converged ? 0 : 1;
  state.counters["failed"] = failed;
  state.counters["k_gamma"] = transmission::SummariseSweep(results, c.stage.planets()).k_gamma;
}
BENCHMARK(BM_StageSweep1000)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
