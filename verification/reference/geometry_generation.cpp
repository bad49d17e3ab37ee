// Generated profiles against closed forms: the envelope of a rack's straight edge (or a shaper's
// involute) is the involute of the generated gear; its thickness at the reference circle is
// m(π/2 + 2x tan α); its curvature is 1/(r_b u).
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>

#include "epicycle/geometry/gear.hpp"
#include "epicycle/geometry/iso.hpp"
#include "figures.hpp"
#include "geometry_fixtures.hpp"

using namespace epicycle::geometry;
using epicycle::test::FigureValue;

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
  GearSpec g = epicycle::test::PaperStage().stage.ring;
  g.shaper = ShaperCutter{22, 0.1, 0, 0.05 * g.module};
  // The shaper's tip: addendum 1.25 m over its shifted reference line.
  g.shaper->tip_radius = g.module * (22 / 2.0 + 0.1 + 1.25);
  return g;
}

}  // namespace

TEST_CASE("rack-generated flanks are the analytic involute", "[reference][geometry]") {
  const auto scene = epicycle::test::PaperStage();
  for (const GearSpec& spec : {scene.stage.sun, scene.stage.planet}) {
    GearSpec s = spec;
    if (&spec == &scene.stage.planet) s.profile_shift = scene.fits[0].profile_shift;
    const Gear g(s);
    INFO(g.name());
    const double deviation = MaxNormalDeviation(g, 400);
    CHECK(deviation <= 1e-9);
    FigureValue("generated vs analytic involute, worst normal deviation, " + g.name(), deviation,
                "m");
    epicycle::test::VerifyRow("rack-generated flank of the " + g.name(), "analytic involute",
                              "worst normal deviation " + epicycle::test::Sci(deviation) + " m",
                              epicycle::test::Sci(deviation) + " m", "1e-9 m", deviation <= 1e-9);
  }
}

TEST_CASE("shaper-generated ring flank is the internal involute", "[reference][geometry]") {
  const Gear ring(ShaperRing());
  CHECK(ring.half_profile().Find(SegmentRole::kInvolute)->kind == SegmentKind::kShaperFlank);
  const double deviation = MaxNormalDeviation(ring, 400);
  CHECK(deviation <= 1e-9);
  FigureValue("shaper-generated vs internal involute, worst normal deviation, ring", deviation,
              "m");
  epicycle::test::VerifyRow("shaper-generated flank of the ring", "internal involute",
                            "worst normal deviation " + epicycle::test::Sci(deviation) + " m",
                            epicycle::test::Sci(deviation) + " m", "1e-9 m", deviation <= 1e-9);
}

TEST_CASE("generated involute curvature is 1/(r_b u)", "[reference][geometry]") {
  const auto scene = epicycle::test::PaperStage();
  double worst = 0;
  for (const Gear& g : {Gear(scene.stage.sun), Gear(ShaperRing())}) {
    const Segment* inv = g.half_profile().Find(SegmentRole::kInvolute);
    for (int i = 1; i < 20; ++i) {
      const double t = inv->t0 + (inv->t1 - inv->t0) * i / 20.0;
      const CurvePoint c = inv->Evaluate(t);
      const double u = InvoluteFlank::RollAtRadius(g.base_radius(), c.p.norm());
      INFO(g.name() << " t = " << t);
      CHECK(std::abs(c.Curvature()) == Approx(1.0 / (g.base_radius() * u)).epsilon(1e-9));
      worst = std::max(worst, std::abs(std::abs(c.Curvature()) * g.base_radius() * u - 1));
    }
  }
  FigureValue("involute curvature vs 1/(r_b u), worst relative error", worst, "");
}

TEST_CASE("tooth thickness at the reference circle is m(pi/2 + 2x tan a)",
          "[reference][geometry]") {
  const auto scene = epicycle::test::PaperStage();
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
    FigureValue("thickness at the reference circle, relative error, " + g.name(),
                std::abs(measured / expected - 1), "");
    epicycle::test::VerifyRow("tooth thickness at the reference circle, " + g.name(),
                              "m(pi/2 + 2x tan a)", epicycle::test::Sci(measured) + " m",
                              epicycle::test::Sci(std::abs(measured / expected - 1)) + " relative",
                              "1e-9", std::abs(measured / expected - 1) <= 1e-9);
  }
}

TEST_CASE("half profiles are continuous with tangent continuity at every join",
          "[unit][geometry]") {
  const auto scene = epicycle::test::PaperStage();
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
  const auto scene = epicycle::test::PaperStage();
  double worst1 = 0, worst2 = 0;
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
      worst1 = std::max(worst1, (c.d1 - d1).norm() / c.d1.norm());
      worst2 = std::max(worst2, (c.d2 - d2).norm() / c.d2.norm());
    }
  }
  FigureValue("envelope first derivative vs central difference, worst relative difference", worst1,
              "");
  FigureValue("envelope second derivative vs central difference, worst relative difference", worst2,
              "");
}

TEST_CASE("operating pressure angle and contact ratio from the layout equal ISO 21771",
          "[reference][geometry]") {
  const auto scene = epicycle::test::PaperStage(0.0);
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
  FigureValue("zero backlash: alpha_w from the line of action vs ISO, relative error, sun mesh",
              std::abs(ls.pressure_angle / aw_s - 1), "");
  FigureValue("zero backlash: alpha_w from the line of action vs ISO, relative error, ring mesh",
              std::abs(lr.pressure_angle / aw_r - 1), "");
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
    const double iso_eps =
        iso::ContactRatio(sun.base_radius(), sun.tip_form_radius(), P.base_radius(),
                          P.tip_form_radius(), ls.centre_distance, aw_s, sun.base_pitch(), false);
    CHECK(eps == Approx(iso_eps).epsilon(1e-9));
    FigureValue(
        "zero backlash: eps_alpha along the line of action vs ISO, relative error, "
        "sun mesh",
        std::abs(eps / iso_eps - 1), "");
  }
  {
    const double s_end = cut(lr, p.planets[0].geometric_centre, P.tip_form_radius())[1];
    const double s_start = cut(lr, p.ring.geometric_centre, R.tip_form_radius())[1];
    const double eps = (s_end - s_start) / P.base_pitch();
    const double iso_eps =
        iso::ContactRatio(P.base_radius(), P.tip_form_radius(), R.base_radius(),
                          R.tip_form_radius(), lr.centre_distance, aw_r, P.base_pitch(), true);
    CHECK(eps == Approx(iso_eps).epsilon(1e-9));
    FigureValue(
        "zero backlash: eps_alpha along the line of action vs ISO, relative error, "
        "ring mesh",
        std::abs(eps / iso_eps - 1), "");
  }
}

TEST_CASE("operating pressure angle and contact ratio of the real stage (0.15 mm backlash)",
          "[reference][geometry]") {
  // The scene as shipped: the planet and ring shifts fitted to 0.15 mm normal backlash at the
  // carrier radius a = m(z_r − z_p)/2, so α_w follows from the actual centre distance,
  // cos α_w = (r_b1 ± r_b2)/a, not from the zero-backlash involute function. ISO 21771, written
  // out here with r_b = m z cos α/2, p_b = π m cos α and the tip circles of the scene's blanks
  // (r + (x + 1) m; the ring's inner tip r + (x − 1) m):
  //   external ε_α = [√(r_a1² − r_b1²) + √(r_a2² − r_b2²) − a sin α_w]/p_b,
  //   internal ε_α = [√(r_a1² − r_b1²) − √(r_a2² − r_b2²) + a sin α_w]/p_b.
  const auto scene = epicycle::test::PaperStage();
  const Stage st(scene.stage);
  const StageSpec& s = scene.stage;
  const double m = s.sun.module, alpha = s.sun.pressure_angle, a = s.carrier_radius;
  REQUIRE(a == Approx(86.715e-3).epsilon(1e-12));
  REQUIRE(scene.fits.size() == 2);
  REQUIRE(scene.fits[0].normal_backlash == Approx(150e-6).epsilon(1e-12));
  const double zs = s.sun.teeth, zp = s.planet.teeth, zr = s.ring.teeth;
  const double xs = s.sun.profile_shift, xp = scene.fits[0].profile_shift,
               xr = scene.fits[1].profile_shift;
  const double rbs = m * zs * std::cos(alpha) / 2, rbp = m * zp * std::cos(alpha) / 2,
               rbr = m * zr * std::cos(alpha) / 2;
  const double ras = m * zs / 2 + (xs + 1) * m, rap = m * zp / 2 + (xp + 1) * m,
               rar = m * zr / 2 + (xr - 1) * m;
  const double pb = kPi * m * std::cos(alpha);
  const double aw_s = std::acos((rbs + rbp) / a), aw_r = std::acos((rbr - rbp) / a);
  const double eps_s =
      (std::sqrt(ras * ras - rbs * rbs) + std::sqrt(rap * rap - rbp * rbp) - a * std::sin(aw_s)) /
      pb;
  const double eps_r =
      (std::sqrt(rap * rap - rbp * rbp) - std::sqrt(rar * rar - rbr * rbr) + a * std::sin(aw_r)) /
      pb;
  // The scene's own statement: the ring mesh at the tool pressure angle, the sun mesh at 27.85°.
  CHECK(aw_r == Approx(alpha).epsilon(1e-12));
  CHECK(aw_s * 180 / kPi == Approx(27.85).margin(0.005));
  // The blanks the stage made are the ones assumed above.
  CHECK(st.sun().tip_radius() == Approx(ras).epsilon(1e-12));
  CHECK(st.planet(0).tip_radius() == Approx(rap).epsilon(1e-12));
  CHECK(st.ring().tip_radius() == Approx(rar).epsilon(1e-12));
  double worst_aw = 0, worst_eps = 0, worst_loa_aw = 0, worst_loa_eps = 0;
  for (int i = 0; i < st.planets(); ++i) {
    for (int k = 0; k < 2; ++k) {
      const MeshSummary& mesh = st.meshes()[2 * i + k];
      const double aw = k == 0 ? aw_s : aw_r, eps = k == 0 ? eps_s : eps_r;
      INFO(mesh.name);
      CHECK(mesh.kind == (k == 0 ? MeshKind::kSunPlanet : MeshKind::kPlanetRing));
      CHECK(mesh.centre_distance == Approx(a).epsilon(1e-15));
      CHECK(mesh.pressure_angle == Approx(aw).epsilon(1e-9));
      CHECK(mesh.contact_ratio_iso == Approx(eps).epsilon(1e-9));
      worst_aw = std::max(worst_aw, std::abs(mesh.pressure_angle / aw - 1));
      worst_eps = std::max(worst_eps, std::abs(mesh.contact_ratio_iso / eps - 1));
    }
  }
  // The same from the geometry: the line of action built from the posed gears at several carrier
  // angles, and the length of it between the two tip circles.
  auto cut = [](const LineOfAction& l, const Vec2& c, double radius) {
    const Vec2 q = l.tangent_a - c;
    const double b = q.dot(l.direction), cc = q.squaredNorm() - radius * radius;
    return std::array<double, 2>{-b - std::sqrt(b * b - cc), -b + std::sqrt(b * b - cc)};
  };
  for (int k = 0; k < 5; ++k) {
    const StagePoses p = st.Poses(0.37 * k);
    for (int i = 0; i < st.planets(); ++i) {
      const LineOfAction ls =
          MakeLineOfAction(st.Sun(p), st.Planet(p, i), false, st.sun_mesh_side());
      const LineOfAction lr =
          MakeLineOfAction(st.Planet(p, i), st.Ring(p), true, st.ring_mesh_planet_side());
      CHECK(ls.pressure_angle == Approx(aw_s).epsilon(1e-9));
      CHECK(lr.pressure_angle == Approx(aw_r).epsilon(1e-9));
      const double es = (cut(ls, p.sun.geometric_centre, ras)[1] -
                         cut(ls, p.planets[i].geometric_centre, rap)[0]) /
                        pb;
      const double er = (cut(lr, p.planets[i].geometric_centre, rap)[1] -
                         cut(lr, p.ring.geometric_centre, rar)[1]) /
                        pb;
      CHECK(es == Approx(eps_s).epsilon(1e-9));
      CHECK(er == Approx(eps_r).epsilon(1e-9));
      worst_loa_aw = std::max({worst_loa_aw, std::abs(ls.pressure_angle / aw_s - 1),
                               std::abs(lr.pressure_angle / aw_r - 1)});
      worst_loa_eps = std::max({worst_loa_eps, std::abs(es / eps_s - 1), std::abs(er / eps_r - 1)});
    }
  }
  FigureValue("0.15 mm backlash: alpha_w (Stage::meshes) vs closed form, worst relative error",
              worst_aw, "");
  FigureValue(
      "0.15 mm backlash: eps_alpha ISO (Stage::meshes) vs closed form, worst relative "
      "error",
      worst_eps, "");
  FigureValue("0.15 mm backlash: alpha_w from the line of action, worst relative error",
              worst_loa_aw, "");
  FigureValue("0.15 mm backlash: eps_alpha along the line of action, worst relative error",
              worst_loa_eps, "");
  FigureValue("0.15 mm backlash: alpha_w sun mesh", aw_s * 180 / kPi, "deg");
  FigureValue("0.15 mm backlash: eps_alpha ISO sun mesh", eps_s, "");
  FigureValue("0.15 mm backlash: eps_alpha ISO ring mesh", eps_r, "");
  epicycle::test::VerifyRow(
      "paper stage (0.15 mm backlash): operating pressure angles of all meshes",
      "cos a_w = (r_b1 +- r_b2)/a", "27.846 / 25.000 deg",
      epicycle::test::Sci(worst_aw) + " relative", "1e-9", worst_aw <= 1e-9);
  epicycle::test::VerifyRow("paper stage (0.15 mm backlash): contact ratios of all meshes",
                            "ISO 21771 from the tip circles",
                            epicycle::test::Sci(eps_s) + " / " + epicycle::test::Sci(eps_r),
                            epicycle::test::Sci(worst_eps) + " relative", "1e-9",
                            worst_eps <= 1e-9);
}
