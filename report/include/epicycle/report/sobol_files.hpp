// The Sobol indices of a study (studies/sobol.hpp, docs/studies.md "Sensitivity: Sobol indices")
// on the console and as a bar plot (their JSON is the study record's, studies/study_run.hpp).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "epicycle/report/svg_plot.hpp"
#include "epicycle/studies/sobol.hpp"

namespace epicycle::report {

/// A table per output with variance: "variable  S_i [lo, hi]  S_Ti [lo, hi]", the sum of S_i
/// with its interval.
std::string SobolText(const studies::SobolSummary& s);

/// The bar plot of one output's indices: per variable (x = 1 … d, named by the labels above the
/// bars) the first-order bar left, the total bar right, each with its interval as a whisker.
LinePlot SobolBarPlot(const std::string& title, const studies::SobolSummary& s,
                      const studies::SobolOutput& output);

}  // namespace epicycle::report
