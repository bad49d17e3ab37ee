// Rigid kinematics of the stage against closed forms: conjugate action at zero backlash, the
// fitted backlash, the mesh phasing of the planets, and run-out projected on the lines of action.
#include <catch2/catch.hpp>

#include <cmath>

#include "epicycle/geometry/pair.hpp"
#include "epicycle/geometry/stage.hpp"
#include "stage_fixtures.hpp"

using namespace epicycle::geometry;

namespace {

const MeshKind kKinds[] = {MeshKind::kSunPlanet, MeshKind::kPlanetRing};

int LoadedSide(const Stage& st, MeshKind k) {
  return k == MeshKind::kSunPlanet ? st.sun_mesh_side() : st.ring_mesh_planet_side();
}

}  // namespace

TEST_CASE("rigid perfect gears at zero backlash: no interpenetration, loaded flanks touch",
          "[reference][geometry]") {
  const auto scene = epicycle::test::ZeroBacklashPaperScene();
  const Stage st(scene.stage);
  ContactSearchOptions opt;
  opt.gap_window = 100e-6;
  const int positions = 240;
  double worst_overlap = -1, worst_touch = 0;
  int checked = 0;
  for (int k = 0; k < positions; ++k) {
    const double phi = st.mesh_cycle() * k / positions;
    const StagePoses p = st.Poses(phi);
    for (int i = 0; i < st.planets(); ++i) {
      for (MeshKind kind : kKinds) {
        const auto contacts = st.Contacts(p, i, kind, opt);
        double loaded = -1, coast = -1;
        for (const PotentialContact& c : contacts) {
          worst_overlap = std::max(worst_overlap, c.overlap);
          if (c.kind != ContactKind::kInvolute) continue;
          (c.side_a == LoadedSide(st, kind) ? loaded : coast) =
              std::max(c.side_a == LoadedSide(st, kind) ? loaded : coast, c.overlap);
        }
        // Zero backlash: the loaded and the coast flank pairs both touch.
        worst_touch = std::max({worst_touch, std::abs(loaded), std::abs(coast)});
        ++checked;
      }
    }
  }
  CHECK(checked == positions * 6);
  CHECK(worst_overlap <= 1e-9);
  CHECK(worst_touch <= 1e-9);
}

TEST_CASE("the coast-side gap equals the fitted normal backlash", "[reference][geometry]") {
  const auto scene = epicycle::test::PaperScene();
  const Stage st(scene.stage);
  REQUIRE(scene.fits.size() == 2);
  for (int k = 0; k < 25; ++k) {
    const StagePoses p = st.Poses(st.mesh_cycle() * k / 25.0);
    for (int i = 0; i < st.planets(); ++i) {
      const double loaded_s =
          NearestLoaOverlap(st.Sun(p), st.Planet(p, i), false, st.sun_mesh_side());
      const double coast_s =
          NearestLoaOverlap(st.Sun(p), st.Planet(p, i), false, -st.sun_mesh_side());
      const double loaded_r =
          NearestLoaOverlap(st.Planet(p, i), st.Ring(p), true, st.ring_mesh_planet_side());
      const double coast_r =
          NearestLoaOverlap(st.Planet(p, i), st.Ring(p), true, -st.ring_mesh_planet_side());
      CHECK(loaded_s == Approx(0).margin(1e-10));
      CHECK(loaded_r == Approx(0).margin(1e-10));
      CHECK(-coast_s == Approx(scene.fits[0].normal_backlash).epsilon(1e-9));
      CHECK(-coast_r == Approx(scene.fits[1].normal_backlash).epsilon(1e-9));
    }
  }
}

TEST_CASE("mesh phase between consecutive planets is 2pi/3", "[reference][geometry]") {
  const auto scene = epicycle::test::PaperScene();
  const Stage st(scene.stage);
  ContactSearchOptions opt;
  opt.both_sides = false;
  // Mesh state of a mesh: the position of its loaded involute contacts along the line of action,
  // in base pitches (all of them differ by whole pitches).
  auto state = [&](const StagePoses& p, int i, MeshKind kind) {
    opt.side_a = LoadedSide(st, kind);
    for (const PotentialContact& c : st.Contacts(p, i, kind, opt)) {
      if (c.kind != ContactKind::kInvolute) continue;
      const LineOfAction l = kind == MeshKind::kSunPlanet
                                 ? MakeLineOfAction(st.Sun(p), st.Planet(p, i), false, opt.side_a)
                                 : MakeLineOfAction(st.Planet(p, i), st.Ring(p), true, opt.side_a);
      const double s = (c.point_a - l.tangent_a).dot(l.direction) / st.sun().base_pitch();
      return s - std::floor(s);
    }
    FAIL("no loaded involute contact");
    return 0.0;
  };
  for (MeshKind kind : kKinds) {
    const StagePoses p0 = st.Poses(0.1 * st.mesh_cycle());
    const StagePoses p1 = st.Poses(0.1001 * st.mesh_cycle());
    // Direction in which the state runs as the carrier turns.
    const double run = state(p1, 0, kind) - state(p0, 0, kind) > 0 ? 1.0 : -1.0;
    for (int i = 1; i < st.planets(); ++i) {
      double lag = -run * (state(p0, i, kind) - state(p0, 0, kind));
      lag -= std::floor(lag);
      INFO("planet " << i + 1 << (kind == MeshKind::kSunPlanet ? " sun mesh" : " ring mesh"));
      CHECK(lag == Approx(i / 3.0).margin(1e-9));
      CHECK(st.meshes()[2 * i].phase == Approx(i / 3.0).margin(1e-12));
    }
  }
}

TEST_CASE("run-out of planet 1 changes its overlaps by the offset projected on each line of action",
          "[reference][geometry]") {
  auto scene = epicycle::test::PaperScene();
  const double e = 20e-6;
  scene.stage.planet_runouts.assign(3, Runout{});
  scene.stage.planet_runouts[0] = Runout{e, 0.7};
  const Stage st(scene.stage);
  const double revolution = 2 * kPi / std::abs(st.planet_ratio());  // carrier turn per planet turn
  double worst = 0;
  const int positions = 360;
  for (int k = 0; k < positions; ++k) {
    const double phi = revolution * k / positions;
    const StagePoses with = st.Poses(phi, true), without = st.Poses(phi, false);
    const Vec2 offset = with.planets[0].geometric_centre - with.planets[0].rotation_centre;
    REQUIRE(offset.norm() == Approx(e).epsilon(1e-12));
    // Sun mesh: the planet is gear B; moving it along +d opens the mesh.
    const LineOfAction ls =
        MakeLineOfAction(st.Sun(without), st.Planet(without, 0), false, st.sun_mesh_side());
    const double ds =
        NearestLoaOverlap(st.Sun(with), st.Planet(with, 0), false, st.sun_mesh_side()) -
        NearestLoaOverlap(st.Sun(without), st.Planet(without, 0), false, st.sun_mesh_side());
    worst = std::max(worst, std::abs(ds - (-offset.dot(ls.direction))));
    // Ring mesh: the planet is gear A; moving it along +d closes the mesh.
    const LineOfAction lr =
        MakeLineOfAction(st.Planet(without, 0), st.Ring(without), true, st.ring_mesh_planet_side());
    const double dr =
        NearestLoaOverlap(st.Planet(with, 0), st.Ring(with), true, st.ring_mesh_planet_side()) -
        NearestLoaOverlap(st.Planet(without, 0), st.Ring(without), true,
                          st.ring_mesh_planet_side());
    worst = std::max(worst, std::abs(dr - offset.dot(lr.direction)));
  }
  CHECK(worst <= 0.01 * e);
}

TEST_CASE("gear pairs: conjugate action of the loaded flanks and the fitted backlash",
          "[reference][geometry]") {
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
    CHECK(pair.summary().normal_backlash == Approx(backlash).margin(1e-12));
  }
}
