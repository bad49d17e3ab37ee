// Tolerance studies (docs/studies.md) on the paper's stage: a study of 1000 quasi-static
// mesh-cycle cases (36 positions each, tangential pin-hole errors σ = 5 µm on every planet, fixed
// sun) with 1 and 2 worker threads → cases per second (counter cases_per_s; the parallel
// efficiency is the ratio of the two rates over 2); and a single quasi-static sweep of the same
// size (36 000 positions) → its cost per 36 positions (counter ms_per_case), the reference of
// the study's per-case cost. Tables from a cache written before the timing. Checks after the
// loop: every case and position converged (counter failed).
#include <benchmark/benchmark.h>

#include <chrono>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include "epicycle/studies/runner.hpp"
#include "epicycle/studies/sampling.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "epicycle/transmission/run_range.hpp"

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
    for (const auto& row : r.rows) failed += row.ok() ? 0 : 1;
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

// The shipped studies (scenes/studies/), one worker thread, cases per second. Args: the study
// (0: pin_tolerance.toml, 200 mesh-cycle cases of 24 positions, fixed sun; 1:
// grades_and_torque.toml, planet revolutions of 120 positions, floating sun: its first 40 cases
// of 300, a whole revolution costing about 40× a mesh cycle), and the cases' first positions
// cold (0) or warm-started from their grid point's first case (1, RunOptions::warm_start_cases).
void BM_ShippedStudy(benchmark::State& state) {
  const char* files[] = {"pin_tolerance.toml", "grades_and_torque.toml"};
  const long limits[] = {-1, 40};
  const studies::StudySpec study =
      studies::ReadStudy(std::string(EPICYCLE_SCENES_DIR) + "/studies/" + files[state.range(0)]);
  const std::string rows =
      (std::filesystem::temp_directory_path() / "epicycle-bench-shipped-study.csv").string();
  studies::RunOptions o;
  o.rows_file = rows;
  o.cache_directory = CacheDir();
  o.threads = 1;
  o.max_new_cases = limits[state.range(0)];
  o.warm_start_cases = state.range(1) != 0;
  long failed = 0, cases = 0;
  double seconds = 0, cpu = 0;
  for (auto _ : state) {
    state.PauseTiming();
    std::filesystem::remove(rows);
    state.ResumeTiming();
    // The process's CPU time of the cases (the table load is timed apart by RunReport).
    const std::clock_t c0 = std::clock();
    const studies::RunReport r = studies::RunStudy(study, o);
    cpu += static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC - r.table_seconds;
    seconds += r.seconds;
    cases += r.computed;
    for (const auto& row : r.rows) failed += row.ok() ? 0 : 1;
  }
  std::filesystem::remove(rows);
  state.counters["cases_per_s"] = static_cast<double>(cases) / seconds;
  state.counters["ms_per_case"] = 1e3 * seconds / static_cast<double>(cases);
  state.counters["cpu_ms_per_case"] = 1e3 * cpu / static_cast<double>(cases);
  state.counters["failed"] = static_cast<double>(failed);
}
BENCHMARK(BM_ShippedStudy)
    ->Args({0, 0})
    ->Args({0, 1})
    ->Args({1, 0})
    ->Args({1, 1})
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();

// Where a case's time goes, the shipped pin-tolerance study's first 100 cases on one thread (the
// thread's CPU time, not disturbed by other jobs on the machine): the case's scene, stage and
// model (setup_ms), its first carrier position solved cold (first_ms) or warm-started from case
// 0's (first_warm_ms: the study's warm start across cases; both solved, the warm one's result
// discarded), and each later position, warm-started from the one before (later_ms, per
// position), with the iterations of each (geometric and contact).
void BM_CasePhases(benchmark::State& state) {
  const studies::StudySpec study =
      studies::ReadStudy(std::string(EPICYCLE_SCENES_DIR) + "/studies/pin_tolerance.toml");
  transmission::FeComplianceOptions fe;
  fe.cache_directory = CacheDir();
  const geometry::Stage nominal = transmission::MakeStage(study.scene);
  const transmission::FeStageCompliance compliance(study.scene, nominal, fe);
  constexpr long kPhaseCases = 100;
  double setup = 0, first = 0, first_warm = 0, later = 0;
  double first_geo = 0, first_contact = 0, later_geo = 0, later_contact = 0;
  double warm_geo = 0, warm_contact = 0;
  long later_count = 0, failed = 0;
  auto now = [] {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
  };
  auto since = [&](double t) { return now() - t; };
  std::unique_ptr<transmission::PositionResult> start;
  for (auto _ : state) {
    for (long k = 0; k < kPhaseCases; ++k) {
      const double t0 = now();
      const transmission::Scene scene = studies::CaseScene(study, studies::SampleCase(study, k));
      const geometry::Stage stage = transmission::MakeStage(scene);
      transmission::StageSetup setup_of = transmission::SetupFromScene(scene);
      if (study.sun) setup_of.sun = *study.sun;
      const transmission::StageModel model(stage, compliance, setup_of);
      const auto angles = transmission::SweepAngles(
          study.start_angle, transmission::CarrierSpan(stage, transmission::RunRange::kMeshCycle),
          study.positions);
      transmission::QuasiStaticOptions opt;
      opt.threads = 1;
      setup += since(t0);
      // The warm first position solved before the case's sweep on even cases, after it on odd
      // ones: whichever runs first pays for the case's model coming into the caches.
      auto warm_first = [&] {
        if (!start) return;
        const double tw = now();
        transmission::SweepEach(
            model, scene.loads, 1, [&](int) { return angles.front(); }, opt,
            [&](const transmission::PositionResult& r, int) {
              warm_geo += r.geometric_iterations;
              warm_contact += r.contact_iterations;
            },
            start.get());
        first_warm += since(tw);
      };
      if (k % 2 == 0) warm_first();
      double t1 = now();
      transmission::SweepEach(
          model, scene.loads, static_cast<int>(angles.size()),
          [&](int i) { return angles[static_cast<std::size_t>(i)]; }, opt,
          [&](const transmission::PositionResult& r, int i) {
            failed += r.converged ? 0 : 1;
            if (i == 0) {
              first += since(t1);
              first_geo += r.geometric_iterations;
              first_contact += r.contact_iterations;
              if (!start) start = std::make_unique<transmission::PositionResult>(r);
              t1 = now();
            } else {
              later_geo += r.geometric_iterations;
              later_contact += r.contact_iterations;
              ++later_count;
            }
          });
      later += since(t1);
      if (k % 2 == 1) warm_first();
    }
  }
  const double n = static_cast<double>(kPhaseCases) * static_cast<double>(state.iterations());
  const double m = static_cast<double>(later_count);
  state.counters["setup_ms"] = 1e3 * setup / n;
  state.counters["first_ms"] = 1e3 * first / n;
  state.counters["first_warm_ms"] = 1e3 * first_warm / (n - 1);
  state.counters["first_warm_contact_it"] = warm_contact / (n - 1);
  state.counters["first_warm_geo_it"] = warm_geo / (n - 1);
  state.counters["later_ms"] = 1e3 * later / m;
  state.counters["first_geo_it"] = first_geo / n;
  state.counters["first_contact_it"] = first_contact / n;
  state.counters["later_geo_it"] = later_geo / m;
  state.counters["later_contact_it"] = later_contact / m;
  state.counters["failed"] = static_cast<double>(failed);
}
BENCHMARK(BM_CasePhases)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
