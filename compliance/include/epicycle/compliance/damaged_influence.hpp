// The influence rows of a gear body with a root crack (docs/model.md §9, "Root crack"): the
// crack breaks the cyclic symmetry of the healthy table, so the loads on the cracked tooth and its
// neighbours get rows of their own, solved on the cracked body; every other pair keeps the
// healthy table.
#pragma once

#include <array>
#include <iosfwd>
#include <vector>

#include <Eigen/Core>

#include "epicycle/compliance/cracked_mesh.hpp"
#include "epicycle/compliance/influence_table.hpp"
#include "epicycle/compliance/root_crack.hpp"

namespace epicycle::compliance {

/// The damaged rows of one body. With D the teeth within ±K (`neighbours`) of the cracked tooth:
///
///   Λ(a → b) = Λ_D(a → b)          a ∈ D (rows solved on the cracked body, responses at all teeth)
///            = Λ_D(b → a)ᵀ         a ∉ D, b ∈ D (Maxwell–Betti)
///            = Λ_healthy(a → b)    otherwise (the shared cyclic table),
///
/// a, b flank positions, their teeth in D or not. Each row table is an InfluenceTable whose
/// "tooth 0" is its load tooth t (values in the frame of tooth t, response teeth counted from t),
/// built with the healthy table's options (same flank grid and join depth h, the join and the
/// layer term of the loaded point computed on the cracked body); the pairs with both teeth in D
/// are symmetrised by averaging. K = 1 by default: the crack changes the compliance of loads two
/// teeth away by less than the table's discretisation error (docs/model.md §9 gives the measured
/// decay). No fillet stresses are tabulated on a cracked body.
class DamagedInfluence {
 public:
  /// Meshes the cracked body (BuildCrackedGearMesh with options.mesh and crack_options; needs
  /// gmsh), factorises once and solves the unit loads on the 2K + 1 teeth of D (all teeth if
  /// 2K + 1 ≥ z). `options` must be those of the body's healthy table (options.fillet_stress is
  /// ignored).
  /// @throws std::invalid_argument for an invalid crack, options, neighbours outside [0, z), a
  ///         mesher failure or a build without gmsh.
  static DamagedInfluence Build(const geometry::Gear& gear, const ElasticMaterial& material,
                                const RootCrack& crack, const InfluenceTableOptions& options = {},
                                int neighbours = 1, const CrackMeshOptions& crack_options = {});

  const RootCrack& crack() const { return crack_; }
  int neighbours() const { return neighbours_; }  ///< K [-]
  int teeth() const { return teeth_; }            ///< z [-]
  /// true if the rows of loads on tooth k (any integer, modulo z) are held (k ∈ D).
  bool HoldsLoadsOn(int tooth) const;
  /// The row table of load tooth k ∈ D. @throws std::invalid_argument if k ∉ D.
  const InfluenceTable& Rows(int tooth) const;

  /// d_rᵀ Λ(load → response) d_l [m/N] by the rule of the class comment; `healthy` is the body's
  /// shared table, which also prepared both nodes (PrepareDirected: same grid, same stencils).
  double DirectedCompliance(const InfluenceTable& healthy, const InfluenceTable::DirectedNode& load,
                            const InfluenceTable::DirectedNode& response) const;
  /// Λ(load, response) [m/N], body frame, by the same rule.
  Eigen::Matrix2d Influence(const InfluenceTable& healthy, const FlankPosition& load,
                            const FlankPosition& response) const;

  /// max over the pairs of D |Λ(a→b) − Λ(b→a)ᵀ| / √(|D_a| |D_b|) before symmetrising [-].
  double raw_asymmetry() const { return raw_asymmetry_; }
  int num_dofs() const { return num_dofs_; }
  int sector_elements() const { return sector_elements_; }  ///< of the cracked sector
  /// CPU time [s]: mesh (healthy body, sector, crack), assembly + factorisation, solves.
  std::array<double, 3> build_seconds() const { return seconds_; }

  /// The rows in binary (the disk cache's payload, influence_cache.hpp): K, z, the counts and
  /// times, the load teeth, then each row table's InfluenceTable::WritePayload.
  void WritePayload(std::ostream& out) const;
  /// Reads a payload written by WritePayload for `gear` and `crack` (the caller has checked the
  /// key). @throws std::runtime_error for a payload that does not fit the gear.
  static DamagedInfluence ReadPayload(std::istream& in, const geometry::Gear& gear,
                                      const RootCrack& crack);

 private:
  RootCrack crack_;
  int neighbours_ = 1, teeth_ = 0, num_dofs_ = 0, sector_elements_ = 0;
  double raw_asymmetry_ = 0.0;
  std::array<double, 3> seconds_{};
  std::vector<InfluenceTable> rows_;
  std::vector<int> row_of_tooth_;  // [k] index into rows_, or −1
};

}  // namespace epicycle::compliance
