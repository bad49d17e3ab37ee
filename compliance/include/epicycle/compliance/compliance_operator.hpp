// The compliance operator of a set of potential contacts (docs/model.md §4, paper Fig. 2): the
// structural compliance of every body that carries two contacts couples them, whichever meshes
// they belong to (a planet couples its sun-side and ring-side meshes; the sun and the ring couple
// all planets), and elastic supports fold in as the compliance of the body's centre.
#pragma once

#include <array>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "epicycle/compliance/influence_table.hpp"

namespace epicycle::compliance {

class DamagedInfluence;  // damaged_influence.hpp

/// One body as the operator sees it: its influence table (body frame, fixed at the hub or rim)
/// and its pose, plus an optional translational support compliance of its centre.
struct OperatorBody {
  const InfluenceTable* table = nullptr;             ///< not owned; several bodies may share one
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  ///< geometric centre, inertial [m]
  double rotation = 0.0;                             ///< θ of the body frame [rad]
  /// S_B [m/N], inertial frame: displacement of the body's centre per unit force on the body
  /// (an elastic bearing); zero for a held body. Symmetric positive semidefinite.
  Eigen::Matrix2d support = Eigen::Matrix2d::Zero();
  std::string name;  ///< for messages
  /// (Last, so that positional initialisers of the fields above keep working.) A damaged tooth's
  /// rows (a root crack), or null for a healthy body; not owned. Its rows replace `table`'s for
  /// every pair that involves a tooth near the damage (DamagedInfluence::DirectedCompliance);
  /// `table` is the healthy table of the same gear and options.
  const DamagedInfluence* damaged = nullptr;
};

/// Where a contact touches one body: the point on that body's profile and the unit direction of
/// the contact force acting on that body (for a contact with normal n from A into B: −n on A,
/// +n on B), both inertial.
struct ContactSide {
  int body = 0;                                         ///< index into the bodies
  int tooth = 0;                                        ///< tooth index in the body frame
  int flank = 1;                                        ///< σ = ±1 in the body frame
  Eigen::Vector2d point = Eigen::Vector2d::Zero();      ///< [m], inertial
  Eigen::Vector2d direction = Eigen::Vector2d::Zero();  ///< unit, inertial
};

/// A potential contact between two bodies.
struct OperatorContact {
  std::array<ContactSide, 2> side;
  std::string label;  ///< for messages
};

/// The contact compliance of the structural term and the supports,
///
///   C_jk = Σ_B [ d_Bjᵀ Λ_B(p_Bk → p_Bj) d_Bk + d_Bjᵀ S_B d_Bk ]   [m/N]
///
/// summed over the bodies B that carry both contacts j and k, with d_Bj the direction of contact
/// j's force on B and Λ_B the body's influence table (body frame, rotated to the inertial frame):
/// the recession of the two surfaces at j under unit forces at k. For j = k and the same body the
/// table's self term is its depth-h read-out, to which the local term of each body is added by the
/// contact problem (solvers::LocalTermParameters). Each contact side is located on its body's
/// flank once; the table is then interpolated for every pair. The result is symmetric (the tables
/// are symmetrised) and positive definite for distinct contacts on held bodies.
/// @param off_flank null: a point that is not on its named flank throws; otherwise such a point
///        (a pose past the tables' flank grids: a geometric outcome, not bad input) returns an
///        empty matrix with the reason here.
/// @throws std::invalid_argument for a body index out of range, a body without table, a
///         non-unit direction, or (off_flank null) a point that is not on the named flank (the
///         message names the contact's label and the body).
Eigen::MatrixXd AssembleCompliance(const std::vector<OperatorBody>& bodies,
                                   const std::vector<OperatorContact>& contacts,
                                   std::string* off_flank = nullptr);
/// The same into `out`, reusing its storage (no allocation once it has held an N×N matrix and
/// the thread has assembled N contacts before); resized to 0×0 for a point off its flank.
void AssembleCompliance(const std::vector<OperatorBody>& bodies,
                        const std::vector<OperatorContact>& contacts, Eigen::MatrixXd* out,
                        std::string* off_flank = nullptr);

/// The root stress of one fillet: side `side` of tooth `tooth` of body `body`.
struct FilletStress {
  int body = 0;
  int tooth = 0;                          ///< k in [0, z), body frame
  int side = 0;                           ///< 0: σ = +1, 1: σ = −1
  std::span<const double> sigma;          ///< σ_tt [Pa] at the body table's fillet_points()
  const InfluenceTable* table = nullptr;  ///< the body's table (its fillet_points()), not owned
  /// The storage `sigma` views: one block for all fillets of a state (FilletStresses), kept alive
  /// by each of them and their copies (a state's fillets cost one allocation, not one each).
  std::shared_ptr<const double[]> values;
};

/// The root stresses of a state (docs/model.md §9): σ_tt(p) = Σ_j S_B(p; j) F_j on both fillets
/// of every tooth within `neighbours` teeth of one that carries a contact with F_j > 0, per body,
/// from each body's table (InfluenceTable::AddFilletStress) with the contact sides located as
/// AssembleCompliance locates them. Contacts with F_j ≤ 0 carry nothing. Bodies are listed in
/// order, teeth ascending, side 0 before 1.
/// @throws std::invalid_argument as AssembleCompliance (a side off its flank throws), for a table
///         built without fillet stresses, a damaged body (no root stresses are tabulated on a
///         cracked body), `force` not of one entry per contact, or neighbours < 0.
std::vector<FilletStress> FilletStresses(const std::vector<OperatorBody>& bodies,
                                         const std::vector<OperatorContact>& contacts,
                                         const Eigen::VectorXd& force, int neighbours = 1);

}  // namespace epicycle::compliance
