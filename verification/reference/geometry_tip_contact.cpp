// Off-line-of-action contacts: a tip round against a flank. The contact normal must pass through
// the round's centre, and the overlap must equal the distance found by brute force on a dense
// polyline of the mating flank.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string>

#include "epicycle/geometry/stage.hpp"
#include "figures.hpp"
#include "geometry_fixtures.hpp"

using namespace epicycle::geometry;
using epicycle::test::FigureValue;

namespace {

// The involute segment of tooth k, side σ, of a posed gear, as a dense polyline in the inertial
// frame.
std::vector<Vec2> DenseFlank(const PosedGear& g, int tooth, int side, int n) {
  const Segment* s = g.gear->half_profile().Find(SegmentRole::kInvolute);
  std::vector<Vec2> out;
  const double turn = g.pose.rotation + tooth * g.gear->pitch_angle();
  for (int i = 0; i <= n; ++i) {
    Vec2 p = s->Point(s->t0 + (s->t1 - s->t0) * i / n);
    p.y() *= side;
    out.push_back(g.pose.geometric_centre + Rotate(p, turn));
  }
  return out;
}

double DistanceToPolyline(const Vec2& c, const std::vector<Vec2>& line) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    const Vec2 ab = line[i + 1] - line[i];
    const double t = std::clamp((c - line[i]).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (line[i] + t * ab - c).norm());
  }
  return best;
}

Vec2 TipRoundCentre(const PosedGear& g, int tooth, int side) {
  Vec2 c = g.gear->tip_round().centre;
  c.y() *= side;
  return g.pose.geometric_centre + Rotate(c, g.pose.rotation + tooth * g.gear->pitch_angle());
}

}  // namespace

TEST_CASE("tip round against flank: normal through the round's centre, brute-force overlap",
          "[reference][geometry]") {
  const auto scene = epicycle::test::PaperStage();
  const Stage st(scene.stage);
  ContactSearchOptions opt;
  opt.gap_window = 100e-6;
  int tested_a = 0, tested_b = 0;
  double worst = 0, worst_normal = 0;
  for (int k = 0; k < 40 && (tested_a < 6 || tested_b < 6); ++k) {
    const StagePoses p = st.Poses(st.mesh_cycle() * k / 40.0);
    epicycle::test::ForEachStageContact(
        st, p, opt,
        [&](const PosedGear& a, const PosedGear& b, MeshKind kind, const PotentialContact& c) {
          if (c.kind == ContactKind::kInvolute) return;
          const bool on_a = c.kind == ContactKind::kTipRoundA;
          const PosedGear& round_owner = on_a ? a : b;
          const PosedGear& flank_owner = on_a ? b : a;
          const double rho = round_owner.gear->tip_round().radius;
          const Vec2 centre =
              TipRoundCentre(round_owner, on_a ? c.tooth_a : c.tooth_b, on_a ? c.side_a : c.side_b);
          const Vec2 on_flank = on_a ? c.point_b : c.point_a;
          const Vec2 on_round = on_a ? c.point_a : c.point_b;
          // The common normal passes through the centre of the round.
          CHECK(std::abs(Cross(centre - on_flank, c.normal)) <= 1e-12);
          worst_normal = std::max(worst_normal, std::abs(Cross(centre - on_flank, c.normal)));
          CHECK((on_round - centre).norm() == Approx(rho).epsilon(1e-12));
          // Brute force: distance from the centre to the mate's flank as a dense polyline.
          const auto flank = DenseFlank(flank_owner, on_a ? c.tooth_b : c.tooth_a,
                                        on_a ? c.side_b : c.side_a, 20000);
          const double overlap = rho - DistanceToPolyline(centre, flank);
          worst = std::max(worst, std::abs(overlap - c.overlap));
          CHECK(c.overlap == Approx(overlap).margin(1e-8));
          // Off the line of action: the normal is not the pair's line-of-action direction.
          const LineOfAction l = MakeLineOfAction(a, b, kind == MeshKind::kPlanetRing, c.side_a);
          CHECK(std::abs(Cross(c.normal, l.direction)) > 1e-6);
          (on_a ? tested_a : tested_b)++;
        });
  }
  CHECK(tested_a >= 6);
  CHECK(tested_b >= 6);
  CHECK(worst <= 1e-8);
  FigureValue("tip round vs flank: contacts checked", tested_a + tested_b, "");
  FigureValue("tip round vs flank: worst distance of the normal from the round's centre",
              worst_normal, "m");
  FigureValue("tip round vs flank: worst |overlap - brute force (20 000-point polyline)|", worst,
              "m");
  epicycle::test::VerifyRow("tip round against flank, off the line of action (" +
                                std::to_string(tested_a + tested_b) + " contacts)",
                            "dense-polyline distance (20 000 points)",
                            "worst difference " + epicycle::test::Sci(worst) + " m",
                            epicycle::test::Sci(worst) + " m", "1e-8 m", worst <= 1e-8);
}

TEST_CASE("the tip rounds tried are all that can touch (against trying every tooth)",
          "[reference][geometry]") {
  // With errors that move the centres and turn the gears off their kinematic phase; the exhaustive
  // search also skips the pre-filter of the rounds tried (contact.cpp, FlankReach), whose window
  // is wider for a relieved mate and for teeth turned by pitch deviations: once more with those.
  // Relief and pitch deviations as a scene sets them (test::AddReliefAndPitchDeviations).
  for (const bool relieved : {false, true}) {
    auto scene = epicycle::test::PaperStage();
    if (relieved) epicycle::test::AddReliefAndPitchDeviations(scene.stage);
    REQUIRE((scene.stage.planet.modification.tip.amount > 0) == relieved);
    scene.stage.planet_runouts.assign(3, Runout{});
    scene.stage.planet_runouts[0] = Runout{40e-6, 1.0};
    scene.stage.pin_errors.assign(3, PinError{});
    scene.stage.pin_errors[2] = PinError{30e-6, -50e-6};
    scene.stage.sun_runout = Runout{25e-6, 2.0};
    const Stage st(scene.stage);
    ContactSearchOptions fast, all;
    fast.gap_window = all.gap_window = 150e-6;
    all.exhaustive_tips = true;
    int tips = 0;
    for (int k = 0; k < 97; ++k) {
      const StagePoses p = st.Poses(st.mesh_cycle() * k * 0.37);
      for (int i = 0; i < st.planets(); ++i) {
        for (MeshKind kind : {MeshKind::kSunPlanet, MeshKind::kPlanetRing}) {
          const auto a = st.Contacts(p, i, kind, fast), b = st.Contacts(p, i, kind, all);
          REQUIRE(a.size() == b.size());
          for (std::size_t j = 0; j < a.size(); ++j) {
            CHECK(a[j].overlap == b[j].overlap);
            tips += a[j].kind != ContactKind::kInvolute;
          }
        }
      }
    }
    CHECK(tips > 100);
    FigureValue(std::string("tip rounds tried vs every tooth: tip contacts compared") +
                    (relieved ? " (relief, pitch deviations)" : ""),
                tips, "");
  }
}
