// Meshers: the interface ("build the Q8 mesh of a region"), and our own mapped (structured)
// mesher of regions made of four-sided patches, by transfinite (Coons) interpolation. The optional
// gmsh mesher behind the same interface is in gmsh_mesher.hpp.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "epicycle/compliance/mesh.hpp"

namespace epicycle::compliance {

/// A parametric plane curve t ∈ [0, 1] ↦ x(t) [m].
using Curve = std::function<Eigen::Vector2d(double)>;

/// The straight segment from a to b [m], x(t) = a + t (b − a).
Curve StraightLine(const Eigen::Vector2d& a, const Eigen::Vector2d& b);
/// The circular arc of centre c [m] and radius r [m] from angle θ0 to θ1 [rad], linear in angle:
/// x(t) = c + r (cos θ(t), sin θ(t)), θ(t) = θ0 + t (θ1 − θ0).
Curve CircularArc(const Eigen::Vector2d& c, double r, double theta0, double theta1);
/// The same curve run backwards, x(1 − t).
Curve Reversed(Curve curve);

/// How the element boundaries are placed along one parametric direction of a patch: either the
/// explicit parameters `breaks` (0 = t_0 < t_1 < … < t_n = 1), or, when `breaks` is empty, n =
/// `divisions` intervals in geometric progression: Δt_{k+1} = ratio · Δt_k. ratio = 1 is uniform;
/// ratio < 1 refines toward t = 1, ratio > 1 toward t = 0 (the last interval over the first is
/// ratio^(n−1)). Mid-side nodes sit at the mid-parameter of each interval.
struct Distribution {
  int divisions = 1;           ///< n [-], ≥ 1 (ignored when breaks are given)
  double ratio = 1.0;          ///< size ratio of consecutive intervals [-], > 0
  std::vector<double> breaks;  ///< explicit parameters t_k [-], or empty

  static Distribution Uniform(int n) { return Distribution{n, 1.0, {}}; }
  /// n intervals whose sizes grow (ratio > 1) or shrink (ratio < 1) from t = 0 to t = 1.
  static Distribution Geometric(int n, double ratio) { return Distribution{n, ratio, {}}; }
  /// n intervals with last/first size = `last_over_first` (> 1: refined toward t = 0).
  static Distribution Graded(int n, double last_over_first);

  /// The element-boundary parameters t_0..t_n. @throws std::invalid_argument naming `field`.
  std::vector<double> Parameters(const std::string& field) const;
};

/// A four-sided patch. The sides are parametrised in the directions of the patch coordinates
/// (u, v) ∈ [0, 1]²:
///   sides[0] bottom: v = 0, u from 0 to 1      sides[1] right: u = 1, v from 0 to 1
///   sides[2] top:    v = 1, u from 0 to 1      sides[3] left:  u = 0, v from 0 to 1
/// so bottom(0) = left(0), bottom(1) = right(0), top(0) = left(1), top(1) = right(1). The interior
/// is the Coons (transfinite) interpolation
///   P(u,v) = (1−v) B(u) + v T(u) + (1−u) L(v) + u R(v)
///            − [(1−u)(1−v) P00 + u(1−v) P10 + (1−u) v P01 + u v P11],
/// which reproduces the four sides exactly: every boundary node, corner and mid-side, lies ON its
/// side curve. Either orientation is accepted (elements are numbered counter-clockwise).
struct Patch {
  std::string name;                       ///< element-set name of this patch's elements ("" = none)
  std::array<Curve, 4> sides;             ///< bottom, right, top, left (see above)
  std::array<std::string, 4> side_names;  ///< node- and edge-set name of each side ("" = none)
  Distribution u;                         ///< element boundaries along u (bottom and top sides)
  Distribution v;                         ///< element boundaries along v (left and right sides)
};

/// The patch rotated by `angle` [rad] about the origin, x ↦ R(angle) x (names kept; rename the
/// copies' sets as needed). Rotated copies of one sector patch set give an exactly cyclic mesh:
/// node k of copy j is R(2πj/z) times node k of copy 0 to round-off.
Patch Rotated(const Patch& patch, double angle);

/// A region made of patches. Patches that share a side must see the same curve with the same
/// node parameters there (same distribution, possibly reversed); the mesh then joins them
/// conformingly.
struct Region {
  std::vector<Patch> patches;
};

/// Builds a Q8 mesh of a region. Implementations: MappedMesher (ours, structured) and GmshMesher
/// (gmsh_mesher.hpp: unstructured, built with EPICYCLE_WITH_GMSH).
class Mesher {
 public:
  virtual ~Mesher() = default;
  /// A short name ("mapped", "gmsh").
  virtual std::string name() const = 0;
  /// The mesh; named sides of the patches become node sets and edge sets of the same names, named
  /// patches become element sets. The mesh is validated (Mesh::Validate).
  /// @throws std::invalid_argument with a message that names the patch/side/element at fault.
  virtual Mesh BuildMesh(const Region& region) const = 0;
};

/// Options of the mapped mesher.
struct MappedMesherOptions {
  /// Nodes closer than merge_tolerance × (diagonal of the region's bounding box) are one node [-].
  double merge_tolerance = 1e-9;
  /// Corner mismatch allowed between adjacent side curves of a patch, same scale [-].
  double corner_tolerance = 1e-9;
  /// Check that no node lies inside another element's free side (a non-conforming join).
  bool check_conformity = true;
  /// @throws std::invalid_argument unless both tolerances are finite, > 0 and < 1e-3.
  void Validate() const;
};

/// Structured mesher: each patch is an (n_u × n_v) grid of Q8 elements placed by Coons
/// interpolation at the distributions' parameters; coincident nodes of different patches are
/// merged by a tolerance search (sort-and-sweep).
class MappedMesher final : public Mesher {
 public:
  explicit MappedMesher(MappedMesherOptions options = {});
  std::string name() const override { return "mapped"; }
  Mesh BuildMesh(const Region& region) const override;

 private:
  MappedMesherOptions options_;
};

}  // namespace epicycle::compliance
