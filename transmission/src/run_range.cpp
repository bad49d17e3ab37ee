#include "epicycle/transmission/run_range.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace epicycle::transmission {

RunRange RunRangeFromName(const std::string& name) {
  if (const std::optional<RunRange> range = io::ValueOf(kRunRangeNames, name)) return *range;
  throw std::invalid_argument("range = '" + name + "': must be " +
                              io::NameList(kRunRangeNames, " or "));
}

double CarrierSpan(const geometry::Stage& stage, RunRange range) {
  switch (range) {
    case RunRange::kMeshCycle:
      return stage.mesh_cycle();
    case RunRange::kPlanetRevolution:
      // With the ring fixed a planet turns once relative to the carrier while the carrier turns
      // z_p/z_r of a revolution (z_p ring teeth pass it).
      return 2.0 * std::numbers::pi * stage.planet(0).teeth() / stage.ring().teeth();
    case RunRange::kSunRevolution:
      // The sun turns once relative to the carrier while z_s mesh cycles pass (f_m = z_s (f_s −
      // f_c) = z_r f_c).
      return 2.0 * std::numbers::pi * stage.sun().teeth() / stage.ring().teeth();
    case RunRange::kCarrierRevolution:
      return 2.0 * std::numbers::pi;
  }
  throw std::invalid_argument("CarrierSpan: unknown range");
}

double MeshCycles(const geometry::Stage& stage, RunRange range) {
  switch (range) {
    case RunRange::kMeshCycle:
      return 1.0;
    case RunRange::kPlanetRevolution:
      return static_cast<double>(stage.planet(0).teeth());
    case RunRange::kSunRevolution:
      return static_cast<double>(stage.sun().teeth());
    case RunRange::kCarrierRevolution:
      return static_cast<double>(stage.ring().teeth());
  }
  throw std::invalid_argument("MeshCycles: unknown range");
}

int DefaultPositions(const geometry::Stage& stage, RunRange range) {
  return static_cast<int>(std::lround(kPositionsPerMeshCycle * MeshCycles(stage, range)));
}

}  // namespace epicycle::transmission
