#include "epicycle/transmission/sweep_summary.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "epicycle/transmission/statistics.hpp"

namespace epicycle::transmission {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}  // namespace

double SweepSummary::LsrMin() const {
  double v = kNaN;
  for (double x : lsr_min) v = std::isnan(v) ? x : std::min(v, x);
  return v;
}

double SweepSummary::LsrMax() const {
  double v = kNaN;
  for (double x : lsr_max) v = std::isnan(v) ? x : std::max(v, x);
  return v;
}

SweepSummary SummariseSweep(const std::vector<PositionResult>& results, int planets) {
  if (planets < 1)
    throw std::invalid_argument("SummariseSweep: planets = " + std::to_string(planets) +
                                ": must be >= 1");
  const auto n = static_cast<std::size_t>(planets);
  std::vector<Accumulator> lsr(n);
  Accumulator te, displacement, k_gamma, efficiency, friction_power, iterations;
  bool friction = false;
  for (const PositionResult& r : results) {
    friction = friction || r.friction;
    if (!r.converged) continue;
    if (r.load_sharing.size() != n)
      throw std::invalid_argument(
          "SummariseSweep: a converged position has " + std::to_string(r.load_sharing.size()) +
          " load-sharing ratios for " + std::to_string(planets) + " planets");
    for (std::size_t i = 0; i < n; ++i) lsr[i].Add(r.load_sharing[i]);
    te.Add(r.transmission_error);
    displacement.Add(r.sun_displacement.norm());
    k_gamma.Add(MeshLoadFactor(r));
    if (r.friction) {
      efficiency.Add(r.Efficiency());
      friction_power.Add(r.friction_power);
      iterations.Add(r.geometric_iterations);
    }
  }
  SweepSummary s;
  s.positions = static_cast<int>(results.size());
  s.converged = static_cast<int>(te.count());
  // No converged position: NaN everywhere (the accumulators' empty rule).
  for (std::size_t i = 0; i < n; ++i) {
    s.lsr_mean.push_back(lsr[i].mean());
    s.lsr_min.push_back(lsr[i].min());
    s.lsr_max.push_back(lsr[i].max());
  }
  s.transmission_error_min = te.min();
  s.transmission_error_max = te.max();
  s.sun_displacement_max = displacement.max();
  s.k_gamma = k_gamma.empty() ? kNaN : std::max(0.0, k_gamma.max());
  s.k_gamma_mean = kNaN;
  if (s.converged > 0) {
    s.k_gamma_mean = 0.0;
    for (double m : s.lsr_mean)
      s.k_gamma_mean = std::max(s.k_gamma_mean, static_cast<double>(planets) * m);
  }
  // Root stresses, when the positions carry them.
  // Root stresses and contact pressures, when the positions carry stresses.
  RootStressTracker root_stress(BodyNames(PlanetBody(planets)));
  ContactPressureTracker pressure;
  for (const PositionResult& r : results) {
    if (!r.converged || r.fillet_stress.empty()) continue;
    root_stress.Add(r.fillet_stress, r.carrier_angle);
    pressure.Add(r.problem.contacts, r.problem.data.local, r.solution.force, r.carrier_angle);
  }
  s.root_stress = root_stress.Result();
  s.contact_pressure = pressure.Result();
  s.friction = friction;
  s.efficiency_mean = efficiency.mean();
  s.efficiency_min = efficiency.min();
  s.friction_power_mean = friction_power.mean();
  s.friction_iterations_mean = iterations.mean();
  return s;
}

}  // namespace epicycle::transmission
