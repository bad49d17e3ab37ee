// A helical stage's axial loads over a set of states (transmission::HelicalLoadRange) as arrays,
// one row per speed of a sweep or point of a branch: shared by speed_sweep and periodic_branch so
// that both name them as their records' `helical` objects do.
#pragma once

#include <vector>

#include "common.hpp"
#include "epicycle/transmission/helical_slices.hpp"

namespace epicycle::python {

/// Per row (null: none, a failed speed) the axial loads as a Result of <name>_mean_<unit> and
/// <name>_max_abs_<unit> arrays, the record's keys: (R,) for the members' fields
/// (sun_axial_force, ring_axial_force, carrier_axial_force [N]) and (R, n) for the planets'
/// (their meshes' axial forces and net axial force [N], the axial forces' and the whole tilting
/// moments [N·m]; a single planet's too: (R,)); NaN where a row has no value.
py::object HelicalRanges(const std::vector<const transmission::HelicalLoadRange*>& rows);

}  // namespace epicycle::python
