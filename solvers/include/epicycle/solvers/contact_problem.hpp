// The nonlinear constrained contact problem (docs/model.md §3): data only, validated on
// construction. It knows nothing of gears: plain Eigen data in SI units.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "epicycle/solvers/local_term.hpp"

namespace epicycle::solvers {

/// One term of a compliance given as a sum of Kronecker products (docs/solvers.md §12): for n
/// source contacts of S slices each, contact i = j·S + s (slice s of source contact j) and
///
///   C_{jS+s, kS+t} = Σ_terms source_jk · kernel_st,   i.e.  C = Σ_terms source ⊗ kernel.
///
/// The face-width slices (transmission/face_width.hpp) give one term C_n ⊗ W; a body compliance
/// acting on the face's mean load adds C_body ⊗ 1 1ᵀ.
struct KroneckerTerm {
  Eigen::MatrixXd source;  ///< n×n [m/N], symmetric positive semidefinite
  Eigen::MatrixXd kernel;  ///< S×S [-], symmetric positive semidefinite
};

/// Unknowns: contact forces F ∈ ℝᴺ and multipliers λ ∈ ℝᵐ (rigid displacements of the members
/// whose position is set by equilibrium). With u(F) = C F + u_local(F):
///
///   gap:          g = C F + u_local(F) − δ0 − Gᵀλ ≥ 0,   F ≥ 0,   Fᵀg = 0
///   equilibrium:  G F + K λ = W
///
/// K = 0 (the default) makes G F = W hard equalities; a positive semidefinite K is the stiffness
/// of elastic supports (rows with K = 0 stay hard): the member's equilibrium is G F + K λ = W with
/// λ its support deflection. This is the KKT system of the convex program
///   min Φ(F) = ½FᵀCF + Σ_j ∫₀^{F_j} u_local,j − δ0ᵀF (+ ½(GF−W)ᵀK⁻¹(GF−W))  s.t. F ≥ 0, (GF = W).
struct ContactProblemData {
  std::string name;                        ///< free text, used in reports and file names
  Eigen::MatrixXd compliance;              ///< C [m/N], N×N, symmetric positive definite (see below)
  Eigen::VectorXd overlap;                 ///< δ0 [m], N; > 0 interpenetration, < 0 gap
  std::vector<LocalTermParameters> local;  ///< empty (no local terms) or N entries
  Eigen::MatrixXd equality_matrix;    ///< G, m×N [-] (force rows) or [m] (moment rows); m may be 0
  Eigen::VectorXd equality_rhs;       ///< W, m [N] or [N·m]
  Eigen::MatrixXd support_stiffness;  ///< K, m×m [N/m] or [N·m/rad]; empty means 0
  std::vector<std::string>
      contact_labels;  ///< empty or N labels (e.g. "sun-planet1 tooth 3 drive")
  std::vector<std::string> multiplier_labels;  ///< empty or m labels (e.g. "sun rotation [rad]")
  /// Empty, or the structure of `compliance`: C = Σ source ⊗ kernel (KroneckerTerm). The dense
  /// `compliance` stays the problem's definition (every residual and every back end uses it); the
  /// structure lets validation prove positive definiteness from the factors and lets the Newton
  /// factorise C_AA block by block when the kernels leave groups of slices uncoupled.
  std::vector<KroneckerTerm> compliance_terms;
};

/// A validated contact problem. Construction checks (each failure throws std::invalid_argument
/// whose message names the field, the offending value and the rule):
///  - sizes: C N×N with N ≥ 1, δ0 N, local empty or N, G m×N, W m, S empty or m×m, labels empty or
///    of the matching size;
///  - every entry finite;
///  - C symmetric to |C_ij − C_ji| ≤ kSymmetryTolerance·max|C| and positive definite (Cholesky of
///    its symmetric part), or, when every contact has an enabled local term, positive
///    semidefinite (eigenvalues ≥ −kSymmetryTolerance·max|C|): contacts that share their rows of
///    C (the strips of a pitted contact) are then told apart by their local terms, which keep
///    the program strictly convex;
///  - compliance_terms, when given: every source n×n and every kernel S×S with n·S = N, each
///    symmetric (same rule), and C = Σ source ⊗ kernel entry by entry to kSymmetryTolerance·max|C|
///    (O(N²)). When every factor is positive semidefinite and one term has both factors positive
///    definite (Cholesky of the n×n and S×S factors), Σ source ⊗ kernel is positive definite
///    (the eigenvalues of A ⊗ B are the products of theirs) and the O(N³) test of C is skipped;
///    otherwise C is tested as above. A C that is exactly (bit for bit) Σ source ⊗ kernel of one
///    or two terms whose factors are exactly symmetric, with finite sums, as the face-width model
///    writes it, meets the rules on C as it stands: it is checked in one pass in storage order
///    instead of the rules' three (finiteness, symmetry, the terms' sum);
///  - S symmetric (same rule) and positive semidefinite (eigenvalues ≥ −kSymmetryTolerance·max|S|);
///  - local-term parameters: face width, R_eq, E, h > 0, 0 ≤ ν < 0.5 (see ValidateLocalTerm).
/// The stored C and S are the symmetric parts of the input.
class ContactProblem {
 public:
  static constexpr double kSymmetryTolerance = 1e-10;  ///< relative [-]

  /// @throws std::invalid_argument naming the field, its value and the rule.
  explicit ContactProblem(ContactProblemData data);

  const ContactProblemData& data() const { return data_; }
  const std::string& name() const { return data_.name; }
  int num_contacts() const { return static_cast<int>(data_.overlap.size()); }
  int num_equalities() const { return static_cast<int>(data_.equality_rhs.size()); }
  bool has_local() const;    ///< any local term enabled
  bool has_support() const;  ///< K has a non-zero entry
  const Eigen::MatrixXd& compliance() const { return data_.compliance; }
  const Eigen::VectorXd& overlap() const { return data_.overlap; }
  const Eigen::MatrixXd& equality_matrix() const { return data_.equality_matrix; }
  const Eigen::VectorXd& equality_rhs() const { return data_.equality_rhs; }
  const Eigen::MatrixXd& support_stiffness() const { return support_; }  ///< m×m (zeros if empty)
  const std::vector<KroneckerTerm>& compliance_terms() const { return data_.compliance_terms; }
  /// S of compliance_terms (1 without them).
  int slices() const {
    return data_.compliance_terms.empty() ? 1
                                          : static_cast<int>(data_.compliance_terms[0].kernel.rows());
  }
  /// Whether validation proved C positive definite from its Kronecker factors (no O(N³) test).
  bool definite_by_structure() const { return definite_by_structure_; }

  /// u_local(F) [m] for every contact (0 where there is no local term), F ≥ 0.
  Eigen::VectorXd LocalApproach(const Eigen::VectorXd& force) const;
  /// Gap g = C F + u_local(F) − δ0 − Gᵀλ [m].
  Eigen::VectorXd Gap(const Eigen::VectorXd& force, const Eigen::VectorXd& multiplier) const;
  /// Φ(F) [J] (without the support term), F ≥ 0.
  double Potential(const Eigen::VectorXd& force) const;
  /// Force [N] at which contact j's Hertz half-width reaches its depth h (+∞ without local term).
  double ValidityLimitForce(int contact) const;

  /// Moves the data out (as validated: C and S their symmetric parts), for a caller that builds a
  /// problem from buffers it reuses (the dynamic model, once per right-hand side): no copy either
  /// way. The problem is left empty and must not be used again.
  ContactProblemData Release() &&;

 private:
  ContactProblemData data_;
  Eigen::MatrixXd support_;
  bool definite_by_structure_ = false;
};

}  // namespace epicycle::solvers
