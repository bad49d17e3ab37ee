// A 2D mesh of 8-node serendipity quadrilaterals with named node sets, boundary-edge sets and
// element sets.
#pragma once

#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "epicycle/compliance/q8_element.hpp"

namespace epicycle::compliance {

/// A quadratic edge of an element side: nodes (first corner, mid-side, second corner), ordered
/// counter-clockwise with respect to `element`, i.e. the element lies to the left when walking
/// from the first to the last node. Its outward unit normal is therefore n = (t_y, −t_x)/|t| with
/// t = dx/dξ, and a point on it is x(ξ) = Σ N_a(ξ) x_a with the edge shape functions
/// N = (ξ(ξ−1)/2, 1−ξ², ξ(ξ+1)/2), ξ ∈ [−1, 1].
struct BoundaryEdge {
  std::array<int, 3> nodes{};  ///< global node indices (first corner, mid-side, second corner)
  int element = -1;            ///< the element this side belongs to
};

/// A point on an edge of an edge set: edge index within the set and local coordinate ξ ∈ [−1, 1]
/// (−1 at the edge's first node, 0 at its mid-side node, +1 at its last node).
struct EdgePoint {
  int edge = 0;     ///< index into the edge set
  double xi = 0.0;  ///< ξ [-]
};

/// Nodes, Q8 elements (local order of q8_element.hpp) and named sets.
struct Mesh {
  std::vector<Eigen::Vector2d> nodes;                 ///< node positions [m]
  std::vector<std::array<int, kQ8Nodes>> elements;    ///< Q8 connectivity, counter-clockwise
  std::map<std::string, std::vector<int>> node_sets;  ///< named node lists (e.g. "hub")
  std::map<std::string, std::vector<BoundaryEdge>> edge_sets;  ///< named element sides
  std::map<std::string, std::vector<int>> element_sets;  ///< named element lists (e.g. patches)

  int num_nodes() const { return static_cast<int>(nodes.size()); }
  int num_elements() const { return static_cast<int>(elements.size()); }

  /// The named node set. @throws std::invalid_argument naming the set and listing those present.
  const std::vector<int>& NodeSet(const std::string& name) const;
  /// The named edge set. @throws std::invalid_argument naming the set and listing those present.
  const std::vector<BoundaryEdge>& EdgeSet(const std::string& name) const;
  /// The named element set. @throws std::invalid_argument as above.
  const std::vector<int>& ElementSet(const std::string& name) const;

  /// Node coordinates of element e.
  Q8Coordinates ElementCoordinates(int e) const;

  /// Structural validity: every node index in range and finite, every node used by some element,
  /// no element repeating a node, edges of edge sets are sides of their elements (in the element's
  /// counter-clockwise order), and every element passes CheckQ8Jacobian.
  /// @throws std::invalid_argument naming the offending item.
  void Validate() const;

  /// Position x(ξ) [m] of a point on an edge of a set.
  Eigen::Vector2d EdgePosition(const std::string& set, const EdgePoint& p) const;
  /// Outward unit normal at a point on an edge of a set (see BoundaryEdge).
  Eigen::Vector2d EdgeNormal(const std::string& set, const EdgePoint& p) const;

  /// The point of an edge set closest to `point` [m] (Newton projection on each quadratic edge).
  /// `distance` [m], if given, receives the distance from `point` to it.
  EdgePoint LocateOnEdgeSet(const std::string& set, const Eigen::Vector2d& point,
                            double* distance = nullptr) const;
};

/// A node that lies inside a free side (a side used by one element only) without being one of its
/// three nodes: the hanging node of a non-conforming join between patches.
struct HangingNode {
  int node = -1;
  std::array<int, 3> side{};  ///< corner, mid-side, corner
  int element = -1;           ///< the element whose free side it is
};

/// The first hanging node of a mesh, if any (closest point on each quadratic free side by Newton
/// from the chord projection; "inside" means within 1e-6 of the side's chord length and not at
/// its ends).
std::optional<HangingNode> FindHangingNode(const Mesh& mesh);

}  // namespace epicycle::compliance
