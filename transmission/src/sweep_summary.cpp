#include "epicycle/transmission/sweep_summary.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

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
  SweepSummary s;
  s.positions = static_cast<int>(results.size());
  s.lsr_mean.assign(n, 0.0);
  s.lsr_min.assign(n, std::numeric_limits<double>::infinity());
  s.lsr_max.assign(n, -std::numeric_limits<double>::infinity());
  s.transmission_error_min = std::numeric_limits<double>::infinity();
  s.transmission_error_max = -std::numeric_limits<double>::infinity();
  for (const PositionResult& r : results) {
    if (!r.converged) continue;
    if (r.load_sharing.size() != n)
      throw std::invalid_argument(
          "SummariseSweep: a converged position has " + std::to_string(r.load_sharing.size()) +
          " load-sharing ratios for " + std::to_string(planets) + " planets");
    ++s.converged;
    for (std::size_t i = 0; i < n; ++i) {
      s.lsr_mean[i] += r.load_sharing[i];
      s.lsr_min[i] = std::min(s.lsr_min[i], r.load_sharing[i]);
      s.lsr_max[i] = std::max(s.lsr_max[i], r.load_sharing[i]);
    }
    s.transmission_error_min = std::min(s.transmission_error_min, r.transmission_error);
    s.transmission_error_max = std::max(s.transmission_error_max, r.transmission_error);
    s.sun_displacement_max = std::max(s.sun_displacement_max, r.sun_displacement.norm());
    s.k_gamma = std::max(s.k_gamma, MeshLoadFactor(r));
  }
  if (s.converged == 0) {
    // Nothing to summarise: NaN everywhere, so that no made-up number is reported.
    for (auto* v : {&s.lsr_mean, &s.lsr_min, &s.lsr_max}) v->assign(n, kNaN);
    s.k_gamma = s.k_gamma_mean = s.transmission_error_min = s.transmission_error_max =
        s.sun_displacement_max = kNaN;
    return s;
  }
  s.k_gamma_mean = 0.0;
  for (double& m : s.lsr_mean) {
    m /= s.converged;
    s.k_gamma_mean = std::max(s.k_gamma_mean, static_cast<double>(planets) * m);
  }
  return s;
}

}  // namespace epicycle::transmission
