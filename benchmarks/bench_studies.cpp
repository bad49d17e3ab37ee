// Tolerance studies (docs/studies.md) on the paper's stage: a study of 1000 quasi-static
// mesh-cycle cases (36 positions each, tangential pin-hole errors σ = 5 µm on every planet, fixed
// sun) with 1 and 2 worker threads → cases per second (counter cases_per_s; the parallel
// efficiency is the ratio of the two rates over 2); and a single quasi-static sweep of the same
// size (36 000 positions) → its cost per 36 positions (counter ms_per_case), the reference of
// the study's per-case cost. Tables from a cache written before the timing. Checks after the
// loop: every case and position converged (counter failed).
#include <benchmark/benchmark.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include "epicycle/studies/runner.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/quasistatic.hpp"

namespace {

using namespace epicycle;

constexpr int kCases = 1000, kPositions = 36;

std::string CacheDir() {
  return (std::filesystem::temp_directory_path() / "epicycle-bench-ilt").string();
}

studies::StudySpec Study() {
  const std::string text = "[study]\nname = \"bench\"\nscene = \"" +
                           std::string(EPICYCLE_SCENES_DIR) +
                           "/paper_stage.toml\"\nseed = 1\nsamples = " + std::to_string(kCases) +
                           "\npositions = " + std::to_string(kPositions) +
                           "\nsun = \"fixed\"\n[[variable]]\nquantity = \"pin_tangential\"\n"
                           "gear = \"planets\"\ndistribution = \"normal\"\nsigma_um = 5.0\n";
  return studies::ParseStudy(text, "bench.toml", "");
}

// Arg: worker threads.
void BM_Study1000MeshCycles(benchmark::State& state) {
  const studies::StudySpec study = Study();
  const std::string rows =
      (std::filesystem::temp_directory_path() / "epicycle-bench-study.csv").string();
  studies::RunOptions o;
  o.rows_file = rows;
  o.cache_directory = CacheDir();
  o.threads = static_cast<int>(state.range(0));
  long failed = 0;
  double seconds = 0;
  for (auto _ : state) {
    state.PauseTiming();
    std::filesystem::remove(rows);
    state.ResumeTiming();
    const studies::RunReport r = studies::RunStudy(study, o);
    seconds += r.seconds;
    for (const auto& row : r.rows) failed += row.ok ? 0 : 1;
  }
  std::filesystem::remove(rows);
  const double cases = static_cast<double>(kCases) * static_cast<double>(state.iterations());
  state.counters["cases_per_s"] = cases / seconds;
  state.counters["ms_per_case"] = 1e3 * seconds / cases;
  state.counters["failed"] = static_cast<double>(failed);
}
BENCHMARK(BM_Study1000MeshCycles)
    ->Arg(1)
    ->Arg(2)
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();

// One sweep of 1000 mesh cycles × 36 positions with planet 1's 5 µm tangential pin error.
void BM_SingleSweepSameSize(benchmark::State& state) {
  transmission::Scene scene =
      transmission::ReadScene(std::string(EPICYCLE_SCENES_DIR) + "/paper_stage.toml");
  scene.stage.pin_errors = {{0.0, 5e-6}, {}, {}};
  const geometry::Stage stage(scene.stage);
  transmission::FeComplianceOptions fe;
  fe.cache_directory = CacheDir();
  const transmission::FeStageCompliance compliance(scene, stage, fe);
  transmission::QuasiStaticOptions o;
  transmission::StageSetup setup = transmission::SetupFromScene(scene);
  setup.sun = transmission::SunSupport::kFixed;
  o.threads = 1;  // as inside a study's case: the reference of its one-thread per-case cost
  const auto angles =
      transmission::SweepAngles(0.0, kCases * stage.mesh_cycle(), kCases * kPositions);
  long failed = 0;
  double seconds = 0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto r = transmission::Sweep(transmission::StageModel(stage, compliance, setup),
                                       scene.loads, angles, o);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    for (const auto& p : r) failed += p.converged ? 0 : 1;
  }
  state.counters["ms_per_case"] =
      1e3 * seconds / (static_cast<double>(kCases) * static_cast<double>(state.iterations()));
  state.counters["failed"] = static_cast<double>(failed);
}
BENCHMARK(BM_SingleSweepSameSize)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
