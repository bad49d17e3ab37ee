// The gear-pair scenes as shipped (scenes/iso_pair_*.toml, paper_sun_planet.toml,
// paper_planet_ring.toml): read by the scene reader, their rigid gears act conjugately on the
// loaded flanks and the coast flanks stand the fitted normal backlash apart (closed forms:
// the overlap along the line of action is zero on the loaded side and −j_n on the coast side).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "epicycle/geometry/contact.hpp"
#include "epicycle/geometry/pair.hpp"
#include "epicycle/transmission/scene.hpp"
#include "figures.hpp"
#include "stage_fixtures.hpp"

using namespace epicycle::geometry;
using epicycle::test::FigureValue;

TEST_CASE("gear pairs: conjugate action of the loaded flanks and the fitted backlash",
          "[reference][transmission][geometry]") {
  for (const char* file : {"iso_pair_20_40.toml", "iso_pair_30_30.toml", "paper_sun_planet.toml",
                           "paper_planet_ring.toml"}) {
    const auto scene = epicycle::transmission::ParseScene(epicycle::test::SceneText(file), file);
    REQUIRE(scene.kind == epicycle::transmission::SceneKind::kPair);
    const GearPair pair(scene.pair);
    INFO(file);
    const double backlash = scene.fits.empty() ? 0.0 : scene.fits[0].normal_backlash;
    double worst_loaded = 0, worst_coast = 0;
    for (int k = 0; k < 200; ++k) {
      const PairPoses p = pair.Poses(pair.mesh_cycle() * k / 200.0);
      worst_loaded = std::max(
          worst_loaded,
          std::abs(NearestLoaOverlap(pair.A(p), pair.B(p), pair.internal(), pair.loaded_side())));
      worst_coast = std::max(
          worst_coast,
          std::abs(-NearestLoaOverlap(pair.A(p), pair.B(p), pair.internal(), -pair.loaded_side()) -
                   backlash));
    }
    CHECK(worst_loaded <= 1e-10);
    CHECK(worst_coast <= 1e-10);
    FigureValue(std::string("gear pair ") + file + ": worst loaded |overlap|", worst_loaded, "m");
    FigureValue(std::string("gear pair ") + file + ": worst |coast gap - backlash|", worst_coast,
                "m");
    CHECK(pair.summary().normal_backlash == Approx(backlash).margin(1e-12));
  }
}
