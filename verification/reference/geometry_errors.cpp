// Manufacturing and assembly errors seen by the contact search, rigid gears, the paper's stage:
// a planet pin-hole position error moves the planet's meshes by its projection on each line of
// action, and a tooth-thickness error moves every flank of its gear by Δs/2 (run-out:
// geometry_kinematics.cpp).
//
// The references are written out here, not taken from the library (stage_closed_forms.hpp):
// the line of action of a mesh on A's flank side σ_A is d = sin α_w u + σ_A cos α_w u⊥, and
// moving B by v changes the overlap by −v·d, moving A by v by +v·d. A planet is B of its sun
// mesh and A of its ring mesh, so its pin error v = Δζ e_r + Δη e_t (e_r = u, e_t = u⊥ at the
// planet's carrier angle) changes
//     the sun mesh by   −Δζ sin α_w,s − σ_s Δη cos α_w,s,
//     the ring mesh by  +Δζ sin α_w,r + σ_r Δη cos α_w,r      (σ_r = −σ_s):
// with the paper's sun torque (σ_s = −1) a tangential error enters both meshes as +Δη cos α_w, a
// radial one with opposite signs (docs/model.md §8). These are first-order in v; the tolerance is
// twice the bound of the second-order remainder, (2 + 1/sin α_w)|v|²/a: 1.2e-9 m for 5 µm on the
// sun mesh (2.4e-4 of the error).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <tuple>

#include "../unit/geometry/stage_closed_forms.hpp"
#include "epicycle/geometry/stage.hpp"
#include "figures.hpp"
#include "geometry_fixtures.hpp"

using namespace epicycle::geometry;
using epicycle::test::ClosedFormLoaDirection;
using epicycle::test::ClosedFormPressureAngle;
using epicycle::test::FigureValue;
using epicycle::test::SecondOrderBound;

namespace {

const MeshKind kKinds[] = {MeshKind::kSunPlanet, MeshKind::kPlanetRing};

// The paper's stage with a pin-hole error on one planet (as an [[errors.pin]] table of
// docs/scenes.md sets it: the other planets' entries zero).
Stage PaperStageWithPinError(int planet, PinError error) {
  StageSpec s = epicycle::test::PaperStage().stage;
  s.pin_errors.assign(static_cast<std::size_t>(s.planets), PinError{});
  s.pin_errors[static_cast<std::size_t>(planet)] = error;
  return Stage(s);
}

// The paper's stage with a tooth-thickness error on one gear, "sun", "ring" or "planet<i>" (as an
// [[errors.thickness]] table sets it).
Stage PaperStageWithThicknessError(const std::string& gear, double ds) {
  StageSpec s = epicycle::test::PaperStage().stage;
  if (gear == "sun") {
    s.sun.thickness_error = ds;
  } else if (gear == "ring") {
    s.ring.thickness_error = ds;
  } else {
    s.planet_thickness_errors.assign(static_cast<std::size_t>(s.planets), 0.0);
    s.planet_thickness_errors[static_cast<std::size_t>(std::stoi(gear.substr(6)) - 1)] = ds;
  }
  return Stage(s);
}

// Involute (on the line of action) contacts of one mesh keyed by (σ_A, tooth of A, tooth of B).
using Key = std::tuple<int, int, int>;
std::map<Key, double> InvoluteOverlaps(const Stage& st, const StagePoses& p, int planet,
                                       MeshKind kind) {
  ContactSearchOptions opt;
  opt.gap_window = 300e-6;  // both flanks: the coast flanks are 150 µm (the backlash) apart
  std::map<Key, double> out;
  for (const PotentialContact& c : st.Contacts(p, planet, kind, opt)) {
    if (c.kind == ContactKind::kInvolute) out[{c.side_a, c.tooth_a, c.tooth_b}] = c.overlap;
  }
  return out;
}

}  // namespace

TEST_CASE("a planet pin-hole error moves its meshes by its projection on each line of action",
          "[reference][geometry]") {
  const Stage nominal(epicycle::test::PaperStage().stage);
  REQUIRE(nominal.sun_mesh_side() == -1);  // the explicit signs below: sun torque −600 N·m
  struct Case {
    int planet;
    double radial, tangential;  // [m]
  };
  const Case cases[] = {{0, 5e-6, 0}, {0, 0, 5e-6}, {0, -3e-6, 4e-6}, {2, 0, -5e-6}, {2, 5e-6, 0}};
  double worst = 0, worst_relative = 0, worst_other = 0, worst_over_bound = 0;
  int matched = 0;
  for (const Case& e : cases) {
    const Stage with(PaperStageWithPinError(e.planet, PinError{e.radial, e.tangential}));
    const double v2 = e.radial * e.radial + e.tangential * e.tangential;
    for (int k = 0; k < 7; ++k) {
      const double phi = nominal.mesh_cycle() * (0.05 + k / 7.0);
      const StagePoses p0 = nominal.Poses(phi), p1 = with.Poses(phi);
      const double psi = phi + 2 * kPi * e.planet / 3;
      const Vec2 v = e.radial * Dir(psi) + e.tangential * DirPerp(psi);
      for (int i = 0; i < 3; ++i) {
        for (MeshKind kind : kKinds) {
          const auto a = InvoluteOverlaps(nominal, p0, i, kind);
          const auto b = InvoluteOverlaps(with, p1, i, kind);
          const double tol = SecondOrderBound(nominal, kind, v2);
          for (const auto& [key, overlap] : a) {
            const auto it = b.find(key);
            if (it == b.end()) continue;  // a pair at the end of its active range
            const double change = it->second - overlap;
            if (i != e.planet) {
              // The other planets do not move.
              worst_other = std::max(worst_other, std::abs(change));
              CHECK(change == Approx(0).margin(1e-15));
              continue;
            }
            const int side_a = std::get<0>(key);
            const Vec2 d = ClosedFormLoaDirection(nominal, kind, side_a, psi);
            // Planet = B of the sun mesh (−v·d), A of the ring mesh (+v·d).
            const double expected = kind == MeshKind::kSunPlanet ? -v.dot(d) : v.dot(d);
            INFO("planet " << i + 1 << (kind == MeshKind::kSunPlanet ? " sun" : " ring")
                           << " mesh, side " << side_a << ", carrier " << phi);
            CHECK(change == Approx(expected).epsilon(0).margin(tol));
            worst = std::max(worst, std::abs(change - expected));
            worst_over_bound = std::max(worst_over_bound, std::abs(change - expected) / tol);
            worst_relative = std::max(worst_relative, std::abs(change - expected) / std::sqrt(v2));
            ++matched;
          }
        }
      }
    }
  }
  // Both flanks of both meshes of the displaced planet, at every position.
  CHECK(matched >= 5 * 7 * 2 * 2);
  FigureValue("pin error: worst |overlap change - projection| (5 um)", worst, "m");
  FigureValue("pin error: worst relative to |error|", worst_relative, "");
  FigureValue("pin error: worst change on the other planets", worst_other, "m");
  epicycle::test::VerifyRow(
      "pin-hole error 5 um (radial, tangential, mixed) on planets 1 and 3",
      "projection on each line of action (+-dz sin a_w, dh cos a_w)",
      "worst difference " + epicycle::test::Sci(worst) + " m",
      epicycle::test::Sci(worst_relative) + " of the error",
      "the second-order bound (" + epicycle::test::Sci(worst_over_bound) + " of it used)",
      worst_over_bound <= 1.0);
}

TEST_CASE("a tooth-thickness error moves every flank of its gear by ds/2",
          "[reference][geometry]") {
  const Stage nominal(epicycle::test::PaperStage().stage);
  struct Case {
    const char* gear;
    double ds;  // [m]
  };
  const Case cases[] = {{"sun", 5e-6}, {"planet1", -5e-6}, {"planet3", 5e-6}, {"ring", 5e-6}};
  double worst = 0, worst_sum = 0;
  int matched = 0;
  for (const Case& e : cases) {
    const Stage with(PaperStageWithThicknessError(e.gear, e.ds));
    const std::string gear = e.gear;
    // Does the thickened gear take part in planet i's mesh of this kind?
    auto involved = [&](int i, MeshKind kind) {
      if (gear == "sun") return kind == MeshKind::kSunPlanet;
      if (gear == "ring") return kind == MeshKind::kPlanetRing;
      return gear == "planet" + std::to_string(i + 1);
    };
    for (int k = 0; k < 7; ++k) {
      const double phi = nominal.mesh_cycle() * (0.05 + k / 7.0);
      // (a) The same poses (rigid gears where the error-free stage puts them): the flanks alone.
      // An involute offset along its normal by Δs/2 stays an involute of the same base circle, so
      // the change is exact up to round-off (1e-12 m against overlaps of ~1e-4 m computed from
      // coordinates of ~0.1 m).
      const StagePoses p0 = nominal.Poses(phi);
      // (b) The error-applied stage's own kinematic poses: its alignment turns gears until the
      // loaded flanks touch, which takes part of a uniform thickness error up as a rigid
      // rotation (a rotation is a degree of freedom of the load-sharing problem, so this is a
      // choice of origin). A rotation moves a gear's two flanks by +r_b dθ and −r_b dθ, so the
      // sum of a mesh's loaded-flank and coast-flank changes is rotation-free: Δs/2 for each of
      // the thickened gear's two flanks, Δs in all.
      const StagePoses p1 = with.Poses(phi);
      for (int i = 0; i < 3; ++i) {
        for (MeshKind kind : kKinds) {
          const auto a = InvoluteOverlaps(nominal, p0, i, kind);
          const auto b = InvoluteOverlaps(with, p0, i, kind);
          const auto c = InvoluteOverlaps(with, p1, i, kind);
          const double expected = involved(i, kind) ? e.ds / 2 : 0.0;
          INFO(e.gear << ": planet " << i + 1 << (kind == MeshKind::kSunPlanet ? " sun" : " ring")
                      << " mesh, carrier " << phi);
          std::map<int, std::pair<double, int>> by_side;  // σ_A → (sum of changes, count)
          for (const auto& [key, overlap] : a) {
            const auto it = b.find(key);
            if (it != b.end()) {
              CHECK(it->second - overlap == Approx(expected).epsilon(0).margin(1e-12));
              worst = std::max(worst, std::abs(it->second - overlap - expected));
              ++matched;
            }
            const auto jt = c.find(key);
            if (jt != c.end()) {
              auto& s = by_side[std::get<0>(key)];
              s.first += jt->second - overlap;
              ++s.second;
            }
          }
          REQUIRE(by_side.size() == 2);
          if (k == 0) {
            // How the alignment shares the error out (for the docs), where it is not zero.
            for (const auto& [side, change] : by_side) {
              const double mean = change.first / change.second;
              if (std::abs(mean) < 1e-12) continue;
              const int loaded = kind == MeshKind::kSunPlanet ? with.sun_mesh_side()
                                                              : with.ring_mesh_planet_side();
              std::string name = "thickness error ";
              name += e.gear;
              name += side == loaded ? ", stage's poses: loaded flanks of "
                                     : ", stage's poses: coast flanks of ";
              name +=
                  with.meshes()[static_cast<std::size_t>(2 * i + (kind == MeshKind::kPlanetRing))]
                      .name;
              FigureValue(name, mean / e.ds, "ds");
            }
          }
          const double sum =
              by_side[1].first / by_side[1].second + by_side[-1].first / by_side[-1].second;
          CHECK(sum == Approx(2 * expected).epsilon(0).margin(1e-12));
          worst_sum = std::max(worst_sum, std::abs(sum - 2 * expected));
        }
      }
    }
  }
  CHECK(matched >= 4 * 7 * 6 * 2);
  FigureValue("thickness error: worst |flank change - ds/2| at fixed poses (5 um)", worst, "m");
  FigureValue("thickness error: worst |loaded + coast change - ds| at the stage's poses", worst_sum,
              "m");
}
