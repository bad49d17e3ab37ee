// The summary of a tolerance study (docs/studies.md) for its JSON file and the console: each
// statistic's distribution with its confidence intervals, and with stresses each gear's root
// stresses over the cases.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "epicycle/studies/study_summary.hpp"

namespace epicycle::report {

/// "count", "mean", "mean_ci", "std", "min", "max", "confidence_level" and "percentiles" (each
/// "p", "value", "ci"); null where a statistic has no value (JSON has no NaN).
nlohmann::json SampleSummaryJson(const studies::SampleSummary& s);

/// Two lines and one per percentile: "NAME mean m [lo, hi], std s, max x UNIT", then
/// "P<p> value [lo, hi]" ("-" where a statistic has no value).
std::string SampleSummaryText(const std::string& name, const studies::SampleSummary& s,
                              const std::string& unit);

/// Per gear its "tension_MPa", "compression_magnitude_MPa" and "largest_range_MPa"
/// (SampleSummaryJson of each case's largest over its sweep).
nlohmann::json StudyRootStressJson(const std::vector<studies::GearStressStatistics>& gears);

/// One line per gear: tension, compression magnitude and range [MPa], each its mean and P95 with
/// the P95's interval ("" without stresses).
std::string StudyRootStressText(const std::vector<studies::GearStressStatistics>& gears);

}  // namespace epicycle::report
