// The contact search with its tip rounds reused under a pose bound (geometry::TipRoundReuse,
// docs/dynamic_cost.md "Tip rounds reused under a pose bound") against the same search without
// reuse: along a motion of the paper's stage like an integrator's (small steps of the carrier,
// the members off their kinematic poses, steps taken back as after a rejected step), every mesh's
// contacts must be the same, field for field and in the same order. The reference is the search
// without reuse (verification/reference/geometry_tip_contact.cpp checks that one against trying
// every tooth); the tolerance is none: a round is only skipped where it provably cannot touch.
#include <cstring>
#include <random>
#include <tuple>
#include <vector>

#include <catch2/catch.hpp>

#include "geometry_fixtures.hpp"

using namespace epicycle::geometry;

namespace {

bool SameContact(const PotentialContact& a, const PotentialContact& b) {
  auto same = [](const Vec2& x, const Vec2& y) { return x.x() == y.x() && x.y() == y.y(); };
  return a.kind == b.kind && a.side_a == b.side_a && a.side_b == b.side_b &&
         a.tooth_a == b.tooth_a && a.tooth_b == b.tooth_b && same(a.point, b.point) &&
         same(a.point_a, b.point_a) && same(a.point_b, b.point_b) &&
         same(a.surface_a, b.surface_a) && same(a.surface_b, b.surface_b) &&
         same(a.normal, b.normal) && a.overlap == b.overlap && a.lever_a == b.lever_a &&
         a.lever_b == b.lever_b && a.curvature_radius_a == b.curvature_radius_a &&
         a.curvature_radius_b == b.curvature_radius_b && a.roll_a == b.roll_a &&
         a.roll_b == b.roll_b;
}

// Moves a pose by a rigid displacement: turned by dθ about its rotation centre, then shifted.
void Move(GearPose* p, double turn, const Vec2& shift) {
  p->geometric_centre = p->rotation_centre + Rotate(p->geometric_centre - p->rotation_centre, turn);
  p->rotation += turn;
  p->rotation_centre += shift;
  p->geometric_centre += shift;
}

struct Counts {
  long contacts = 0, tip_contacts = 0, refreshes = 0, reuses = 0, skipped = 0;
};

// `steps` poses per mesh cycle over `cycles` mesh cycles, each displaced by random deviations of
// up to `shift` [m] and `turn` [rad]; every 7th step goes back by 3 steps (a rejected step).
Counts Compare(const Stage& st, double window, double budget, int steps, double cycles,
               double shift, double turn) {
  ContactSearchOptions opt;
  opt.gap_window = window;
  std::vector<TipRoundReuse> reuse(static_cast<std::size_t>(2 * st.planets()));
  for (TipRoundReuse& r : reuse) r.budget = budget;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Counts n;
  const int total = static_cast<int>(steps * cycles);
  StagePoses p;
  std::vector<PotentialContact> plain, reused;
  for (int k = 0, s = 0; k < total; ++k, s += (k % 7 == 0 ? -3 : 1)) {
    st.Poses(st.mesh_cycle() * s / steps, &p);
    Move(&p.sun, turn * unit(rng), shift * Vec2(unit(rng), unit(rng)));
    for (GearPose& q : p.planets) Move(&q, turn * unit(rng), shift * Vec2(unit(rng), unit(rng)));
    for (int i = 0; i < st.planets(); ++i) {
      for (MeshKind kind : {MeshKind::kSunPlanet, MeshKind::kPlanetRing}) {
        plain.clear();
        reused.clear();
        st.AppendContacts(p, i, kind, opt, &plain);
        st.AppendContacts(p, i, kind, opt, &reused,
                          &reuse[static_cast<std::size_t>(MeshIndex(i, kind))]);
        REQUIRE(plain.size() == reused.size());
        for (std::size_t j = 0; j < plain.size(); ++j) {
          INFO("step " << k << ", planet " << i + 1 << ", mesh " << static_cast<int>(kind)
                       << ", contact " << j);
          REQUIRE(SameContact(plain[j], reused[j]));
          n.tip_contacts += plain[j].kind != ContactKind::kInvolute;
        }
        n.contacts += static_cast<long>(plain.size());
      }
    }
  }
  for (const TipRoundReuse& r : reuse) {
    n.refreshes += r.refreshes;
    n.reuses += r.reuses;
    n.skipped += r.skipped;
  }
  return n;
}

}  // namespace

TEST_CASE("tip rounds reused under a pose bound: the same contacts as the search without reuse",
          "[unit][geometry]") {
  // The paper's stage with run-outs and a pin error, and once more with relief and pitch
  // deviations (the filter's window is wider for a relieved mate and teeth turned by offsets).
  const auto errors = [](StageSpec& s) {
    s.planet_runouts.assign(3, Runout{});
    s.planet_runouts[0] = Runout{20e-6, 1.0};
    s.pin_errors.assign(3, PinError{});
    s.pin_errors[2] = PinError{30e-6, -50e-6};
    s.sun_runout = Runout{25e-6, 2.0};
  };
  for (const bool relieved : {false, true}) {
    auto scene = epicycle::test::PaperStage();
    errors(scene.stage);
    if (relieved) epicycle::test::AddReliefAndPitchDeviations(scene.stage);
    const Stage st(scene.stage);
    // As in a dynamic run (about 1200 steps a mesh cycle at 1500 rpm, deviations of micrometres),
    // and with coarse steps and deviations of 20 µm and 0.2 mrad that cross the budget often.
    for (const auto& [steps, shift, turn, budget] :
         std::vector<std::tuple<int, double, double, double>>{
             {600, 2e-6, 2e-5, 100e-6}, {40, 20e-6, 2e-4, 100e-6}, {300, 5e-6, 5e-5, 400e-6}}) {
      INFO("relieved " << relieved << ", " << steps << " steps a cycle, budget " << budget);
      const Counts n = Compare(st, 100e-6, budget, steps, 2.3, shift, turn);
      // Not vacuous: tip contacts were found; with fine steps most calls reused a refresh and
      // skipped rounds, with coarse ones (each step past the budget) every call refreshed.
      CHECK(n.tip_contacts > 50);
      if (steps >= 300) {
        CHECK(n.reuses > 5 * n.refreshes);
        CHECK(n.skipped > n.reuses);
      } else {
        CHECK(n.refreshes > 0);
      }
    }
  }
}
