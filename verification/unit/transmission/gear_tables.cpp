// GearTables::Healthy (fe_compliance.hpp): a selection of a built compliance's tables.
#include <catch2/catch.hpp>

#include <stdexcept>
#include <string>

#include "fe_fixtures.hpp"

using namespace epicycle;

TEST_CASE("GearTables::Healthy refuses a gear it does not hold", "[unit][transmission]") {
  const transmission::FeStageCompliance& c = test::Compliance("paper_stage.toml");
  const int n = c.tables().size();
  CHECK(c.tables().Healthy({0, n - 1}).size() == 2);
  CHECK_THROWS_WITH(c.tables().Healthy({0, n}), "GearTables::Healthy: gear " + std::to_string(n) +
                                                    ": must lie in [0, " + std::to_string(n) + ")");
  CHECK_THROWS_AS(c.tables().Healthy({-1}), std::invalid_argument);
}
