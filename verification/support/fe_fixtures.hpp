// FE compliance shared by the transmission suite's test cases: the influence tables in the build
// tree's cache (built once, then loaded by every test process) and one stage compliance per scene
// file.
#pragma once

#include <map>
#include <memory>
#include <string>

#include "epicycle/transmission/fe_compliance.hpp"
#include "stage_fixtures.hpp"

namespace epicycle::test {

inline transmission::FeComplianceOptions CachedTables() {
  transmission::FeComplianceOptions o;
  o.cache_directory = EPICYCLE_TEST_CACHE_DIR;
  return o;
}

/// A coarse gear-body mesh for tests of the table machinery (cache, concurrency), not of its
/// accuracy: a table in about a second.
inline compliance::InfluenceTableOptions CoarseTableOptions() {
  compliance::InfluenceTableOptions o;
  o.mesh.involute_elements = 4;
  o.mesh.tip_round_elements = 1;
  o.mesh.tip_land_elements = 1;
  o.mesh.fillet_elements = 2;
  o.mesh.band_layers = 2;
  o.mesh.rim_layers = 2;
  return o;
}

/// The FE compliance of a scene file's bodies; scenes that only add errors, relief or pitch
/// deviations share it (those move or modify the surfaces, they do not change the bodies).
inline const transmission::FeStageCompliance& Compliance(const std::string& file) {
  static std::map<std::string, std::unique_ptr<transmission::FeStageCompliance>> cache;
  auto& slot = cache[file];
  if (!slot) {
    const auto scene = transmission::ParseScene(SceneText(file), file);
    slot = std::make_unique<transmission::FeStageCompliance>(scene, geometry::Stage(scene.stage),
                                                             CachedTables());
  }
  return *slot;
}

}  // namespace epicycle::test
