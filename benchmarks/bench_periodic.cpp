// The periodic solver (docs/periodic.md) on the gear pair with backlash of Kahraman & Singh
// (BacklashOscillator: ζ = 0.05, F_m = 0.1, F_a = 0.05): one shooting solve at Ω = 0.6 on the
// large (separating) orbit from a cold guess, and the continuation over Ω from 1.5 to 0.4 with both
// folds, at rtol 1e-8. Checks after the loop: the shooting converged and its residual, the
// continuation's folds and point count.
// The perfect paper stage over 500–12 000 rpm (docs/periodic.md §4, must-show 6), one thread, CPU
// time of the process, best of 3: the 116-speed time-integration sweep (3 mesh cycles a speed) and
// the harmonic-balance branch with Hill's stability (H = 12 and 16); after the loop, the branch's
// K_γ and TE amplitude interpolated at the sweep's speeds against the sweep's.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "epicycle/dynamics/branch_run.hpp"
#include "epicycle/dynamics/periodic.hpp"
#include "epicycle/dynamics/periodic_systems.hpp"
#include "epicycle/dynamics/speed_sweep.hpp"
#include "epicycle/dynamics/speed_sweep_run.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/scene.hpp"

namespace {

using namespace epicycle::dynamics;
using epicycle::dynamics::DynamicRequest;

ShootingOptions Options() {
  ShootingOptions o;
  o.rtol = 1e-8;
  o.atol = Eigen::VectorXd::Constant(1, 1e-10);
  return o;
}

void BM_ShootingBacklash(benchmark::State& state) {
  const BacklashOscillator s;
  const Eigen::Vector2d p(0.6, s.alternating_force);
  ShootingResult r;
  for (auto _ : state) {
    // From rest at x = 0: the teeth separate at once, Newton reaches the large orbit.
    r = SolvePeriodicOrbit(s, Options(), Eigen::Vector2d(0, 0), p);
    benchmark::DoNotOptimize(r.initial_state.data());
  }
  state.counters["converged"] = r.status == ShootingStatus::kConverged ? 1 : 0;
  state.counters["newton_iterations"] = r.iterations;
  state.counters["periods_integrated"] = static_cast<double>(r.integrations);
  state.counters["steps"] = static_cast<double>(r.steps);
  state.counters["residual_wrms"] = r.residual_norm;
  state.counters["spectral_radius"] = r.floquet.spectral_radius;
}
BENCHMARK(BM_ShootingBacklash)->Unit(benchmark::kMillisecond);

void BM_ContinuationBacklash(benchmark::State& state) {
  const BacklashOscillator s;
  ContinuationOptions c;
  c.parameter = "Omega";
  c.start = 1.5;
  c.end = 0.4;
  c.max_step = 0.02;
  c.shooting = Options();
  ContinuationResult r;
  for (auto _ : state) {
    r = ContinuePeriodicOrbit(s, c, Eigen::Vector2d(1.1, 0),
                              Eigen::Vector2d(c.start, s.alternating_force));
    benchmark::DoNotOptimize(r.points.data());
  }
  int folds = 0;
  for (const Bifurcation& b : r.bifurcations) folds += b.kind == BifurcationKind::kFold;
  state.counters["completed"] = r.status == ContinuationStatus::kCompleted ? 1 : 0;
  state.counters["folds"] = folds;
  state.counters["points"] = static_cast<double>(r.points.size());
  state.counters["periods_integrated"] = static_cast<double>(r.integrations);
  state.counters["steps"] = static_cast<double>(r.steps);
}
BENCHMARK(BM_ContinuationBacklash)->Unit(benchmark::kMillisecond);

DynamicRequest PaperStage() {
  DynamicRequest r;
  r.scene = epicycle::transmission::ReadScene(std::string(EPICYCLE_SCENES_DIR) + "/paper_stage.toml");
  r.tables.cache_directory = epicycle::transmission::DefaultCacheDirectory();
  return r;
}

// The time-integration sweep's speeds, K_γ and TE amplitude [µrad], kept for the branch's check.
std::vector<double> sweep_rpm, sweep_k_gamma, sweep_te;

void BM_PaperStageTimeSweep(benchmark::State& state) {
  SpeedSweepRequest request;
  request.run = PaperStage();
  request.sun_speeds_rpm = SpeedGrid(500, 12000, 116);
  request.window_cycles = 3;
  request.threads = 1;
  SpeedSweepSink sink;
  SpeedSweepRecord r;
  for (auto _ : state) {
    r = RunSpeedSweep(request, sink);
    benchmark::DoNotOptimize(r.speeds.data());
  }
  sweep_rpm.clear();
  sweep_k_gamma.clear();
  sweep_te.clear();
  for (const SpeedResult& s : r.speeds) {
    sweep_rpm.push_back(s.sun_speed_rpm);
    sweep_k_gamma.push_back(s.k_gamma);
    sweep_te.push_back(s.te_amplitude * 1e6);
  }
  state.counters["speeds"] = static_cast<double>(r.speeds.size());
  state.counters["failed"] = r.failed();
}
BENCHMARK(BM_PaperStageTimeSweep)
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->Repetitions(3)
    ->MeasureProcessCPUTime()
    ->ReportAggregatesOnly(false);

// y(x) of the branch (x increasing along it here: no fold) at x0, linearly.
double Interpolate(const std::vector<double>& x, const std::vector<double>& y, double x0) {
  const auto it = std::lower_bound(x.begin(), x.end(), x0);
  if (it == x.begin()) return y.front();
  if (it == x.end()) return y.back();
  const std::size_t k = static_cast<std::size_t>(it - x.begin());
  const double w = (x0 - x[k - 1]) / (x[k] - x[k - 1]);
  return y[k - 1] + w * (y[k] - y[k - 1]);
}

void BM_PaperStageHarmonicBalance(benchmark::State& state) {
  BranchRequest request;
  request.run = PaperStage();
  request.parameter = StagePeriodicSystem::kSunSpeed;
  request.start = 500;
  request.end = 12000;
  request.steps = 20;
  request.method = PeriodicMethod::kHarmonicBalance;
  request.harmonics = static_cast<int>(state.range(0));
  BranchSink sink;
  BranchRecord r;
  for (auto _ : state) {
    r = RunBranch(request, sink);
    benchmark::DoNotOptimize(r.branch.points.data());
  }
  std::vector<double> rpm, kg, te;
  int unstable = 0;
  for (const StageBranchPoint& p : r.branch.points) {
    rpm.push_back(p.sun_speed_rpm);
    kg.push_back(p.k_gamma);
    te.push_back(p.te_amplitude * 1e6);
    unstable += p.stability == Stability::kUnstable;
  }
  state.counters["completed"] = r.ok() ? 1 : 0;
  state.counters["points"] = static_cast<double>(rpm.size());
  state.counters["unstable"] = unstable;
  state.counters["bifurcations"] = static_cast<double>(r.branch.bifurcations.size());
  state.counters["evaluations"] = static_cast<double>(r.branch.steps);
  double spectral = 0;
  for (const StageBranchPoint& p : r.branch.points) spectral = std::max(spectral, p.spectral_radius);
  state.counters["max_spectral_radius"] = spectral;
  // Against the time-integration sweep (when it ran first): the largest and median differences.
  std::vector<double> dk, dt;
  for (std::size_t k = 0; k < sweep_rpm.size() && !rpm.empty(); ++k) {
    if (sweep_rpm[k] < rpm.front() || sweep_rpm[k] > rpm.back()) continue;
    dk.push_back(std::abs(Interpolate(rpm, kg, sweep_rpm[k]) - sweep_k_gamma[k]));
    dt.push_back(std::abs(Interpolate(rpm, te, sweep_rpm[k]) - sweep_te[k]) / sweep_te[k]);
  }
  if (!dk.empty()) {
    auto median = [](std::vector<double> v) {
      std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
      return v[v.size() / 2];
    };
    state.counters["K_gamma_max_diff"] = *std::max_element(dk.begin(), dk.end());
    state.counters["K_gamma_median_diff"] = median(dk);
    state.counters["te_amplitude_max_rel_diff"] = *std::max_element(dt.begin(), dt.end());
    state.counters["te_amplitude_median_rel_diff"] = median(dt);
  }
}
BENCHMARK(BM_PaperStageHarmonicBalance)
    ->Arg(12)
    ->Arg(16)
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->Repetitions(3)
    ->MeasureProcessCPUTime();

}  // namespace

BENCHMARK_MAIN();
