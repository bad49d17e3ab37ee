// The active-set Newton's direct path for problems without equalities (every dynamic step):
// Newton on the natural map min(x, g(x)) = 0, g = C x + u(x) − δ0, with the active set
// A = {j : x_j > g_j} re-chosen at every step, and on a warm start a third-order first step on the
// factorisation kept from the previous call (docs/solvers.md §3, "Direct path for problems without
// equalities"). Its answer is a proposal: the driver (contact_solver.cpp) recomputes the residual
// from the forces alone and runs the general path when that residual misses the tolerance,
// whatever the path's own stopping test said.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Dense>

#include "backend.hpp"
#include "epicycle/solvers/contact_solver.hpp"

namespace epicycle::solvers::internal {

/// A fast path the driver tries before a back end's general path on problems without equalities.
class DirectPath {
 public:
  virtual ~DirectPath() = default;
  /// @param target the path's own stopping threshold on ‖min(x, g)‖∞ (scaled).
  /// @param reuse may start with state kept from the previous call (a warm start).
  /// @param x in: the start (empty: cold, x = 0); out: the proposed answer.
  /// @return false if the path gave up (the general path then runs from the caller's start).
  virtual bool Run(const ScaledProblem& p, double target, int max_iterations, bool reuse,
                   Eigen::VectorXd* x, int* iterations) = 0;
};

/// With `reuse`, the first step, if its active set is the one of the factorisation kept from the
/// previous call (a warm start's neighbour) and u'_A has moved by less than 1 % since, solves on
/// that factorisation the model of g_A at x + dx to second order in the local terms,
///   (C_AA + diag u'_A) dx + ½ u''_A ∘ dx² = r,
/// by fixed-point sweeps (each one substitution and one product with C_AA; ModelStep): a
/// Chebyshev step, of third order, that from the previous time step reaches the target at once
/// without a factorisation, where Newton's step (second order) left ~1e-7 and needed a second
/// step on a new factorisation. Sweeps that do not contract 100× each give up and the step is
/// Newton's on a new factorisation, as every later step is; the answer is judged by the same
/// residual either way.
class DirectNewton final : public DirectPath {
 public:
  bool Run(const ScaledProblem& p, double target, int max_iterations, bool reuse,
           Eigen::VectorXd* x, int* iterations) override;

 private:
  /// The step on the local model (see Run), on llt_; false if its sweeps do not converge.
  bool ModelStep(const ScaledProblem& p, const Eigen::VectorXd& x, double target);
  void Substitute(Eigen::VectorXd* v) const;  ///< v ← (L Lᵀ)⁻¹ v with llt_

  Eigen::VectorXd u_, du_, g_;             ///< per contact (g_ its own gap, for its steps)
  Eigen::VectorXd r_, du_a_, q_, dx_, e_;  ///< per active contact
  Eigen::MatrixXd c_aa_;                   ///< C_AA of the step
  Eigen::VectorXd inv_diag_;               ///< 1/L_ii of llt_
  Eigen::MatrixXd h_;
  Eigen::LLT<Eigen::MatrixXd> llt_;
  std::vector<int> active_, released_;
  // What llt_ factorises: C_AA + diag u'_A for the active set factor_active_ of a problem with
  // factor_n_ contacts (−1: nothing usable).
  std::vector<int> factor_active_;
  Eigen::VectorXd factor_du_;  ///< the u'_A in it
  int factor_n_ = -1;
};

/// The driver (contact_solver.cpp) for `backend` with `direct` as its direct path (used only by
/// the Newton back end on problems without equalities and without back-end options). Public
/// solvers come from MakeContactSolver, whose Newton uses DirectNewton; this entry lets the
/// suite hand the driver a path whose answers it controls.
std::unique_ptr<ContactSolver> MakeDriverSolver(Backend backend,
                                                std::unique_ptr<DirectPath> direct);

}  // namespace epicycle::solvers::internal
