// The Newton's direct path (direct_newton.hpp).
#include "direct_newton.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace epicycle::solvers::internal {
namespace {

// The direct path's sweeps on a factorisation must contract at least this much each
// (DirectNewton::ModelStep); it also bounds how far u' may have moved from a kept factorisation.
constexpr double kMinContraction = 1e-2;

}  // namespace

void DirectNewton::Begin(bool reuse) {
  if (!reuse) factor_n_ = -1;  // a cold start does not use the previous call's factorisation
}

bool DirectNewton::Step(const ScaledProblem& p, const Eigen::VectorXd& g,
                        const Eigen::VectorXd& du, int it, double target, Eigen::VectorXd* x_io) {
  const int n = p.num_contacts();
  Eigen::VectorXd& x = *x_io;
  active_.clear();
  released_.clear();  // inactive contacts whose force is not yet zero
  for (int j = 0; j < n; ++j)
    if (!(x(j) > g(j)) && x(j) != 0.0) released_.push_back(j);
  // The active contacts ordered by slice group (ScaledProblem::slice_group; one group without a
  // Kronecker structure): C_AA is then block diagonal with one block per group, and Factor
  // factorises the blocks alone.
  group_start_.clear();
  for (int grp = 0; grp < p.slice_groups; ++grp) {
    group_start_.push_back(static_cast<int>(active_.size()));
    for (int j = 0; j < n; ++j)
      if (x(j) > g(j) && (p.slice_groups == 1 || p.slice_group[j % p.slices] == grp))
        active_.push_back(j);
  }
  group_start_.push_back(static_cast<int>(active_.size()));
  const int na = static_cast<int>(active_.size());
  r_.resize(na);
  du_a_.resize(na);
  // C_AA copied entry by entry: Eigen's indexed view with std::vector indices copies them
  // (allocations on every step). Only its diagonal blocks (one per slice group, the whole matrix
  // without a structure): every use of C_AA and of H_AA below stays inside them.
  c_aa_.resize(na, na);
  for (std::size_t grp = 0; grp + 1 < group_start_.size(); ++grp)
    for (int b = group_start_[grp]; b < group_start_[grp + 1]; ++b)
      for (int a = group_start_[grp]; a < group_start_[grp + 1]; ++a)
        c_aa_(a, b) = p.C(active_[a], active_[b]);
  for (int a = 0; a < na; ++a) {
    const int ja = active_[a];
    du_a_(a) = du(ja);
    if (x(ja) == 0.0) {
      // Entering from zero force, where u'(0⁺) = +∞: the secant u(x̂)/x̂ to the force x̂ =
      // −g_j/C_jj that would close its gap through the linear part alone (the floor keeps
      // it finite). The step then sees the local term's compliance at the scale of the
      // force it is heading for; the tangent at the floor (u' ~ ln(1/x), large) made the
      // first step of a cold start on the stage go only half way (4 iterations, now 3).
      const double guess = std::max(-g(ja) / p.C(ja, ja), kDerivativeFloor);
      double u_guess = 0.0, du_guess = 0.0;
      p.LocalAt(ja, guess, kDerivativeFloor, &u_guess, &du_guess);
      du_a_(a) = u_guess / guess;
    }
    // −g_A + C_AI x_I: the inactive contacts' forces go to zero in this step.
    double s = -g(ja);
    for (int j : released_) s += p.C(ja, j) * x(j);
    r_(a) = s;
  }
  for (int j : released_) x(j) = 0.0;
  if (na > 0) {
    // The first step of a warm start may solve, on the factorisation kept from the previous
    // call, the model of g_A at x + dx to second order in the local terms (ModelStep): when
    // that factorisation's active set is this one and its diagonal u' within kMinContraction
    // of this step's (C has moved by one time step, which the sweeps measure). Every other
    // step is Newton's on a new factorisation of C_AA + diag u'_A.
    bool kept = it == 0 && factor_n_ == n && active_ == factor_active_;
    for (int a = 0; kept && a < na; ++a)
      kept = std::abs(du_a_(a) - factor_du_(a)) <= kMinContraction * h_(a, a);
    if (!kept || !ModelStep(p, x, target)) {
      factor_n_ = -1;  // until the factorisation below has succeeded
      h_ = c_aa_;
      h_.diagonal() += du_a_;
      if (!Factor()) return false;
      factor_n_ = n;
      factor_active_ = active_;
      factor_du_ = du_a_;
      inv_diag_ = l_.diagonal().cwiseInverse();
      dx_ = r_;
      Substitute(&dx_);
    }
    for (int a = 0; a < na; ++a) x(active_[a]) += dx_(a);
  }
  return true;
}

bool DirectNewton::Factor() {
  // One group: Eigen's blocked Cholesky, its factor copied (no allocation at a size seen
  // before). Several: L is block diagonal like H (the entries between groups are zero), each
  // block's Cholesky column by column in place (L_jj = √(H_jj − Σ L_jk²), L_ij = (H_ij −
  // Σ L_ik L_jk)/L_jj over the block's own columns k), Σ_b n_b³/6 multiply-adds.
  const int groups = static_cast<int>(group_start_.size()) - 1;
  if (groups <= 1) {
    llt_.compute(h_);
    if (llt_.info() != Eigen::Success) return false;
    l_ = llt_.matrixLLT();
    return true;
  }
  // Only the blocks are copied: an entry of C between groups within validation's tolerance of
  // zero must not enter L.
  const int na = static_cast<int>(h_.rows());
  l_.setZero(na, na);
  for (int b = 0; b < groups; ++b) {
    const int lo = group_start_[static_cast<std::size_t>(b)],
              hi = group_start_[static_cast<std::size_t>(b) + 1];
    l_.block(lo, lo, hi - lo, hi - lo) = h_.block(lo, lo, hi - lo, hi - lo);
    for (int j = lo; j < hi; ++j) {
      double pivot = l_(j, j);
      for (int k = lo; k < j; ++k) pivot -= l_(j, k) * l_(j, k);
      if (!(pivot > 0.0)) return false;
      const double ljj = std::sqrt(pivot);
      l_(j, j) = ljj;
      for (int i = j + 1; i < hi; ++i) {
        double v = l_(i, j);
        for (int k = lo; k < j; ++k) v -= l_(i, k) * l_(j, k);
        l_(i, j) = v / ljj;
      }
    }
  }
  return true;
}

void DirectNewton::Substitute(Eigen::VectorXd* v) const {
  // L Lᵀ y = v by forward and back substitution, both along the columns of L (contiguous in
  // memory): for the few contacts of a stage, plain loops cost less than the general triangular
  // solvers, and with the diagonal's reciprocals kept with the factorisation the chain of
  // dependent operations multiplies instead of dividing.
  // With slice groups L is block diagonal: each block [lo, hi) is substituted on its own.
  double* r = v->data();
  const double* l = l_.data();  // lower triangle: L
  const double* inv_d = inv_diag_.data();
  const int na = static_cast<int>(v->size());
  for (std::size_t grp = 0; grp + 1 < group_start_.size(); ++grp) {
    const int lo = group_start_[grp], hi = group_start_[grp + 1];
    for (int k = lo; k < hi; ++k) {  // L z = v, column by column
      const double zk = r[k] * inv_d[k];
      r[k] = zk;
      const double* col = l + static_cast<std::ptrdiff_t>(k) * na;
      for (int i = k + 1; i < hi; ++i) r[i] -= col[i] * zk;
    }
    for (int i = hi - 1; i >= lo; --i) {  // Lᵀ y = z: row i of Lᵀ is column i of L
      const double* col = l + static_cast<std::ptrdiff_t>(i) * na;
      double s = r[i];
      for (int k = i + 1; k < hi; ++k) s -= col[k] * r[k];
      r[i] = s * inv_d[i];
    }
  }
}

bool DirectNewton::ModelStep(const ScaledProblem& p, const Eigen::VectorXd& x, double target) {
  // The model of the active gaps at x + dx, to second order in the local terms,
  //   (C_AA + diag u'_A) dx + q ∘ dx² = r,   q = ½ u''_A,
  // solved by fixed-point sweeps on the kept factorisation H_f, from dx = H_f⁻¹ r:
  //   dx ← dx + H_f⁻¹ (r − (C_AA + diag u'_A) dx − q ∘ dx²).
  // They contract by ρ ≈ ‖H_f⁻¹ (H − H_f + 2 diag(q∘dx))‖, ~1e-3 from the previous time step.
  //  - The quadratic term enters for contacts with x_a > 0 and |dx_a| ≤ x_a/2 (the first
  //    solve's step), where the Taylor series of u (a logarithm in x) converges fast; elsewhere
  //    (a contact entering from zero force) it is left out.
  //  - The sweeps stop when the estimated distance to the model's solution, ‖δ‖ρ/(1 − ρ), is
  //    below what the model itself neglects: 1 % of the target, or the third-order term
  //    |q_a dx_a³|/x_a (u''' ~ u''/x) when that is larger. The step is then Chebyshev's, of
  //    third order: from a warm start its error is below the target and one step reaches it,
  //    where Newton's (second order) needed a second step and a factorisation.
  //  - Sweeps that contract by less than kMinContraction each, or that need more than six, give
  //    up (false): the caller factorises and takes Newton's step.
  const int na = static_cast<int>(active_.size());
  dx_ = r_;
  Substitute(&dx_);
  q_.resize(na);
  for (int a = 0; a < na; ++a) {
    const int ja = active_[a];
    const double xa = x(ja);
    q_(a) =
        xa > 0.0 && std::abs(dx_(a)) <= 0.5 * xa ? 0.5 * p.LocalSecondDerivativeAt(ja, xa) : 0.0;
  }
  e_.resize(na);
  constexpr int kMaxSweeps = 6;
  double previous = dx_.cwiseAbs().maxCoeff();
  for (int k = 0; k < kMaxSweeps; ++k) {
    // e = r − C_AA dx − (u'_A + q∘dx)∘dx, C_AA dx by columns (contiguous; the general product
    // costs more at this size).
    e_ = r_;
    for (std::size_t grp = 0; grp + 1 < group_start_.size(); ++grp) {  // block by block
      const int lo = group_start_[grp], hi = group_start_[grp + 1];
      for (int b = lo; b < hi; ++b) {
        const double* col = c_aa_.data() + static_cast<std::ptrdiff_t>(b) * na;
        const double d = dx_(b);
        for (int a = lo; a < hi; ++a) e_(a) -= col[a] * d;
      }
    }
    double neglected = 0.01 * target;
    for (int a = 0; a < na; ++a) {
      const double qd = q_(a) * dx_(a);
      e_(a) -= (du_a_(a) + qd) * dx_(a);
      if (qd != 0.0)
        neglected = std::max(neglected, std::abs(qd * dx_(a) * dx_(a)) / x(active_[a]));
    }
    Substitute(&e_);
    dx_ += e_;
    const double size = e_.cwiseAbs().maxCoeff();
    const double rho = previous > 0.0 ? size / previous : 0.0;
    if (!(rho <= kMinContraction)) return false;
    if (size * rho <= (1.0 - rho) * neglected) return true;
    previous = size;
  }
  return false;
}

}  // namespace epicycle::solvers::internal
