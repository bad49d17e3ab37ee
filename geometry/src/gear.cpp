#include "epicycle/geometry/gear.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "messages.hpp"

namespace epicycle::geometry {

namespace {

// An arc from direction a0 to the direction a1 taken the short way round (|Δ| < π).
Segment Arc(SegmentRole role, const Vec2& centre, double radius, double a0, double a1,
            double rotation = 0) {
  Segment s;
  s.role = role;
  s.kind = SegmentKind::kArc;
  s.centre = centre;
  s.radius = radius;
  s.t0 = a0;
  s.t1 = a0 + WrapAngle(a1 - a0);
  s.rotation = rotation;
  return s;
}

}  // namespace

Gear::Gear(GearSpec spec) : spec_(std::move(spec)) {
  Validate();
  r_ = spec_.module * spec_.teeth / 2.0;
  rb_ = r_ * std::cos(spec_.pressure_angle);
  if (spec_.min_tip_thickness < 0) spec_.min_tip_thickness = 0.2 * spec_.module;
  if (internal()) {
    if (spec_.shaper) {
      BuildInternalShaper();
    } else {
      BuildInternalDirect();
    }
  } else {
    BuildExternal();
  }
  // Body checks that need the generated radii.
  if (!internal() && spec_.hub_radius >= rf_) {
    Fail(spec_.name, "hub_radius_mm", Mm(spec_.hub_radius),
         "must be below the root radius " + Mm(rf_) + " mm");
  }
  if (internal() && spec_.hub_radius <= rf_) {
    Fail(spec_.name, "rim_radius_mm", Mm(spec_.hub_radius),
         "must exceed the root radius " + Mm(rf_) + " mm");
  }
  const double sa = tip_thickness();
  if (sa < spec_.min_tip_thickness) {
    Fail(spec_.name, "tip_radius_mm", Mm(ra_),
         "pointed tooth: the tip thickness s_a = " + Mm(sa) + " mm is below the limit " +
             Mm(spec_.min_tip_thickness) + " mm (shorten the tip or reduce the profile shift)");
  }
  nominal_tip_round_ = tip_round_;
  BuildModifications();
}

ReliefValue Gear::ReliefZone::At(double u) const {
  if (!(amount > 0)) return {};
  const double span = u_end - u_start;
  const double xi = (u - u_start) / span;
  if (xi <= 0.0) return {};
  if (power == 1) return {amount * xi, amount / span, 0.0};
  return {amount * xi * xi, 2.0 * amount * xi / span, 2.0 * amount / (span * span)};
}

ReliefValue Gear::ReliefAt(double u) const {
  const ReliefValue t = tip_relief_.At(u), r = root_relief_.At(u);
  return {t.c + r.c, t.d1 + r.d1, t.d2 + r.d2};
}

void Gear::BuildModifications() {
  const std::string& n = spec_.name;
  // Pitch deviations: one cumulative deviation per tooth, an arc on the reference circle.
  const std::vector<double>& fp = spec_.pitch_deviations;
  if (!fp.empty()) {
    if (static_cast<int>(fp.size()) != spec_.teeth) {
      Fail(n, "pitch.deviations", std::to_string(fp.size()) + " entries",
           "needs one entry per tooth (" + std::to_string(spec_.teeth) + ")");
    }
    offsets_.resize(fp.size());
    for (std::size_t k = 0; k < fp.size(); ++k) {
      if (!std::isfinite(fp[k]) || std::abs(fp[k]) > 0.1 * spec_.module) {
        Fail(n, "pitch.deviations[" + std::to_string(k) + "]", Num(fp[k] * 1e6) + " um",
             "must be finite and below m/10 in magnitude");
      }
      offsets_[k] = fp[k] / r_;
      max_offset_ = std::max(max_offset_, std::abs(offsets_[k]));
    }
  }
  tooth_directions_.resize(spec_.teeth);
  for (int k = 0; k < spec_.teeth; ++k)
    tooth_directions_[k] = Dir(k * pitch_angle() + tooth_offset(k));
  // Reliefs: the zone must lie on the active involute, between the form circle and the tip-round
  // tangency, and leave the tooth a tip (the two flanks' reliefs together keep s_a ≥ s_a,min).
  const ProfileModification& mod = spec_.modification;
  const double r_lo = std::min(r_form_, r_tip_form_), r_hi = std::max(r_form_, r_tip_form_);
  const double u_tip = InvoluteFlank::RollAtRadius(rb_, ra_);
  const double u_form = internal() ? involute_.u_max : involute_.u_min;
  auto zone = [&](const Relief& r, const std::string& key, double u_end, ReliefZone* out) {
    if (!std::isfinite(r.amount) || r.amount < 0) {
      Fail(n, "modification." + key + "_relief_um", Num(r.amount * 1e6), "must be >= 0");
    }
    if (r.amount == 0) return;
    if (!(r.start_radius > r_lo && r.start_radius < r_hi)) {
      Fail(n, "modification." + key + "_relief_start_mm", Mm(r.start_radius),
           "must lie on the active involute, between " + Mm(r_lo) + " and " + Mm(r_hi) + " mm");
    }
    out->amount = r.amount;
    out->u_start = InvoluteFlank::RollAtRadius(rb_, r.start_radius);
    out->u_end = u_end;
    out->power = r.shape == ReliefShape::kLinear ? 1 : 2;
    // The relief tilts the flank by dC/ds (s the arc length, ds = r_b u du); above 0.05 rad it is
    // no longer a modification of the involute but another profile, outside what the contact
    // search's along-the-line-of-action normal assumes.
    const double slope =
        r.amount / (rb_ * std::abs(out->u_end - out->u_start) * std::min(out->u_start, out->u_end));
    if (slope > 0.05) {
      Fail(n, "modification." + key + "_relief_um", Num(r.amount * 1e6),
           "too large for its zone: the relieved flank's slope C/(arc length) = " + Num(slope) +
               " exceeds 0.05 rad (start the relief further from the " + key + " or reduce it)");
    }
  };
  zone(mod.tip, "tip", u_tip, &tip_relief_);
  zone(mod.root, "root", u_form, &root_relief_);
  if (tip_relief_.amount > 0 && root_relief_.amount > 0 &&
      (tip_relief_.u_start - root_relief_.u_start) * (u_tip - u_form) <= 0) {
    Fail(n, "modification.root_relief_start_mm", Mm(mod.root.start_radius),
         "the root relief must start nearer the root than the tip relief (" +
             Mm(mod.tip.start_radius) + " mm)");
  }
  if (tip_relief_.amount > 0) {
    const double margin = 0.5 * (tip_thickness() - spec_.min_tip_thickness);
    if (tip_relief_.amount > margin) {
      Fail(
          n, "modification.tip_relief_um", Num(tip_relief_.amount * 1e6),
          "larger than the tooth can take: the two flanks' relief would thin the tip below s_a,min "
          "(at most " +
              Num(margin * 1e6) + " um)");
    }
    RelieveTipRound();
  }
}

void Gear::RelieveTipRound() {
  const double rho = spec_.tip_round_radius;
  if (!(rho > 0)) return;
  // The relieved flank x(u) − C(u) n(u) and its outward normal (σ = +1, body frame):
  //   x′ = (r_b u + h C) e − C′ e⊥,  n = e⊥ rotated with the tangent.
  // The round of radius ρ tangent to it has its centre x − ρ n on the circle r_a ∓ ρ, as in
  // AddTip; found by bisection between the relief's start and the tip circle.
  const int h = involute_.hand;
  auto normal = [&](double u) -> Vec2 {
    const ReliefValue c = ReliefAt(u);
    const double b = involute_.start + h * u;
    const Vec2 t = (rb_ * u + h * c.c) * Dir(b) - c.d1 * DirPerp(b);
    return Vec2(-t.y(), t.x()).normalized();
  };
  auto point = [&](double u) -> Vec2 {
    return involute_.Point(u) - ReliefAt(u).c * DirPerp(involute_.start + h * u);
  };
  auto centre = [&](double u) -> Vec2 { return point(u) - rho * normal(u); };
  const double rc = internal() ? ra_ + rho : ra_ - rho;
  double lo = tip_relief_.u_start, hi = tip_relief_.u_end;  // relief start → tip circle
  const double f_lo = centre(lo).norm() - rc, f_hi = centre(hi).norm() - rc;
  if (f_lo * f_hi > 0) {
    Fail(spec_.name, "modification.tip_relief_um", Num(tip_relief_.amount * 1e6),
         "the relieved flank leaves no room for the tip round");
  }
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    ((centre(mid).norm() - rc) * f_lo > 0 ? lo : hi) = mid;
  }
  const double u_t = 0.5 * (lo + hi);
  const Vec2 c = centre(u_t);
  if (Angle(c) <= 0) {
    Fail(spec_.name, "modification.tip_relief_um", Num(tip_relief_.amount * 1e6),
         "pointed tooth: the relieved tip rounds of the two flanks meet at the tooth centre line");
  }
  (internal() ? involute_.u_min : involute_.u_max) = u_t;
  r_tip_form_ = involute_.Point(u_t).norm();
  const double tip_dir = internal() ? Angle(c) + kPi : Angle(c);
  tip_round_.centre = c;
  tip_round_.normal_from = Angle(normal(u_t));
  tip_round_.normal_to = tip_round_.normal_from + WrapAngle(tip_dir - tip_round_.normal_from);
}

void Gear::Validate() const {
  const std::string& n = spec_.name;
  if (spec_.teeth < 3) Fail(n, "teeth", std::to_string(spec_.teeth), "must be >= 3");
  RequirePositive(n, "module_mm", spec_.module);
  RequirePositive(n, "face_width_mm", spec_.face_width);
  if (!(spec_.pressure_angle > 0 && spec_.pressure_angle < Rad(45.0))) {
    Fail(n, "pressure_angle_deg", Num(Deg(spec_.pressure_angle)), "must be in (0, 45)");
  }
  if (!std::isfinite(spec_.profile_shift) || std::abs(spec_.profile_shift) > 2.0) {
    Fail(n, "profile_shift", Num(spec_.profile_shift), "must be a number in [-2, 2]");
  }
  if (!(spec_.tip_round_radius >= 0) || !std::isfinite(spec_.tip_round_radius)) {
    Fail(n, "tip_round_radius_mm", Mm(spec_.tip_round_radius), "must be >= 0");
  }
  if (!std::isfinite(spec_.thickness_error) ||
      std::abs(spec_.thickness_error) > 0.5 * spec_.module) {
    Fail(n, "thickness_error_um", Num(spec_.thickness_error * 1e6), "must be finite and below m/2");
  }
  if (internal()) {
    RequirePositive(n, "tip_radius_mm", spec_.tip_radius);
    RequirePositive(n, "rim_radius_mm", spec_.hub_radius);
    if (spec_.rack)
      Fail(n, "cutter", "rack", "an internal gear is cut by a shaper or defined directly");
    if (spec_.shaper) {
      const ShaperCutter& c = *spec_.shaper;
      if (c.teeth < 3) Fail(n, "shaper.teeth", std::to_string(c.teeth), "must be >= 3");
      if (c.teeth >= spec_.teeth) {
        Fail(n, "shaper.teeth", std::to_string(c.teeth),
             "must be below the ring's tooth count " + std::to_string(spec_.teeth));
      }
      RequirePositive(n, "shaper.tip_radius_mm", c.tip_radius);
      RequirePositive(n, "shaper.tip_round_radius_mm", c.tip_round_radius);
    } else {
      RequirePositive(n, "root_radius_mm", spec_.root_radius);
      RequirePositive(n, "root_round_radius_mm", spec_.root_round_radius);
      if (spec_.root_radius <= spec_.tip_radius) {
        Fail(n, "root_radius_mm", Mm(spec_.root_radius),
             "must exceed tip_radius_mm = " + Mm(spec_.tip_radius));
      }
    }
  } else {
    RequirePositive(n, "hub_radius_mm", spec_.hub_radius);
    if (!spec_.rack) Fail(n, "cutter", "none", "an external gear needs its rack cutter");
    if (spec_.shaper) Fail(n, "cutter", "shaper", "external gears are cut by a rack here");
    const RackCutter& c = *spec_.rack;
    RequirePositive(n, "cutter.addendum_per_module", c.addendum / spec_.module);
    RequirePositive(n, "cutter.dedendum_per_module", c.dedendum / spec_.module);
    if (!(c.tip_radius >= 0) || c.tip_radius >= c.addendum) {
      Fail(n, "cutter.tip_radius_per_module", Num(c.tip_radius / spec_.module),
           "must be >= 0 and below the tool addendum");
    }
    if (spec_.tip_radius < 0) Fail(n, "tip_radius_mm", Mm(spec_.tip_radius), "must be > 0");
  }
}

double Gear::MinimumShiftWithoutUndercut() const {
  if (internal()) return -2.0;
  const RackCutter& c = *spec_.rack;
  const double a = spec_.pressure_angle;
  return (c.addendum - c.tip_radius * (1.0 - std::sin(a))) / spec_.module -
         spec_.teeth * std::sin(a) * std::sin(a) / 2.0;
}

void Gear::BuildExternal() {
  const double m = spec_.module, x = spec_.profile_shift, a = spec_.pressure_angle;
  const double sa = std::sin(a), ca = std::cos(a), ta = std::tan(a);
  const RackCutter& c = *spec_.rack;
  const double rho = c.tip_radius;
  rf_ = r_ + x * m - c.addendum;
  const double reach = r_ + x * m + c.dedendum;
  ra_ = spec_.tip_radius > 0 ? spec_.tip_radius : reach;
  if (ra_ > reach * (1 + 1e-12)) {
    Fail(spec_.name, "tip_radius_mm", Mm(ra_),
         "exceeds the tool's reach r + x m + h_f0 = " + Mm(reach) +
             " mm (the cutter would cut the tip)");
  }
  if (rf_ <= 0) Fail(spec_.name, "profile_shift", Num(x), "gives a non-positive root radius");

  RackGeneration g;
  g.pitch_radius = r_;
  g.pressure_angle = a;
  g.flank_offset = kPi * m / 4.0 + x * m * ta;
  const double xi_c_rel = -c.addendum + rho;  // tip-round centre, relative to the reference line
  const double eta_c = (rho + kPi * m / 4.0 * ca - xi_c_rel * sa) / ca;
  const double xi_c = r_ + x * m + xi_c_rel;
  g.round_centre = Vec2(xi_c, eta_c);
  g.round_radius = rho;
  if (xi_c >= r_) {
    Fail(spec_.name, "profile_shift", Num(x),
         "too large for this cutter: its tip-round centre lies outside the rolling circle");
  }
  if (eta_c >= kPi * m / 2.0) {
    // The rack tooth's two tip rounds meet. Its width at the tip line, π m/2 − 2 h_a0 tan α, sets
    // the largest pressure angle, α_max = φ − asin(ρ/R) with R = |(h_a0 − ρ, π m/4)| and
    // φ = atan2(π m/4, h_a0 − ρ) (η_c = π m/2 there); above atan(π m/(4 h_a0)) no tip round fits.
    const double wide = c.addendum - rho, half = kPi * m / 4.0;
    const double a_max = std::atan2(half, wide) - std::asin(rho / std::hypot(wide, half));
    if (ta >= half / c.addendum)
      Fail(spec_.name, "pressure_angle_deg", Num(a * 180.0 / kPi),
           "too large for the rack cutter: with its addendum h_a0 = " + Num(c.addendum / m) +
               " m (cutter.addendum_per_module) its tooth is pointed (tip width π m/2 − 2 h_a0 "
               "tan α = " +
               Mm(2 * half - 2 * c.addendum * ta) + " mm); the tool needs α < " +
               Num(a_max * 180.0 / kPi) + "° with its tip round ρ = " + Num(rho / m) +
               " m, at most " + Num(std::atan(half / c.addendum) * 180.0 / kPi) + "° without one");
    // Else the round alone: η_c = π m/2 at ρ_max = (π m/4 cos α − h_a0 sin α)/(1 − sin α).
    Fail(spec_.name, "cutter.tip_radius_per_module", Num(rho / m),
         "too large: the tool's two tip rounds overlap; at α = " + Num(a * 180.0 / kPi) +
             "° with h_a0 = " + Num(c.addendum / m) + " m it must be below " +
             Num((half * ca - c.addendum * sa) / (1 - sa) / m));
  }
  // Undercut: the straight edge's lowest point (tangency with the tip round) reaches below the
  // interference point, where the line of action touches the base circle. The tooth is then
  // generated as cut (docs/model.md §1): the tip round's trochoid cuts into the involute, and the
  // profile is the involute down to where the trochoid crosses it, the trochoid below.
  const double xi_limit = xi_c - rho * sa;
  undercut_ = xi_limit < r_ * ca * ca - 1e-12 * r_;
  flank_turn_ = spec_.thickness_error / (2.0 * rb_);
  const double phi_root = -eta_c / r_;

  involute_.base_radius = rb_;
  involute_.start = g.flank_offset / r_ + Inv(a) + flank_turn_;
  involute_.hand = -1;
  double phi_fillet_top = ((xi_c - r_) / ta - eta_c) / r_;
  if (undercut_) phi_fillet_top = UndercutCrossing(g, phi_root, phi_fillet_top);

  half_.segments.clear();
  half_.segments.push_back(
      Arc(SegmentRole::kRootLand, Vec2::Zero(), rf_, kPi / spec_.teeth, eta_c / r_, flank_turn_));
  Segment fillet;
  fillet.role = SegmentRole::kFillet;
  fillet.kind = SegmentKind::kRackRound;
  fillet.rack = g;
  fillet.t0 = phi_root;
  fillet.t1 = phi_fillet_top;
  fillet.rotation = flank_turn_;
  half_.segments.push_back(fillet);
  Segment flank = fillet;
  flank.role = SegmentRole::kInvolute;
  flank.kind = SegmentKind::kRackFlank;
  // Without undercut the fillet meets the flank tangentially at the same generating roll; with
  // undercut they cross at a corner, and the flank's roll follows from the crossing's radius R:
  // the rack's contact point I + t n has |I + t n|² = R², t = −r sin α + √(R² − r_b²) on the
  // involute's outer branch.
  if (undercut_) {
    r_form_ = fillet.Point(phi_fillet_top).norm();
    flank.t0 =
        (-r_ * sa + std::sqrt(r_form_ * r_form_ - rb_ * rb_)) / (r_ * ca) - g.flank_offset / r_;
  } else {
    flank.t0 = phi_fillet_top;
    r_form_ = flank.Point(phi_fillet_top).norm();
  }
  involute_.u_min = InvoluteFlank::RollAtRadius(rb_, r_form_);
  AddTip();
  // The involute ends where the tip round begins: invert radius(φ) of the rack's contact point,
  // |I + t n|² = r² + 2 r t sin α + t² = R².
  const double t_end = -r_ * sa + std::sqrt(r_tip_form_ * r_tip_form_ - rb_ * rb_);
  flank.t1 = t_end / (r_ * ca) - g.flank_offset / r_;
  half_.segments.insert(half_.segments.begin() + 2, flank);
}

double Gear::UndercutCrossing(const RackGeneration& g, double phi_root, double phi_top) const {
  // Which side of the involute a fillet point at radius R > r_b lies on: its polar angle minus the
  // involute's at the same radius, θ0 − inv α_R for the σ = +1 flank (negative: inside the tooth).
  // From the root the trochoid of the tool's tip round climbs through the base circle inside the
  // tooth (the undercut pocket), then leaves the tooth across the involute: that crossing is where
  // the involute ends and the undercut fillet begins. Past the straight edge's end (φ_top) the
  // round keeps cutting: its envelope continues there (the whole round lies inside the tool), so
  // the scan runs on up to three times the fillet's nominal range. A scan brackets the crossing,
  // bisection finds it to round-off.
  Segment fillet;
  fillet.kind = SegmentKind::kRackRound;
  fillet.rack = g;
  const double theta0 = involute_.start - flank_turn_;
  auto side = [&](double phi, double* radius) {
    const Vec2 p = fillet.Point(phi);
    *radius = p.norm();
    const double u = InvoluteFlank::RollAtRadius(rb_, *radius);  // 0 inside the base circle
    return Angle(p) - (theta0 - (u - std::atan(u)));
  };
  // 1. Where the trochoid passes the base circle (its radius grows along this range).
  constexpr int kScan = 6000;
  const double span = 3.0 * (phi_top - phi_root);
  double radius = 0, lo = phi_root, hi = phi_root;
  bool passed = false;
  for (int i = 1; i <= kScan && !passed; ++i) {
    hi = phi_root + span * i / kScan;
    side(hi, &radius);
    if (radius > rb_) {
      passed = true;
    } else {
      lo = hi;
    }
  }
  auto bisect = [&](auto&& below) {  // below(lo) true, below(hi) false
    for (int it = 0; it < 200; ++it) {
      const double mid = 0.5 * (lo + hi);
      if (mid == lo || mid == hi) break;
      (below(mid) ? lo : hi) = mid;
    }
  };
  if (passed) {
    bisect([&](double phi) {
      side(phi, &radius);
      return radius <= rb_;
    });
  }
  // 2. From there, the trochoid is inside the tooth (side < 0) until it crosses the involute.
  const double phi_base = lo;
  bool found = passed && side(phi_base, &radius) < 0.0;
  if (found) {
    found = false;
    for (int i = 1; i <= kScan && !found; ++i) {
      hi = phi_base + span * i / kScan;
      if (side(hi, &radius) >= 0.0) found = true;
      if (radius >= ra_) break;
    }
  }
  if (!found) {
    Fail(spec_.name, "profile_shift", Num(spec_.profile_shift),
         "undercut generation found no crossing of the fillet trochoid and the involute");
  }
  lo = phi_base;
  bisect([&](double phi) { return side(phi, &radius) < 0.0; });
  return hi;
}

void Gear::BuildInternalDirect() {
  const double m = spec_.module, x = spec_.profile_shift, a = spec_.pressure_angle;
  ra_ = spec_.tip_radius;
  rf_ = spec_.root_radius;
  if (ra_ <= rb_) {
    Fail(spec_.name, "tip_radius_mm", Mm(ra_),
         "must exceed the base radius " + Mm(rb_) + " mm (no involute inside the base circle)");
  }
  flank_turn_ = spec_.thickness_error / (2.0 * rb_);
  const double s = m * (kPi / 2.0 - 2.0 * x * std::tan(a));
  involute_.base_radius = rb_;
  involute_.start = s / (2.0 * r_) - Inv(a) + flank_turn_;
  involute_.hand = +1;

  // Base rounding: an arc in the space tangent to the involute and to the root circle. Offsetting
  // an involute along its normal by d gives the involute of the same base circle turned by d/r_b.
  const double rho = spec_.root_round_radius;
  const double rc = rf_ - rho;
  if (rc <= rb_ || rc <= ra_) {
    Fail(spec_.name, "root_round_radius_mm", Mm(rho),
         "too large: the base rounding's centre falls inside the base or tip circle");
  }
  InvoluteFlank offset{rb_, involute_.start + rho / rb_, +1, 0, 0};
  const double uc = InvoluteFlank::RollAtRadius(rb_, rc);
  const Vec2 cf = offset.Point(uc);
  const double u_form = uc + rho / rb_;
  const Vec2 f = involute_.Point(u_form);
  r_form_ = f.norm();
  if (Angle(cf) >= kPi / spec_.teeth) {
    Fail(spec_.name, "root_round_radius_mm", Mm(rho),
         "too large: the base rounding crosses the centre line of the tooth space");
  }
  involute_.u_max = u_form;
  half_.segments.clear();
  half_.segments.push_back(
      Arc(SegmentRole::kRootLand, Vec2::Zero(), rf_, kPi / spec_.teeth, Angle(cf)));
  half_.segments.push_back(Arc(SegmentRole::kFillet, cf, rho, Angle(cf), Angle(f - cf)));
  AddTip();
  Segment flank;
  flank.role = SegmentRole::kInvolute;
  flank.kind = SegmentKind::kInvolute;
  flank.base_radius = rb_;
  flank.involute_start = involute_.start;
  flank.hand = +1;
  flank.t0 = u_form;
  flank.t1 = involute_.u_min;  // set by AddTip: the tip-round tangency
  half_.segments.insert(half_.segments.begin() + 2, flank);
}

void Gear::BuildInternalShaper() {
  const double m = spec_.module, x = spec_.profile_shift, a = spec_.pressure_angle;
  const ShaperCutter& c = *spec_.shaper;
  const double zr = spec_.teeth, zc = c.teeth;
  // The generating mesh works at zero backlash: inv α0 = inv α + 2 tan α (x − x_c)/(z − z_c).
  const double inv0 = Inv(a) + 2.0 * std::tan(a) * (x - c.profile_shift) / (zr - zc);
  if (inv0 <= 0) {
    Fail(spec_.name, "shaper.profile_shift", Num(c.profile_shift),
         "gives a non-positive generating pressure angle");
  }
  const double a0 = InvInverse(inv0);
  ShaperGeneration g;
  g.centre_distance = m * (zr - zc) / 2.0 * std::cos(a) / std::cos(a0);
  g.pitch_point = g.centre_distance * zr / (zr - zc);
  g.ratio = zc / zr;
  g.ring_pitch_angle = 2.0 * kPi / zr;
  const double rc = m * zc / 2.0;
  g.base_radius = rc * std::cos(a);
  g.pressure_angle = a0;
  g.involute_start = (kPi * m / 4.0 + c.profile_shift * m * std::tan(a)) / rc + Inv(a);
  const double rho = c.tip_round_radius;
  if (c.tip_radius - rho <= g.base_radius) {
    Fail(spec_.name, "shaper.tip_round_radius_mm", Mm(rho),
         "too large: the shaper's tip-round centre falls inside its base circle");
  }
  InvoluteFlank shaper_offset{g.base_radius, g.involute_start - rho / g.base_radius, -1, 0, 0};
  const double uc = InvoluteFlank::RollAtRadius(g.base_radius, c.tip_radius - rho);
  g.round_centre = shaper_offset.Point(uc);
  g.round_radius = rho;
  if (Angle(g.round_centre) <= 0) {
    Fail(spec_.name, "shaper.tip_radius_mm", Mm(c.tip_radius), "the shaper's tooth is pointed");
  }
  const double u_tangent = uc + rho / g.base_radius;
  const double phi_tip = -Angle(g.round_centre);
  const double phi_tangent = u_tangent - g.involute_start - a0;

  ra_ = spec_.tip_radius;
  rf_ = g.centre_distance + c.tip_radius;
  if (ra_ <= rb_) {
    Fail(spec_.name, "tip_radius_mm", Mm(ra_),
         "must exceed the base radius " + Mm(rb_) + " mm (no involute inside the base circle)");
  }
  flank_turn_ = spec_.thickness_error / (2.0 * rb_);
  const double s = m * (kPi / 2.0 - 2.0 * x * std::tan(a));
  involute_.base_radius = rb_;
  involute_.start = s / (2.0 * r_) - Inv(a) + flank_turn_;
  involute_.hand = +1;

  Segment fillet;
  fillet.role = SegmentRole::kFillet;
  fillet.kind = SegmentKind::kShaperRound;
  fillet.shaper = g;
  fillet.t0 = phi_tip;
  fillet.t1 = phi_tangent;
  fillet.rotation = flank_turn_;
  Segment flank = fillet;
  flank.role = SegmentRole::kInvolute;
  flank.kind = SegmentKind::kShaperFlank;
  flank.t0 = phi_tangent;
  r_form_ = flank.Point(phi_tangent).norm();
  if (r_form_ <= ra_) {
    Fail(spec_.name, "shaper.tip_radius_mm", Mm(c.tip_radius),
         "the generated fillet reaches the ring's tip circle: no involute is left");
  }
  const Vec2 root_point = fillet.Point(phi_tip);
  if (Angle(root_point) >= kPi / spec_.teeth) {
    Fail(spec_.name, "shaper.tip_round_radius_mm", Mm(rho),
         "too large: the generated fillet crosses the centre line of the ring's tooth space");
  }
  const double u_form = InvoluteFlank::RollAtRadius(rb_, r_form_);
  involute_.u_max = u_form;
  half_.segments.clear();
  half_.segments.push_back(Arc(SegmentRole::kRootLand, Vec2::Zero(), rf_, kPi / spec_.teeth,
                               Angle(root_point) - flank_turn_, flank_turn_));
  half_.segments.push_back(fillet);
  AddTip();
  // The generated involute ends at the tip-round tangency: along the generating line of action
  // the ring's roll length is the shaper's plus the offset of the two tangency points.
  const Vec2 bc = Vec2(g.centre_distance, 0.0) + g.base_radius * Dir(-a0);
  const Vec2 d = DirPerp(-a0);
  const double ell = rb_ * involute_.u_min - bc.dot(d);
  flank.t1 = ell / g.base_radius - g.involute_start - a0;
  half_.segments.insert(half_.segments.begin() + 2, flank);
}

void Gear::AddTip() {
  const double rho = spec_.tip_round_radius;
  const int h = involute_.hand;
  const double tip_side_u = InvoluteFlank::RollAtRadius(rb_, ra_);
  if (rho <= 0) {
    r_tip_form_ = ra_;
    const Vec2 t = involute_.Point(tip_side_u);
    if (internal()) {
      involute_.u_min = tip_side_u;
    } else {
      involute_.u_max = tip_side_u;
    }
    tip_round_ = TipRound{t, 0.0, Angle(t), Angle(t)};
    half_.segments.push_back(Arc(SegmentRole::kTipLand, Vec2::Zero(), ra_, Angle(t), 0.0));
    return;
  }
  // Vedmar tip rounding: the round's centre lies on the involute offset into the tooth by r_t
  // (same base circle turned by −r_t/r_b) and on the circle r_a ∓ r_t.
  const double rc = internal() ? ra_ + rho : ra_ - rho;
  if (rc <= rb_) {
    Fail(spec_.name, "tip_round_radius_mm", Mm(rho),
         "too large: the tip round's centre falls inside the base circle");
  }
  InvoluteFlank offset{rb_, involute_.start - rho / rb_, h, 0, 0};
  const double uc = InvoluteFlank::RollAtRadius(rb_, rc);
  const Vec2 centre = offset.Point(uc);
  // Offset curves of an involute share the roll's normal line: the flank point on the round's
  // normal has roll u = u_c + ρ/r_b (external, h = −1) or u_c − ρ/r_b (internal, h = +1).
  const double u_t = internal() ? uc - rho / rb_ : uc + rho / rb_;
  if (u_t <= 0) {
    Fail(spec_.name, "tip_round_radius_mm", Mm(rho),
         "too large: the round reaches the base circle");
  }
  const Vec2 t = involute_.Point(u_t);
  r_tip_form_ = t.norm();
  if (internal() ? r_tip_form_ >= r_form_ : r_tip_form_ <= r_form_) {
    Fail(spec_.name, "tip_round_radius_mm", Mm(rho),
         "too large: the tip round leaves no involute between the form circle (" + Mm(r_form_) +
             " mm) and the tip");
  }
  if (Angle(centre) <= 0) {
    Fail(spec_.name, "tip_radius_mm", Mm(ra_),
         "pointed tooth: the tip rounds of the two flanks meet at the tooth centre line");
  }
  if (internal()) {
    involute_.u_min = u_t;
  } else {
    involute_.u_max = u_t;
  }
  const double tip_dir = internal() ? Angle(centre) + kPi : Angle(centre);
  tip_round_.centre = centre;
  tip_round_.radius = rho;
  tip_round_.normal_from = Angle(t - centre);
  tip_round_.normal_to = tip_round_.normal_from + WrapAngle(tip_dir - tip_round_.normal_from);
  half_.segments.push_back(
      Arc(SegmentRole::kTipRound, centre, rho, tip_round_.normal_from, tip_round_.normal_to));
  half_.segments.push_back(Arc(SegmentRole::kTipLand, Vec2::Zero(), ra_, Angle(centre), 0.0));
}

double Gear::ThicknessAt(double radius) const {
  const double u = InvoluteFlank::RollAtRadius(rb_, radius);
  const double half = involute_.start + involute_.hand * (u - std::atan(u));
  return 2.0 * radius * half;
}

std::vector<Vec2> Gear::Outline(int per_segment) const {
  const Polyline half = half_.Sample(per_segment);
  std::vector<Vec2> tooth;
  for (const Vec2& p : half.points) tooth.emplace_back(p.x(), -p.y());
  for (auto it = half.points.rbegin() + 1; it != half.points.rend(); ++it) tooth.push_back(*it);
  std::vector<Vec2> out;
  out.reserve(tooth.size() * spec_.teeth);
  for (int k = 0; k < spec_.teeth; ++k) {
    const double turn = k * pitch_angle();
    for (const Vec2& p : tooth) out.push_back(Rotate(p, turn));
  }
  return out;
}

}  // namespace epicycle::geometry
