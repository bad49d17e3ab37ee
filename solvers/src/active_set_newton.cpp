// Our own back end, in two phases on the nondimensional problem:
//
// 1. Semismooth (primal-dual active-set) Newton on the natural map of the KKT system,
//      R(x, λ) = ( min(x, g(x, λ)) ; G x + S λ − W ),   g = C x + u(x) − δ0 − Gᵀλ,
//    globalised by a non-monotone backtracking line search on ½‖R‖². Each iteration takes
//    A = {j : x_j > g_j}, sets x_j = 0 off A and solves the linearised g_A = 0, G x + S λ = W.
//    Fast (a handful of iterations from a cold start, one from a good warm start) but, like any
//    natural-map Newton, not globally convergent.
// 2. If phase 1 stalls (line search failures, iteration budget): a primal feasible active-set
//    Newton that decreases the potential Φ: start from a point with x ≥ 0, G x = W
//    (non-negative least squares), Newton steps on the current face with a ratio test and an
//    Armijo search on Φ, drop blocking contacts, add the contact with the most negative gap.
//    Φ decreases monotonically over finitely many faces: globally convergent. Elastic supports
//    are folded into the potential for this phase (see Run), so that it has hard equalities only.
//
// Both phases solve the same linear systems
//      [ H_AA  −G_Aᵀ ] [dx_A]   [r1]        H_AA = C_AA + diag(u'(x_A)),
//      [ G_A     S   ] [ dλ ] = [r2],
// by the Cholesky factorisation of H_AA and of the m×m Schur complement G_A H_AA⁻¹ G_Aᵀ + S
// (a pseudo-inverse if it is singular or nearly so), with one step of iterative refinement. u'(0⁺)
// = +∞ (logarithmically): u' is evaluated at max(|x_j|, kDerivativeFloor), which only matters for
// contacts entering the active set from zero force (the direct path, direct_newton.hpp, uses a
// secant there).
// Without local terms H_AA does not depend on x and the factorisation is reused while the active
// set does not change. The face system is face_solver.hpp's: block by block over uncoupled slice
// groups, or in the kernel's eigenbasis for a Kronecker compliance C_n ⊗ W at the cold start.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <limits>
#include <stdexcept>
#include <string>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "backend.hpp"
#include "face_solver.hpp"

namespace epicycle::solvers::internal {
namespace {

double ParseOption(const ContactOptions& options, const std::string& key, double fallback) {
  const auto it = options.backend_options.find("newton." + key);
  if (it == options.backend_options.end()) return fallback;
  try {
    std::size_t used = 0;
    const double v = std::stod(it->second, &used);
    if (used != it->second.size()) throw std::invalid_argument("trailing characters");
    return v;
  } catch (const std::exception&) {
    throw std::invalid_argument("backend_options[newton." + key + "] = '" + it->second +
                                "': must be a number");
  }
}

// u'_A at max(|x_A|, floor) (0 for a contact without a local term), the diagonal of the face
// system's H_AA; empty without local terms.
void ActiveDerivatives(const ScaledProblem& p, const std::vector<int>& active,
                       const Eigen::VectorXd& x, Eigen::VectorXd* du) {
  if (!p.has_local) {
    du->resize(0);
    return;
  }
  du->setZero(static_cast<Eigen::Index>(active.size()));
  for (std::size_t a = 0; a < active.size(); ++a)
    if (p.local[active[a]].enabled)
      (*du)(static_cast<Eigen::Index>(a)) =
          p.LocalDerivativeAt(active[a], std::max(std::abs(x(active[a])), kDerivativeFloor));
}

class ActiveSetNewton final : public BackendImpl {
 public:
  bool available() const override { return true; }
  std::vector<std::string> option_keys() const override {
    return {"ls_beta", "ls_sigma", "ls_max_halvings", "ls_memory", "phase1_only", "phase2_only"};
  }

  BackendResult Run(const ScaledProblem& p, const ContactOptions& options,
                    const Eigen::VectorXd* x0, const Eigen::VectorXd* lambda0) override {
    start_ = std::chrono::steady_clock::now();
    beta_ = ParseOption(options, "ls_beta", 0.5);
    sigma_ = ParseOption(options, "ls_sigma", 1e-4);
    max_halvings_ = static_cast<int>(ParseOption(options, "ls_max_halvings", 40));
    memory_ = static_cast<int>(ParseOption(options, "ls_memory", 5));
    const bool phase1_only = ParseOption(options, "phase1_only", 0) != 0;
    const bool phase2_only = ParseOption(options, "phase2_only", 0) != 0;
    if (!(beta_ > 0 && beta_ < 1) || !(sigma_ > 0 && sigma_ < 0.5) || max_halvings_ < 1 ||
        memory_ < 1)
      throw std::invalid_argument(
          "backend_options newton.*: need 0 < ls_beta < 1, 0 < ls_sigma < 0.5, "
          "ls_max_halvings >= 1, ls_memory >= 1");
    options_ = &options;
    // Stop a little below the driver's tolerance so that its own evaluation agrees.
    target_ = 0.1 * options.tolerance;

    BackendResult out;
    if (!phase2_only) {
      out = Phase1(p, x0, lambda0);
      if (!out.failed && !out.limit_reached) return out;
    }
    if (phase1_only) return out;
    BackendResult second;
    if (p.has_support) {
      // Phase 2 needs hard equalities: the supported rows P are folded into the potential,
      // ½(G_P x − W_P)ᵀ S_PP⁻¹ (G_P x − W_P), i.e. C + G_Pᵀ S_PP⁻¹ G_P and δ0 + G_Pᵀ S_PP⁻¹ W_P
      // (docs/model.md §5), and λ_P = S_PP⁻¹ (W_P − G_P x) afterwards.
      std::vector<int> supported, hard;
      for (int i = 0; i < p.num_equalities(); ++i)
        (p.S.row(i).cwiseAbs().maxCoeff() > 0.0 ? supported : hard).push_back(i);
      const Eigen::MatrixXd spp = p.S(supported, supported);
      const Eigen::LLT<Eigen::MatrixXd> spp_llt(spp);
      if (spp_llt.info() != Eigen::Success || !(spp_llt.rcond() > 1e-12)) {
        if (phase2_only) {
          out.failed = true;
          out.message = "phase 2: the support block S_PP is singular";
        }
        return out;
      }
      ScaledProblem q = p;
      const Eigen::MatrixXd gp = p.G(supported, Eigen::all);
      const Eigen::MatrixXd s_inv_gp = spp_llt.solve(gp);
      q.C = p.C + gp.transpose() * s_inv_gp;
      q.slice_groups = 1;  // the folded supports couple every contact: no block structure
      q.kron_source.resize(0, 0);  // nor a Kronecker one
      q.kron_kernel.resize(0, 0);
      const Eigen::VectorXd wp = p.W(supported);
      q.delta0 = p.delta0 + s_inv_gp.transpose() * wp;
      q.G = p.G(hard, Eigen::all);
      q.W = p.W(hard);
      q.S = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(hard.size()),
                                  static_cast<Eigen::Index>(hard.size()));
      q.has_support = false;
      second = Phase2(q);
      if (second.force.size() == p.num_contacts() && second.force.allFinite()) {
        Eigen::VectorXd lambda = Eigen::VectorXd::Zero(p.num_equalities());
        if (second.multiplier.size() == static_cast<Eigen::Index>(hard.size()))
          lambda(hard) = second.multiplier;
        const Eigen::VectorXd rest = wp - gp * second.force;
        const Eigen::VectorXd lp = spp_llt.solve(rest);
        lambda(supported) = lp;
        second.multiplier = lambda;
      }
    } else {
      second = Phase2(p);
    }
    second.iterations += out.iterations;
    second.message = (phase2_only ? std::string() : "phase 1 (" + out.message + ") -> ") +
                     "phase 2 (primal, Phi descent): " + second.message;
    // Return the better of the two answers (by the residual the driver will compute).
    if (!phase2_only && out.force.size() == p.num_contacts() && out.force.allFinite() &&
        out.multiplier.allFinite() && second.force.size() == p.num_contacts() &&
        second.multiplier.size() == p.num_equalities()) {
      const double r1 = p.Residuals(out.force, out.multiplier).total;
      const double r2 = p.Residuals(second.force, second.multiplier).total;
      if (r1 < r2) {
        out.iterations = second.iterations;
        out.message =
            second.message + "; phase 1 answer kept (residual " + std::to_string(r1) + ")";
        return out;
      }
    }
    return second;
  }

 private:
  bool OutOfTime() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count() >
           options_->time_limit;
  }

  void Evaluate(const ScaledProblem& p, const Eigen::VectorXd& x, const Eigen::VectorXd& l,
                Eigen::VectorXd* g, Eigen::VectorXd* e) {
    p.LocalValue(x, &u_);
    *g = p.C * x + u_ - p.delta0;
    if (p.num_equalities() > 0) {
      g->noalias() -= p.G.transpose() * l;
      *e = p.G * x - p.W;
      if (p.has_support) e->noalias() += p.S * l;
    } else {
      e->resize(0);
    }
  }

  static double Merit(const Eigen::VectorXd& x, const Eigen::VectorXd& g, const Eigen::VectorXd& e,
                      double* inf_norm) {
    double sq = 0.0, mx = 0.0;
    for (Eigen::Index j = 0; j < x.size(); ++j) {
      const double v = std::min(x(j), g(j));
      sq += v * v;
      mx = std::max(mx, std::abs(v));
    }
    for (Eigen::Index i = 0; i < e.size(); ++i) {
      sq += e(i) * e(i);
      mx = std::max(mx, std::abs(e(i)));
    }
    *inf_norm = mx;
    return 0.5 * sq;
  }

  BackendResult Phase1(const ScaledProblem& p, const Eigen::VectorXd* x0,
                       const Eigen::VectorXd* lambda0) {
    const int n = p.num_contacts(), m = p.num_equalities();
    BackendResult out;
    Eigen::VectorXd x = x0 ? *x0 : Eigen::VectorXd::Zero(n);
    Eigen::VectorXd lambda = lambda0 && lambda0->size() == m ? *lambda0 : Eigen::VectorXd::Zero(m);
    bool all_active = (x0 == nullptr);  // cold start: first step with every contact active
    Eigen::VectorXd g, e, x_new, l_new, g_new, e_new, dx(n), dl, dxa;
    Evaluate(p, x, lambda, &g, &e);
    double res = 0.0;
    double psi = Merit(x, g, e, &res);
    std::deque<double> history{psi};
    FaceSolver face(p);
    Eigen::VectorXd du;
    std::vector<int> active, inactive;
    int rescues = 0;
    // The best point seen: returned at a round-off floor or when a limit stops the iteration.
    Eigen::VectorXd best_x = x, best_l = lambda;
    double best_res = res;
    int since_best = 0;
    for (int it = 0;; ++it) {
      out.iterations = it;
      if (res < best_res) {
        best_res = res;
        best_x = x;
        best_l = lambda;
        since_best = 0;
      } else if (it > 0) {
        ++since_best;
      }
      // Stagnation: no new best for 5 iterations. Near the tolerance that is the round-off
      // floor (return the best point, the driver judges it); far from it, phase 1 has failed.
      if (since_best >= 5 && best_res <= 1e4 * options_->tolerance) {
        char buf[96];
        std::snprintf(buf, sizeof buf, "stagnation at residual %.3e after %d iterations", best_res,
                      it);
        out.message = buf;
        if (best_res > options_->tolerance) out.failed = true;
        break;
      }
      if (!std::isfinite(psi)) {
        out.failed = true;
        out.message = "non-finite residual";
        break;
      }
      if (res <= target_) {
        char buf[96];
        std::snprintf(buf, sizeof buf, "residual %.3e after %d iterations", res, it);
        out.message = buf;
        break;
      }
      if (it >= options_->max_iterations || OutOfTime()) {
        out.limit_reached = true;
        out.message = it >= options_->max_iterations ? "iteration limit" : "time limit";
        break;
      }
      active.clear();
      inactive.clear();
      for (int j = 0; j < n; ++j) (all_active || x(j) > g(j) ? active : inactive).push_back(j);
      all_active = false;
      const int na = static_cast<int>(active.size());
      // dx_I = −x_I; its effect on g_A and on the equalities goes to the right-hand sides.
      dx.setZero();
      for (int j : inactive) dx(j) = -x(j);
      Eigen::VectorXd r1(na), r2 = -e;
      for (int a = 0; a < na; ++a) {
        double s = -g(active[a]);
        for (int j : inactive) s -= p.C(active[a], j) * dx(j);
        r1(a) = s;
      }
      if (m > 0)
        for (int j : inactive) r2 -= p.G.col(j) * dx(j);
      ActiveDerivatives(p, active, x, &du);
      if (!face.Factor(active, du)) {
        out.failed = true;
        out.message = "Cholesky of C_AA + diag(u') failed";
        break;
      }
      face.Solve(r1, r2, &dxa, &dl);
      for (int a = 0; a < na; ++a) dx(active[a]) = dxa(a);
      // Non-monotone backtracking on ½‖R‖².
      const double psi_ref = *std::max_element(history.begin(), history.end());
      double t = 1.0, psi_new = 0.0, res_new = 0.0;
      bool accepted = false;
      for (int k = 0; k <= max_halvings_; ++k) {
        x_new = x + t * dx;
        l_new = m > 0 ? Eigen::VectorXd(lambda + t * dl) : lambda;
        Evaluate(p, x_new, l_new, &g_new, &e_new);
        psi_new = Merit(x_new, g_new, e_new, &res_new);
        if (std::isfinite(psi_new) && psi_new <= (1.0 - 2.0 * sigma_ * t) * psi_ref) {
          accepted = true;
          break;
        }
        t *= beta_;
      }
      if (!accepted) {
        if (++rescues > 3) {
          out.failed = true;
          out.message = "line search failed repeatedly";
          break;
        }
        // Rescue: the full step (the active-set change it brings may be what is needed).
        x_new = x + dx;
        l_new = m > 0 ? Eigen::VectorXd(lambda + dl) : lambda;
        Evaluate(p, x_new, l_new, &g_new, &e_new);
        psi_new = Merit(x_new, g_new, e_new, &res_new);
      } else {
        rescues = 0;
      }
      x.swap(x_new);
      lambda.swap(l_new);
      g.swap(g_new);
      e.swap(e_new);
      psi = psi_new;
      res = res_new;
      history.push_back(psi);
      if (static_cast<int>(history.size()) > memory_) history.pop_front();
    }
    if (std::isfinite(res) && res <= best_res) {
      best_x = x;
      best_l = lambda;
    }
    out.force = best_x;
    out.multiplier = best_l;
    out.code = out.failed ? 2 : (out.limit_reached ? 1 : 0);
    return out;
  }

  BackendResult Phase2(const ScaledProblem& p) {
    const int n = p.num_contacts(), m = p.num_equalities();
    BackendResult out;
    Eigen::VectorXd x = Eigen::VectorXd::Zero(n), lambda = Eigen::VectorXd::Zero(m);
    if (m > 0) {
      const double infeas = NonNegativeLeastSquares(p.G, p.W, &x);
      if (infeas > 1e-6 * std::max(1.0, p.W.cwiseAbs().maxCoeff())) {
        out.failed = true;
        out.code = 3;
        out.force = x;
        out.message =
            "no x >= 0 with G x = W (least-squares residual " + std::to_string(infeas) + ")";
        return out;
      }
    }
    if (m > 0) {
      // The NNLS point is a vertex: often only a few contacts carry load (one planet path, say),
      // G_F is then rank deficient and the faces degenerate (zero steps that cycle). A better
      // start: the minimiser of ½xᵀCx − δ0⁺ᵀx on G x = W over a set of contacts (gaps ignored:
      // an elastic distribution of the load), the set shrunk to the positive entries until none
      // is negative (a few passes); used when it is feasible.
      std::vector<int> set(static_cast<std::size_t>(n));
      for (int j = 0; j < n; ++j) set[j] = j;
      const double w_scale = std::max(1.0, p.W.cwiseAbs().maxCoeff());
      for (int pass = 0; pass < 10 && !set.empty(); ++pass) {
        const int k = static_cast<int>(set.size());
        Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(k + m, k + m);
        kkt.topLeftCorner(k, k) = p.C(set, set);
        kkt.topRightCorner(k, m) = p.G(Eigen::all, set).transpose();
        kkt.bottomLeftCorner(m, k) = p.G(Eigen::all, set);
        Eigen::VectorXd rhs(k + m);
        rhs << p.delta0(set).cwiseMax(0.0), p.W;
        const Eigen::VectorXd xs = kkt.completeOrthogonalDecomposition().solve(rhs).head(k);
        if (!xs.allFinite() ||
            (p.G(Eigen::all, set) * xs - p.W).cwiseAbs().maxCoeff() > 1e-9 * w_scale)
          break;  // G restricted to the set cannot carry the load: keep the NNLS point
        if (xs.minCoeff() >= 0.0) {
          x.setZero();
          for (int a = 0; a < k; ++a) x(set[a]) = xs(a);
          break;
        }
        std::vector<int> next;
        for (int a = 0; a < k; ++a)
          if (xs(a) > 0.0) next.push_back(set[a]);
        set = std::move(next);
      }
    }
    std::vector<bool> free(n, false);
    for (int j = 0; j < n; ++j) free[j] = x(j) > 0.0;
    FaceSolver face(p);
    Eigen::VectorXd du;
    const int budget = std::max(options_->max_iterations, 10 * n);
    Eigen::VectorXd grad, g, dxa, lnew, e;
    std::vector<int> fset;
    int small_steps = 0;
    for (int it = 0;; ++it) {
      out.iterations = it;
      if (it >= budget || OutOfTime()) {
        out.limit_reached = true;
        out.message = it >= budget ? "iteration limit" : "time limit";
        break;
      }
      fset.clear();
      for (int j = 0; j < n; ++j)
        if (free[j]) fset.push_back(j);
      p.Gradient(x, &grad);
      const int nf = static_cast<int>(fset.size());
      bool face_done = true;
      if (nf > 0) {
        ActiveDerivatives(p, fset, x, &du);
        if (!face.Factor(fset, du)) {
          out.failed = true;
          out.message = "Cholesky of C_FF + diag(u') failed";
          break;
        }
        Eigen::VectorXd r1(nf);
        for (int a = 0; a < nf; ++a) r1(a) = -grad(fset[a]);
        // Keep G x = W: the step satisfies G_F dx = W − G x (zero up to round-off).
        const Eigen::VectorXd r2 = m > 0 ? Eigen::VectorXd(p.W - p.G * x) : Eigen::VectorXd();
        face.Solve(r1, r2, &dxa, &lnew);
        if (m > 0) lambda = lnew;  // H dx − G_Fᵀλ = −∇Φ_F: λ itself, not an increment
        // Face optimality: g_F = ∇Φ_F − G_Fᵀλ ≈ 0 (the Newton step is then tiny).
        Eigen::VectorXd gf(nf);
        for (int a = 0; a < nf; ++a)
          gf(a) = grad(fset[a]) - (m > 0 ? p.G.col(fset[a]).dot(lambda) : 0.0);
        // (or the Newton step is negligible: then g_F is as small as round-off in the terms of
        // the gradient allows, e.g. with large gaps δ0 on the face)
        // Two small steps in a row also end the face: Newton has reached round-off.
        const double step = dxa.cwiseAbs().maxCoeff(),
                     size = std::max(1.0, x.cwiseAbs().maxCoeff());
        small_steps = step <= 1e-9 * size ? small_steps + 1 : 0;
        face_done = gf.cwiseAbs().maxCoeff() <= target_ || step <= 1e-13 * size || small_steps >= 2;
        if (face_done) small_steps = 0;
        if (!face_done) {
          double amax = 1.0;
          int block = -1;
          for (int a = 0; a < nf; ++a)
            if (dxa(a) < 0.0) {
              const double r = -x(fset[a]) / dxa(a);
              if (r < amax) {
                amax = r;
                block = fset[a];
              }
            }
          // Armijo on Φ along the feasible segment.
          const double phi0 = p.Objective(x);
          double slope = 0.0;
          for (int a = 0; a < nf; ++a) slope += grad(fset[a]) * dxa(a);
          double t = amax;
          Eigen::VectorXd xt = x;
          bool armijo = false;
          for (int k = 0; k < 60 && !armijo; ++k) {
            xt = x;
            for (int a = 0; a < nf; ++a) xt(fset[a]) = std::max(0.0, x(fset[a]) + t * dxa(a));
            armijo = p.Objective(xt) <= phi0 + 1e-4 * t * std::min(slope, 0.0);
            if (!armijo) t *= 0.5;
          }
          if (!armijo) {
            // Near the face optimum the decrease of Φ drowns in its round-off: the full
            // Newton step is then the right one.
            t = amax;
            for (int a = 0; a < nf; ++a) xt(fset[a]) = std::max(0.0, x(fset[a]) + t * dxa(a));
          }
          x = xt;
          if (block >= 0 && t == amax) {
            x(block) = 0.0;
            free[block] = false;
          }
          for (int j : fset)
            if (x(j) <= 0.0) {
              x(j) = 0.0;
              free[j] = false;
            }
          continue;
        }
      }
      // Pricing: the fixed contact with the most negative gap enters.
      g = grad;
      if (m > 0) g.noalias() -= p.G.transpose() * lambda;
      int enter = -1;
      for (int j = 0; j < n; ++j)
        if (!free[j] && g(j) < -target_ && (enter < 0 || g(j) < g(enter))) enter = j;
      if (enter < 0) {
        out.message = "optimal after " + std::to_string(it) + " iterations";
        break;
      }
      free[enter] = true;
    }
    out.force = x;
    out.multiplier = lambda;
    out.code = out.failed ? 2 : (out.limit_reached ? 1 : 0);
    return out;
  }

  std::chrono::steady_clock::time_point start_;
  const ContactOptions* options_ = nullptr;
  double beta_ = 0.5, sigma_ = 1e-4, target_ = 1e-11;
  int max_halvings_ = 40, memory_ = 5;
  Eigen::VectorXd u_;
};

}  // namespace

std::unique_ptr<BackendImpl> MakeActiveSetNewtonBackend() {
  return std::make_unique<ActiveSetNewton>();
}

}  // namespace epicycle::solvers::internal
