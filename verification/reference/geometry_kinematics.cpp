// Rigid kinematics of the stage against closed forms: conjugate action at zero backlash, the
// fitted backlash, the mesh phasing of the planets, and run-out projected on the lines of action.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "../unit/geometry/stage_closed_forms.hpp"
#include "epicycle/geometry/pair.hpp"
#include "epicycle/geometry/stage.hpp"
#include "figures.hpp"
#include "geometry_fixtures.hpp"

using namespace epicycle::geometry;
using epicycle::test::FigureValue;

namespace {

const MeshKind kKinds[] = {MeshKind::kSunPlanet, MeshKind::kPlanetRing};

int LoadedSide(const Stage& st, MeshKind k) {
  return k == MeshKind::kSunPlanet ? st.sun_mesh_side() : st.ring_mesh_planet_side();
}

}  // namespace

TEST_CASE("rigid perfect gears at zero backlash: no interpenetration, loaded flanks touch",
          "[reference][geometry]") {
  const auto scene = epicycle::test::PaperStage(0.0);
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
  FigureValue("conjugate action, zero backlash, 240 positions: worst overlap", worst_overlap, "m");
  FigureValue(
      "conjugate action, zero backlash, 240 positions: worst |overlap| of the touching "
      "flank pairs",
      worst_touch, "m");
  epicycle::test::VerifyRow("rigid perfect gears, zero backlash, 240 positions x 6 meshes",
                            "no overlap; loaded flanks touch",
                            "worst overlap " + epicycle::test::Sci(worst_overlap) +
                                " m, worst touch " + epicycle::test::Sci(worst_touch) + " m",
                            epicycle::test::Sci(std::max(worst_overlap, worst_touch)) + " m",
                            "1e-9 m", worst_overlap <= 1e-9 && worst_touch <= 1e-9);
}

TEST_CASE("the coast-side gap equals the fitted normal backlash", "[reference][geometry]") {
  const auto scene = epicycle::test::PaperStage();
  const Stage st(scene.stage);
  REQUIRE(scene.fits.size() == 2);
  double worst_loaded = 0, worst_backlash = 0;
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
      worst_loaded = std::max({worst_loaded, std::abs(loaded_s), std::abs(loaded_r)});
      worst_backlash =
          std::max({worst_backlash, std::abs(-coast_s / scene.fits[0].normal_backlash - 1),
                    std::abs(-coast_r / scene.fits[1].normal_backlash - 1)});
    }
  }
  FigureValue("0.15 mm backlash, 25 positions: worst loaded |overlap|", worst_loaded, "m");
  FigureValue(
      "0.15 mm backlash, 25 positions: coast gap vs fitted backlash, worst relative "
      "error",
      worst_backlash, "");
}

TEST_CASE("mesh phase between consecutive planets is 2pi/3", "[reference][geometry]") {
  const auto scene = epicycle::test::PaperStage();
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
  double worst_phase = 0;
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
      worst_phase = std::max(worst_phase, std::abs(lag - i / 3.0));
    }
  }
  FigureValue("mesh phase of planets 2, 3 from the contacts: worst error", worst_phase, "cycles");
}

TEST_CASE("run-out of planet 1 changes its overlaps by the offset projected on each line of action",
          "[reference][geometry]") {
  auto scene = epicycle::test::PaperStage();
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
  FigureValue("run-out 20 um, planet 1, 360 positions: worst |overlap change - projection|", worst,
              "m");
  epicycle::test::VerifyRow(
      "run-out 20 um on planet 1, 360 positions: overlap change of its meshes",
      "projection of the offset on each line of action",
      "worst difference " + epicycle::test::Sci(worst) + " m",
      epicycle::test::Sci(worst / e) + " of e", "1 % of e", worst <= 0.01 * e);
}

TEST_CASE(
    "run-out turns with its gear at the stage's kinematic speed, and moves the meshes by "
    "its projection on the closed-form lines of action",
    "[reference][geometry]") {
  // Willis, ring fixed (ω_r = 0): the sun mesh is external, (ω_s − ω_c)/(ω_p − ω_c) = −z_p/z_s,
  // the ring mesh internal, (ω_p − ω_c)/(ω_r − ω_c) = +z_r/z_p; so ω_p = (1 − z_r/z_p) ω_c and
  // ω_s = ω_c − (z_p/z_s)(ω_p − ω_c) = (1 + z_r/z_s) ω_c. The rotations at φ_c = 0 are the
  // stage's aligned start (a choice of origin) and are read from the poses once; the ring does not
  // turn. The geometric centre is then the rotation centre + e (cos(θ + φ), sin(θ + φ)).
  auto scene = epicycle::test::PaperStage();
  const Runout planet_runout{20e-6, 0.7}, sun_runout{15e-6, -1.2}, ring_runout{10e-6, 2.5};
  scene.stage.planet_runouts.assign(3, Runout{});
  scene.stage.planet_runouts[0] = planet_runout;
  scene.stage.sun_runout = sun_runout;
  scene.stage.ring_runout = ring_runout;
  const Stage st(scene.stage);
  const double zs = scene.stage.sun.teeth, zp = scene.stage.planet.teeth,
               zr = scene.stage.ring.teeth;
  const double sun_speed = 1 + zr / zs, planet_speed = 1 - zr / zp;
  const StagePoses start = st.Poses(0.0);
  const double sun0 = start.sun.rotation, planet0 = start.planets[0].rotation;
  auto offset = [](const Runout& r, double theta) {
    return Vec2(r.amplitude * std::cos(theta + r.phase), r.amplitude * std::sin(theta + r.phase));
  };
  ContactSearchOptions opt;
  opt.gap_window = 300e-6;  // both flanks
  const double revolution = 2 * kPi / std::abs(planet_speed);
  double worst_direction = 0, worst_projection = 0;
  int projected = 0;
  for (int k = 0; k <= 36; ++k) {
    const double phi = revolution * (-0.3 + 1.6 * k / 36.0);
    const StagePoses with = st.Poses(phi, true), without = st.Poses(phi, false);
    const Vec2 o_sun = offset(sun_runout, sun0 + sun_speed * phi);
    const Vec2 o_planet = offset(planet_runout, planet0 + planet_speed * phi);
    const Vec2 o_ring = offset(ring_runout, 0.0);
    INFO("carrier " << phi);
    const double ds = (with.sun.geometric_centre - with.sun.rotation_centre - o_sun).norm();
    const double dp =
        (with.planets[0].geometric_centre - with.planets[0].rotation_centre - o_planet).norm();
    const double dr = (with.ring.geometric_centre - with.ring.rotation_centre - o_ring).norm();
    CHECK(ds <= 1e-9 * sun_runout.amplitude);
    CHECK(dp <= 1e-9 * planet_runout.amplitude);
    CHECK(dr <= 1e-9 * ring_runout.amplitude);
    CHECK((with.planets[1].geometric_centre - with.planets[1].rotation_centre).norm() == 0.0);
    worst_direction = std::max({worst_direction, ds, dp, dr});
    // The overlap changes of every mesh: A's offset minus B's, projected on the mesh's line of
    // action (sun mesh: A = sun, B = planet; ring mesh: A = planet, B = ring).
    for (int i = 0; i < st.planets(); ++i) {
      const double psi = phi + 2 * kPi * i / st.planets();
      const Vec2 o_p = i == 0 ? o_planet : Vec2::Zero();
      for (MeshKind kind : kKinds) {
        const Vec2 relative = kind == MeshKind::kSunPlanet ? o_sun - o_p : o_p - o_ring;
        const double tol = epicycle::test::SecondOrderBound(st, kind, relative.squaredNorm());
        std::map<std::tuple<int, int, int>, double> before;
        for (const PotentialContact& c : st.Contacts(without, i, kind, opt)) {
          if (c.kind == ContactKind::kInvolute)
            before[{c.side_a, c.tooth_a, c.tooth_b}] = c.overlap;
        }
        for (const PotentialContact& c : st.Contacts(with, i, kind, opt)) {
          if (c.kind != ContactKind::kInvolute) continue;
          const auto it = before.find({c.side_a, c.tooth_a, c.tooth_b});
          if (it == before.end()) continue;  // a pair at the end of its active range
          const Vec2 d = epicycle::test::ClosedFormLoaDirection(st, kind, c.side_a, psi);
          const double expected = relative.dot(d);
          CHECK(c.overlap - it->second == Approx(expected).epsilon(0).margin(tol));
          worst_projection =
              std::max(worst_projection, std::abs(c.overlap - it->second - expected));
          ++projected;
        }
      }
    }
  }
  CHECK(projected >= 37 * 3 * 2 * 2);
  FigureValue("run-out (sun 15, planet 1 20, ring 10 um): worst |offset - e Dir(theta + phi)|",
              worst_direction, "m");
  FigureValue(
      "run-out (sun 15, planet 1 20, ring 10 um): worst |overlap change - closed-form "
      "projection|",
      worst_projection, "m");
}
