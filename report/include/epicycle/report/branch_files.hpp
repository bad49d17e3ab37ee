// The files of a branch of periodic orbits (docs/periodic.md §3, "The stage's branch"): the CSV
// written a point at a time as the continuation computes it, the JSON record, and the figures
// against the continued parameter with stable orbits solid, unstable dashed and the folds marked.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "epicycle/dynamics/branch_run.hpp"
#include "epicycle/dynamics/stage_branch.hpp"
#include "epicycle/report/files.hpp"
#include "epicycle/report/svg_plot.hpp"

namespace epicycle::report {

/// A curve y(x) split where `stable` changes: one series per run of equal stability (the run and
/// the first point of the next, so that the curve stays connected), unstable runs dashed, every
/// run in `colour`; the first stable and first unstable runs named "<name>, stable" and
/// "<name>, unstable". @throws std::invalid_argument for sizes that differ.
std::vector<PlotSeries> StabilitySegments(const std::string& name, const std::vector<double>& x,
                                          const std::vector<double>& y,
                                          const std::vector<bool>& stable, int colour = 0);

/// PATH.csv of a stage branch: one line per point as the continuation computes it, with the
/// bifurcations located just before it. A helical stage's `helical_planets` > 0 planets add,
/// after sun_orbit_radius_um, each point's axial loads over its period
/// (StageBranchPoint::helical) in the speed sweep's columns (SpeedSweepFile): <name>_mean_<unit>
/// and <name>_max_abs_<unit> of sun_axial_force, ring_axial_force, carrier_axial_force [N], and
/// per planet i sun_mesh_axial_force, ring_mesh_axial_force [N], tilting_moment_radial,
/// tilting_moment_tangential [N·m] with the suffix _<i>; a spur stage's file has none of them.
class BranchFile {
 public:
  /// `parameter`: the continued parameter's key with its unit ("sun_speed_rpm"), the first
  /// figure's column; the sun speed's column follows when it is another. @throws std::runtime_error naming the file if it cannot be written.
  BranchFile(const std::string& path, const nlohmann::json& provenance,
             const std::string& parameter, int helical_planets = 0);
  /// Writes the record's points not yet written (as the continuation streams it).
  void Update(const dynamics::StageBranchRecord& record);
  void Close();

 private:
  CsvFile csv_;
  bool speed_column_ = true;  // sun_speed_rpm beside another parameter
  int helical_planets_ = 0;   // axial-load columns: 3 + 4 per planet (mean and max_abs), 0 without
  std::size_t written_ = 0;
};

/// The branch's header: what is continued over which range (`given`: as the user gave it), the
/// stage's period and tolerance, the tables' messages, and the columns of BranchPointsText.
std::string BranchPlanText(const dynamics::BranchPlan& plan, const std::string& given);

/// The console lines of the branch's points from index `from` on (each with the bifurcations
/// located just before it).
std::string BranchPointsText(const dynamics::StageBranchRecord& branch, std::size_t from);

/// The branch's closing line: points, unstable ones, bifurcations, integrations and times.
std::string BranchRecordText(const dynamics::BranchRecord& record);

/// PATH_k_gamma.svg, _te_amplitude.svg, _orbit.svg (a sun that moves) and
/// _spectral_radius.svg against the parameter.
void WriteBranchPlots(const std::string& path, const std::string& scene_name,
                      const dynamics::StageBranchRecord& record);

}  // namespace epicycle::report
