// The Dolan–Moré performance profile of a set of solver runs (E. D. Dolan, J. J. Moré,
// "Benchmarking optimization software with performance profiles", Math. Program. 91 (2002)):
// for back end b and problem p with run time t_p,b, the ratio r_p,b = t_p,b / min_b' t_p,b'
// (the least time any back end solved p in); ρ_b(τ) = |{p : b solved p and r_p,b ≤ τ}| / n_p is
// the fraction of the n_p problems b solves within τ times the best time.
#pragma once

#include <string>
#include <vector>

namespace epicycle::solvers {

/// One (problem, back end) run of a comparison.
struct ProfileRun {
  std::string problem;  ///< the problem's name
  std::string backend;  ///< the back end's name
  double seconds = 0;   ///< run time t_p,b [s], > 0 where solved
  bool solved = false;  ///< converged (only solved runs enter the profile)
};

/// One back end's profile: its ratios r_p,b ≥ 1 over the problems it solved, ascending.
struct PerformanceProfile {
  std::string backend;
  std::vector<double> ratios;  ///< r_p,b [-], ascending
  /// ρ_b(τ) for `problems` problems in all [-].
  double Fraction(double tau, int problems) const;
};

/// The profile of each of `backends` (in that order) over `runs`; a problem no back end solved
/// has no best time and enters no profile.
std::vector<PerformanceProfile> DolanMoreProfile(const std::vector<ProfileRun>& runs,
                                                 const std::vector<std::string>& backends);

}  // namespace epicycle::solvers
