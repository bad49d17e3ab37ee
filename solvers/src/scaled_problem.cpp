// The nondimensional problem every back end sees, its evaluation and the one residual.
#include <algorithm>
#include <cmath>
#include <limits>

#include "backend.hpp"

namespace epicycle::solvers::internal {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Eval {
  double u = 0, du = 0, d2u = 0, big_u = 0;
};

// Value, derivative and integral of one scaled local term at x > 0 (closed forms of
// local_term.hpp in scaled units). Per body, with r = L/h = 1/s and w = √(1 + r²):
//   asinh(s) = ln(s + √(1+s²)) = ln((1 + w)/r),
// one logarithm instead of asinh's; for r > 2 (s < 0.5, L > 2h, far beyond the term's validity)
// asinh itself keeps full relative accuracy. All three forms need only Σ_B a_B asinh(s_B); when
// the two bodies have the same a_B (same material, the usual case) it is a·ln(Π_B (1 + w_B)/r_B):
// one logarithm per contact instead of two.
// The second derivative needs no logarithm: with d asinh(s)/dx = −1/(2xw) and
// d(1/w)/dx = −r²/(2xw³),
//   u''(x) = −(1/(2x)) Σ_B a_B [1/w_B − (1 + c_B) r_B²/(2 w_B³)]   (< 0: u' falls with the force).
Eval EvalLocal(const ScaledProblem::Local& l, double x, bool want_u, bool want_du, bool want_int,
               bool want_d2u = false) {
  Eval e;
  const double len = std::sqrt(l.l2 * x);
  double r[2] = {0, 0}, w[2] = {1, 1};
  bool far = false;  // some body with r > 2
  for (int b = 0; b < 2; ++b) {
    if (l.a[b] == 0.0) continue;
    r[b] = len * l.inv_h[b];
    w[b] = std::sqrt(1.0 + r[b] * r[b]);  // L/h is moderate: no overflow, hypot not needed
    far = far || r[b] > 2.0;
  }
  double a_asinh = 0.0;  // Σ_B a_B asinh(s_B)
  if (want_u || want_du || want_int) {
    if (l.same_a && !far) {
      a_asinh = l.a[0] * std::log((1.0 + w[0]) * (1.0 + w[1]) / (r[0] * r[1]));
    } else {
      for (int b = 0; b < 2; ++b)
        if (l.a[b] != 0.0)
          a_asinh += l.a[b] * (r[b] > 2.0 ? std::asinh(1.0 / r[b]) : std::log((1.0 + w[b]) / r[b]));
    }
  }
  // Σ_B a_B c_B/(1 + w_B) and Σ_B a_B (1 + c_B)/(2 w_B), each over one common denominator.
  if (want_u)
    e.u = x * (a_asinh -
               (l.ac[0] * (1.0 + w[1]) + l.ac[1] * (1.0 + w[0])) / ((1.0 + w[0]) * (1.0 + w[1])));
  if (want_du) e.du = a_asinh - (l.a1c[0] * w[1] + l.a1c[1] * w[0]) / (w[0] * w[1]);
  if (want_d2u) {
    const double inv_ww = 1.0 / (w[0] * w[1]);
    const double iw[2] = {w[1] * inv_ww, w[0] * inv_ww};  // 1/w_B
    double sum = 0.0;
    for (int b = 0; b < 2; ++b) sum += (l.a[b] - l.a1c[b] * r[b] * r[b] * iw[b] * iw[b]) * iw[b];
    e.d2u = -0.5 * sum / x;
  }
  if (want_int) {
    double rest = 0.0;
    for (int b = 0; b < 2; ++b) {
      if (l.a[b] == 0.0) continue;
      const double w1 = (1.0 + w[b]) * (1.0 + w[b]);
      rest += l.a[b] * ((w[b] + 2.0) / (12.0 * w1) - l.c[b] * (2.0 * w[b] + 1.0) / (6.0 * w1));
    }
    e.big_u = 2.0 * x * x * (a_asinh / 4.0 + rest);
  }
  return e;
}

}  // namespace

double ScaledProblem::Objective(const Eigen::VectorXd& x) const {
  double phi = 0.5 * x.dot(C * x) - delta0.dot(x);
  if (has_local)
    for (int j = 0; j < num_contacts(); ++j)
      if (local[j].enabled && x(j) != 0.0)
        phi += EvalLocal(local[j], std::abs(x(j)), false, false, true).big_u;
  return phi;
}

void ScaledProblem::LocalValue(const Eigen::VectorXd& x, Eigen::VectorXd* u) const {
  u->setZero(num_contacts());
  if (!has_local) return;
  for (int j = 0; j < num_contacts(); ++j)
    if (local[j].enabled && x(j) != 0.0) {
      const double v = EvalLocal(local[j], std::abs(x(j)), true, false, false).u;
      (*u)(j) = x(j) > 0 ? v : -v;
    }
}

void ScaledProblem::LocalDerivative(const Eigen::VectorXd& x, Eigen::VectorXd* du) const {
  du->setZero(num_contacts());
  if (!has_local) return;
  for (int j = 0; j < num_contacts(); ++j)
    if (local[j].enabled)
      (*du)(j) = x(j) == 0.0 ? std::numeric_limits<double>::infinity()
                             : EvalLocal(local[j], std::abs(x(j)), false, true, false).du;
}

double ScaledProblem::LocalDerivativeAt(int j, double x) const {
  if (!has_local || !local[j].enabled) return 0.0;
  if (x == 0.0) return std::numeric_limits<double>::infinity();
  return EvalLocal(local[j], std::abs(x), false, true, false).du;
}

void ScaledProblem::Gradient(const Eigen::VectorXd& x, Eigen::VectorXd* grad) const {
  Eigen::VectorXd u;
  LocalValue(x, &u);
  *grad = C * x + u - delta0;
}

void ScaledProblem::LocalAt(int j, double x, double floor, double* u, double* du) const {
  *u = *du = 0.0;
  if (!has_local || !local[j].enabled) return;
  const double ax = std::max(std::abs(x), floor);
  const Eval e = EvalLocal(local[j], ax, true, true, false);
  // The value of the odd extension at x itself (0 at x = 0, as LocalValue), the slope at ax.
  if (x != 0.0)
    *u = ax == std::abs(x)
             ? (x > 0 ? e.u : -e.u)
             : EvalLocal(local[j], std::abs(x), true, false, false).u * (x > 0 ? 1.0 : -1.0);
  *du = e.du;
}

double ScaledProblem::LocalSecondDerivativeAt(int j, double x) const {
  if (!has_local || !local[j].enabled || !(x > 0.0)) return 0.0;
  return EvalLocal(local[j], x, false, false, false, true).d2u;
}

ContactResiduals ScaledProblem::ResidualsFromGap(const Eigen::VectorXd& x,
                                                 const Eigen::VectorXd& g) {
  ContactResiduals r;
  // ‖x − max(0, x − g)‖∞ = ‖min(x, g)‖∞ for x ≥ 0.
  r.complementarity = x.cwiseMin(g).cwiseAbs().maxCoeff();
  r.total = r.complementarity;
  if (!std::isfinite(r.total)) r.total = std::numeric_limits<double>::infinity();
  return r;
}

ContactResiduals ScaledProblem::Residuals(const Eigen::VectorXd& x_in,
                                          const Eigen::VectorXd& lambda) const {
  Eigen::VectorXd g;
  return Residuals(x_in, lambda, &g);
}

ContactResiduals ScaledProblem::Residuals(const Eigen::VectorXd& x_in,
                                          const Eigen::VectorXd& lambda,
                                          Eigen::VectorXd* gap) const {
  ContactResiduals r;
  const Eigen::VectorXd x = x_in.cwiseMax(0.0);
  Eigen::VectorXd& g = *gap;
  Gradient(x, &g);
  if (num_equalities() > 0) {
    g -= G.transpose() * lambda;
    Eigen::VectorXd e = G * x - W;
    if (has_support) e += S * lambda;
    r.equilibrium = e.size() ? e.cwiseAbs().maxCoeff() : 0.0;
  }
  r.complementarity = ResidualsFromGap(x, g).complementarity;
  // A negative component of the raw answer counts as an error too.
  r.complementarity = std::max(r.complementarity, (x_in - x).cwiseAbs().maxCoeff());
  r.total = std::max(r.complementarity, r.equilibrium);
  if (!std::isfinite(r.total)) r.total = std::numeric_limits<double>::infinity();
  return r;
}

double ScaledProblem::NaturalResidual(const Eigen::VectorXd& x, double floor, Eigen::VectorXd* u_out,
                                      Eigen::VectorXd* du_out, Eigen::VectorXd* g_out,
                                      bool* negative) const {
  const int n = num_contacts();
  Eigen::VectorXd &u = *u_out, &du = *du_out, &g = *g_out;
  u.resize(n);
  du.resize(n);
  // A contact at zero force has u = 0; its slope is needed only if it enters the active set.
  for (int j = 0; j < n; ++j)
    if (x(j) != 0.0)
      LocalAt(j, x(j), floor, &u(j), &du(j));
    else
      u(j) = du(j) = 0.0;
  // ∇Φ(x) = C x + u − δ0, by the columns of C with a force (contiguous; a contact at zero force
  // adds nothing). The sums' order differs from Gradient's only in round-off.
  g = u - delta0;
  for (int j = 0; j < n; ++j) {
    const double xj = x(j);
    if (xj == 0.0) continue;
    const double* col = C.data() + static_cast<std::ptrdiff_t>(j) * n;
    for (int i = 0; i < n; ++i) g(i) += col[i] * xj;
  }
  double res = 0.0;
  *negative = false;
  for (int j = 0; j < n; ++j) {
    res = std::max(res, std::abs(std::min(x(j), g(j))));
    *negative = *negative || x(j) < 0.0;
  }
  return g.allFinite() ? res : std::numeric_limits<double>::infinity();
}

ScaledProblem MakeScaledProblem(const ContactProblem& problem) {
  ScaledProblem sp;
  MakeScaledProblem(problem, &sp);
  return sp;
}

void MakeScaledProblem(const ContactProblem& problem, ScaledProblem* out) {
  // Every field is overwritten; Eigen and std::vector keep their storage when the size is the
  // same, so a solver reused on problems of one size does not allocate here.
  ScaledProblem& sp = *out;
  const int n = problem.num_contacts();
  const int m = problem.num_equalities();
  const Eigen::MatrixXd& c = problem.compliance();
  const double c_diag = c.diagonal().maxCoeff();

  sp.row_scale.setOnes(m);
  for (int i = 0; i < m; ++i) {
    const double r = problem.equality_matrix().row(i).cwiseAbs().maxCoeff();
    if (r > 0.0) sp.row_scale(i) = r;
  }
  // The larger of the two drivers of the forces: the loads and the overlaps.
  double f_scale = 0.0;
  for (int i = 0; i < m; ++i)
    f_scale = std::max(f_scale, std::abs(problem.equality_rhs()(i)) / sp.row_scale(i));
  const double d_max = problem.overlap().maxCoeff();
  if (d_max > 0.0) f_scale = std::max(f_scale, d_max / c_diag);
  if (!(f_scale > 0.0) || !std::isfinite(f_scale)) f_scale = 1.0;
  const double l_scale = f_scale * c_diag;
  sp.force_scale = f_scale;
  sp.length_scale = l_scale;

  sp.C = c * (f_scale / l_scale);
  sp.delta0 = problem.overlap() / l_scale;
  sp.G = sp.row_scale.cwiseInverse().asDiagonal() * problem.equality_matrix();
  sp.W = problem.equality_rhs().cwiseQuotient(sp.row_scale) / f_scale;
  sp.has_support = problem.has_support();
  if (sp.has_support) {
    const Eigen::VectorXd inv_r = sp.row_scale.cwiseInverse();
    sp.S = inv_r.asDiagonal() * problem.support_stiffness() * inv_r.asDiagonal();
    sp.S *= l_scale / f_scale;
  } else {
    sp.S.setZero(m, m);
  }

  // The groups of slices that no kernel couples (connected components of the kernels' pattern),
  // by flooding from each unlabelled slice; S is small (≤ 200) and this runs once per problem.
  sp.slices = problem.slices();
  sp.slice_group.assign(static_cast<std::size_t>(sp.slices), -1);
  sp.slice_groups = 0;
  const std::vector<KroneckerTerm>& terms = problem.compliance_terms();
  auto coupled = [&](int s, int t) {
    for (const KroneckerTerm& term : terms)
      if (term.kernel(s, t) != 0.0) return true;
    return false;
  };
  for (int s = 0; s < sp.slices; ++s) {
    if (sp.slice_group[s] >= 0) continue;
    const int g = sp.slice_groups++;
    sp.slice_group[s] = g;
    for (bool grew = true; grew;) {
      grew = false;
      for (int a = 0; a < sp.slices; ++a) {
        if (sp.slice_group[a] != g) continue;
        for (int b = 0; b < sp.slices; ++b)
          if (sp.slice_group[b] < 0 && coupled(a, b)) {
            sp.slice_group[b] = g;
            grew = true;
          }
      }
    }
  }

  if (terms.size() == 1 && sp.slices > 1 && sp.slice_groups == 1) {
    sp.kron_source = terms[0].source * (f_scale / l_scale);
    sp.kron_kernel = terms[0].kernel;
  } else {
    sp.kron_source.resize(0, 0);
    sp.kron_kernel.resize(0, 0);
  }

  sp.has_local = problem.has_local();
  sp.local.assign(n, {});
  if (sp.has_local) {
    // Everything but L²'s radius depends on the materials, depths and face width, which the
    // contacts of a stage share: a contact with the same ones as the last computed copies its
    // terms (bit for bit what computing them again gives) and divides only for l2.
    const LocalTermParameters* same = nullptr;
    const ScaledProblem::Local* same_l = nullptr;
    double same_d = 0.0;  // π b E* of `same`
    auto shares = [](const LocalTermParameters& p, const LocalTermParameters& q) {
      auto body = [](const LocalBody& u, const LocalBody& v) {
        return u.youngs_modulus == v.youngs_modulus && u.poisson_ratio == v.poisson_ratio &&
               u.depth == v.depth;
      };
      return p.plane == q.plane && p.face_width == q.face_width && body(p.body[0], q.body[0]) &&
             body(p.body[1], q.body[1]);
    };
    for (int j = 0; j < n; ++j) {
      const LocalTermParameters& p = problem.data().local[j];
      if (!p.enabled) continue;
      ScaledProblem::Local& l = sp.local[j];
      // L² = 4 R F/(π b E*) with F = F*·x and L in units of ℓ*.
      if (same != nullptr && shares(p, *same)) {
        l = *same_l;
        l.l2 = 4.0 * p.reduced_radius / same_d * f_scale / (l_scale * l_scale);
        continue;
      }
      l.enabled = true;
      double k[2];
      for (int b = 0; b < 2; ++b) {
        const double nu = p.body[b].poisson_ratio;
        k[b] = p.plane == PlaneAssumption::kPlaneStrain ? (1.0 - nu * nu) / p.body[b].youngs_modulus
                                                        : 1.0 / p.body[b].youngs_modulus;
      }
      // E* from the same k_B, with the operations of EffectiveModulus() (local_term.cpp), so the
      // value is the same to the bit without dividing again for each body.
      const double e_star = 1.0 / (k[0] + k[1]);
      for (int b = 0; b < 2; ++b) {
        const double nu = p.body[b].poisson_ratio;
        l.a[b] = 2.0 * k[b] / (kPi * p.face_width) * f_scale / l_scale;
        l.c[b] = p.plane == PlaneAssumption::kPlaneStrain ? nu / (1.0 - nu) : nu;
        l.h[b] = p.body[b].depth / l_scale;
      }
      same_d = kPi * p.face_width * e_star;
      l.l2 = 4.0 * p.reduced_radius / same_d * f_scale / (l_scale * l_scale);
      for (int b = 0; b < 2; ++b) {
        l.inv_h[b] = 1.0 / l.h[b];
        l.ac[b] = l.a[b] * l.c[b];
        l.a1c[b] = 0.5 * l.a[b] * (1.0 + l.c[b]);
      }
      l.same_a = l.a[0] == l.a[1];
      same = &p;
      same_l = &l;
    }
  }
}

double NonNegativeLeastSquares(const Eigen::MatrixXd& g, const Eigen::VectorXd& w,
                               Eigen::VectorXd* x_out) {
  // Lawson–Hanson active-set method.
  const int n = static_cast<int>(g.cols());
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  std::vector<bool> in_p(n, false);
  const double tol =
      1e-12 * std::max(1.0, w.cwiseAbs().maxCoeff()) * std::max(1.0, g.cwiseAbs().maxCoeff());
  auto solve_passive = [&](Eigen::VectorXd* z) {
    std::vector<int> idx;
    for (int j = 0; j < n; ++j)
      if (in_p[j]) idx.push_back(j);
    z->setZero(n);
    if (idx.empty()) return;
    const Eigen::MatrixXd gp = g(Eigen::all, idx);
    const Eigen::VectorXd zp = gp.completeOrthogonalDecomposition().solve(w);
    for (std::size_t k = 0; k < idx.size(); ++k) (*z)(idx[k]) = zp(k);
  };
  for (int outer = 0; outer < 3 * n + 10; ++outer) {
    const Eigen::VectorXd grad = g.transpose() * (w - g * x);
    int best = -1;
    for (int j = 0; j < n; ++j)
      if (!in_p[j] && grad(j) > tol && (best < 0 || grad(j) > grad(best))) best = j;
    if (best < 0) break;
    in_p[best] = true;
    Eigen::VectorXd z;
    for (int inner = 0; inner < 3 * n + 10; ++inner) {
      solve_passive(&z);
      double alpha = 1.0;
      bool all_positive = true;
      for (int j = 0; j < n; ++j)
        if (in_p[j] && z(j) <= 0.0) {
          all_positive = false;
          alpha = std::min(alpha, x(j) / (x(j) - z(j)));
        }
      if (all_positive) break;
      x += alpha * (z - x);
      for (int j = 0; j < n; ++j)
        if (in_p[j] && x(j) <= 1e-14) {
          in_p[j] = false;
          x(j) = 0.0;
        }
    }
    x = z.cwiseMax(0.0);
  }
  if (x_out) *x_out = x;
  return (g * x - w).cwiseAbs().maxCoeff();
}

bool EqualitiesInfeasible(const ScaledProblem& sp) {
  if (sp.num_equalities() == 0) return false;
  const double res = NonNegativeLeastSquares(sp.G, sp.W, nullptr);
  return res > 1e-6 * std::max(1.0, sp.W.cwiseAbs().maxCoeff());
}

void Unscale(const ScaledProblem& sp, const Eigen::VectorXd& x, const Eigen::VectorXd& lambda,
             ContactSolution* out) {
  out->force = x * sp.force_scale;
  out->multiplier = lambda.cwiseQuotient(sp.row_scale) * sp.length_scale;
}

void Scale(const ScaledProblem& sp, const ContactSolution& in, Eigen::VectorXd* x,
           Eigen::VectorXd* lambda) {
  *x = in.force / sp.force_scale;
  *lambda = in.multiplier.cwiseProduct(sp.row_scale) / sp.length_scale;
}

}  // namespace epicycle::solvers::internal
