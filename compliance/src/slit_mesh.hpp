// The gmsh mesh of a polygon with an embedded polyline that can be opened into a crack (a seam
// whose two faces are separate nodes); used by the cracked gear body (cracked_mesh.hpp). Defined
// in gmsh_mesher.cpp (gmsh builds) or gmsh_mesher_unavailable.cpp (throws, naming the option).
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "epicycle/compliance/q8_element.hpp"

namespace epicycle::compliance::internal {

struct SlitInput {
  /// The boundary as in the gmsh mesher's patch loop: even entries element corners, odd entries
  /// the mid-side samples of the interval between them (closed, either orientation).
  std::vector<Eigen::Vector2d> loop;
  /// Loop index (even) of the crack's mouth.
  int mouth = 0;
  /// The crack's points after the mouth, the last the tip; each gmsh node, joined by straight
  /// segments that the mesh keeps as element sides.
  std::vector<Eigen::Vector2d> crack;
  /// Duplicate the nodes of the crack (all but the tip): the faces become separate.
  bool open = true;
};

struct SlitMesh {
  /// Node ids: below loop.size() the loop samples, the others interior[id − loop.size()].
  std::vector<Eigen::Vector2d> interior;
  std::vector<std::array<int, kQ8Nodes>> elements;  ///< counter-clockwise Q8
  /// Corner nodes of the crack's two faces from the mouth to the tip (the tip in both): `left`
  /// the face on the left of the path's direction (mouth → tip), `right` the other; equal lists
  /// when the seam is closed. Mid-side nodes of the faces: `left_mid` / `right_mid` (one per
  /// interval, mouth → tip).
  std::vector<int> left, right, left_mid, right_mid;
};

/// @throws std::invalid_argument ("gmsh mesher: …") if gmsh fails or the result is not a valid
///         all-quadrilateral mesh; in a build without gmsh, always (naming EPICYCLE_WITH_GMSH).
SlitMesh MeshSlitPolygon(const SlitInput& input);

}  // namespace epicycle::compliance::internal
