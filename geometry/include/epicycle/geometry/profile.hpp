// Tooth profiles as piecewise parametric curves with exact first and second derivatives.
//
// Body frame of every gear: origin at the gear's geometric centre, tooth 0 centred on +x, tooth k
// on the ray at 2πk/z. A *half profile* is the flank on the counter-clockwise side (σ = +1) of
// tooth 0, from the centre line of the adjacent space at the root to the tooth centre line at the
// tip: root land, fillet, involute, tip round, tip land. The clockwise flank (σ = −1) is its mirror
// image in the x axis.
#pragma once

#include <string>
#include <vector>

#include "epicycle/geometry/plane.hpp"

namespace epicycle::geometry {

enum class SegmentRole { kRootLand, kFillet, kInvolute, kTipRound, kTipLand };
std::string RoleName(SegmentRole role);

/// How a segment's points are computed.
enum class SegmentKind {
  kArc,        ///< circular arc; parameter = polar angle about its centre [rad]
  kInvolute,   ///< analytic involute; parameter = roll angle u [rad]
  kRackFlank,  ///< envelope of a rack cutter's straight edge; parameter = generating roll φ [rad]
  kRackRound,  ///< envelope of a rack cutter's tip round; parameter = generating roll φ [rad]
  kShaperFlank,  ///< envelope of a shaper cutter's involute; parameter = shaper rotation [rad]
  kShaperRound,  ///< envelope of a shaper cutter's tip round; parameter = shaper rotation [rad]
};

/// A point of a curve with its derivatives with respect to the curve parameter t.
struct CurvePoint {
  Vec2 p = Vec2::Zero();   ///< position [m]
  Vec2 d1 = Vec2::Zero();  ///< dp/dt [m]
  Vec2 d2 = Vec2::Zero();  ///< d²p/dt² [m]
  /// Signed curvature κ = (p′ × p″)/|p′|³ [1/m] (positive: turning counter-clockwise along t).
  double Curvature() const;
  /// Unit tangent along increasing t.
  Vec2 Tangent() const { return d1.normalized(); }
};

/// Data of a rack-cutter envelope (the gear rolls on its pitch circle r, the rack's rolling line
/// is tangent at I = (r, 0) and moves r·φ along +y while the gear turns φ).
struct RackGeneration {
  double pitch_radius = 0;    ///< r [m]
  double pressure_angle = 0;  ///< α [rad]
  double flank_offset = 0;    ///< πm/4 + x m tan α [m]: the straight edge's position at φ = 0
  Vec2 round_centre = Vec2::Zero();  ///< cutter tip-round centre at φ = 0, fixed frame [m]
  double round_radius = 0;           ///< ρ [m]
};

/// Data of a pinion-type shaper envelope generating an internal gear (fixed frame: ring centre at
/// the origin, shaper centre at (a0, 0), pitch point I = (r_w,ring, 0); the ring turns
/// (z_c/z_r)·φ while the shaper turns φ).
struct ShaperGeneration {
  double centre_distance = 0;        ///< a0 [m]
  double pitch_point = 0;            ///< r_w of the ring in the generating mesh [m]
  double ratio = 0;                  ///< z_c/z_r [-]
  double ring_pitch_angle = 0;       ///< 2π/z_r [rad]
  double base_radius = 0;            ///< r_bc of the shaper [m]
  double pressure_angle = 0;         ///< α0 of the generating mesh [rad]
  double involute_start = 0;         ///< θ0 of the shaper's σ = +1 involute (body) [rad]
  Vec2 round_centre = Vec2::Zero();  ///< shaper tip-round centre (σ = +1, shaper body) [m]
  double round_radius = 0;           ///< ρ_c [m]
};

/// One piece of a half profile. Points are rotated by `rotation` after evaluation (used for the
/// tooth-thickness error, which turns each flank about the gear centre).
struct Segment {
  SegmentRole role = SegmentRole::kInvolute;
  SegmentKind kind = SegmentKind::kArc;
  double t0 = 0, t1 = 0;  ///< parameter range, traversed from root (t0) to tip (t1)
  double rotation = 0;    ///< [rad]
  // kArc
  Vec2 centre = Vec2::Zero();  ///< [m]
  double radius = 0;           ///< [m]
  // kInvolute: p(u) = r_b [e(θ0 + h u) − h u e⊥(θ0 + h u)]
  double base_radius = 0;     ///< r_b [m]
  double involute_start = 0;  ///< θ0 [rad]
  int hand = 1;               ///< h = ±1
  RackGeneration rack;
  ShaperGeneration shaper;

  CurvePoint Evaluate(double t) const;
  Vec2 Point(double t) const { return Evaluate(t).p; }
};

/// The analytic involute of a flank (σ = +1, body frame), valid between two roll angles.
///   p(u) = r_b [e(θ0 + h u) − h u e⊥(θ0 + h u)],  outward normal σ·e⊥(θ0 + h u),
///   radius of curvature r_b·u, polar angle θ0 + h (u − atan u).
/// External gears have h = −1 (the tooth narrows outward), internal gears h = +1.
struct InvoluteFlank {
  double base_radius = 0;  ///< r_b [m]
  double start = 0;        ///< θ0 [rad], where the involute leaves the base circle
  int hand = -1;           ///< h
  double u_min = 0;        ///< smallest roll angle of the active involute [rad]
  double u_max = 0;        ///< largest roll angle of the active involute [rad]
  Vec2 Point(double u) const;
  static double RollAtRadius(double base_radius, double radius);
};

/// The tooth tip round of the σ = +1 flank (body frame).
struct TipRound {
  Vec2 centre = Vec2::Zero();  ///< [m]
  double radius = 0;           ///< r_t [m]
  double normal_from = 0;      ///< direction [rad] of the outward normal at the flank tangency
  double normal_to = 0;        ///< direction [rad] of the outward normal at the tip-circle tangency
};

/// A polyline with the profile role of each point.
struct Polyline {
  std::vector<Vec2> points;
  std::vector<SegmentRole> roles;
};

class HalfProfile {
 public:
  std::vector<Segment> segments;  ///< root → tip
  /// Points along every segment, `per_segment` + 1 points per segment (shared ends once).
  Polyline Sample(int per_segment) const;
  /// The first segment with the given role, or nullptr.
  const Segment* Find(SegmentRole role) const;
};

}  // namespace epicycle::geometry
