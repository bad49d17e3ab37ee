// Variance-based sensitivity of a study's outputs to its random variables (docs/studies.md
// "Sensitivity: Sobol indices"): the Saltelli design, the first-order and total Sobol indices with
// bootstrap confidence intervals.
//
// With Y = f(X_1, …, X_d) and independent X_i, the first-order index S_i = V[E(Y | X_i)] / V(Y)
// is the share of V(Y) that X_i explains alone, the total index S_Ti = E[V(Y | X_~i)] / V(Y) its
// share with every interaction it takes part in; 0 ≤ S_i ≤ S_Ti ≤ 1 and Σ S_i ≤ 1 (= 1 for an
// additive f). The design (Saltelli et al. 2010, "Variance based sensitivity analysis of model
// output. Design and estimator for the total sensitivity index", Comput. Phys. Commun. 181,
// 259–270): two independent samples A and B of N rows, and for each variable i the matrix
// A_B^(i), A with variable i's values taken from B; N (d + 2) evaluations. A run-out is one
// variable of two values (amplitude and phase, drawn from one stream): they move together
// (the indices of the group).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "epicycle/studies/runner.hpp"
#include "epicycle/studies/study.hpp"

namespace epicycle::studies {

/// The smallest base sample N of a Sobol design (the study file's `samples`) [-].
inline constexpr long kSobolMinSamples = 10;

/// Where case k of a Sobol study sits in the design: case k = j (d + 2) + m, so that the cases
/// of row j are consecutive (a prefix of the cases holds whole rows).
struct SobolCase {
  long row = 0;    ///< j, the row of A and B, in [0, N) [-]
  int matrix = 0;  ///< m: 0 A, 1 B, 2 + i A_B^(i) [-]
};
SobolCase SobolCaseOf(const StudySpec& study, long case_id);

/// Case k's sampled values (file units, StudySpec::Columns()): row j of A is the Monte-Carlo draw
/// of stream 2j, row j of B that of stream 2j + 1 (DrawValues: the seeds of a Monte-Carlo study),
/// A_B^(i) row j that of A with variable i's column(s) from B's.
std::vector<double> SobolCaseValues(const StudySpec& study, long case_id);

/// The variables' names for the indices: "planet1.pin_tangential", "sun.runout" (amplitude and
/// phase), one per StudySpec::variables entry.
std::vector<std::string> SobolVariableNames(const StudySpec& study);

struct SobolOptions {
  int bootstrap = 1000;    ///< bootstrap resamples of the rows [-] (0: no intervals)
  double level = 0.95;     ///< confidence level of the intervals [-]
  std::uint64_t seed = 0;  ///< of the resampling stream (CaseStream(seed, −1, 0)) [-]
  void Validate() const;   ///< @throws std::invalid_argument naming the field, value and rule
};

/// One index: the estimate and its bootstrap interval.
struct SobolIndex {
  double value = 0;             ///< [-]
  double lower = 0, upper = 0;  ///< percentile bootstrap interval at SobolOptions::level [-]
  double standard_error = 0;    ///< standard deviation of the bootstrap replicates [-]
};

struct SobolEstimate {
  long rows = 0;        ///< rows j used: every one of its d + 2 outputs finite [-]
  double mean = 0;      ///< of the outputs of every used case (the centring) [output unit]
  double variance = 0;  ///< V(Y), sample variance of the 2·rows outputs of A and B [unit²]
  /// Per variable; NaN when V(Y) = 0 (a constant output has no shares).
  std::vector<SobolIndex> first, total;
  /// Σ_i S_i, its interval from the same resamples (≤ 1 in theory: the rest is interactions).
  SobolIndex sum_first;
};

/// The indices of one output from its values in the design's case order, y[j (d + 2) + m]
/// (SobolCase); a row with a non-finite value (a failed case) is left out whole. With the outputs
/// centred on their mean μ (y ← y − μ) and V(Y) from A and B:
///
///   S_i  = (1/N) Σ_j y_B,j (y_ABi,j − y_A,j) / V(Y)       (Saltelli et al. 2010, Table 2 (b))
///   S_Ti = (1/2N) Σ_j (y_A,j − y_ABi,j)² / V(Y)           (Jansen 1999; Saltelli 2010 (f))
///
/// Intervals: percentile bootstrap over the rows (each resample recomputes μ, V(Y) and the
/// indices; every output resampled alike for a given seed).
/// @throws std::invalid_argument if y.size() is not a multiple of d + 2, d < 1, or
///         options are invalid; fewer than 2 usable rows give NaN indices.
SobolEstimate EstimateSobol(const std::vector<double>& y, int d, const SobolOptions& options);

/// The indices of every output of a Sobol study.
struct SobolOutput {
  std::string name;  ///< the rows file's column: "K_gamma", "TE_pp_urad", "sigma_t_sun_MPa", ...
  SobolEstimate estimate;
};
struct SobolSummary {
  long base_samples = 0;               ///< N of the design [-]
  long complete_rows = 0;              ///< rows j with all d + 2 cases in the file and ok [-]
  int bootstrap = 0;                   ///< resamples [-]
  double level = 0;                    ///< of the intervals [-]
  std::vector<std::string> variables;  ///< SobolVariableNames
  /// The rows file's results in its order: K_gamma, K_gamma_mean, LSR_min, LSR_max, TE_pp_urad,
  /// sun_orbit_um, then with stresses the root stresses and safety factors.
  std::vector<SobolOutput> outputs;
};
/// @throws std::invalid_argument if the study's design is not Sobol.
SobolSummary SummariseSobol(const StudySpec& study, const std::vector<CaseRow>& rows,
                            const SobolOptions& options);

}  // namespace epicycle::studies
