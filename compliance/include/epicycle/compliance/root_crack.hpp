// A root crack in one tooth of a gear body (docs/model.md §9, "Root crack"): where it starts on a
// fillet, the polyline it follows into the tooth, and where a crack is placed by default (the
// largest root tension of a load, or ISO 6336-3's 30° tangent point).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "epicycle/compliance/influence_table.hpp"
#include "epicycle/geometry/gear.hpp"

namespace epicycle::compliance {

/// One straight piece of a crack path.
struct CrackSegment {
  double length = 0.0;  ///< [m], finite, > 0
  /// ν [rad], the angle between the piece and the tooth centre line, in (0, π): the piece runs
  /// across the tooth toward the other flank, toward the root for ν < π/2 (the usual 45–70°),
  /// straight across at π/2, toward the tip above. In tooth k's frame (x along its centre line
  /// from the body's centre, y toward its σ = +1 flank), with e_r = κ x̂ pointing from the root to
  /// the tip (κ = +1 external, −1 internal gear), the direction is d = −cos ν e_r − σ sin ν ŷ.
  double angle = 0.0;
};

/// A crack in the body of tooth `tooth`, starting on the fillet of its σ = `side` flank.
/// The crack is open (its faces do not touch): docs/model.md §9 "Root crack".
struct RootCrack {
  int tooth = 0;  ///< k [-], in [0, z), body frame (tooth k is tooth 0 rotated by k·2π/z)
  int side =
      1;  ///< σ = ±1: the fillet of tooth k's σ flank (the loaded flank's side is in tension)
  /// Where the crack starts (its mouth): arc length along the fillet from the space centre line
  /// [m] (the arc length of InfluenceTable::FilletPoint), in (0, s_form), s_form the form point's.
  double start_arc = 0.0;
  /// The path from the mouth, in order (a straight crack is one segment).
  std::vector<CrackSegment> path;

  /// Total length of the path [m] (the crack's depth q along its path).
  double depth() const;
  /// The polyline in the body frame [m]: the mouth, then the end of each segment (the last point
  /// is the tip). No validation.
  std::vector<Eigen::Vector2d> Points(const geometry::Gear& gear) const;

  /// Clearance between the path and the body's outline, in modules [-] (see Validate).
  static constexpr double kClearance = 0.05;
  /// Smallest angle between the crack and the fillet at the mouth [rad] (see Validate): 10°.
  static constexpr double kMinMouthAngle = 0.17453292519943295;
  /// Most segments a path may have.
  static constexpr int kMaxSegments = 64;

  /// @throws std::invalid_argument naming the field ("RootCrack.tooth", "RootCrack.path[2].angle",
  ///         …), its value and the rule: tooth in [0, z); side ±1; start_arc finite in (0, s_form);
  ///         1 to kMaxSegments segments of finite length > 0 and angle in (0, π); and the path
  ///         stays inside tooth k's body sector (between the two space centre lines, outside the
  ///         hub circle, or inside the outer rim of a ring, and inside the tooth's outline): every
  ///         point at distance ℓ along the path from the mouth at least min(ℓ·sin(kMinMouthAngle),
  ///         kClearance·m) from the sector's outline (the message names the part it comes near:
  ///         the other flank or fillet, the hub or outer rim, the neighbour's space centre line).
  void Validate(const geometry::Gear& gear) const;
};

/// ISO 6336-3's critical fillet point: the arc length [m] (from the space centre line, σ = +1
/// fillet of tooth 0) where the fillet's tangent makes 30° with the tooth centre line (external
/// gears; 60° for internal gears), found from the form point toward the root.
/// @throws std::invalid_argument if the fillet has no such point (the message names the gear).
double IsoCriticalFilletArc(const geometry::Gear& gear);

/// The fillet arc length [m] of the largest tension σ_tt on side `side` (σ = ±1) of tooth
/// `load.tooth` under a unit normal force pressing on the flank at `load` (along −n, n the outward
/// normal of the profile): the tabulated fillet points of `table` (built with fillet_stress) and
/// the vertex of the parabola through the largest and its two neighbours.
/// @throws std::invalid_argument if the table has no fillet stresses, for a bad position, or if no
///         fillet point is in tension.
double LargestRootTensionArc(const InfluenceTable& table, const geometry::Gear& gear,
                             const FlankPosition& load, int side);

/// The start of a crack on side `side` of `load.tooth`: LargestRootTensionArc when `table` is
/// given and has fillet stresses, IsoCriticalFilletArc otherwise.
double RootCrackStartArc(const geometry::Gear& gear, const InfluenceTable* table,
                         const FlankPosition& load, int side);

}  // namespace epicycle::compliance
