#include "epicycle/transmission/validity.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "epicycle/solvers/local_term.hpp"

namespace epicycle::transmission {

namespace {

std::string Num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string Deg(double rad) { return Num(rad * 180.0 / geometry::kPi); }

// The transmission-error warning: `worst` and `limit` are rotations [rad] of the gear named in
// `along` (a tenth of its module along its line of action).
std::string TransmissionErrorWarning(int count, double worst, double limit, const char* along) {
  return "transmission error |TE| = " + Num(worst * 1e6) + " urad (" + Deg(worst) + " deg) at " +
         std::to_string(count) + " position(s) exceeds a tenth of the module along " + along +
         " line of action (" + Num(limit * 1e6) +
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

std::vector<std::string> QuasiStaticWarnings(const geometry::Stage& stage,
                                             const std::vector<PositionResult>& results) {
  std::vector<std::string> out;
  const int n = stage.planets();
  // Negative shares, per planet.
  for (int i = 0; i < n; ++i) {
    int count = 0;
    double worst = 0, at = 0;
    for (const PositionResult& r : results) {
      if (!r.converged || i >= static_cast<int>(r.load_sharing.size())) continue;
      if (r.load_sharing[i] < 0) {
        ++count;
        if (r.load_sharing[i] < worst) {
          worst = r.load_sharing[i];
          at = r.carrier_angle;
        }
      }
    }
    if (count > 0) {
      out.push_back("planet " + std::to_string(i + 1) + ": load-sharing ratio LSR = " + Num(worst) +
                    " < 0 at carrier " + Deg(at) + " deg (" + std::to_string(count) +
                    " position(s)): the planet is jammed, driven through its coast flanks (its "
                    "errors exceed the backlash); outside the model's validity");
    }
  }
  // Transmission error against a tenth of the module along the sun's line of action.
  const double limit = 0.1 * stage.sun().spec().module / stage.sun().base_radius();
  {
    int count = 0;
    double worst = 0;
    for (const PositionResult& r : results) {
      if (!r.converged || !std::isfinite(r.transmission_error)) continue;
      if (std::abs(r.transmission_error) > limit) {
        ++count;
        worst = std::max(worst, std::abs(r.transmission_error));
      }
    }
    if (count > 0) out.push_back(TransmissionErrorWarning(count, worst, limit, "the sun's"));
  }
  // Contact forces against the local term's validity limit.
  {
    int count = 0;
    double worst_ratio = 0, worst_force = 0;
    for (const PositionResult& r : results) {
      if (!r.converged) continue;
      const auto& local = r.problem.data.local;
      for (Eigen::Index j = 0; j < r.solution.force.size(); ++j) {
        const auto k = static_cast<std::size_t>(j);
        if (k >= local.size() || !local[k].enabled) continue;
        const double f = r.solution.force(j), lim = solvers::ValidityLimitForce(local[k]);
        if (f > lim && lim > 0) {
          ++count;
          if (f / lim > worst_ratio) {
            worst_ratio = f / lim;
            worst_force = f;
          }
        }
      }
    }
    if (count > 0) out.push_back(LocalTermWarning(count, worst_force, worst_ratio, "contact(s)"));
  }
  return out;
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
  if (te_count > 0) out.push_back(TransmissionErrorWarning(te_count, te_worst, limit, "gear 1's"));
  if (local_count > 0)
    out.push_back(LocalTermWarning(local_count, 0.0, ratio_worst, "position(s)"));
  return out;
}

}  // namespace epicycle::transmission
