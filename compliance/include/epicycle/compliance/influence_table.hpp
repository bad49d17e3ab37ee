// The structural influence table of one gear body (docs/model.md §4): unit loads at the flank grid
// of tooth 0, displacements at the flank grids of all teeth, joined to the local contact term at
// depth h, symmetrised (Maxwell–Betti) and interpolated over load position, response position and
// tooth-index difference.
#pragma once

#include <array>
#include <cstdint>
#include <iosfwd>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "epicycle/compliance/gear_mesh.hpp"
#include "epicycle/compliance/material.hpp"
#include "epicycle/geometry/gear.hpp"

namespace epicycle::compliance {

/// Options of an influence-table build.
struct InfluenceTableOptions {
  GearMeshOptions mesh;  ///< mesh density (the flank grid follows it)
  /// Join depth h [m] below the surface, along the inward normal, where the FE structural term
  /// of the loaded point is read (docs/model.md §4). 0 selects the default
  ///   h = kDefaultDepthFraction · min_i d_i,   d_i = y_i / n_y,i,
  /// d_i the distance from grid point i along its inward normal to the tooth centre line (the
  /// largest h that keeps the read-out on the loaded tooth's side), so that h ± 50 % stays valid.
  double join_depth = 0.0;
  /// Factor on the default h [-], used when join_depth is 0: h = join_depth_factor ·
  /// kDefaultDepthFraction · min_i d_i, so that one factor scales every body's own default (the
  /// discretisation study, docs/quasistatic.md). Finite and > 0; h must still stay below min_i d_i,
  /// i.e. the factor below 1/kDefaultDepthFraction ≈ 1.67.
  double join_depth_factor = 1.0;
  /// Add the layer term to the depth-h self entries (docs/compliance.md, "The layer term"): the
  /// structural strain between the surface and h that the half-plane local term does not carry,
  ///   c_i = −h · dR_i/dr,   R_i(r) = D_i(r) + a ln r,   a = 2k/(π b),
  /// D_i(r) = mᵀ U_i(r) m the FE's normal approach at depth r below grid point i under a unit
  /// normal load there (m the outward normal; −a ln r is Flamant's half-plane part, so R is the
  /// structural rest), dR/dr the least-squares slope over kLayerSamples depths evenly in
  /// [r1, r2], r1 = kDefaultDepthFraction · min_i d_i, r2 = kLayerDepthRatio · r1,
  /// k = (1−ν²)/E plane strain, 1/E plane stress; then filtered along the flank by (1, 2, 1)/4
  /// (removes the alternation between grid points on corner and mid-side nodes). false: the join of
  /// the paper (FE at depth h plus the local term, nothing in between), kept for the comparison.
  bool layer_term = true;
  /// Also tabulate the root stress (docs/model.md §9): the surface tangential stress σ_tt along
  /// both fillets of every tooth under each unit load, from the same solves (see
  /// InfluenceTable::AddFilletStress). Off, the build and the table are those without stress.
  bool fillet_stress = false;
  /// Right-hand sides solved per sweep of the factor [-], ≥ 1 (bounds the memory of the solve).
  int batch = 32;
  /// @throws std::invalid_argument naming the field, its value and the rule.
  void Validate() const;
};

/// A position on a flank: tooth k (any integer, taken modulo z), flank σ = +1 (counter-clockwise
/// side of the tooth) or −1, and arc length s [m] from the form point along the flank grid
/// (0 ≤ s ≤ s_max, the tip-round end).
struct FlankPosition {
  int tooth = 0;            ///< k [-]
  int flank = 1;            ///< σ = ±1
  double arc_length = 0.0;  ///< s [m]
};

/// The influence table Λ of one body in its body frame: Λ(p_load, p_response) is the 2×2 matrix
/// whose column c is the displacement [m] at p_response due to a unit force [N] along axis c at
/// p_load, with the hub (external gears) or the outer rim (ring) fixed. For the loaded point
/// itself (same tooth, flank and position) the displacement is read at depth h below the surface,
/// at x − h n (the join with the local term u_local of solvers/local_term.hpp, which carries the
/// approach between the surface and depth h); elsewhere it is the surface displacement.
///
/// Cyclic symmetry: with R_k the rotation by k·2π/z,
///   Λ(tooth k1 → tooth k2) = R_k1 Λ(tooth 0 → tooth k2 − k1) R_k1ᵀ,
/// so only loads on tooth 0 are stored: 2 flanks × N points × 2 directions, each with the
/// displacements of z teeth × 2 flanks × N points (N the flank-grid size).
///
/// Interpolation: over the load position and the response position, each by the C1 piecewise
/// cubic Hermite interpolant in arc length whose nodal slopes are those of the parabola through
/// three neighbouring grid points (exact for quadratics, error O(Δs³)); the table is the tensor
/// product of the two. The self term (load and response at the same position) interpolates the
/// depth-h blocks alone. Maxwell–Betti symmetry Λ(a → b) = Λ(b → a)ᵀ is measured on the raw table
/// and then enforced by averaging each pair, so the interpolated operator is symmetric too.
class InfluenceTable {
 public:
  /// Meshes `gear`, assembles with `material` (E, ν, b, plane assumption), fixes the hub,
  /// factorises once and solves all unit loads.
  /// @throws std::invalid_argument for bad options or material, a mesher failure, or a join depth
  ///         past the tooth centre line (the message names the grid point and the limit).
  static InfluenceTable Build(const geometry::Gear& gear, const ElasticMaterial& material,
                              const InfluenceTableOptions& options = {});

  /// Default h as a fraction of the smallest distance to the tooth centre line (see options).
  static constexpr double kDefaultDepthFraction = 0.6;
  /// The join needs h ≥ kMinDepthOverHalfWidth · L (L the Hertz half-width) so that the FE point
  /// load and the Hertzian pressure give the same displacement at depth h (Saint-Venant).
  static constexpr double kMinDepthOverHalfWidth = 3.0;
  /// r2/r1 of the depths where the layer term's strain is measured (see
  /// InfluenceTableOptions::layer_term): r2 = 0.9 min_i d_i stays on the loaded side of the tooth.
  static constexpr double kLayerDepthRatio = 1.5;
  /// Depths sampled evenly over [r1, r2] for the layer term's least-squares slope.
  static constexpr int kLayerSamples = 7;

  int teeth() const { return teeth_; }
  const FlankGrid& grid() const { return grid_; }
  double join_depth() const { return depth_; }  ///< h [m]
  /// The largest admissible h [m]: min_i d_i (see InfluenceTableOptions::join_depth).
  double max_join_depth() const { return max_depth_; }
  double arc_length_max() const { return grid_.arc_length.back(); }  ///< s_max [m]
  int num_dofs() const { return num_dofs_; }
  int num_elements() const { return num_elements_; }
  /// max over reciprocal pairs |Λ(a→b) − Λ(b→a)ᵀ| / √(|D_a| |D_b|) on the raw table, D the depth-h
  /// self blocks (max-abs norms) [-]; and the same for the self blocks' own skew part.
  double raw_asymmetry() const { return raw_asymmetry_; }
  double raw_self_asymmetry() const { return raw_self_asymmetry_; }
  /// Timings of the build [s] (CPU): mesh, assembly + factorisation, solves + extraction.
  std::array<double, 3> build_seconds() const { return seconds_; }

  /// @throws std::invalid_argument unless h ≥ kMinDepthOverHalfWidth · L, naming both values.
  void CheckHalfWidth(double half_width) const;

  /// Λ(load, response) [m/N], body frame (see the class comment).
  /// @throws std::invalid_argument for a flank other than ±1 or an arc length outside [0, s_max].
  Eigen::Matrix2d Influence(const FlankPosition& load, const FlankPosition& response) const;

  /// A flank position with its interpolation stencil, prepared once when one position meets many
  /// others (a compliance matrix interpolates every pair of its contacts): Λ along the flank is
  /// the cubic Hermite interpolant of the grid values with finite-difference slopes, a weighted
  /// sum over 4 consecutive grid points.
  struct Node {
    FlankPosition position;
    int first = 0;                   ///< first grid point of the stencil
    std::array<double, 4> weight{};  ///< weights of grid points first … first + 3 [-]
  };
  /// @throws std::invalid_argument for a flank other than ±1 or an arc length outside [0, s_max].
  Node Prepare(const FlankPosition& position) const;
  /// Λ(load, response) [m/N] of prepared positions (the same value as from the positions).
  Eigen::Matrix2d PreparedInfluence(const Node& load, const Node& response) const;

  /// A prepared position with a unit direction d in the body frame (of a contact force, or of the
  /// displacement read there), for the scalar compliance between many pairs (AssembleCompliance).
  /// With R_k the rotation of the node's tooth k, v = R_kᵀ d is the direction in the frame where
  /// the tooth is tooth 0, and the products w_p v_c of the stencil's weights with it are what the
  /// node contributes as a load (see DirectedCompliance).
  struct DirectedNode {
    Node node;
    Eigen::Vector2d direction = Eigen::Vector2d::Zero();  ///< d [-], unit, body frame
    int tooth = 0;                                        ///< k mod z, in [0, z)
    int flank_index = 0;                                  ///< 0 for σ = +1, 1 for σ = −1
    std::array<double, 8> load_weight{};                  ///< w_p (R_kᵀ d)_c at index 2p + c
  };
  /// @throws std::invalid_argument as Prepare.
  DirectedNode PrepareDirected(const FlankPosition& position,
                               const Eigen::Vector2d& direction) const;
  /// d_rᵀ Λ(load, response) d_l [m/N], d_l and d_r the nodes' directions: the same value as
  /// `response.direction.dot(PreparedInfluence(load.node, response.node) * load.direction)` to
  /// round-off, with the directions contracted into the interpolation instead of forming the 2×2
  /// block (see the implementation for the sum).
  double DirectedCompliance(const DirectedNode& load, const DirectedNode& response) const;

  /// The flank position of a body-frame point on tooth k's flank σ: the foot of the point on a
  /// polyline of the generated profile with 32 points per grid interval (chord error κΔ²/8 below
  /// 1e-8 m here; grid nodes are located exactly), about 0.2 µs. @throws std::invalid_argument if
  /// the point lies farther than 1e-3·m from the flank between the form point and the tip-round
  /// end.
  FlankPosition Locate(const Eigen::Vector2d& point, int tooth, int flank) const;
  /// The same, returning false instead of throwing when the point is off the flank (hot paths
  /// that add their own context to the message).
  bool TryLocate(const Eigen::Vector2d& point, int tooth, int flank, FlankPosition* out,
                 double* distance) const;

  /// n_rᵀ Λ(p_load, p_response) n_l [m/N]: the structural compliance between a load along the
  /// unit vector n_l at p_load (tooth k1, flank σ1) and the displacement along n_r at p_response
  /// (tooth k2, flank σ2), all in the body frame.
  double Compliance(const Eigen::Vector2d& load_point, const Eigen::Vector2d& load_normal,
                    int load_tooth, int load_flank, const Eigen::Vector2d& response_point,
                    const Eigen::Vector2d& response_normal, int response_tooth,
                    int response_flank) const;

  /// The raw (unsymmetrised, unjoined) surface value — only on a table built in this process, not
  /// one loaded from the cache (@throws std::invalid_argument then) — and the (symmetrised)
  /// depth-h self block, at grid nodes, for tests: column c = displacement of response (tooth k,
  /// flank f, point j) under a unit force along c at (tooth 0, flank fl, point i). f, fl: 0 for σ =
  /// +1, 1 for σ = −1.
  Eigen::Matrix2d GridValue(int fl, int i, int k, int f, int j) const;
  Eigen::Matrix2d SelfBlock(int fl, int i) const;
  /// The layer term c_i [m/N] of grid point i of flank fl (0 when layer_term is off), already
  /// contained in SelfBlock along the normal: SelfBlock = FE block at h (symmetrised) + c_i m mᵀ.
  double LayerCompliance(int fl, int i) const;

  // ---- Root stress (built with InfluenceTableOptions::fillet_stress) ----
  //
  // The structural FE is linear, so the surface tangential stress at a fillet point is
  //   σ_tt(p) = Σ_j S(p; load j) · F_j,
  // S the stress under a unit force at the load's flank position (docs/model.md §9). S is
  // tabulated like Λ: unit loads along x and y at the flank grid of tooth 0, σ_tt at the fillet
  // points of both sides of every tooth, interpolated over the load position by the same
  // Hermite weights (Prepare), carried to other teeth by the cyclic symmetry (a stress is
  // invariant under the rotation R_k). σ_tt = tᵀσt at a free surface is the non-zero in-plane
  // principal stress (LinearElasticModel::SurfaceStress), positive in tension; at a node shared by
  // two fillet edges the two elements' values are averaged. The local (Hertz) term acts within
  // the join depth and does not reach the fillet: it adds nothing here.

  /// A point of the fillet of tooth 0's σ = +1 side (root land and fillet, from the space centre
  /// line to the form point); the σ = −1 side is its mirror image, tooth k its rotation.
  struct FilletPoint {
    double arc_length = 0.0;  ///< along the profile from the space centre line [m]
    Eigen::Vector2d position = Eigen::Vector2d::Zero();  ///< body frame [m]
    Eigen::Vector2d tangent = Eigen::Vector2d::Zero();   ///< unit, toward the form point
  };
  bool has_fillet_stress() const { return !fillet_.empty(); }
  /// The fillet points, ordered from the space centre line to the form point (empty without
  /// stress).
  const std::vector<FilletPoint>& fillet_points() const { return fillet_; }
  /// σ += F · S at every fillet point of tooth `tooth`, side `side` (0: σ = +1, 1: σ = −1), for a
  /// force F [N] along `load`'s direction at its position: `sigma` has fillet_points().size()
  /// entries [Pa]. @throws std::logic_error on a table without stress.
  void AddFilletStress(const DirectedNode& load, double force, int tooth, int side,
                       double* sigma) const;
  /// A load prepared once for the superposition on many fillets: its non-zero stencil weights
  /// times the force, F w_p (R_kᵀ d)_c [N], each with the tabulated row it scales (response tooth
  /// 0, side 0; a fillet is a fixed offset from it).
  struct FilletLoad {
    int tooth = 0;  ///< the loaded tooth, k mod z
    int count = 0;  ///< non-zero weights [-], ≤ 8
    std::array<double, 8> weight{};
    std::array<const double*, 8> row{};
  };
  /// @throws std::logic_error on a table without stress.
  FilletLoad PrepareFilletLoad(const DirectedNode& load, double force) const;
  /// The same sum as AddFilletStress(load's node, force, ...), bit for bit, in one pass over the
  /// fillet points.
  void AddFilletStress(const FilletLoad& load, int tooth, int side, double* sigma) const;
  /// One fillet to add to: tooth `tooth`, side `side` (0: σ = +1, 1: σ = −1), its σ [Pa] at the
  /// fillet_points() (not owned).
  struct FilletTarget {
    int tooth = 0;
    int side = 0;
    double* sigma = nullptr;
  };
  /// AddFilletStress(load, f.tooth, f.side, f.sigma) for each fillet f, the same sums bit for bit
  /// (a fillet adds its loads in the order they are given, whichever loop is outer), with the
  /// load's weights set up once.
  void AddFilletStress(const FilletLoad& load, std::span<const FilletTarget> fillets) const;
  /// The tabulated σ_tt [Pa/N] at fillet point m of (tooth k, side f) under a unit force along
  /// axis c at grid point i of tooth 0's flank fl (fl, f: 0 for σ = +1, 1 for σ = −1).
  double FilletGridValue(int fl, int i, int c, int k, int f, int m) const;

  /// Binary serialisation (see influence_cache.hpp for the file format and its checks): the
  /// payload only, without header or checksum.
  void WritePayload(std::ostream& out) const;
  /// Reads a payload written by WritePayload for `gear` (the caller has checked the key, which
  /// says whether the payload carries fillet stresses).
  /// @throws std::runtime_error if the payload is truncated or inconsistent.
  static InfluenceTable ReadPayload(std::istream& in, const geometry::Gear& gear,
                                    bool fillet_stress = false);

 private:
  friend class DamagedInfluence;
  static std::vector<InfluenceTable> SolveLoads(const geometry::Gear& gear,
                                                const ElasticMaterial& material,
                                                const InfluenceTableOptions& options,
                                                GearBodyMesh body, double t_mesh_before,
                                                const std::vector<int>& load_teeth, bool cyclic);
  // Where T_(c, e)(i → j) of load flank fl, tooth offset k, response flank f starts in surface_
  // (inline: DirectedCompliance reads it for every pair of contact sides).
  std::size_t Index(int fl, int i, int c, int k, int f, int j) const {
    const std::size_t per_load = static_cast<std::size_t>(teeth_) * 2 * n_ * 2;
    return ((static_cast<std::size_t>(fl) * n_ + i) * 2 + c) * per_load +
           ((static_cast<std::size_t>(k) * 2 + f) * n_ + j) * 2;
  }
  void BuildDerived();  // slope_, dense_, dense_key_, bucket_, tooth_rotation_ (grid_, path_)
  void Weights(double s, int* first, std::array<double, 4>* w) const;

  int teeth_ = 0;
  int n_ = 0;  // grid points per flank
  int num_dofs_ = 0, num_elements_ = 0;
  double depth_ = 0.0, max_depth_ = 0.0, module_ = 0.0;
  double raw_asymmetry_ = 0.0, raw_self_asymmetry_ = 0.0;
  std::array<double, 3> seconds_{};
  FlankGrid grid_;
  std::vector<double> surface_;        // symmetrised, joined (self entries = depth blocks)
  std::vector<double> raw_;            // as solved (surface values everywhere)
  std::vector<Eigen::Matrix2d> self_;  // [fl][i], symmetrised, with the layer term
  std::vector<double> layer_;          // [fl][i], the layer term [m/N]
  std::vector<FilletPoint> fillet_;    // M points of tooth 0's σ = +1 fillet
  std::vector<double> fillet_stress_;  // [fl][i][c][k][f][m] [Pa/N]
  std::size_t FilletIndex(int fl, int i, int c, int k, int f) const;
  std::vector<std::array<double, 3>> slope_;  // [m]: nodal slope weights (Weights)
  double interval_scale_ = 0.0;               // (n − 1)/s_max [1/m]: Weights' first guess
  std::shared_ptr<const geometry::Gear> gear_;
  std::shared_ptr<const ProfilePath> path_;
  // The σ = +1 flank of tooth 0 as a dense polyline (Locate): kDense points per grid interval.
  static constexpr int kDense = 32;
  struct DensePoint {
    Eigen::Vector2d point;
    double arc_length;  // from the form point [m]
  };
  std::vector<DensePoint> dense_;
  // ±|point|, rising along the profile (Locate's bisection), and buckets of equal key width over
  // it: bucket b's answers lie in [bucket_[b], bucket_[b + 1]] (empty if the keys are not sorted).
  double key_sign_ = 1.0;
  std::vector<double> dense_key_;
  std::vector<int> bucket_;
  double bucket_origin_ = 0.0, bucket_scale_ = 0.0;  // key of bucket 0's lower edge, buckets/key
  std::vector<Eigen::Matrix2d> tooth_rotation_;      // R(k·2π/z), k = 0 … z − 1
};

}  // namespace epicycle::compliance
