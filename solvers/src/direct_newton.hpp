// The active-set Newton's direct path for problems without equalities (every dynamic step):
// Newton on the natural map min(x, g(x)) = 0, g = C x + u(x) − δ0, with the active set
// A = {j : x_j > g_j} re-chosen at every step, and on a warm start a third-order first step on the
// factorisation kept from the previous call (docs/solvers.md §3, "Direct path for problems without
// equalities"). The driver (contact_solver.cpp) runs the iterations and judges every iterate by
// its own residual; the path only proposes the next iterate.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Dense>

#include "backend.hpp"
#include "epicycle/solvers/contact_solver.hpp"

namespace epicycle::solvers::internal {

/// A fast path the driver tries before a back end's general path on problems without equalities.
/// The driver runs its iterations: at every iterate it computes the gap g, the local terms'
/// slopes u' and the residual itself (ScaledProblem::NaturalResidual), stops when its residual
/// meets the target, gives up after three iterates without a new best residual or at the
/// iteration limit, and otherwise asks the path for the next iterate. The path has no stopping
/// test of its own: what it proposes is judged by the driver's residual alone.
class DirectPath {
 public:
  virtual ~DirectPath() = default;
  /// Before the first step of a solve; `reuse`: a warm start, which may use state kept from the
  /// previous call.
  virtual void Begin(bool reuse) = 0;
  /// The next iterate from x, given the driver's g = ∇Φ(x) and u'(x) at it; `iteration` counts
  /// from 0, `target` is the driver's stopping threshold on ‖min(x, g)‖∞ (scaled).
  /// @return false if the path cannot step (the general path then runs).
  virtual bool Step(const ScaledProblem& p, const Eigen::VectorXd& g, const Eigen::VectorXd& du,
                    int iteration, double target, Eigen::VectorXd* x) = 0;
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
  void Begin(bool reuse) override;
  bool Step(const ScaledProblem& p, const Eigen::VectorXd& g, const Eigen::VectorXd& du,
            int iteration, double target, Eigen::VectorXd* x) override;

 private:
  /// The step on the local model (see the class comment), on l_; false if its sweeps do not
  /// converge.
  bool ModelStep(const ScaledProblem& p, const Eigen::VectorXd& x, double target);
  void Substitute(Eigen::VectorXd* v) const;  ///< v ← (L Lᵀ)⁻¹ v with l_
  /// L of h_ into l_ (block by block over the slice groups); false if h_ is not positive
  /// definite.
  bool Factor();

  Eigen::VectorXd r_, du_a_, q_, dx_, e_;  ///< per active contact
  Eigen::MatrixXd c_aa_;                   ///< C_AA of the step
  Eigen::VectorXd inv_diag_;               ///< 1/L_ii of l_
  Eigen::MatrixXd h_;
  Eigen::LLT<Eigen::MatrixXd> llt_;
  Eigen::MatrixXd l_;  ///< L of h_ (lower triangle), the factor every substitution uses
  std::vector<int> active_, released_;
  std::vector<int> group_start_;  ///< first position in active_ of each slice group, then n_A
  // What l_ factorises: C_AA + diag u'_A for the active set factor_active_ of a problem with
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
