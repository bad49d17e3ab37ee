// The body mesh of a gear with a root crack (docs/model.md §9, "Root crack"): the gear body mesh
// of gear_mesh.hpp, with the cracked tooth's sector meshed again by gmsh around the crack, a seam
// whose two faces are separate nodes.
#pragma once

#include <vector>

#include "epicycle/compliance/gear_mesh.hpp"
#include "epicycle/compliance/root_crack.hpp"

namespace epicycle::compliance {

/// Options of the crack's mesh.
struct CrackMeshOptions {
  /// Elements along the crack [-], in [2, 200] (times GearMeshOptions::refinement).
  int crack_elements = 12;
  /// Size of the element at the mouth over the one at the tip [-], in [1, 100]: the elements
  /// shrink geometrically toward the tip, where the displacement has its √r singularity.
  double tip_grading = 4.0;
  /// Largest element along the crack in modules [-], in (0, 1]: a short crack keeps
  /// crack_elements elements, a long one gets more so that none exceeds this.
  double max_element = 0.1;
  /// true: the faces are separate nodes (the crack). false: the same mesh with the seam closed
  /// (one node on both faces): the healthy body on the cracked tooth's mesh, for comparisons.
  bool open = true;
  /// @throws std::invalid_argument naming the field, its value and the rule.
  void Validate() const;
};

/// A cracked gear body.
struct CrackedBodyMesh {
  /// The mesh, flank grid and grid nodes as for a healthy body (BuildGearMesh), with the sets of
  /// BuildGearMesh (element sets "band", "core", "fillet", "rim" without the cracked sector, whose
  /// elements form the set "crack_sector") plus the node and edge sets "crack_tip_side" and
  /// "crack_root_side": the crack's faces (the tip side's face bounds the part of the tooth toward
  /// its tip).
  GearBodyMesh body;
  /// Corner nodes of each face from the mouth to the tip (the tip node, not duplicated, in both;
  /// with a closed seam both lists are the same nodes).
  std::vector<int> tip_side, root_side;
  /// Mid-side nodes of each face, one per interval from the mouth to the tip.
  std::vector<int> tip_side_mid, root_side_mid;
  /// Unit normal at the mouth from the root-side face into the tip-side face [-], body frame: the
  /// crack mouth opening displacement is (u_tip_side − u_root_side) · this (positive = open).
  Eigen::Vector2d opening_normal = Eigen::Vector2d::Zero();
  int sector_elements = 0;  ///< elements of the cracked sector
};

/// The mesh of `gear`'s body with `crack` (validated against the gear first). The body is first
/// meshed as BuildGearMesh does (options.mesher); the elements of the cracked tooth's sector
/// (centroid within ±π/z of its centre line) are removed, and the sector is meshed by gmsh as one
/// polygon whose boundary is that of the removed elements, every sample kept: the nodes shared
/// with the neighbours (the space centre lines), the hub and the flank grid (the table's load and
/// response points) are the same nodes, so the mesh stays conforming and the grid stays on the
/// profile. The fillet interval holding the mouth is split there (its mid-side nodes on the
/// profile) — into three when needed to keep the boundary's interval count even. The crack is a
/// polyline of segments embedded in the polygon (element sizes graded from the mouth to the tip,
/// see CrackMeshOptions); with an open crack its nodes, all but the tip's, are duplicated: the
/// elements on either side of the crack use their own copy, so the mouth on the fillet opens.
/// @throws std::invalid_argument for an invalid crack (RootCrack::Validate) or options, a gmsh
///         failure, or in a build without gmsh (naming EPICYCLE_WITH_GMSH).
CrackedBodyMesh BuildCrackedGearMesh(const geometry::Gear& gear, const RootCrack& crack,
                                     const GearMeshOptions& options = {},
                                     const CrackMeshOptions& crack_options = {});

}  // namespace epicycle::compliance
