#include "epicycle/solvers/performance_profile.hpp"

#include <algorithm>
#include <map>

namespace epicycle::solvers {

double PerformanceProfile::Fraction(double tau, int problems) const {
  if (problems <= 0) return 0.0;
  const auto within = std::upper_bound(ratios.begin(), ratios.end(), tau) - ratios.begin();
  return static_cast<double>(within) / static_cast<double>(problems);
}

std::vector<PerformanceProfile> DolanMoreProfile(const std::vector<ProfileRun>& runs,
                                                 const std::vector<std::string>& backends) {
  std::map<std::string, double> best;
  for (const ProfileRun& r : runs)
    if (r.solved) {
      const auto it = best.find(r.problem);
      best[r.problem] = it != best.end() ? std::min(it->second, r.seconds) : r.seconds;
    }
  std::vector<PerformanceProfile> profiles;
  for (const std::string& b : backends) {
    PerformanceProfile p;
    p.backend = b;
    for (const ProfileRun& r : runs)
      if (r.backend == b && r.solved) p.ratios.push_back(r.seconds / best[r.problem]);
    std::sort(p.ratios.begin(), p.ratios.end());
    profiles.push_back(std::move(p));
  }
  return profiles;
}

}  // namespace epicycle::solvers
