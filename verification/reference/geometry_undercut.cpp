// Undercut teeth are generated as the rack cuts them (docs/model.md §3). References written here,
// independently of the library's envelope formulas:
//  - the cut flank is the lower envelope of the area swept by the rack's outline (straight edge,
//    tip round, tip line), placed at thousands of rolling positions and intersected with circles
//    in the gear frame;
//  - the radius where involute and undercut fillet meet is where the closed-form involute leaves
//    the area swept by the rack's tip round (distance to the round-centre trochoid = ρ), found by
//    bisection.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "epicycle/geometry/gear.hpp"
#include "figures.hpp"

using namespace epicycle::geometry;
using epicycle::test::Sci;
using epicycle::test::VerifyRow;

namespace {

// ISO 53 profile A as a cutter: α = 20°, tool addendum 1.25 m, tip round 0.38 m, the tips at the
// tool's reach r + x m + m.
GearSpec StandardRackGear(int z, double x) {
  GearSpec g;
  g.name = "gear";
  g.teeth = z;
  g.module = 4e-3;
  g.face_width = 20e-3;
  g.pressure_angle = Rad(20.0);
  g.profile_shift = x;
  g.hub_radius = 0.3 * g.module * z / 2;
  g.rack = RackCutter{1.25 * g.module, 1.0 * g.module, 0.38 * g.module};
  return g;
}

// The rack in the fixed frame at generating roll φ: the gear turns by φ about the origin, the
// rack's rolling line is tangent to the pitch circle r at I = (r, 0) and moves r φ along +y. The
// cutter half-tooth that cuts the σ = +1 flank of tooth 0: straight edge (material on the side
// (p − I)·n ≥ t, n = (sin α, cos α)), tip round (centre C, radius ρ), tip line ξ = ξ_tip.
struct Rack {
  double r, alpha, m, x, ha, rho;
  double FlankOffset() const { return kPi * m / 4 + x * m * std::tan(alpha); }
  double Xi_c() const { return r + x * m - ha + rho; }
  double Eta_c() const {  // the round touches the edge and the tip line
    const double sa = std::sin(alpha), ca = std::cos(alpha);
    return (rho + kPi * m / 4 * ca - (-ha + rho) * sa) / ca;
  }
  // Smallest gear-frame polar angle of the outline at radius R, rolled by φ (+∞ if none).
  double MinAngle(double R, double phi) const {
    const double sa = std::sin(alpha), ca = std::cos(alpha);
    const Vec2 n(sa, ca), I(r, 0);
    const double t = ca * (FlankOffset() + r * phi);
    const Vec2 c(Xi_c(), Eta_c() + r * phi);
    const double xi_t = c.x() - rho * sa;  // edge/round tangency
    const double xi_tip = c.x() - rho;
    const double eta_mid = kPi * m / 2 + r * phi;
    double best = std::numeric_limits<double>::infinity();
    auto take = [&](const Vec2& p) { best = std::min(best, std::atan2(p.y(), p.x()) - phi); };
    // Edge: p = I + t n + s e, e = (cos α, −sin α) along the edge; |p| = R.
    {
      const Vec2 e(ca, -sa), q = I + t * n;
      const double b = q.dot(e), cc = q.squaredNorm() - R * R, disc = b * b - cc;
      if (disc >= 0) {
        for (double s : {-b - std::sqrt(disc), -b + std::sqrt(disc)}) {
          const Vec2 p = q + s * e;
          if (p.x() >= xi_t && p.y() <= eta_mid) take(p);
        }
      }
    }
    // Tip round: circle–circle intersection, kept on the arc between the tangencies (polar angle
    // about C in [π, 3π/2 − α]).
    {
      const double d = c.norm();
      const double a = (R * R - rho * rho + d * d) / (2 * d), h2 = R * R - a * a;
      if (h2 >= 0) {
        const Vec2 u = c / d, v(-u.y(), u.x());
        for (double sgn : {-1.0, 1.0}) {
          const Vec2 p = a * u + sgn * std::sqrt(h2) * v;
          double w = std::atan2((p - c).y(), (p - c).x());
          if (w < 0) w += 2 * kPi;
          if (w >= kPi - 1e-12 && w <= 1.5 * kPi - alpha + 1e-12) take(p);
        }
      }
    }
    // Tip line ξ = ξ_tip, from the round's tangency to the half-tooth's middle.
    if (R > xi_tip) {
      for (double sgn : {-1.0, 1.0}) {
        const Vec2 p(xi_tip, sgn * std::sqrt(R * R - xi_tip * xi_tip));
        if (p.y() >= c.y() && p.y() <= eta_mid) take(p);
      }
    }
    return best;
  }
  // The lower envelope: min over rolling positions (a grid of `n` positions, then golden-section
  // refinement around the best one so that the grid's spacing does not limit the accuracy).
  double EnvelopeAngle(double R, int n) const {
    const double lo = -1.2, hi = 0.6;
    double best = std::numeric_limits<double>::infinity(), arg = 0;
    for (int i = 0; i <= n; ++i) {
      const double phi = lo + (hi - lo) * i / n;
      const double v = MinAngle(R, phi);
      if (v < best) best = v, arg = phi;
    }
    double a = arg - (hi - lo) / n, b = arg + (hi - lo) / n;
    const double g = (std::sqrt(5.0) - 1) / 2;
    for (int it = 0; it < 100; ++it) {
      const double c1 = b - g * (b - a), c2 = a + g * (b - a);
      if (MinAngle(R, c1) < MinAngle(R, c2)) {
        b = c2;
      } else {
        a = c1;
      }
    }
    return std::min(best, MinAngle(R, 0.5 * (a + b)));
  }
};

// The generated half profile's polar angle at radius R (fillet or involute segment; bisection on
// the segment parameter, radius monotone on each).
double ProfileAngle(const Gear& g, double R) {
  for (const Segment& s : g.half_profile().segments) {
    if (s.role != SegmentRole::kFillet && s.role != SegmentRole::kInvolute) continue;
    double a = s.t0, b = s.t1;
    const double ra = s.Point(a).norm(), rb = s.Point(b).norm();
    if ((R - ra) * (R - rb) > 0) continue;
    for (int it = 0; it < 200; ++it) {
      const double mid = 0.5 * (a + b);
      ((s.Point(mid).norm() - R) * (rb - ra) < 0 ? a : b) = mid;
    }
    const Vec2 p = s.Point(0.5 * (a + b));
    return std::atan2(p.y(), p.x());
  }
  return std::numeric_limits<double>::quiet_NaN();
}

// Where the closed-form involute leaves the area swept by the tip round: the distance from the
// involute point at radius R to the round-centre trochoid C(φ) = R(−φ)(ξ_c, η_c + r φ) equals ρ.
double UndercutRadiusByBisection(const Rack& k, double rb, double theta0, double r_hi) {
  auto inv_point = [&](double R) {
    const double aR = std::acos(rb / R), polar = theta0 - (std::tan(aR) - aR);
    return Vec2(R * std::cos(polar), R * std::sin(polar));
  };
  auto distance = [&](double R) {
    const Vec2 p = inv_point(R);
    auto d = [&](double phi) {
      const Vec2 c(k.Xi_c(), k.Eta_c() + k.r * phi);
      const Vec2 cg = Rotate(c, -phi);
      return (p - cg).norm();
    };
    double best = 1e9, arg = 0;
    for (int i = 0; i <= 4000; ++i) {
      const double phi = -1.2 + 1.8 * i / 4000;
      if (d(phi) < best) best = d(phi), arg = phi;
    }
    double a = arg - 1.8 / 4000, b = arg + 1.8 / 4000;
    const double g = (std::sqrt(5.0) - 1) / 2;
    for (int it = 0; it < 100; ++it) {
      const double c1 = b - g * (b - a), c2 = a + g * (b - a);
      (d(c1) < d(c2) ? b : a) = (d(c1) < d(c2) ? c2 : c1);
    }
    return d(0.5 * (a + b)) - k.rho;
  };
  double lo = rb * (1 + 1e-9), hi = r_hi;  // cut at the base circle, uncut at the pitch circle
  REQUIRE(distance(lo) < 0);
  REQUIRE(distance(hi) > 0);
  for (int it = 0; it < 100; ++it) {
    const double mid = 0.5 * (lo + hi);
    (distance(mid) < 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

TEST_CASE("undercut teeth: the generated flank is the rack's swept envelope",
          "[reference][geometry]") {
  for (const auto& [z, x] : {std::pair{12, 0.0}, std::pair{17, 0.0}}) {
    const GearSpec spec = StandardRackGear(z, x);
    const Gear g(spec);
    INFO("z = " << z);
    REQUIRE(g.undercut());
    CHECK(g.MinimumShiftWithoutUndercut() > x);
    const Rack k{g.reference_radius(), spec.pressure_angle,  spec.module, x,
                 spec.rack->addendum,  spec.rack->tip_radius};
    // Compare between the fillet's lower part (0.05 m above the root, where the profile leaves the
    // root circle steeply) and the tip-form circle. R·Δθ is the distance along the circle, an
    // upper bound of the normal distance between the curves.
    double worst = 0;
    const int samples = 120;
    const double r0 = g.root_radius() + 0.05 * spec.module, r1 = g.tip_form_radius();
    for (int i = 0; i <= samples; ++i) {
      const double R = r0 + (r1 - r0) * i / samples;
      const double model = ProfileAngle(g, R);
      const double brute = k.EnvelopeAngle(R, 3000);
      worst = std::max(worst, R * std::abs(model - brute));
    }
    // 1e-8 m: the bound; the envelope's own error is round-off after golden-section
    // refinement (≈ 1e-12 m), the profile's that of the bisection on its crossing.
    CHECK(worst <= 1e-8);
    const double theta0 = g.involute().start;
    const double ref = UndercutRadiusByBisection(k, g.base_radius(), theta0, g.reference_radius());
    const double err = std::abs(g.undercut_radius() - ref);
    CHECK(err <= 1e-9);  // two bisections to round-off; the golden-section minimum is exact to
                         // ~1e-13 m in distance, moving the root by less than that over its slope
    CHECK(g.form_radius() == g.undercut_radius());
    VerifyRow(
        "undercut z = " + std::to_string(z) + ", x = 0 (ISO 53 A rack): flank vs swept envelope",
        "brute-force envelope, 3000 rack positions", "generated profile", Sci(worst) + " m",
        "1e-8 m", worst <= 1e-8);
    VerifyRow("undercut z = " + std::to_string(z) + ": radius where involute meets fillet",
              Sci(ref * 1e3, 9) + " mm (root-find)", Sci(g.undercut_radius() * 1e3, 9) + " mm",
              Sci(err) + " m", "1e-9 m", err <= 1e-9);
  }
}
