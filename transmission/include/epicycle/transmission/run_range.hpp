// What a run of a stage covers in carrier angle: one mesh cycle, one planet revolution relative
// to the carrier (the period of a planet's run-out), one sun revolution relative to the carrier
// (the period of a sun tooth's damage), or one carrier revolution (ring fixed). One
// definition for the quasi-static sweep, the dynamic run, the speed sweep's window and the
// tolerance studies.
#pragma once

#include <array>
#include <string>

#include "epicycle/geometry/stage.hpp"
#include "epicycle/io/enum_names.hpp"

namespace epicycle::transmission {

enum class RunRange {
  kMeshCycle,          ///< "cycle": 2π/z_r of carrier rotation
  kPlanetRevolution,   ///< "planet": 2π z_p/z_r, one planet turn relative to the carrier
  kSunRevolution,      ///< "sun": 2π z_s/z_r, one sun turn relative to the carrier
  kCarrierRevolution,  ///< "revolution": 2π
};

/// The ranges' names (the programs' --range, Python's range): the one table of RunRangeFromName.
inline constexpr std::array<io::EnumName<RunRange>, 4> kRunRangeNames{{
    {RunRange::kMeshCycle, "cycle"},
    {RunRange::kPlanetRevolution, "planet"},
    {RunRange::kSunRevolution, "sun"},
    {RunRange::kCarrierRevolution, "revolution"},
}};

/// "cycle", "planet", "sun" or "revolution". @throws std::invalid_argument naming the value otherwise.
RunRange RunRangeFromName(const std::string& name);

/// Carrier rotation of the range [rad]: 2π/z_r, 2π z_p/z_r, 2π z_s/z_r or 2π.
double CarrierSpan(const geometry::Stage& stage, RunRange range);

/// The same in mesh cycles [-]: 1, z_p, z_s or z_r (exact integers).
double MeshCycles(const geometry::Stage& stage, RunRange range);

/// Positions per mesh cycle of a quasi-static sweep by default (docs/quasistatic.md, "Positions"):
/// the contact set changes about 4 n times per mesh cycle (n planets, two meshes each, a tooth
/// pair entering and leaving), every 1/12 cycle with three planets; 60 positions put about five
/// between two changes, so that a plot shows each step of the load sharing, not a row of spikes.
inline constexpr int kPositionsPerMeshCycle = 60;
/// kPositionsPerMeshCycle × MeshCycles(range): the sweep's positions when none are asked for.
int DefaultPositions(const geometry::Stage& stage, RunRange range);

}  // namespace epicycle::transmission
