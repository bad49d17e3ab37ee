// Generated profiles against closed forms: the envelope of a rack's straight edge (or a shaper's
// involute) is the involute of the generated gear; its thickness at the reference circle is
// m(π/2 + 2x tan α); its curvature is 1/(r_b u).
#include <catch2/catch.hpp>

#include <cmath>

#include "epicycle/geometry/gear.hpp"
#include "epicycle/geometry/iso.hpp"
#include "stage_fixtures.hpp"

using namespace epicycle::geometry;

namespace {

// The analytic involute of the gear's σ = +1 flank, written out independently of the library:
// polar angle at radius R is ψ_ref ∓ (inv α − inv α_R) with ψ_ref = s/(2r), s from the closed form.
struct AnalyticFlank {
  double rb, psi_ref, alpha;
  bool internal;
  Vec2 AtRadius(double R) const {
    const double aR = std::acos(rb / R);
    const double inv_a = std::tan(alpha) - alpha, inv_R = std::tan(aR) - aR;
    const double polar = internal ? psi_ref - inv_a + inv_R : psi_ref + inv_a - inv_R;
    return R * Vec2(std::cos(polar), std::sin(polar));
  }
  // Unit normal of the involute at radius R: the generating line is tangent to the base circle.
  Vec2 NormalAtRadius(double R) const {
    const Vec2 p = AtRadius(R);
    const Vec2 q = AtRadius(R * (1 + 1e-7));
    const Vec2 t = (q - p).normalized();
    return Vec2(-t.y(), t.x());
  }
};

AnalyticFlank Analytic(const Gear& g) {
  const GearSpec& s = g.spec();
  const double r = g.reference_radius(), m = s.module, a = s.pressure_angle;
  const double sign = g.internal() ? -1.0 : 1.0;
  const double thickness = m * (kPi / 2 + sign * 2 * s.profile_shift * std::tan(a));
  return {r * std::cos(a), thickness / (2 * r), a, g.internal()};
}

double MaxNormalDeviation(const Gear& g, int samples) {
  const Segment* inv = g.half_profile().Find(SegmentRole::kInvolute);
  REQUIRE(inv != nullptr);
  const AnalyticFlank a = Analytic(g);
  double worst = 0;
  for (int i = 0; i <= samples; ++i) {
    const double t = inv->t0 + (inv->t1 - inv->t0) * i / samples;
    const Vec2 p = inv->Point(t);
    const double R = p.norm();
    worst = std::max(worst, std::abs((p - a.AtRadius(R)).dot(a.NormalAtRadius(R))));
  }
  return worst;
}

GearSpec ShaperRing() {
  GearSpec g = epicycle::test::PaperScene().stage.ring;
  g.shaper = ShaperCutter{22, 0.1, 0, 0.05 * g.module};
  // The shaper's tip: addendum 1.25 m over its shifted reference line.
  g.shaper->tip_radius = g.module * (22 / 2.0 + 0.1 + 1.25);
  return g;
}

}  // namespace

TEST_CASE("rack-generated flanks are the analytic involute", "[reference][geometry]") {
  const auto scene = epicycle::test::PaperScene();
  for (const GearSpec& spec : {scene.stage.sun, scene.stage.planet}) {
    GearSpec s = spec;
    if (&spec == &scene.stage.planet) s.profile_shift = scene.fits[0].profile_shift;
    const Gear g(s);
    INFO(g.name());
    CHECK(MaxNormalDeviation(g, 400) <= 1e-9);
  }
}

TEST_CASE("shaper-generated ring flank is the internal involute", "[reference][geometry]") {
  const Gear ring(ShaperRing());
  CHECK(ring.half_profile().Find(SegmentRole::kInvolute)->kind == SegmentKind::kShaperFlank);
  CHECK(MaxNormalDeviation(ring, 400) <= 1e-9);
}

TEST_CASE("generated involute curvature is 1/(r_b u)", "[reference][geometry]") {
  const auto scene = epicycle::test::PaperScene();
  for (const Gear& g : {Gear(scene.stage.sun), Gear(ShaperRing())}) {
    const Segment* inv = g.half_profile().Find(SegmentRole::kInvolute);
    for (int i = 1; i < 20; ++i) {
      const double t = inv->t0 + (inv->t1 - inv->t0) * i / 20.0;
      const CurvePoint c = inv->Evaluate(t);
      const double u = InvoluteFlank::RollAtRadius(g.base_radius(), c.p.norm());
      INFO(g.name() << " t = " << t);
      CHECK(std::abs(c.Curvature()) == Approx(1.0 / (g.base_radius() * u)).epsilon(1e-9));
    }
  }
}

TEST_CASE("tooth thickness at the reference circle is m(pi/2 + 2x tan a)",
          "[reference][geometry]") {
  const auto scene = epicycle::test::PaperScene();
  for (const GearSpec& s : {scene.stage.sun, scene.stage.planet, scene.stage.ring}) {
    const Gear g(s);
    // Find the generated involute's point at the reference radius by bisection on its parameter.
    const Segment* inv = g.half_profile().Find(SegmentRole::kInvolute);
    double lo = inv->t0, hi = inv->t1;
    const double r = g.reference_radius();
    const bool rising = inv->Point(hi).norm() > inv->Point(lo).norm();
    for (int k = 0; k < 200; ++k) {
      const double mid = 0.5 * (lo + hi);
      ((inv->Point(mid).norm() < r) == rising ? lo : hi) = mid;
    }
    const Vec2 p = inv->Point(0.5 * (lo + hi));
    const double measured = 2 * r * std::atan2(p.y(), p.x());
    const double sign = g.internal() ? -1.0 : 1.0;
    const double expected =
        s.module * (kPi / 2 + sign * 2 * s.profile_shift * std::tan(s.pressure_angle));
    INFO(g.name());
    CHECK(measured == Approx(expected).epsilon(1e-9));
  }
}

TEST_CASE("half profiles are continuous with tangent continuity at every join",
          "[unit][geometry]") {
  const auto scene = epicycle::test::PaperScene();
  for (const Gear& g : {Gear(scene.stage.sun), Gear(scene.stage.planet), Gear(scene.stage.ring),
                        Gear(ShaperRing())}) {
    const auto& segs = g.half_profile().segments;
    REQUIRE(segs.size() == 5);
    for (std::size_t i = 0; i + 1 < segs.size(); ++i) {
      const CurvePoint a = segs[i].Evaluate(segs[i].t1);
      const CurvePoint b = segs[i + 1].Evaluate(segs[i + 1].t0);
      INFO(g.name() << ": " << RoleName(segs[i].role) << " -> " << RoleName(segs[i + 1].role));
      CHECK((a.p - b.p).norm() <= 1e-9);
      // Tangent directions agree up to orientation (1e-6 rad: the joins are computed in closed
      // form).
      CHECK(std::abs(Cross(a.Tangent(), b.Tangent())) <= 1e-6);
    }
    // The half profile runs from the space centre line to the tooth centre line.
    CHECK(std::atan2(segs.front().Point(segs.front().t0).y(),
                     segs.front().Point(segs.front().t0).x()) ==
          Approx(kPi / g.teeth()).epsilon(1e-12));
    CHECK(segs.back().Point(segs.back().t1).y() == Approx(0).margin(1e-12));
  }
}

TEST_CASE("envelope derivatives are exact (against central differences)", "[unit][geometry]") {
  const auto scene = epicycle::test::PaperScene();
  for (const Gear& g : {Gear(scene.stage.sun), Gear(ShaperRing())}) {
    for (const Segment& s : g.half_profile().segments) {
      if (s.kind == SegmentKind::kArc) continue;
      const double t = 0.5 * (s.t0 + s.t1), h = 1e-5 * std::abs(s.t1 - s.t0);
      const CurvePoint c = s.Evaluate(t);
      const Vec2 d1 = (s.Point(t + h) - s.Point(t - h)) / (2 * h);
      const Vec2 d2 = (s.Point(t + h) - 2 * s.Point(t) + s.Point(t - h)) / (h * h);
      INFO(g.name() << " " << RoleName(s.role));
      CHECK((c.d1 - d1).norm() <= 1e-7 * c.d1.norm());
      CHECK((c.d2 - d2).norm() <= 1e-3 * c.d2.norm());
    }
  }
}

TEST_CASE("operating pressure angle and contact ratio from the layout equal ISO 21771",
          "[reference][geometry]") {
  const auto scene = epicycle::test::ZeroBacklashPaperScene();
  const Stage st(scene.stage);
  const StagePoses p = st.Poses(0.0);
  // Geometry: the line of action built from the actual centres; ISO: the closed forms.
  const LineOfAction ls = MakeLineOfAction(st.Sun(p), st.Planet(p, 0), false, st.sun_mesh_side());
  const LineOfAction lr =
      MakeLineOfAction(st.Planet(p, 0), st.Ring(p), true, st.ring_mesh_planet_side());
  const GearSpec& S = scene.stage.sun;
  const Gear& P = st.planet(0);
  const Gear& R = st.ring();
  const double aw_s = iso::ZeroBacklashPressureAngle(
      S.teeth, P.teeth(), S.profile_shift, P.spec().profile_shift, S.pressure_angle, false);
  const double aw_r = iso::ZeroBacklashPressureAngle(
      P.teeth(), R.teeth(), P.spec().profile_shift, R.spec().profile_shift, S.pressure_angle, true);
  CHECK(ls.pressure_angle == Approx(aw_s).epsilon(1e-9));
  CHECK(lr.pressure_angle == Approx(aw_r).epsilon(1e-9));
  // Contact ratio: where the tip-form circles cut the line of action, measured along it.
  auto cut = [](const LineOfAction& l, const Vec2& c, double radius) {
    // |N_A + s d − c| = radius: the root with the contact side.
    const Vec2 q = l.tangent_a - c;
    const double b = q.dot(l.direction), cc = q.squaredNorm() - radius * radius;
    return std::array<double, 2>{-b - std::sqrt(b * b - cc), -b + std::sqrt(b * b - cc)};
  };
  const Gear& sun = st.sun();
  {
    const double s_end = cut(ls, p.sun.geometric_centre, sun.tip_form_radius())[1];
    const double s_start = cut(ls, p.planets[0].geometric_centre, P.tip_form_radius())[0];
    const double eps = (s_end - s_start) / sun.base_pitch();
    CHECK(eps == Approx(iso::ContactRatio(sun.base_radius(), sun.tip_form_radius(), P.base_radius(),
                                          P.tip_form_radius(), ls.centre_distance, aw_s,
                                          sun.base_pitch(), false))
                     .epsilon(1e-9));
  }
  {
    const double s_end = cut(lr, p.planets[0].geometric_centre, P.tip_form_radius())[1];
    const double s_start = cut(lr, p.ring.geometric_centre, R.tip_form_radius())[1];
    const double eps = (s_end - s_start) / P.base_pitch();
    CHECK(eps == Approx(iso::ContactRatio(P.base_radius(), P.tip_form_radius(), R.base_radius(),
                                          R.tip_form_radius(), lr.centre_distance, aw_r,
                                          P.base_pitch(), true))
                     .epsilon(1e-9));
  }
}
