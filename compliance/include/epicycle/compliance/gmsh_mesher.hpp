// The optional second mesher: gmsh (https://gmsh.info, C++ API) meshes the interior of every patch
// of a Region with unstructured quadrilaterals, behind the same Mesher interface as MappedMesher.
// Built with EPICYCLE_WITH_GMSH=ON only (gmsh is GPL; see the option in CMakeLists.txt); in other
// builds the class exists, Available() is false and BuildMesh throws.
#pragma once

#include <string>

#include "epicycle/compliance/mesher.hpp"

namespace epicycle::compliance {

/// Options of the gmsh mesher.
struct GmshMesherOptions {
  /// gmsh's 2D algorithm (option Mesh.Algorithm) for the triangles that are then recombined into
  /// quadrilaterals: 6 Frontal-Delaunay (default) or 5 Delaunay. (8, "Frontal-Delaunay for
  /// quads", crashes (SIGSEGV in backgroundMesh::getAngle) in Debian's gmsh 4.8.4 and is refused.)
  int algorithm = 6;
  /// Nodes closer than merge_tolerance × (diagonal of the region's bounding box) are one node [-].
  double merge_tolerance = 1e-9;
  /// Corner mismatch allowed between adjacent side curves of a patch, same scale [-].
  double corner_tolerance = 1e-9;
  /// Give a patch that is a rotated copy (about the origin) of an earlier patch the rotated mesh
  /// of that patch instead of meshing it again: a region made of rotated sectors (a gear body)
  /// then gets an exactly cyclic mesh, node k of copy j = R(θ_j) × node k of the original to
  /// round-off, as with MappedMesher. false meshes every patch on its own.
  bool reuse_rotated_copies = true;
  /// Check that no node lies inside another element's free side (a non-conforming join).
  bool check_conformity = true;
  /// @throws std::invalid_argument naming the field, its value and the rule.
  void Validate() const;
};

/// Unstructured Q8 mesher using gmsh, for the same regions as MappedMesher.
///
/// Boundary. Side k of a patch is sampled at its Distribution's parameters exactly as
/// MappedMesher samples it: element corners at t_i, mid-side nodes at (t_i + t_{i+1})/2, every
/// point x_k(t) exactly on the side curve. On NAMED sides (flanks, hub: the sets the model loads
/// and fixes) these are the boundary nodes, so every flank-grid point is a node exactly on the
/// profile and the node and edge sets hold the same points as with MappedMesher. On unnamed sides
/// (interfaces between patches, unnamed outer sides) an interval whose chord L is more than two
/// element sizes long (∫_0^L dx/σ > 2) is cut further so that an isotropic mesh can grade from
/// short to long intervals: with h_a, h_b the sizes at its ends (the shortest interval at that
/// vertex over all patches) and σ(x) = min(h_a + g x, h_b + g (L − x)), g = 0.3, it is cut into
/// the odd number of pieces nearest to ∫_0^L dx/σ, of equal ∫ dx/σ (odd keeps 2(n_u + n_v)
/// intervals around a patch even; the cut points are computed from the nearer end, so that the
/// patches on both sides of an interface cut it at the same points).
///
/// Interior. Each patch is one gmsh plane surface bounded by the polygon of its corner samples
/// (one straight gmsh line per interval, transfinite with 2 nodes, so that gmsh adds no boundary
/// vertex). The mesh size is the background field h(x) = min_k (h_k + g |x − x_k|) over the
/// boundary vertices x_k (h_k the mean of the two intervals at x_k). gmsh triangulates with
/// `algorithm` (Frontal-Delaunay by default) and recombines the triangles into quadrilaterals
/// with the Blossom perfect matching (Mesh.RecombinationAlgorithm = 1) and its smoothing. Where
/// Blossom leaves triangles (it refuses quadrilaterals below its quality threshold: acute patch
/// corners, clusters of very short intervals such as the tip round's), each is paired with another
/// triangle along a chain of quadrilaterals (an augmenting path of the matching, diagonals chosen
/// for the best smallest corner angle), a quadrilateral that would still be poor (a corner at
/// 180°) being replaced by five; a smart Laplacian smoothing of the inner vertices follows.
///
/// Second order. The linear quadrilaterals become 8-node serendipity quadrilaterals (node order
/// of q8_element.hpp, counter-clockwise): the mid-side node of a boundary interval is its
/// mid-side sample, exactly on the side curve; inside, the straight midpoint shared by the two
/// elements of the side. (The mid-side nodes are placed here rather than by gmsh's setOrder(2),
/// which would put them on gmsh's straight boundary lines and need moving anyway.)
///
/// Assembly. Nodes are merged across patches by the tolerance search of MappedMesher, so patches
/// that share a side (same curve, same node parameters, possibly reversed) join conformingly. A
/// patch whose boundary nodes are R(θ) times those of an earlier patch reuses its mesh rotated
/// (reuse_rotated_copies): a gear body, built of rotated sectors, gets an exactly cyclic mesh. The
/// mirror halves of a sector are meshed separately, so the two flanks of a tooth see different
/// (not mirror-image) meshes. Named sides become node sets (along the curve) and edge sets, named
/// patches element sets, as with MappedMesher; the mesh is validated (Mesh::Validate).
///
/// gmsh is global state: calls are serialised by a mutex, gmsh::initialize runs once per process
/// (without reading configuration files, General.Terminal = 0), each patch is meshed in a fresh
/// model that is removed afterwards, and every option the mesh depends on is set on each call.
/// gmsh runs with General.AbortOnError = 0 and its errors are read from its logger: it meshes
/// inside an OpenMP parallel region, from which its usual exception would not escape (the process
/// would terminate). The mesh depends on the gmsh version (the influence-table cache key
/// includes it).
class GmshMesher final : public Mesher {
 public:
  /// @throws std::invalid_argument if the options are invalid.
  explicit GmshMesher(GmshMesherOptions options = {});
  std::string name() const override { return "gmsh"; }
  /// @throws std::invalid_argument whose message starts "gmsh mesher:" and names the patch and
  ///         side (or element) at fault: bad patch data, a gmsh error, triangles that cannot be
  ///         turned into valid quadrilaterals, an invalid element (Jacobian), a non-conforming
  ///         join; in a build without gmsh, always (naming EPICYCLE_WITH_GMSH).
  Mesh BuildMesh(const Region& region) const override;

  /// true if this build has gmsh (EPICYCLE_WITH_GMSH=ON).
  static bool Available();
  /// The gmsh API version this build was compiled against ("4.8.0"), "" without gmsh.
  static std::string LibraryVersion();

 private:
  GmshMesherOptions options_;
};

}  // namespace epicycle::compliance
