// The mapped Q8 mesh of a whole gear body built from its generated profile: one tooth sector as
// a few Coons patches (flank band, tip band, tooth core, fillet block, rim), mirrored and rotated
// to all z teeth so that the mesh is exactly cyclic, with the flank-grid points (the influence
// table's load and response points) as nodes placed exactly on the profile.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "epicycle/compliance/mesh.hpp"
#include "epicycle/compliance/mesher.hpp"
#include "epicycle/geometry/gear.hpp"

namespace epicycle::compliance {

/// The σ = +1 half profile of tooth 0 (geometry::HalfProfile, body frame) parametrised by arc
/// length s [m] from the start of the root land (space centre line) to the tooth centre line:
///
///   x(s) = segment_k(t_k(s)),  s = s_k + ∫_{t_k,0}^{t} |dx/dt| dt   on segment k,
///
/// the arc length computed by composite 5-point Gauss quadrature and inverted by Newton. Every
/// point returned is the segment's own Evaluate(t), so it lies exactly on the generated profile
/// whatever the accuracy of the inversion. The outward unit normal is κ·(−t_y, t_x) with t the
/// unit tangent along s and κ = +1 (external) or −1 (internal gear).
class ProfilePath {
 public:
  explicit ProfilePath(const geometry::Gear& gear);

  double length() const { return total_; }  ///< [m]
  /// Arc length [m] where the first segment of `role` starts / the last one ends.
  /// @throws std::invalid_argument if the profile has no such segment.
  double RoleStart(geometry::SegmentRole role) const;
  double RoleEnd(geometry::SegmentRole role) const;
  bool HasRole(geometry::SegmentRole role) const;

  Eigen::Vector2d Point(double s) const;    ///< x(s) [m]
  Eigen::Vector2d Tangent(double s) const;  ///< unit dx/ds
  Eigen::Vector2d Normal(double s) const;   ///< outward unit normal
  /// Arc length of the point of [s_lo, s_hi] closest to q [m]; `distance` [m] if given. A scan
  /// of `scan` + 1 equally spaced points picks the start of a Gauss–Newton iteration along s.
  double Project(const Eigen::Vector2d& q, double s_lo, double s_hi, double* distance = nullptr,
                 int scan = 64) const;

 private:
  struct Piece {
    const geometry::Segment* segment = nullptr;
    double s0 = 0.0, length = 0.0;
    std::vector<double> table;  // arc length at θ = k/K, k = 0..K (θ: fraction of [t0, t1])
  };
  void Locate(double s, int* piece, double* theta) const;
  double ArcWithin(const Piece& p, double theta) const;  // s − s0 at θ
  std::vector<Piece> pieces_;
  double total_ = 0.0;
  int sign_ = 1;  // κ
};

/// Element counts and shape of the gear-body mesh. The defaults are the "default density" of the
/// influence tables (docs/compliance.md, gear section).
struct GearMeshOptions {
  /// Elements along the involute (from the form circle to the tip-round tangency) [-], ≥ 1. The
  /// flank grid has two grid intervals per element (corner and mid-side nodes are grid points),
  /// equally spaced in arc length on the involute.
  int involute_elements = 16;
  /// Elements along the tip round [-], ≥ 1 (ignored without a tip round); equally spaced.
  int tip_round_elements = 3;
  /// Elements along the tip land (tip circle to the tooth centre line) [-], ≥ 1.
  int tip_land_elements = 2;
  /// Elements along root land + fillet (space centre line to the form circle) [-], ≥ 1.
  int fillet_elements = 5;
  /// Layers of the flank band (surface to its inner side Γ) [-], ≥ 1, graded toward the surface.
  int band_layers = 3;
  /// Thickness of the deepest band layer over the surface layer [-], ≥ 1.
  double band_grading = 3.0;
  /// Depth of Γ as a fraction of the distance from the flank to the tooth centre line [-], in
  /// [0.1, 0.6] (at the form point along the cut toward the rim corner, at the tip-round tangency
  /// along the normal).
  double band_depth_fraction = 0.35;
  /// Radial layers of the rim (root block to the hub or to the ring's rim) [-], ≥ 1.
  int rim_layers = 4;
  /// Size of the layer at the hub (ring: at the outer rim) over the one at the root block [-], ≥ 1.
  double rim_grading = 3.0;
  /// Depth of the rim corner B below the root circle in modules [-], in (0, 2): the fillet block
  /// spans from the root circle to r_f ∓ depth·m.
  double root_block_depth = 0.5;
  /// Whole-sector density factor [-], ≥ 1: multiplies every element count (for refinement
  /// studies); the flank grid refines with it.
  int refinement = 1;
  /// The mesher of the body region [-]: "mapped" (MappedMesher, structured) or "gmsh"
  /// (GmshMesher, unstructured quadrilaterals inside the same patches, same boundary nodes; needs
  /// a build with EPICYCLE_WITH_GMSH=ON). Both place the flank grid as nodes on the profile.
  std::string mesher = "mapped";

  /// @throws std::invalid_argument naming the field, its value and the rule.
  void Validate() const;
};

/// The flank grid of a gear: the points along involute and tip round (σ = +1 flank of tooth 0)
/// where unit loads are applied and responses read. Point i has arc length s_i [m] measured from
/// the form point (the start of the involute); the σ = −1 flank is its mirror image in the x axis
/// and tooth k its rotation by k·2π/z.
struct FlankGrid {
  std::vector<double> arc_length;         ///< s_i [m], from the form point, increasing
  std::vector<Eigen::Vector2d> position;  ///< x_i [m], σ = +1 flank of tooth 0
  std::vector<Eigen::Vector2d> normal;    ///< outward unit normal at x_i
  double form_arc = 0.0;                  ///< arc length of the form point along ProfilePath [m]
  int num_points() const { return static_cast<int>(arc_length.size()); }
};

/// A gear body ready for the elastic model: the mesh, its flank grid and the grid's node indices.
/// Mesh sets: node set "hub" (external gears: the axis circle; ring: the outer rim) to fix; node
/// and edge sets "flank<k>+" / "flank<k>-" (involute, tip round and tip land of tooth k's σ = ±1
/// flank) and "fillet<k>+" / "fillet<k>-" (root land and fillet of tooth k's σ = ±1 side, from the
/// space centre line to the form point); element sets "band", "core", "fillet", "rim".
struct GearBodyMesh {
  Mesh mesh;
  FlankGrid grid;
  int teeth = 0;  ///< z
  /// grid_nodes[k][f][i]: node of grid point i on tooth k, flank f (0: σ = +1, 1: σ = −1).
  std::vector<std::array<std::vector<int>, 2>> grid_nodes;
  double min_jacobian_ratio = 0.0;  ///< min over elements of det J / max det J (Gauss points) [-]
};

/// Builds the mesh of the whole body of `gear` (both gear kinds) with options.mesher.
/// The sector of tooth 0, upper half (0 ≤ θ ≤ π/z), is five Coons patches:
///   band  — between the flank (form point F → tip-round tangency T1) and the straight inner side
///           G→K, `band_layers` graded toward the surface, nodes at the flank grid;
///   tip   — between tip round + tip land (T1 → tip centre C) and K→D, D on the x axis;
///   core  — between G→K and the x axis B→D;
///   fillet— between root land + fillet (R0 → F), the cut F→G→B, the circle r_m = |B| and the
///           space centre line;
///   rim   — between the circle r_m and the hub circle (ring: the rim circle);
/// the lower half is its mirror image in the x axis, the other teeth rotated copies (Rotated).
/// @throws std::invalid_argument (bad options, or the construction fails for this profile: the
///         message names the gear, the point or patch at fault and the rule).
GearBodyMesh BuildGearMesh(const geometry::Gear& gear, const GearMeshOptions& options = {});

/// The flank grid alone (same construction as BuildGearMesh).
FlankGrid MakeFlankGrid(const geometry::Gear& gear, const GearMeshOptions& options = {});

/// Area of the body enclosed by its outline [m²] (shoelace formula on Gear::Outline with
/// `per_segment` points per profile segment, minus the hub disc, or for the ring the rim disc
/// minus the enclosed inner outline): the independent reference of the mesh area.
double OutlineArea(const geometry::Gear& gear, int per_segment);

/// Area of a mesh [m²], Σ_e ∫∫ det J dξ dη (3×3 Gauss).
double MeshArea(const Mesh& mesh);
/// min over elements of det J / max det J over 3×3 Gauss points [-] (GearBodyMesh's quality
/// figure).
double MinJacobianRatio(const Mesh& mesh);

}  // namespace epicycle::compliance
