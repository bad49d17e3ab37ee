// The summary of a tolerance study (docs/studies.md) for its JSON file and the console: each
// statistic's distribution with its confidence intervals, and with stresses each gear's root
// stresses over the cases.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "epicycle/studies/shards.hpp"
#include "epicycle/studies/study_run.hpp"
#include "epicycle/studies/study_summary.hpp"

namespace epicycle::report {

/// One line: "P(K_gamma > x) = p [lo, hi] (k of n cases)".
std::string ExceedanceText(const studies::Exceedance& e);
/// A study's summary on the terminal (a run's and a merge's): the cases, K_γ and the outputs'
/// statistics, root stresses, K_γ's exceedances, the Spearman correlations and the Sobol indices.
std::string StudySummaryText(const studies::StudySpec& study, const studies::StudySummary& s);

/// Two lines and one per percentile: "NAME mean m [lo, hi], std s, max x UNIT", then
/// "P<p> value [lo, hi]" ("-" where a statistic has no value).
std::string SampleSummaryText(const std::string& name, const studies::SampleSummary& s,
                              const std::string& unit);

/// One line per gear: tension, compression magnitude and range [MPa], each its mean and P95 with
/// the P95's interval ("" without stresses).
std::string StudyRootStressText(const std::vector<studies::GearStressStatistics>& gears);

/// The rows file's first line (without "# "): the provenance (ProvenanceCsvLine) and
/// "; study <study_path>".
std::string StudyComment(const nlohmann::json& provenance, const std::string& study_path);

/// `base`_summary.json (the record's one serialisation, RecordJson, with "provenance"),
/// `base`_kgamma_hist.svg, `base`_kgamma_cdf.svg and with Sobol indices `base`_sobol.svg: the
/// files a study run writes beside its rows. @throws std::runtime_error if one cannot be written.
void WriteStudySummaryFiles(const std::string& base, const std::string& study_name,
                            const studies::StudyRecord& record, const nlohmann::json& provenance);

/// What MergeStudy did.
struct MergedStudy {
  studies::StudySpec study;            ///< the study of the parts (its file as read)
  std::string study_path;              ///< that file
  std::vector<std::string> parts;      ///< the part files joined
  std::vector<studies::CaseRow> rows;  ///< every case, sorted by id
  studies::StudyRecord record;         ///< the summary of every case (computed_seconds 0)
};
/// Joins the parts of one study (studies::FindParts of `paths`: part files or folders of them)
/// into `out_dir`/study_rows.csv, _summary.json, _kgamma_hist.svg and _kgamma_cdf.svg, the files
/// a single run of the study writes (its rows in case order, as one thread writes them;
/// computed_seconds 0, as a run that resumes every row). The study file is `study_path`, or
/// (empty) the one the first part names; its hash must be the parts'.
/// @throws std::invalid_argument as studies::MergeParts, or for a study file that is not the
///         parts'; std::runtime_error if a file cannot be written.
MergedStudy MergeStudy(const std::vector<std::string>& paths, const std::string& out_dir,
                       const std::string& study_path = {});

}  // namespace epicycle::report
