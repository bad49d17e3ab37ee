#include "epicycle/dynamics/summary.hpp"

#include <algorithm>
#include <cmath>

#include "epicycle/transmission/validity.hpp"

namespace epicycle::dynamics {

DynamicSummary Summarise(const std::vector<DynamicSample>& samples) {
  DynamicSummary s;
  s.samples = static_cast<int>(samples.size());
  if (samples.empty()) return s;
  const std::size_t n = samples.front().load_sharing.size();
  s.lsr_min.assign(n, INFINITY);
  s.lsr_max.assign(n, -INFINITY);
  s.lsr_mean.assign(n, 0.0);
  s.te_min = INFINITY;
  s.te_max = -INFINITY;
  for (const DynamicSample& x : samples) {
    for (std::size_t i = 0; i < n; ++i) {
      s.lsr_min[i] = std::min(s.lsr_min[i], x.load_sharing[i]);
      s.lsr_max[i] = std::max(s.lsr_max[i], x.load_sharing[i]);
      s.lsr_mean[i] += x.load_sharing[i] / static_cast<double>(samples.size());
      s.k_gamma = std::max(s.k_gamma, static_cast<double>(n) * x.load_sharing[i]);
    }
    s.te_min = std::min(s.te_min, x.transmission_error);
    s.te_max = std::max(s.te_max, x.transmission_error);
    const double r = x.sun_centre.norm();
    s.orbit_radius = std::max(s.orbit_radius, r);
    s.orbit_mean_radius += r / static_cast<double>(samples.size());
    if (x.evaluation.total_force.size() > 0)
      s.max_pair_force = std::max(s.max_pair_force, x.evaluation.total_force.maxCoeff());
  }
  return s;
}

std::vector<std::string> DynamicWarnings(const geometry::Stage& stage,
                                         const std::vector<DynamicSample>& samples) {
  transmission::ValidityTally tally(stage, "output step(s)");
  for (const DynamicSample& x : samples)
    if (x.evaluation.ok)
      tally.Add(x.carrier_angle, x.load_sharing, x.transmission_error, x.evaluation.terms.local,
                x.evaluation.force);
  return tally.Messages();
}

}  // namespace epicycle::dynamics
