// The active-set Newton's face system (active_set_newton.cpp), on the active contacts A:
//
//      [ H_AA  −G_Aᵀ ] [dx_A]   [r1]        H_AA = C_AA + diag(u'_A),
//      [ G_A     S   ] [ dλ ] = [r2],
//
// solved by the Cholesky factorisation of H_AA and of the m×m Schur complement
// G_A H_AA⁻¹ G_Aᵀ + S (an eigen-decomposition with a ridge if it is singular or nearly so), with
// one step of iterative refinement (docs/solvers.md §12).
//
// Block factorisation: when the compliance's Kronecker structure leaves groups of slices
// uncoupled (ScaledProblem::slice_group), H_AA is block diagonal over the groups and each block
// is factorised on its own; the Schur complement is the sum of the blocks' G_b H_b⁻¹ G_bᵀ.
//
// Without local terms H_AA depends on A alone: an unchanged A keeps the factorisation.
//
// Kronecker factorisation (docs/solvers.md §12, "Kronecker factorisation"): with one term
// C = C_n ⊗ W whose kernel W = Q Λ Qᵀ couples every slice, an active set made of whole contacts
// (every slice of the contacts J) and a diagonal uniform over each contact's slices
// (u'_{jS+s} = d_j: the cold start, x = 0), H_AA = C_n,JJ ⊗ W + D_J ⊗ I. In W's eigenbasis it is
// block diagonal, (I ⊗ Q)ᵀ H_AA (I ⊗ Q) = ⊕_s (λ_s C_n,JJ + D_J) in the slice-major order, so S
// Cholesky factorisations of |J|×|J| (S·|J|³/3 multiply-adds instead of (S·|J|)³/3) and two
// products by Q per solve (2·S²·|J|) replace the dense factorisation. The factors match the dense
// C to 1e-10·max|C| (validation's rule), so every Kronecker solve takes one step of iterative
// refinement on the dense H_AA. Any other active set or diagonal takes the dense (or block)
// path.
#pragma once

#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include "backend.hpp"

namespace epicycle::solvers::internal {

class FaceSolver {
 public:
  explicit FaceSolver(const ScaledProblem& p) : p_(p), m_(p.num_equalities()) {}

  /// H_AA = C_AA + diag(du) (du: one entry per active contact, or empty for none). Returns false
  /// if H_AA is not positive definite.
  bool Factor(const std::vector<int>& active, const Eigen::VectorXd& du);

  /// The face system's solution for the current H_AA.
  void Solve(const Eigen::VectorXd& r1, const Eigen::VectorXd& r2, Eigen::VectorXd* dxa,
             Eigen::VectorXd* dl) const;

  bool ridged() const { return pinv_; }
  void Invalidate() { have_ = false; }

  /// Counts since construction: factorisations of H_AA (dense or block), and those of them done
  /// through the Kronecker structure.
  int factorisations() const { return factorisations_; }
  int kronecker_factorisations() const { return kronecker_factorisations_; }

 private:
  bool FactorH();
  bool FactorKronecker(const Eigen::VectorXd& du);
  void Residual(const Eigen::VectorXd& r1, const Eigen::VectorXd& r2, const Eigen::VectorXd& dxa,
                const Eigen::VectorXd& dl, Eigen::VectorXd* e1, Eigen::VectorXd* e2) const;
  void SolveOnce(const Eigen::VectorXd& r1, const Eigen::VectorXd& r2, Eigen::VectorXd* dxa,
                 Eigen::VectorXd* dl) const;
  Eigen::VectorXd HSolve(const Eigen::VectorXd& r) const;

  const ScaledProblem& p_;
  int m_;
  std::vector<int> active_;
  bool have_ = false, pinv_ = false;
  int factorisations_ = 0, kronecker_factorisations_ = 0;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> s_eig_;
  Eigen::VectorXd inv_ev_;
  Eigen::MatrixXd h_, ga_, y_, schur_;
  Eigen::LLT<Eigen::MatrixXd> h_llt_, s_llt_;
  std::vector<std::vector<int>> blocks_;  // positions in active_ of each slice group; empty: dense
  std::vector<Eigen::LLT<Eigen::MatrixXd>> block_llt_;
  Eigen::MatrixXd hb_;
  // Kronecker path: the kernel's eigenvectors Q (S×S) and eigenvalues λ (once per solver), the
  // factors of λ_s C_n,JJ + D_J per slice mode s; kron_ says the current factorisation is one.
  bool kron_ = false;
  Eigen::MatrixXd kq_;
  Eigen::VectorXd klambda_;
  std::vector<Eigen::LLT<Eigen::MatrixXd>> kron_llt_;
};

}  // namespace epicycle::solvers::internal
