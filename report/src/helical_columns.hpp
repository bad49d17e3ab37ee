// The CSV columns of a helical stage's axial loads over a set of states (a speed sweep's window,
// a branch point's period: transmission::HelicalLoadRange), shared by the files that write them
// (run_files.hpp SpeedSweepFile, branch_files.hpp BranchFile) so that both name them alike.
#pragma once

#include <string>

#include "epicycle/transmission/helical_slices.hpp"

namespace epicycle::report {

/// The head of the columns, each preceded by a comma: <name>_mean_<unit> and
/// <name>_max_abs_<unit> of sun_axial_force, ring_axial_force, carrier_axial_force [N], then per
/// planet i = 1..planets those of sun_mesh_axial_force, ring_mesh_axial_force [N],
/// tilting_moment_radial, tilting_moment_tangential [N·m] with the suffix _<i> (the members'
/// columns whatever `planets`).
std::string HelicalRangeColumns(int planets);

/// The cells of `range` in those columns, each preceded by a comma: the values when `has`, empty
/// cells otherwise (a failed speed, a range without states: no value, never a NaN).
std::string HelicalRangeCells(int planets, const transmission::HelicalLoadRange& range, bool has);

}  // namespace epicycle::report
