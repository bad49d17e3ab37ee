#include "epicycle/dynamics/summary.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "epicycle/transmission/statistics.hpp"
#include "epicycle/transmission/validity.hpp"

namespace epicycle::dynamics {

DynamicSummary Summarise(const std::vector<DynamicSample>& samples) {
  DynamicSummary s;
  s.samples = static_cast<int>(samples.size());
  const std::size_t n = samples.empty() ? 0 : samples.front().load_sharing.size();
  std::vector<transmission::Accumulator> lsr(n);
  transmission::Accumulator te, orbit, k_gamma, pair_force;
  transmission::RootStressTracker root_stress(
      transmission::BodyNames(transmission::PlanetBody(static_cast<int>(n))));
  for (const DynamicSample& x : samples) {
    root_stress.Add(x.fillet_stress, x.time);
    for (std::size_t i = 0; i < n; ++i) lsr[i].Add(x.load_sharing[i]);
    k_gamma.Add(x.k_gamma);
    te.Add(x.transmission_error);
    orbit.Add(x.sun_centre.norm());
    if (x.evaluation.total_force.size() > 0) pair_force.Add(x.evaluation.total_force.maxCoeff());
  }
  for (std::size_t i = 0; i < n; ++i) {
    s.lsr_min.push_back(lsr[i].min());
    s.lsr_max.push_back(lsr[i].max());
    s.lsr_mean.push_back(lsr[i].mean());
  }
  s.k_gamma = k_gamma.max();
  s.te_min = te.min();
  s.te_max = te.max();
  s.orbit_radius = orbit.max();
  s.orbit_mean_radius = orbit.mean();
  // No step: NaN; steps without a contact force: 0.
  s.max_pair_force = samples.empty()      ? std::numeric_limits<double>::quiet_NaN()
                     : pair_force.empty() ? 0.0
                                          : std::max(0.0, pair_force.max());
  s.root_stress = root_stress.Result();
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
