#include "epicycle/geometry/profile.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "jet.hpp"

namespace epicycle::geometry {

using internal::Jet;
using internal::JetVec;

double InvInverse(double v) {
  if (!(v >= 0.0) || !std::isfinite(v)) {
    throw std::invalid_argument("InvInverse: argument " + std::to_string(v) + " must be >= 0");
  }
  // Start from the cubic approximation inv α ≈ α³/3, then Newton on tan α − α = v.
  double a = std::min(std::cbrt(3.0 * v), 1.5);
  for (int i = 0; i < 60; ++i) {
    const double t = std::tan(a);
    const double f = t - a - v;
    const double step = f / (t * t);  // d/dα (tan α − α) = tan² α
    a -= step;
    if (a <= 0) a = 1e-12;
    if (a >= kPi / 2) a = 0.5 * (a + kPi / 2);
    if (std::abs(step) < 1e-16 * std::max(1.0, a)) break;
  }
  return a;
}

std::string RoleName(SegmentRole role) {
  switch (role) {
    case SegmentRole::kRootLand:
      return "root land";
    case SegmentRole::kFillet:
      return "fillet";
    case SegmentRole::kInvolute:
      return "involute";
    case SegmentRole::kTipRound:
      return "tip round";
    case SegmentRole::kTipLand:
      return "tip land";
  }
  return "?";
}

double CurvePoint::Curvature() const {
  const double n = d1.norm();
  return Cross(d1, d2) / (n * n * n);
}

namespace {

CurvePoint FromJet(const JetVec& q) {
  return {Vec2(q.x.v, q.y.v), Vec2(q.x.d, q.y.d), Vec2(q.x.dd, q.y.dd)};
}

JetVec Const(const Vec2& v) { return {Jet(v.x()), Jet(v.y())}; }

// Rack flank: the contact point is the foot of the normal from the pitch point I to the straight
// edge (equation of meshing: the common normal passes through I), seen from the rotated gear.
JetVec RackFlank(const RackGeneration& g, double phi) {
  const Jet ph = Jet::Variable(phi);
  const double sa = std::sin(g.pressure_angle), ca = std::cos(g.pressure_angle);
  const Jet t = ca * (g.flank_offset + g.pitch_radius * ph);
  const JetVec q{g.pitch_radius + t * sa, t * ca};
  return internal::RotateJet(q, -ph);
}

// Rack tip round: centre C moves with the rack; the contact point lies on the line I–C, on the
// side of C away from I (that is where the cutting arc's outward normal points).
JetVec RackRound(const RackGeneration& g, double phi) {
  const Jet ph = Jet::Variable(phi);
  const JetVec c{Jet(g.round_centre.x()), g.round_centre.y() + g.pitch_radius * ph};
  const JetVec d = c - Const(Vec2(g.pitch_radius, 0.0));
  const JetVec q = c + (g.round_radius / internal::Norm(d)) * d;
  return internal::RotateJet(q, -ph);
}

// Shaper generation seen from the ring: rotate back by the ring's turn, move from the space at
// +x (tooth 1's clockwise flank) to tooth 0's counter-clockwise flank by a mirror in x.
JetVec ToRing(const ShaperGeneration& g, const JetVec& q, const Jet& phi) {
  const JetVec r = internal::RotateJet(q, -0.5 * g.ring_pitch_angle - g.ratio * phi);
  return {r.x, -r.y};
}

JetVec ShaperFlank(const ShaperGeneration& g, double phi) {
  const Jet ph = Jet::Variable(phi);
  const Jet u = g.involute_start + ph + g.pressure_angle;
  const Vec2 b = Vec2(g.centre_distance, 0.0) + g.base_radius * Dir(-g.pressure_angle);
  const Vec2 d = DirPerp(-g.pressure_angle);
  const JetVec q{b.x() + g.base_radius * u * d.x(), b.y() + g.base_radius * u * d.y()};
  return ToRing(g, q, ph);
}

JetVec ShaperRound(const ShaperGeneration& g, double phi) {
  const Jet ph = Jet::Variable(phi);
  const JetVec c =
      Const(Vec2(g.centre_distance, 0.0)) + internal::RotateJet(Const(g.round_centre), ph);
  const JetVec d = c - Const(Vec2(g.pitch_point, 0.0));
  const JetVec q = c + (g.round_radius / internal::Norm(d)) * d;
  return ToRing(g, q, ph);
}

CurvePoint Rotated(CurvePoint c, double a) {
  if (a == 0.0) return c;
  return {Rotate(c.p, a), Rotate(c.d1, a), Rotate(c.d2, a)};
}

}  // namespace

CurvePoint Segment::Evaluate(double t) const {
  CurvePoint c;
  switch (kind) {
    case SegmentKind::kArc:
      c = {centre + radius * Dir(t), radius * DirPerp(t), -radius * Dir(t)};
      break;
    case SegmentKind::kInvolute: {
      const double b = involute_start + hand * t;
      const double h = hand;
      c.p = base_radius * (Dir(b) - h * t * DirPerp(b));
      c.d1 = base_radius * t * Dir(b);
      c.d2 = base_radius * (Dir(b) + h * t * DirPerp(b));
      break;
    }
    case SegmentKind::kRackFlank:
      c = FromJet(RackFlank(rack, t));
      break;
    case SegmentKind::kRackRound:
      c = FromJet(RackRound(rack, t));
      break;
    case SegmentKind::kShaperFlank:
      c = FromJet(ShaperFlank(shaper, t));
      break;
    case SegmentKind::kShaperRound:
      c = FromJet(ShaperRound(shaper, t));
      break;
  }
  return Rotated(c, rotation);
}

Vec2 InvoluteFlank::Point(double u) const {
  const double b = start + hand * u;
  return base_radius * (Dir(b) - static_cast<double>(hand) * u * DirPerp(b));
}

double InvoluteFlank::RollAtRadius(double base_radius, double radius) {
  return std::sqrt(std::max(0.0, radius * radius - base_radius * base_radius)) / base_radius;
}

Polyline HalfProfile::Sample(int per_segment) const {
  // The front ends hold a user's count to kPointsPerSegment; a finer sampling is the meshers' and
  // the tests' (thousands of points): only a count that samples nothing is refused here.
  if (per_segment < 1)
    throw std::invalid_argument("HalfProfile::Sample: points_per_segment = " +
                                std::to_string(per_segment) + ": must be >= 1");
  Polyline out;
  for (std::size_t s = 0; s < segments.size(); ++s) {
    const Segment& seg = segments[s];
    for (int i = (s == 0 ? 0 : 1); i <= per_segment; ++i) {
      const double t = seg.t0 + (seg.t1 - seg.t0) * i / per_segment;
      out.points.push_back(seg.Point(t));
      out.roles.push_back(seg.role);
    }
  }
  return out;
}

const Segment* HalfProfile::Find(SegmentRole role) const {
  for (const Segment& s : segments) {
    if (s.role == role) return &s;
  }
  return nullptr;
}

}  // namespace epicycle::geometry
