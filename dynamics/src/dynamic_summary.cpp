#include "epicycle/dynamics/dynamic_summary.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace epicycle::dynamics {

void DynamicAccumulator::Add(const DynamicSample& x) {
  if (samples_ == 0) {
    const std::size_t n = x.load_sharing.size();
    lsr_.assign(n, {});
    root_stress_.emplace(transmission::BodyNames(transmission::PlanetBody(static_cast<int>(n))));
  } else if (x.load_sharing.size() != lsr_.size()) {
    throw std::invalid_argument("DynamicAccumulator: a step with " +
                                std::to_string(x.load_sharing.size()) +
                                " load-sharing ratios after steps with " +
                                std::to_string(lsr_.size()));
  }
  ++samples_;
  root_stress_->Add(x.fillet_stress, x.root_stress, x.time);
  for (std::size_t i = 0; i < lsr_.size(); ++i) lsr_[i].Add(x.load_sharing[i]);
  k_gamma_.Add(x.k_gamma);
  te_.Add(x.transmission_error);
  orbit_.Add(x.sun_centre.norm());
  if (x.evaluation.total_force.size() > 0) pair_force_.Add(x.evaluation.total_force.maxCoeff());
  if (!x.face_loads.empty()) {
    std::vector<double> factors;
    for (double lsr : x.load_sharing) factors.push_back(static_cast<double>(lsr_.size()) * lsr);
    faces_.Add(x.face_loads, factors, x.carrier_angle);
  }
  if (!x.helical.planets.empty()) {
    transmission::AddHelicalLoads(x.helical, 1.0, &helical_sum_);
    ++helical_steps_;
  }
}

DynamicSummary DynamicAccumulator::Result() const {
  DynamicSummary s;
  s.samples = samples_;
  for (const transmission::Accumulator& a : lsr_) {
    s.lsr_min.push_back(a.min());
    s.lsr_max.push_back(a.max());
    s.lsr_mean.push_back(a.mean());
  }
  s.k_gamma = k_gamma_.max();
  s.te_min = te_.min();
  s.te_max = te_.max();
  s.orbit_radius = orbit_.max();
  s.orbit_mean_radius = orbit_.mean();
  // No step: NaN; steps without a contact force: 0.
  s.max_pair_force = samples_ == 0        ? std::numeric_limits<double>::quiet_NaN()
                     : pair_force_.empty() ? 0.0
                                           : std::max(0.0, pair_force_.max());
  if (root_stress_) s.root_stress = root_stress_->Result();
  s.face_width = faces_.Result();
  if (helical_steps_ > 0)
    transmission::AddHelicalLoads(helical_sum_, 1.0 / helical_steps_, &s.helical_mean);
  return s;
}

DynamicSummary Summarise(const std::vector<DynamicSample>& samples) {
  DynamicAccumulator a;
  for (const DynamicSample& x : samples) a.Add(x);
  return a.Result();
}

DynamicWarningTally::DynamicWarningTally(const geometry::Stage& stage)
    : tally_(stage, "output step(s)") {}

void DynamicWarningTally::Add(const DynamicSample& x) {
  if (x.evaluation.ok)
    tally_.Add(x.carrier_angle, x.load_sharing, x.transmission_error, x.evaluation.terms.local,
               x.evaluation.force);
}

std::vector<std::string> DynamicWarnings(const geometry::Stage& stage,
                                         const std::vector<DynamicSample>& samples) {
  DynamicWarningTally tally(stage);
  for (const DynamicSample& x : samples) tally.Add(x);
  return tally.Messages();
}

}  // namespace epicycle::dynamics
