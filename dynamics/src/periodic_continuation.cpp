// Pseudo-arclength continuation of periodic orbits (docs/periodic.md §1 and §2, "Continuation").
#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

#include <Eigen/LU>

#include "epicycle/dynamics/periodic.hpp"
#include "continuation.hpp"
#include "period_integrator.hpp"

namespace epicycle::dynamics {

using io::Num;
using periodic_detail::CheckState;
using periodic_detail::Flow;
using periodic_detail::ParametersOr;
using periodic_detail::PeriodIntegrator;
using periodic_detail::Wrms;

namespace {

using periodic_detail::ContinuationProblem;

// Shooting's unknowns in scaled coordinates u = (y/state_scale, λ/Λ).
class Continuer : public ContinuationProblem {
 public:
  Continuer(const PeriodicSystem& system, const ContinuationOptions& options, Eigen::VectorXd p,
            int column)
      : sys_(system), o_(options), p_(std::move(p)), column_(column), n_(system.size()) {
    scale_ = o_.state_scale.size() == 1 ? Eigen::VectorXd::Constant(n_, o_.state_scale(0))
                                        : o_.state_scale;
    lambda_scale_ = std::abs(o_.end - o_.start);
  }

  int size() const override { return n_; }
  Eigen::VectorXd Y(const Eigen::VectorXd& u) const { return u.head(n_).cwiseProduct(scale_); }
  Eigen::VectorXd State(const Eigen::VectorXd& u) const override { return Y(u); }
  double Lambda(const Eigen::VectorXd& u) const override { return u(n_) * lambda_scale_; }
  double LambdaScale() const override { return lambda_scale_; }
  Eigen::VectorXd Scaled(const Eigen::VectorXd& y, double lambda) const {
    return periodic_detail::ScaledPoint(y, scale_, lambda, lambda_scale_);
  }
  Eigen::VectorXd P(double lambda) const {
    return periodic_detail::WithParameter(p_, column_, lambda);
  }
  double Period(double lambda) const override {
    return PeriodIntegrator(sys_, o_.shooting, P(lambda), false, -1, lambda_scale_).period();
  }

  // R and its scaled Jacobian at u (one integration with the variational equations).
  bool Linearise(const Eigen::VectorXd& u, Eigen::VectorXd* r, Point* at) override {
    Flow f;
    if (!Integrate(u, true, r, at, &f)) return false;
    at->monodromy = f.phi;
    at->jacobian.resize(n_, n_ + 1);
    // R̃ = R/scale: ∂R̃/∂ỹ = diag(1/scale)(M − I) diag(scale), ∂R̃/∂λ̃ = ψ Λ/scale.
    at->jacobian.leftCols(n_) = scale_.cwiseInverse().asDiagonal() *
                                (f.phi - Eigen::MatrixXd::Identity(n_, n_)) * scale_.asDiagonal();
    at->jacobian.col(n_) = f.psi.cwiseQuotient(scale_) * lambda_scale_;
    return true;
  }

  // R̃ = R/scale at u alone: one integration of the state without the variational equations.
  bool Residual(const Eigen::VectorXd& u, Eigen::VectorXd* r, Point* at) override {
    Flow f;
    if (!Integrate(u, false, r, at, &f)) return false;
    *r = r->cwiseQuotient(scale_);
    return true;
  }

  // One period from u, with the variational equations and the parameter column or without:
  // R = φ − y into *r, its weighted norm and u into *at, the flow into *f.
  bool Integrate(const Eigen::VectorXd& u, bool variational, Eigen::VectorXd* r, Point* at,
                 Flow* f) {
    const double lambda = Lambda(u);
    const Eigen::VectorXd y = Y(u);
    // A corrector's iterate may leave the parameter's domain (a speed through zero): the system
    // refuses it, and the step fails and is retried shorter, as a failed integration is.
    try {
      PeriodIntegrator integrator(sys_, o_.shooting, P(lambda), variational,
                                  variational ? column_ : -1, lambda_scale_);
      *f = integrator.Shoot(y);
    } catch (const std::invalid_argument& e) {
      at->message = o_.parameter + " = " + Num(lambda) + ": " + e.what();
      return false;
    }
    ++(variational ? integrations : plain_integrations);
    steps += f->steps;
    if (!f->ok) {
      at->message = f->message;
      return false;
    }
    *r = f->end - y;
    at->residual = Wrms(*r, y, o_.shooting);
    at->u = u;
    return true;
  }

  double tolerance() const override { return o_.shooting.newton_tolerance; }
  // The update below the integrator's tolerance in y and in λ.
  bool UpdateConverged(const Eigen::VectorXd& u, const Eigen::VectorXd& du) const override {
    const Eigen::VectorXd dy = du.head(n_).cwiseProduct(scale_);
    return Wrms(dy, Y(u), o_.shooting) <= o_.shooting.newton_tolerance &&
           std::abs(du(n_) * lambda_scale_) <=
               o_.shooting.newton_tolerance * o_.shooting.rtol * (std::abs(Lambda(u)) + lambda_scale_);
  }
  FloquetReport Stability(const Point& at) const override {
    return FloquetMultipliers(at.monodromy, o_.shooting.unit_circle_tolerance);
  }

  double Amplitude(const Eigen::VectorXd& u) const override {
    if (o_.amplitude_samples == 0) return 0;
    const Eigen::MatrixXd orbit =
        SampleOrbit(sys_, o_.shooting, Y(u), P(Lambda(u)), o_.amplitude_samples);
    const Eigen::VectorXd c = orbit.col(o_.amplitude_component);
    return (c.maxCoeff() - c.minCoeff()) / 2;
  }


 private:
  const PeriodicSystem& sys_;
  const ContinuationOptions& o_;
  Eigen::VectorXd p_;
  int column_;
  int n_;
  Eigen::VectorXd scale_;
  double lambda_scale_ = 1;
};

// The real multiplier nearest +1.
std::complex<double> NearestToOne(const FloquetReport& f) {
  std::complex<double> best = std::numeric_limits<double>::quiet_NaN();
  for (const auto m : f.multipliers)
    if (std::isnan(best.real()) || std::abs(m - 1.0) < std::abs(best - 1.0)) best = m;
  return best;
}

// The most negative real multiplier (NaN if none), and the largest |μ| of a complex one.
double MostNegativeReal(const FloquetReport& f) {
  double m = std::numeric_limits<double>::quiet_NaN();
  for (const auto mu : f.multipliers)
    if (std::abs(mu.imag()) <= 1e-12 * std::max(1.0, std::abs(mu)) && mu.real() < 0 &&
        !(mu.real() >= m))
      m = mu.real();
  return m;
}
double LargestComplex(const FloquetReport& f) {
  double m = std::numeric_limits<double>::quiet_NaN();
  for (const auto mu : f.multipliers)
    if (std::abs(mu.imag()) > 1e-12 * std::max(1.0, std::abs(mu)) && !(std::abs(mu) <= m))
      m = std::abs(mu);
  return m;
}


using Point = ContinuationProblem::Point;

// The bordered system's LU: full pivoting for shooting's n + 1 unknowns (robust where M − I is
// ill-conditioned, at no cost for a few states), partial pivoting for harmonic balance's
// n(2H + 1) + 1 (several times cheaper at hundreds of unknowns).
class BorderedLu {
 public:
  explicit BorderedLu(const Eigen::MatrixXd& a) : small_(a.rows() <= kFullPivotSize) {
    if (small_)
      full_.compute(a);
    else
      partial_.compute(a);
  }
  bool invertible() const { return small_ ? full_.isInvertible() : true; }
  Eigen::VectorXd Solve(const Eigen::VectorXd& b) const {
    return small_ ? Eigen::VectorXd(full_.solve(b)) : Eigen::VectorXd(partial_.solve(b));
  }

 private:
  static constexpr Eigen::Index kFullPivotSize = 64;
  bool small_;
  Eigen::FullPivLU<Eigen::MatrixXd> full_;
  Eigen::PartialPivLU<Eigen::MatrixXd> partial_;
};

// Corrector: a chord Newton on [R̃(u); τ·(u − u0) − ds] = 0 from u0 + ds τ, its matrix the
// bordered Jacobian `chord` of the point u0 (docs/periodic.md §2, "Continuation"): each
// iteration evaluates the residual alone, and the Jacobian (shooting: the monodromy matrix and
// ∂φ/∂λ) once, at the converged point.
Point Correct(ContinuationProblem& pr, const ContinuationOptions& o, const Eigen::VectorXd& u0,
              const Eigen::VectorXd& tangent, double ds, const Eigen::MatrixXd& chord) {
  const int m = pr.size();
  Point at;
  Eigen::VectorXd u = u0 + ds * tangent;
  Eigen::VectorXd r;
  Eigen::MatrixXd a(m + 1, m + 1);
  a.topRows(m) = chord;
  a.row(m) = tangent.transpose();
  const BorderedLu lu(a);
  if (!lu.invertible()) {
    at.message = "the bordered Jacobian is singular";
    return at;
  }
  auto converged = [&](int iterations) {
    Point done;
    done.ok = pr.Linearise(u, &r, &done);
    done.iterations = iterations;
    return done;
  };
  double previous = std::numeric_limits<double>::infinity();
  for (at.iterations = 1; at.iterations <= o.max_corrector_iterations; ++at.iterations) {
    if (!pr.Residual(u, &r, &at)) return at;
    if (at.residual <= pr.tolerance()) return converged(at.iterations);
    if (at.residual > 2 * previous && at.iterations > 2) {
      at.message = "the corrector diverged (weighted |R| " + Num(previous) + " -> " +
                   Num(at.residual) + ")";
      return at;
    }
    previous = at.residual;
    Eigen::VectorXd g(m + 1);
    g.head(m) = r;
    g(m) = tangent.dot(u - u0) - ds;
    const Eigen::VectorXd du = -lu.Solve(g);
    if (!du.allFinite()) {
      at.message = "the bordered Jacobian is singular";
      return at;
    }
    if (pr.UpdateConverged(u, du)) return converged(at.iterations);
    u += du;
  }
  at.iterations = o.max_corrector_iterations;
  at.message = "the corrector did not converge in " + std::to_string(o.max_corrector_iterations) +
               " iterations (weighted |R| " + Num(at.residual) + ")";
  return at;
}

// The unit tangent: the null vector of the scaled Jacobian, oriented along `previous`.
Eigen::VectorXd Tangent(const Eigen::MatrixXd& jacobian, const Eigen::VectorXd& previous) {
  const Eigen::Index m = jacobian.rows();
  Eigen::MatrixXd a(m + 1, m + 1);
  a.topRows(m) = jacobian;
  a.row(m) = previous.transpose();
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(m + 1);
  rhs(m) = 1;
  Eigen::VectorXd t = BorderedLu(a).Solve(rhs);
  t.normalize();
  if (t.dot(previous) < 0) t = -t;
  return t;
}

}  // namespace

namespace periodic_detail {

void Continue(ContinuationProblem& c, const ContinuationOptions& options, Point here,
              ContinuationResult* out, const std::function<void(const ContinuationResult&)>& on_point) {
  ContinuationResult& result = *out;
  const int n = c.size();
  const double direction = options.end > options.start ? 1.0 : -1.0;
  const double lo = std::min(options.start, options.end), hi = std::max(options.start, options.end);
  Eigen::VectorXd u = here.u;
  Eigen::VectorXd axis = Eigen::VectorXd::Zero(n + 1);
  axis(n) = direction;
  Eigen::VectorXd tangent = Tangent(here.jacobian, axis);
  Eigen::MatrixXd chord = here.jacobian;  // the bordered Jacobian of the point u

  auto add_point = [&](const Point& at, const Eigen::VectorXd& t, double s) {
    BranchPoint b;
    b.state = c.State(at.u);
    b.coefficients = c.Coefficients(at.u);
    b.parameter = c.Lambda(at.u);
    b.period = c.Period(b.parameter);
    b.floquet = c.Stability(at);
    b.tangent_parameter = t(n);
    b.arclength = s;
    b.corrector_iterations = at.iterations;
    b.amplitude = c.Amplitude(at.u);
    result.points.push_back(std::move(b));
  };
  here.iterations = 0;
  add_point(here, tangent, 0.0);
  if (on_point) on_point(result);

  double ds = options.initial_step, s = 0;
  auto stop = [&](ContinuationStatus status, const std::string& message) {
    result.status = status;
    result.message = message;
    result.integrations += c.integrations;
    result.plain_integrations += c.plain_integrations;
    result.steps += c.steps;
  };
  while (static_cast<int>(result.points.size()) < options.max_points) {
    Point next = Correct(c, options, u, tangent, ds, chord);
    // A corrector that lands further from its predictor than the step is long has left the
    // branch for another part of the solution set (the hyperplane τ·(u − u_k) = Δs crosses the
    // branch again far away): the step is retried shorter.
    if (next.ok && (next.u - (u + ds * tangent)).norm() > ds) {
      next.ok = false;
      next.message = "the corrector moved " + Num((next.u - (u + ds * tangent)).norm()) +
                     " from its predictor, more than the step " + Num(ds);
    }
    if (!next.ok) {
      ++result.rejected_steps;
      if (ds <= options.min_step)
        return stop(ContinuationStatus::kStepTooSmall,
                    "continuation stopped after " + options.parameter + " = " + Num(c.Lambda(u)) +
                        " " + result.unit + " (point " + std::to_string(result.points.size() - 1) +
                        ", arclength " + Num(s) + "): the step at its minimum " +
                        Num(options.min_step) + " failed: " + next.message);
      ds = std::max(ds / 2, options.min_step);
      continue;
    }
    const Eigen::VectorXd new_tangent = Tangent(next.jacobian, tangent);
    // A fold: dλ/ds changes sign between the two points. Locate it by the secant method on
    // h(σ) = dλ/ds of the point σ along the previous tangent's corrector.
    if (new_tangent(n) * tangent(n) < 0) {
      double a = 0, ha = tangent(n), b = ds, hb = new_tangent(n);
      Point best = next;
      for (int k = 0; k < options.fold_refinements; ++k) {
        const double sigma = a - ha * (b - a) / (hb - ha);
        if (!(sigma > a && sigma < b)) break;
        const Point mid = Correct(c, options, u, tangent, sigma, chord);
        if (!mid.ok) break;
        const double h = Tangent(mid.jacobian, tangent)(n);
        best = mid;
        if (std::abs(h) < 1e-8) break;
        if (h * ha > 0) {
          a = sigma;
          ha = h;
        } else {
          b = sigma;
          hb = h;
        }
      }
      Bifurcation fold;
      fold.kind = BifurcationKind::kFold;
      fold.parameter = c.Lambda(best.u);
      fold.state = c.State(best.u);
      fold.after_point = static_cast<int>(result.points.size());
      fold.multiplier = NearestToOne(c.Stability(best));
      result.bifurcations.push_back(std::move(fold));
    }
    s += ds;
    u = next.u;
    tangent = new_tangent;
    chord = next.jacobian;
    add_point(next, tangent, s);
    const BranchPoint& prev = result.points[result.points.size() - 2];
    const BranchPoint& cur = result.points.back();
    if (prev.floquet.real_below_minus_one != cur.floquet.real_below_minus_one) {
      Bifurcation pd;
      pd.kind = BifurcationKind::kPeriodDoubling;
      const double m0 = MostNegativeReal(prev.floquet), m1 = MostNegativeReal(cur.floquet);
      const double w = std::isfinite(m0) && std::isfinite(m1) && m1 != m0
                           ? std::clamp((-1 - m0) / (m1 - m0), 0.0, 1.0)
                           : 0.5;
      pd.parameter = prev.parameter + w * (cur.parameter - prev.parameter);
      pd.state = cur.state;
      pd.after_point = static_cast<int>(result.points.size()) - 1;
      pd.multiplier = std::isfinite(m1) ? std::complex<double>(m1, 0) : std::complex<double>(-1, 0);
      result.bifurcations.push_back(std::move(pd));
    }
    if (prev.floquet.complex_outside != cur.floquet.complex_outside) {
      Bifurcation ns;
      ns.kind = BifurcationKind::kNeimarkSacker;
      const double m0 = LargestComplex(prev.floquet), m1 = LargestComplex(cur.floquet);
      const double w = std::isfinite(m0) && std::isfinite(m1) && m1 != m0
                           ? std::clamp((1 - m0) / (m1 - m0), 0.0, 1.0)
                           : 0.5;
      ns.parameter = prev.parameter + w * (cur.parameter - prev.parameter);
      ns.state = cur.state;
      ns.after_point = static_cast<int>(result.points.size()) - 1;
      for (const auto mu : cur.floquet.multipliers)
        if (mu.imag() > 0) {
          ns.multiplier = mu;
          break;
        }
      result.bifurcations.push_back(std::move(ns));
    }
    if (on_point) on_point(result);
    if (cur.parameter > hi || cur.parameter < lo) return stop(ContinuationStatus::kCompleted, "");
    // Step control: grow after an easy corrector, shrink after a hard one.
    if (next.iterations <= options.fast_iterations)
      ds = std::min(ds * 1.5, options.max_step);
    else if (next.iterations >= options.max_corrector_iterations - 1)
      ds = std::max(ds / 2, options.min_step);
  }
  stop(ContinuationStatus::kPointLimit,
       "continuation: " + std::to_string(options.max_points) + " points reached at " +
           options.parameter + " = " + Num(result.points.back().parameter) + " " + result.unit +
           " before the end " + Num(options.end));
}

ContinuationResult NamedResult(const PeriodicSystem& system, const ContinuationOptions& options,
                               const Eigen::VectorXd& p_in, int* column, Eigen::VectorXd* p) {
  *column = system.ParameterIndex(options.parameter);
  ContinuationResult result;
  result.parameter = options.parameter;
  result.unit = system.parameters()[static_cast<std::size_t>(*column)].unit;
  *p = ParametersOr(system, p_in);
  (*p)(*column) = options.start;
  return result;
}

}  // namespace periodic_detail

ContinuationResult ContinuePeriodicOrbit(
    const PeriodicSystem& system, const ContinuationOptions& options, const Eigen::VectorXd& y0,
    const Eigen::VectorXd& p_in, const std::function<void(const ContinuationResult&)>& on_point) {
  const int n = system.size();
  options.Validate(n);
  CheckState(system, y0, "continuation");
  int column = 0;
  Eigen::VectorXd p;
  ContinuationResult result = periodic_detail::NamedResult(system, options, p_in, &column, &p);
  Continuer c(system, options, p, column);

  // The first point: shooting at λ = start.
  result.start = SolvePeriodicOrbit(system, options.shooting, y0, p);
  result.integrations += result.start.integrations;
  result.steps += result.start.steps;
  if (result.start.status != ShootingStatus::kConverged) {
    result.status = ContinuationStatus::kStartFailed;
    result.message = "continuation: the first orbit, at " + options.parameter + " = " +
                     Num(options.start) + " " + result.unit +
                     ", was not found: " + result.start.message;
    return result;
  }
  Point here;
  Eigen::VectorXd r;
  if (!c.Linearise(c.Scaled(result.start.initial_state, options.start), &r, &here)) {
    result.status = ContinuationStatus::kStartFailed;
    result.message = "continuation: the first orbit's parameter derivative: " + here.message;
    return result;
  }
  periodic_detail::Continue(c, options, std::move(here), &result, on_point);
  return result;
}

}  // namespace epicycle::dynamics
