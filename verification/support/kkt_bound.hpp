// How far two answers of one contact problem, each meeting the driver's residual tolerance τ,
// may lie apart (docs/solvers.md §12): a bound derived from the problem's KKT matrix on the
// reference's active set, computed here by a dense LU of its own (independent of any back end's
// factorisation).
//
// In the driver's nondimensional units (x = F/F*, λ̃_i = r_i λ_i/ℓ*, C̃ = C F*/ℓ*, G̃_i = G_i/r_i,
// S̃ = S ℓ*/(F* r r)), an answer meeting τ has on its active set A (x_j > τ) a gap
// g_A = C̃ x + u(x) − δ̃0 − G̃ᵀλ̃ with |g_A| ≤ τ, an equilibrium G̃ x + S̃ λ̃ − W̃ within τ, and off A
// 0 ≤ x_j ≤ τ. Two such answers with the same A differ by (Δx_A, Δλ̃) solving
//   K [Δx_A; Δλ̃] = Δr,   K = [H_AA  −G̃_Aᵀ; G̃_A  S̃],   H_AA = C̃_AA + diag u'(x_A),
// with |Δr| ≤ 2τ + ‖C̃_AI‖∞ τ on the gap rows (the |Δx_I| ≤ τ of the inactive contacts) and ≤ 2τ
// on the equilibrium rows, so
//   ‖Δx‖∞ ≤ max(τ, ‖K⁻¹‖∞ (2 + ‖C̃_AI‖∞) τ).
// u' is taken at the reference; between the two answers it moves by u''Δx, a relative change of
// the order of Δx/x ≈ 1e-8 here, second order in the bound.
#pragma once

#include <algorithm>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/LU>

#include "epicycle/solvers/contact_problem.hpp"
#include "epicycle/solvers/contact_solver.hpp"
#include "epicycle/solvers/local_term.hpp"

namespace epicycle::test {

struct KktBound {
  double bound = 0;              ///< on ‖x − x_ref‖∞ [-] (scaled forces)
  std::vector<int> active;       ///< A of the reference
  Eigen::VectorXd scaled_force;  ///< x_ref = F_ref/F*
  double force_scale = 1;        ///< F* [N]
};

inline KktBound ScaledKktBound(const solvers::ContactProblem& problem,
                               const solvers::ContactSolution& reference, double tolerance) {
  KktBound out;
  const solvers::ContactScales sc = solvers::ComputeContactScales(problem);
  out.force_scale = sc.force;
  const int n = problem.num_contacts(), m = problem.num_equalities();
  out.scaled_force = reference.force / sc.force;
  std::vector<int> inactive;
  for (int j = 0; j < n; ++j)
    (out.scaled_force(j) > tolerance ? out.active : inactive).push_back(j);
  const int na = static_cast<int>(out.active.size());
  const Eigen::MatrixXd c = problem.compliance() * (sc.force / sc.length);
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(na + m, na + m);
  k.topLeftCorner(na, na) = c(out.active, out.active);
  const auto& local = problem.data().local;
  for (int a = 0; a < na; ++a) {
    const int j = out.active[static_cast<std::size_t>(a)];
    if (!local.empty() && local[static_cast<std::size_t>(j)].enabled)
      k(a, a) += solvers::LocalApproachDerivative(local[static_cast<std::size_t>(j)],
                                                  reference.force(j)) *
                 sc.force / sc.length;
  }
  if (m > 0) {
    const Eigen::VectorXd inv_r = sc.row.cwiseInverse();
    const Eigen::MatrixXd g = inv_r.asDiagonal() * problem.equality_matrix();
    k.topRightCorner(na, m) = -g(Eigen::all, out.active).transpose();
    k.bottomLeftCorner(m, na) = g(Eigen::all, out.active);
    k.bottomRightCorner(m, m) =
        inv_r.asDiagonal() * problem.support_stiffness() * inv_r.asDiagonal() * (sc.length / sc.force);
  }
  const Eigen::MatrixXd k_inv = k.fullPivLu().inverse();
  const double k_inv_norm = k_inv.cwiseAbs().rowwise().sum().maxCoeff();
  const double c_ai =
      inactive.empty() ? 0.0 : c(out.active, inactive).cwiseAbs().rowwise().sum().maxCoeff();
  out.bound = std::max(tolerance, k_inv_norm * (2.0 + c_ai) * tolerance);
  return out;
}

}  // namespace epicycle::test
