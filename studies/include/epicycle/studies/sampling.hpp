// The random values of a study's cases. Counter-based: case k's values depend only on (seed, k)
// and the variable's index, never on the order cases are computed in, so that a study gives the
// same rows whatever the number of threads or MPI ranks, and a restarted study the same rows as
// an uninterrupted one.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "epicycle/studies/study.hpp"
#include "epicycle/transmission/scene.hpp"

namespace epicycle::studies {

/// ISO 1328-1:2013 (cylindrical gears, flank tolerance classification), the single-pitch
/// independent cumulative pitch tolerance of flank tolerance class A,
///
///   F_pT = (0.002 d + 0.55 √d + 0.7 m_n + 12) · (√2)^(A − 5)   [µm; d, m_n in mm],
///
/// and the radial run-out tolerance of its informative annex, F_rT = 0.9 F_pT. The standard's
/// rounding of tabulated values is not applied. Valid for classes A = 1…11,
/// 0.5 mm ≤ m_n ≤ 70 mm and 5 mm ≤ d ≤ 15 000 mm (d the reference diameter).
/// @return F_rT [m]. @throws std::invalid_argument outside that range (naming the value).
double Iso1328RunoutTolerance(int grade, double reference_diameter, double module);
/// Whether (grade, d, m_n) lies in the range above.
bool Iso1328Applies(int grade, double reference_diameter, double module);

/// A random stream of one variable of one case: std::mt19937_64 (its output sequence is fixed by
/// the C++ standard) seeded with SplitMix64 of (seed, case, variable); uniform and normal
/// variates made here (53-bit uniform, Box–Muller), not by std::*_distribution whose output is
/// implementation-defined.
class CaseStream {
 public:
  CaseStream(std::uint64_t seed, long case_id, int variable);
  double Uniform();  ///< in [0, 1) [-]
  double Normal();   ///< standard normal [-]

 private:
  std::mt19937_64 engine_;
};

/// The sampled values of case k in file units (the Columns() of the study: µm, deg, N·m): with
/// the Monte-Carlo design DrawValues(study, k), with the Sobol design SobolCaseValues.
/// @throws std::invalid_argument for k outside [0, Cases()).
std::vector<double> SampleCase(const StudySpec& study, long case_id);

/// The values of random stream s in file units: variable j from CaseStream(seed, s, j), a grid
/// variable at grid point s mod GridPoints() (the first grid variable varies fastest).
std::vector<double> DrawValues(const StudySpec& study, long stream);

/// The base scene with case k's values applied (they replace the scene's). Input that the
/// geometry rejects (a run-out beyond its limits) surfaces when the case's stage is built.
/// @throws std::invalid_argument for a torque that changes sign from the scene's (the loaded
///         flanks are the scene's).
transmission::Scene CaseScene(const StudySpec& study, const std::vector<double>& values);

}  // namespace epicycle::studies
