// `epicycle modes` on the console: the rig before the modes are solved, then the mesh
// stiffnesses, each mode group's frequency, multiplicity, type and energy shares, and the
// coincidences of mesh harmonics with modes over the speed range.
#pragma once

#include <string>

#include "epicycle/dynamics/modes_run.hpp"

namespace epicycle::report {

/// "NAME: n planets, sun SUPPORT, N DOFs (ring fixed|elastic)".
std::string ModesPlanText(const dynamics::ModesPlan& plan);
/// The record's mesh stiffnesses, modes and coincidences, a table each.
std::string ModesRecordText(const dynamics::ModesRecord& record);

}  // namespace epicycle::report
