#include "epicycle/transmission/validity.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "epicycle/io/number_format.hpp"
#include "epicycle/solvers/local_term.hpp"

namespace epicycle::transmission {

namespace {

using io::Num;

// The transmission-error warning: `worst` and `limit` are rotations [rad] of the gear named in
// `along` (a tenth of its module along its line of action).
std::string TransmissionErrorWarning(int count, double worst, double limit, const char* along,
                                     const std::string& counted) {
  return "transmission error |TE| = " + Num(worst * 1e6) + " urad (" + Num(geometry::Deg(worst)) +
         " deg) at " + std::to_string(count) + " " + counted +
         " exceeds a tenth of the module along " + along + " line of action (" + Num(limit * 1e6) +
         " urad): rotations that large break the small-displacement assumption";
}

// The local-term warning: the worst force and its ratio to ValidityLimitForce, over `count`
// contacts (or positions) past the limit.
std::string LocalTermWarning(int count, double worst_force, double worst_ratio,
                             const char* counted) {
  return "contact force " +
         (worst_force > 0 ? Num(worst_force) + " N is " : std::string("up to ")) +
         Num(worst_ratio) +
         " times the local term's validity limit (Hertz half-width beyond the joining depth) on " +
         std::to_string(count) + " " + counted +
         ": loads past the local term's validity (reduce the torque or widen the face)";
}

}  // namespace

ValidityTally::ValidityTally(const geometry::Stage& stage, std::string counted)
    : planets_(stage.planets()),
      te_limit_(0.1 * stage.sun().spec().module / stage.sun().base_radius()),
      counted_(std::move(counted)),
      lsr_count_(static_cast<std::size_t>(planets_), 0),
      lsr_worst_(static_cast<std::size_t>(planets_), 0.0),
      lsr_at_(static_cast<std::size_t>(planets_), 0.0) {}

void ValidityTally::Add(double carrier_angle, const std::vector<double>& load_sharing,
                        double transmission_error,
                        const std::vector<solvers::LocalTermParameters>& local,
                        const Eigen::VectorXd& force) {
  // Negative shares, per planet.
  const int n = std::min(planets_, static_cast<int>(load_sharing.size()));
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (!(load_sharing[k] < 0)) continue;
    ++lsr_count_[k];
    if (load_sharing[k] < lsr_worst_[k]) {
      lsr_worst_[k] = load_sharing[k];
      lsr_at_[k] = carrier_angle;
    }
  }
  // The sun out of contact with every planet: no share carries anything.
  if (n > 0 && std::all_of(load_sharing.begin(), load_sharing.begin() + n,
                           [](double l) { return l == 0; })) {
    if (free_count_++ == 0) free_at_ = carrier_angle;
  }
  // Transmission error against a tenth of the module along the sun's line of action.
  if (std::isfinite(transmission_error) && std::abs(transmission_error) > te_limit_) {
    ++te_count_;
    te_worst_ = std::max(te_worst_, std::abs(transmission_error));
  }
  // Contact forces against the local term's validity limit.
  for (Eigen::Index j = 0; j < force.size(); ++j) {
    const auto k = static_cast<std::size_t>(j);
    if (k >= local.size() || !local[k].enabled) continue;
    const double f = force(j), lim = solvers::ValidityLimitForce(local[k]);
    if (f > lim && lim > 0) {
      ++local_count_;
      if (f / lim > local_worst_ratio_) {
        local_worst_ratio_ = f / lim;
        local_worst_force_ = f;
      }
    }
  }
}

void ValidityTally::Add(const PositionResult& r) {
  if (r.converged)
    Add(r.carrier_angle, r.load_sharing, r.transmission_error, r.problem.data.local,
        r.solution.force);
}

std::vector<std::string> ValidityTally::Messages() const {
  std::vector<std::string> out;
  for (int i = 0; i < planets_; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (lsr_count_[k] == 0) continue;
    out.push_back("planet " + std::to_string(i + 1) + ": load-sharing ratio LSR = " +
                  Num(lsr_worst_[k]) + " < 0 at carrier " + Num(geometry::Deg(lsr_at_[k])) +
                  " deg (" + std::to_string(lsr_count_[k]) + " " + counted_ +
                  "): the planet is jammed, driven through its coast flanks (its errors exceed "
                  "the backlash); outside the model's validity");
  }
  if (free_count_ > 0)
    out.push_back("the sun touches no planet at " + std::to_string(free_count_) + " " + counted_ +
                  " (the first at carrier " + Num(geometry::Deg(free_at_)) +
                  " deg): the teeth separate and strike again (rattle), the input torque being "
                  "small against the dynamic loads; the load-sharing ratios and K_gamma then "
                  "say nothing about how the planets share the load");
  if (te_count_ > 0)
    out.push_back(TransmissionErrorWarning(te_count_, te_worst_, te_limit_, "the sun's", counted_));
  if (local_count_ > 0)
    out.push_back(
        LocalTermWarning(local_count_, local_worst_force_, local_worst_ratio_, "contact(s)"));
  return out;
}

std::vector<std::string> QuasiStaticWarnings(const geometry::Stage& stage,
                                             const std::vector<PositionResult>& results) {
  ValidityTally tally(stage, "position(s)");
  for (const PositionResult& r : results) tally.Add(r);
  return tally.Messages();
}

std::vector<std::string> MeshStiffnessWarnings(const geometry::GearPair& pair,
                                               const MeshStiffnessResult& result) {
  std::vector<std::string> out;
  const double limit = 0.1 * pair.gear1().spec().module / pair.gear1().base_radius();
  int te_count = 0, local_count = 0;
  double te_worst = 0, ratio_worst = 0;
  for (const MeshSample& s : result.samples) {
    if (!s.converged) continue;
    if (std::isfinite(s.rotation) && std::abs(s.rotation) > limit) {
      ++te_count;
      te_worst = std::max(te_worst, std::abs(s.rotation));
    }
    if (s.local_validity_ratio > 1) {
      ++local_count;
      ratio_worst = std::max(ratio_worst, s.local_validity_ratio);
    }
  }
  if (te_count > 0)
    out.push_back(TransmissionErrorWarning(te_count, te_worst, limit, "gear 1's", "position(s)"));
  if (local_count > 0)
    out.push_back(LocalTermWarning(local_count, 0.0, ratio_worst, "position(s)"));
  return out;
}

}  // namespace epicycle::transmission
