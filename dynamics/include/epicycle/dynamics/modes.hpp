// Natural modes of the linearised stage and their classification after Lin & Parker (1999)
// (docs/model.md §7, docs/modes.md).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace epicycle::dynamics {

/// Where one member's coordinates sit in the DOF vector q (inertial frame, docs/model.md §2).
struct MemberDofs {
  std::string name;     ///< "sun", "ring", "carrier", "planet 1", ... (for messages and tables)
  bool central = true;  ///< sun, ring, carrier: true; planets: false
  int x = -1;           ///< index of x [m] in q, −1: not a DOF (held)
  int y = -1;           ///< index of y [m] in q, −1: not a DOF
  int theta = -1;       ///< index of θ [rad] in q, −1: not a DOF
};

/// Lin & Parker's (1999) classes of planetary modes.
enum class ModeType {
  kRotational,     ///< central members only rotate (no translation); multiplicity 1
  kTranslational,  ///< central members only translate (no rotation); multiplicity 2
  kPlanet,         ///< central members still, only planets move; multiplicity n − 3
  kOther           ///< none of these (e.g. unequally spaced planets, mixed degenerate groups)
};

/// "rotational", "translational", "planet", "other".
std::string ModeTypeName(ModeType type);

/// One distinct natural frequency with its (possibly degenerate) mode subspace.
struct Mode {
  double frequency = 0;  ///< f = ω/2π [Hz] (exactly 0 for rigid-body modes)
  ModeType type = ModeType::kOther;
  int multiplicity = 1;    ///< number of eigenvalues grouped into this frequency
  bool rigid = false;      ///< a rigid-body (zero-frequency) group, see SolveModes
  Eigen::VectorXd shape;   ///< the first mode of the group, M-normalised: φᵀMφ = 1
  Eigen::MatrixXd shapes;  ///< all modes of the group (columns), M-orthonormal: ΦᵀMΦ = I
  /// Kinetic-energy fractions of the group (sum to 1), averaged over its modes:
  ///   e_d = (1/m) Σ_k φ_k,d (M φ_k)_d
  /// summed over the DOFs of each class. Σ_k φ_k φ_kᵀ M is the M-orthogonal projector on the
  /// group's subspace, so these numbers do not depend on which basis the eigensolver picked
  /// inside a degenerate subspace.
  double central_translation = 0;     ///< x, y of central members [-]
  double central_rotation = 0;        ///< θ of central members [-]
  double planets = 0;                 ///< every DOF of non-central members [-]
  std::vector<double> member_energy;  ///< per member of the layout, in its order [-]
};

/// Energy fraction below which a class of motion counts as absent in the classification [-].
/// Why 1e-8: an eigenvector component that is zero in exact arithmetic comes out of a dense
/// symmetric eigensolver at ~ε·κ ≈ 1e-16·1e4 relative size, i.e. an energy of ~1e-24; a class
/// that truly moves carries a fraction far above 1e-8 in any model with sensible stiffness ratios.
inline constexpr double kModeEnergyTolerance = 1e-8;
/// Eigenvalues λ = ω² with |λ| ≤ kRigidEigenvalueTolerance·max|λ| are rigid-body modes
/// (frequency 0). Why: round-off in λ is ~ε·max|λ| ≈ 2e-16·max|λ|; the threshold is 5·10⁵ times
/// that, and corresponds to f ≤ 1e-5·f_max (e.g. 0.1 Hz below a 10 kHz top mode).
inline constexpr double kRigidEigenvalueTolerance = 1e-10;

/// Solves the generalised symmetric eigenproblem K φ = ω² M φ (M symmetric positive definite,
/// K symmetric positive semidefinite) and groups and classifies its modes:
/// - sorted by frequency; consecutive frequencies f_j with |f_j − f_first| ≤ tol·f_j, f_first the
///   lowest of the group, form one entry with its multiplicity (tol = degeneracy_tolerance);
/// - rigid-body eigenvalues (see kRigidEigenvalueTolerance) form one group at frequency 0, rigid;
/// - classified from the group's kinetic-energy fractions with kModeEnergyTolerance:
///   planet if central_translation + central_rotation ≤ tol; else rotational if
///   central_translation ≤ tol; else translational if central_rotation ≤ tol; else other.
/// Every DOF of q must belong to exactly one member of `layout`.
/// @throws std::invalid_argument naming the argument, value and rule if M, K are not square, of
///   equal size, finite and symmetric (|A_ij − A_ji| ≤ 1e-10·max|A|), M not positive definite, the
///   layout's indices out of range, repeated or incomplete, or degeneracy_tolerance not in (0, 1).
/// @throws std::domain_error if K has an eigenvalue below −kRigidEigenvalueTolerance·max|λ|
///   (the linearisation is unstable: no real frequency exists).
std::vector<Mode> SolveModes(const Eigen::MatrixXd& M, const Eigen::MatrixXd& K,
                             const std::vector<MemberDofs>& layout,
                             double degeneracy_tolerance = 1e-6);

}  // namespace epicycle::dynamics
