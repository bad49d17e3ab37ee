// The Sobol indices of a study (studies/sobol.hpp, docs/studies.md "Sensitivity: Sobol indices")
// for its JSON summary, the console and a bar plot.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "epicycle/report/svg_plot.hpp"
#include "epicycle/studies/sobol.hpp"

namespace epicycle::report {

/// {"design": ..., "base_samples_N", "complete_rows", "bootstrap_resamples", "confidence_level",
/// "variables": [...], "outputs": {NAME: {"rows", "mean", "variance", "first_order": [{"variable",
/// "value", "ci", "standard_error"}...], "total": [...], "sum_first_order": {"value", "ci",
/// "standard_error"}}}}; null where an index
/// has no value (a constant output).
nlohmann::json SobolJson(const studies::SobolSummary& s);

/// A table per output with variance: "variable  S_i [lo, hi]  S_Ti [lo, hi]", the sum of S_i
/// with its interval.
std::string SobolText(const studies::SobolSummary& s);

/// The bar plot of one output's indices: per variable (x = 1 … d, named by the labels above the
/// bars) the first-order bar left, the total bar right, each with its interval as a whisker.
LinePlot SobolBarPlot(const std::string& title, const studies::SobolSummary& s,
                      const studies::SobolOutput& output);

}  // namespace epicycle::report
