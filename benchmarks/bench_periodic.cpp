// The periodic solver (docs/periodic.md) on the gear pair with backlash of Kahraman & Singh
// (BacklashOscillator: ζ = 0.05, F_m = 0.1, F_a = 0.05): one shooting solve at Ω = 0.6 on the
// large (separating) orbit from a cold guess, and the continuation over Ω from 1.5 to 0.4 with both
// folds, at rtol 1e-8. Checks after the loop: the shooting converged and its residual, the
// continuation's folds and point count.
#include <benchmark/benchmark.h>

#include <cmath>

#include "epicycle/dynamics/periodic.hpp"
#include "epicycle/dynamics/periodic_systems.hpp"

namespace {

using namespace epicycle::dynamics;

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

}  // namespace

BENCHMARK_MAIN();
