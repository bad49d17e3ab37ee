// The summary of a study's rows (docs/studies.md): K_γ's distribution with confidence intervals,
// the same for the sweep-mean load factor (and each gear's root stresses), and the rank correlation
// of K_γ with every sampled variable (which tolerance matters).
#pragma once

#include <string>
#include <vector>

#include <optional>

#include "epicycle/studies/runner.hpp"
#include "epicycle/studies/sobol.hpp"
#include "epicycle/studies/statistics.hpp"

namespace epicycle::studies {

/// One gear's root stresses over a study's ok cases (each case's largest over its sweep, the
/// rows' sigma_*_<gear>_MPa) [MPa].
struct GearStressStatistics {
  std::string gear;
  SampleSummary tension;      ///< largest tension σ_t ≥ 0
  SampleSummary compression;  ///< magnitude |σ_c| of the most negative compression
  SampleSummary range;        ///< largest range max − min at one fillet point
  /// With StudySpec::Rated (else count 0): each case's S_F and S_H of this gear from its own
  /// stresses [-] (the rows' S_F_<gear>, S_H_<gear>), percentiles at kSafetyPercentiles.
  SampleSummary s_f, s_h;
};

/// One mesh's face loads over a study's ok cases (the rows' K_Hbeta_<mesh>,
/// K_gamma_K_Hbeta_<mesh>) [-].
struct MeshFaceStatistics {
  std::string mesh;
  SampleSummary k_h_beta;          ///< each case's largest K_Hβ over its sweep
  SampleSummary k_gamma_k_h_beta;  ///< each case's largest L_i·K_Hβ at one position
};

/// One result column's values over the ok rows.
struct ColumnStatistics {
  std::string column;  ///< its name in the rows file (with its unit)
  SampleSummary values;
};

struct StudySummary {
  long cases = 0;   ///< rows [-]
  long failed = 0;  ///< rows not completed (left out of the statistics) [-]
  /// The failed rows by how they ended (CaseRow::status): contact failure, geometry, bad sampled
  /// value [-].
  long failed_contact = 0, failed_geometry = 0, failed_bad_sampled_value = 0;
  SampleSummary k_gamma;             ///< K_γ over the ok rows
  SampleSummary k_gamma_mean;        ///< max_i mean L_i over the ok rows
  SampleSummary te_peak_to_peak;     ///< [µrad]
  SampleSummary sun_orbit;           ///< [µm]
  std::vector<std::string> columns;  ///< the sampled-value columns
  std::vector<double> spearman;      ///< ρ_s(K_γ, column) per column (NaN: constant column)
  Histogram k_gamma_histogram;
  std::vector<double> k_gamma_sorted;  ///< the empirical CDF's steps: F(x_(i)) = i/n
  /// P(K_γ > x) over the ok rows with its interval, per x of StudySpec::k_gamma_limits.
  std::vector<Exceedance> k_gamma_exceedance;
  /// Per gear of StudySpec::StressGears (none without stresses).
  std::vector<GearStressStatistics> root_stress;
  /// Per mesh of StudySpec::FaceMeshes (none without slices of the face width).
  std::vector<MeshFaceStatistics> face_width;
  /// Per column of StudySpec::HelicalColumns (none for a spur stage), in that order: its values
  /// over the ok rows [the column's unit].
  std::vector<ColumnStatistics> helical;
  /// With the Sobol design: the indices of every output over all rows, their bootstrap seeded by
  /// the study's seed (reproducible intervals) at the summary's level.
  std::optional<SobolSummary> sobol;
};

/// Percentile levels of the summaries: 0.50, 0.95, 0.99, 0.999.
inline const std::vector<double> kStudyPercentiles{0.5, 0.95, 0.99, 0.999};
/// Of the safety factors, whose tail that matters is the low one: 0.50, 0.05, 0.01, 0.001.
inline const std::vector<double> kSafetyPercentiles{0.5, 0.05, 0.01, 0.001};

/// With the Sobol design (StudySpec::design) the distributions and correlations come from the
/// 2N independent cases of A and B only (cases and failed count every row).
/// @param level confidence level of every interval [-]
StudySummary SummariseStudy(const StudySpec& study, const std::vector<CaseRow>& rows,
                            double level = 0.95);

}  // namespace epicycle::studies
