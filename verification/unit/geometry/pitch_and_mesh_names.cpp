// ISO 1328-1 figures of a gear's cumulative pitch deviations, counted by hand, and the names and
// indices of a stage's meshes against Stage::meshes().
#include <catch2/catch.hpp>

#include "epicycle/geometry/iso.hpp"
#include "epicycle/geometry/stage.hpp"
#include "geometry_fixtures.hpp"

using namespace epicycle;

TEST_CASE("pitch deviation statistics of four teeth", "[unit][geometry]") {
  // F_p = 0, 4, 1, −3 µm: single pitches 4, −3, −4 and, closing the circle, 3 µm: largest 4 µm;
  // total cumulative 4 − (−3) = 7 µm.
  const auto s = geometry::iso::PitchDeviationStatistics({0.0, 4e-6, 1e-6, -3e-6});
  CHECK(s.largest_single == Approx(4e-6).epsilon(1e-12));
  CHECK(s.total_cumulative == Approx(7e-6).epsilon(1e-12));
  // The closing pitch counts: F_p = 0, 1, 2, 9 µm has its largest single pitch from tooth 3 back
  // to tooth 0 (9 µm), not between neighbours in the list (7 µm).
  const auto closing = geometry::iso::PitchDeviationStatistics({0.0, 1e-6, 2e-6, 9e-6});
  CHECK(closing.largest_single == Approx(9e-6).epsilon(1e-12));
  const auto none = geometry::iso::PitchDeviationStatistics({});
  CHECK(none.largest_single == 0.0);
  CHECK(none.total_cumulative == 0.0);
}

TEST_CASE("mesh names and indices follow Stage::meshes()", "[unit][geometry]") {
  const geometry::Stage stage(test::PaperStage().stage);
  REQUIRE(stage.meshes().size() == 6);
  CHECK(geometry::MeshName(0, geometry::MeshKind::kSunPlanet) == "sun-planet1");
  CHECK(geometry::MeshName(2, geometry::MeshKind::kPlanetRing) == "planet3-ring");
  for (int i = 0; i < 3; ++i)
    for (geometry::MeshKind k : {geometry::MeshKind::kSunPlanet, geometry::MeshKind::kPlanetRing}) {
      const geometry::MeshSummary& m = stage.meshes()[geometry::MeshIndex(i, k)];
      CHECK(m.planet == i);
      CHECK(m.kind == k);
      CHECK(m.name == geometry::MeshName(i, k));
    }
  CHECK(geometry::MeshIndex(1, geometry::MeshKind::kPlanetRing) == 3);
}
