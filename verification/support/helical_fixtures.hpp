// The helical paper stage's FE compliance with the slices' flank positions (helical_slices.hpp),
// built once per test process and shared by the tests of scenes with its gears
// (paper_stage_helical.toml and its copies with pins).
#pragma once

#include <memory>

#include "epicycle/transmission/fe_compliance.hpp"
#include "fe_fixtures.hpp"

namespace epicycle::test {

inline const transmission::FeStageCompliance& HelicalCompliance(const transmission::Scene& scene,
                                                                const geometry::Stage& stage) {
  static std::unique_ptr<transmission::FeStageCompliance> c;
  if (!c) {
    transmission::FeComplianceOptions o = CachedTables();
    o.helical_slices = true;
    c = std::make_unique<transmission::FeStageCompliance>(scene, stage, o);
  }
  return *c;
}

}  // namespace epicycle::test
