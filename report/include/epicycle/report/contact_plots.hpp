// The figures of `epicycle contact compare` (docs/solvers.md): the Dolan–Moré performance profile
// of the back ends and their error against the reference versus run time; the provenance of its
// files.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "epicycle/solvers/backend_comparison.hpp"
#include "epicycle/solvers/performance_profile.hpp"

namespace epicycle::report {

/// ρ_b(τ) for τ from 1 to 1e4 (log axis), one step line per back end, as an SVG document.
std::string PerformanceProfileSvg(const std::vector<solvers::PerformanceProfile>& profiles,
                                  std::size_t problems);

/// One run of the error-versus-time figure.
struct ErrorTimePoint {
  std::string backend;
  double seconds = 0;   ///< median run time [s]
  double error = 0;     ///< error against the reference [-]; not finite: drawn at the top edge
  bool solved = false;  ///< a dot if solved, an "x" if not
};

/// Error against the reference versus run time, log-log, one colour per back end (in the order
/// of `backends`), as an SVG document.
std::string ErrorVersusTimeSvg(const std::vector<std::string>& backends,
                               const std::vector<ErrorTimePoint>& points);

/// PREFIX_profile.svg and PREFIX_error_vs_time.svg of a comparison's runs.
void WriteComparisonPlots(const std::string& prefix, const solvers::ComparisonRecord& record);

/// The provenance of a comparison's files: the back ends, the number of problem files and the
/// hash of their hashes.
nlohmann::json ComparisonProvenance(const solvers::ComparisonRequest& request);

}  // namespace epicycle::report
