// Harmonic balance with alternating frequency/time evaluation and Hill's stability
// (harmonic_balance.hpp; docs/periodic.md §1, "Harmonic balance", and §2).
#include "epicycle/dynamics/harmonic_balance.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "epicycle/io/number_format.hpp"
#include "continuation.hpp"
#include "period_integrator.hpp"

namespace epicycle::dynamics {

using io::Num;
using periodic_detail::ParametersOr;

namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;

[[noreturn]] void Fail(const std::string& field, double value, const std::string& rule) {
  throw std::invalid_argument("harmonic balance: " + field + " = " + Num(value) + ": " + rule);
}

// The weights of the convergence test per component: rtol max_s |y_i| + atol_i.
Eigen::VectorXd Weights(const Eigen::MatrixXd& samples, const Eigen::VectorXd& atol, double rtol) {
  Eigen::VectorXd w(samples.cols());
  for (Eigen::Index i = 0; i < samples.cols(); ++i)
    w(i) = rtol * samples.col(i).cwiseAbs().maxCoeff() + atol(i);
  return w;
}

// Weighted RMS of the samples `d` (N × n) with the weights per column.
double WeightedRms(const Eigen::MatrixXd& d, const Eigen::VectorXd& w) {
  return std::sqrt((d * w.cwiseInverse().asDiagonal()).squaredNorm() /
                   static_cast<double>(std::max<Eigen::Index>(d.size(), 1)));
}

// ∂f/∂y at (t, y): the system's own, or forward differences of f with steps
// √ε max(|y_j|, atol_j/rtol) (as the shooting's, docs/periodic.md §1).
bool SystemJacobian(const PeriodicSystem& system, double t, const Eigen::VectorXd& y,
                    const Eigen::VectorXd& p, const Eigen::VectorXd& f, const Eigen::VectorXd& atol,
                    double rtol, Eigen::MatrixXd* jac, long* evaluations) {
  const int n = system.size();
  if (system.has_jacobian()) return system.Jacobian(t, y, p, jac) && jac->allFinite();
  jac->resize(n, n);
  Eigen::VectorXd yh = y, fh(n);
  const double root_eps = std::sqrt(std::numeric_limits<double>::epsilon());
  for (int j = 0; j < n; ++j) {
    const double h = root_eps * std::max(std::abs(y(j)), atol(j) / rtol);
    yh(j) = y(j) + h;
    ++*evaluations;
    if (!system.Rhs(t, yh, p, &fh)) return false;
    jac->col(j) = (fh - f) / (yh(j) - y(j));
    yh(j) = y(j);
  }
  return jac->allFinite();
}

}  // namespace

Eigen::VectorXd ComponentTolerances(const Eigen::VectorXd& atol, int n) {
  return atol.size() == 1 ? Eigen::VectorXd::Constant(n, atol(0)) : atol;
}

void HarmonicBalanceOptions::Validate(int n) const {
  if (harmonics < 1) Fail("harmonics", harmonics, "must be >= 1");
  if (samples != 0 && samples < 2 * harmonics + 1)
    Fail("samples", samples,
         "must be 0 (4 harmonics) or >= 2 harmonics + 1 = " + std::to_string(2 * harmonics + 1));
  if (!(rtol > 0 && rtol <= 0.1)) Fail("rtol", rtol, "must lie in (0, 0.1]");
  if (atol.size() != 1 && atol.size() != n)
    Fail("atol's size", static_cast<double>(atol.size()),
         "must be 1 or the state's size " + std::to_string(n));
  for (Eigen::Index k = 0; k < atol.size(); ++k)
    if (!(atol(k) > 0) || !std::isfinite(atol(k))) Fail("atol", atol(k), "must be > 0 and finite");
  if (!(newton_tolerance > 0) || !std::isfinite(newton_tolerance))
    Fail("newton_tolerance", newton_tolerance, "must be > 0 and finite");
  if (max_iterations < 1) Fail("max_iterations", max_iterations, "must be >= 1");
  if (hill_harmonics < 0 || hill_harmonics > harmonics)
    Fail("hill_harmonics", hill_harmonics,
         "must lie in [0, harmonics = " + std::to_string(harmonics) + "] (0: harmonics)");
  if (!(unit_circle_tolerance >= 0 && unit_circle_tolerance < 1))
    Fail("unit_circle_tolerance", unit_circle_tolerance, "must lie in [0, 1)");
}

FourierBasis::FourierBasis(int h, int n) : harmonics(h), samples(n) {
  const int m = 2 * h + 1;
  synthesis.resize(n, m);
  analysis.resize(m, n);
  derivative = Eigen::MatrixXd::Zero(m, m);
  for (int j = 0; j < n; ++j) {
    synthesis(j, 0) = 1;
    analysis(0, j) = 1.0 / n;
    for (int k = 1; k <= h; ++k) {
      const double a = kTwoPi * k * j / n;
      synthesis(j, 2 * k - 1) = std::cos(a);
      synthesis(j, 2 * k) = std::sin(a);
      analysis(2 * k - 1, j) = 2.0 / n * std::cos(a);
      analysis(2 * k, j) = 2.0 / n * std::sin(a);
    }
  }
  // d/ds (a cos 2πks + b sin 2πks) = 2πk (b cos 2πks − a sin 2πks).
  for (int k = 1; k <= h; ++k) {
    derivative(2 * k - 1, 2 * k) = kTwoPi * k;
    derivative(2 * k, 2 * k - 1) = -kTwoPi * k;
  }
}

Eigen::MatrixXd FourierBasis::Evaluate(const Eigen::MatrixXd& c, const Eigen::VectorXd& s) const {
  Eigen::MatrixXd e(s.size(), 2 * harmonics + 1);
  for (Eigen::Index j = 0; j < s.size(); ++j) {
    e(j, 0) = 1;
    for (int k = 1; k <= harmonics; ++k) {
      e(j, 2 * k - 1) = std::cos(kTwoPi * k * s(j));
      e(j, 2 * k) = std::sin(kTwoPi * k * s(j));
    }
  }
  return e * c;
}

bool HarmonicBalanceResidual(const PeriodicSystem& system, const FourierBasis& basis,
                             const Eigen::VectorXd& atol, double rtol, const Eigen::MatrixXd& c,
                             const Eigen::VectorXd& p, double period, Eigen::MatrixXd* residual,
                             Eigen::MatrixXd* jacobian, std::string* message) {
  const int n = system.size(), ns = basis.samples, mh = 2 * basis.harmonics + 1;
  const Eigen::MatrixXd y = basis.synthesis * c;  // N × n
  Eigen::MatrixXd f(ns, n);
  // J_ij at every instant, one row per (i, j) pair (n² × N).
  Eigen::MatrixXd jac_samples;
  if (jacobian) jac_samples.resize(static_cast<Eigen::Index>(n) * n, ns);
  Eigen::VectorXd yj(n), fj(n);
  Eigen::MatrixXd jj(n, n);
  long evaluations = 0;
  for (int j = 0; j < ns; ++j) {
    const double t = period * j / ns;
    yj = y.row(j).transpose();
    ++evaluations;
    if (!system.Rhs(t, yj, p, &fj) || !fj.allFinite()) {
      *message = "the system could not be evaluated at t = " + Num(t) + " s (instant " +
                 std::to_string(j) + " of " + std::to_string(ns) + ")";
      return false;
    }
    f.row(j) = fj.transpose();
    if (jacobian) {
      if (!SystemJacobian(system, t, yj, p, fj, atol, rtol, &jj, &evaluations)) {
        *message = "the system's Jacobian could not be evaluated at t = " + Num(t) + " s";
        return false;
      }
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) jac_samples(a * n + b, j) = jj(a, b);
    }
  }
  *residual = basis.derivative * c - period * basis.analysis * f;
  if (!jacobian) return true;
  // ∂R/∂C, block (a, b) = D δ_ab − T P diag(J_ab(s_j)) E; a J_ab constant over the period gives
  // T J_ab I (P E = I), a zero one nothing.
  const Eigen::Index m = static_cast<Eigen::Index>(n) * mh;
  jacobian->setZero(m, m);
  for (int a = 0; a < n; ++a) {
    jacobian->block(a * mh, a * mh, mh, mh) = basis.derivative;
    for (int b = 0; b < n; ++b) {
      const auto row = jac_samples.row(a * n + b);
      const double lo = row.minCoeff(), hi = row.maxCoeff();
      auto block = jacobian->block(a * mh, b * mh, mh, mh);
      if (lo == 0 && hi == 0) continue;
      if (lo == hi) {
        block.diagonal().array() -= period * lo;
        continue;
      }
      block.noalias() -=
          period * (basis.analysis * row.transpose().asDiagonal()) * basis.synthesis;
    }
  }
  return true;
}

FloquetReport HillStability(const Eigen::MatrixXd& jacobian, int n, int all_harmonics,
                            int harmonics, double tol,
                            std::vector<std::complex<double>>* exponents) {
  const int mh = 2 * harmonics + 1, all = 2 * all_harmonics + 1;
  // The rows and columns of harmonics ≤ H_s, component by component.
  std::vector<Eigen::Index> keep;
  for (int i = 0; i < n; ++i)
    for (int h = 0; h < mh; ++h) keep.push_back(static_cast<Eigen::Index>(i) * all + h);
  const Eigen::MatrixXd hill = -jacobian(keep, keep);
  const Eigen::EigenSolver<Eigen::MatrixXd> es(hill, true);
  const Eigen::VectorXcd nu = es.eigenvalues();
  const Eigen::MatrixXcd v = es.eigenvectors();
  // Each eigenvector's centroid over the complex harmonics: a cos + b sin at harmonic k is
  // (a − ib)/2 at +k and (a + ib)/2 at −k.
  std::vector<std::pair<double, Eigen::Index>> order;
  for (Eigen::Index q = 0; q < nu.size(); ++q) {
    double weight = 0, moment = 0;
    for (int i = 0; i < n; ++i) {
      const std::complex<double> a0 = v(i * mh, q);
      weight += std::norm(a0);
      for (int k = 1; k <= harmonics; ++k) {
        const std::complex<double> a = v(i * mh + 2 * k - 1, q), b = v(i * mh + 2 * k, q);
        const std::complex<double> ib(0, 1);
        const double wp = std::norm((a - ib * b) / 2.0), wm = std::norm((a + ib * b) / 2.0);
        weight += wp + wm;
        moment += k * (wp - wm);
      }
    }
    order.emplace_back(std::abs(moment / weight), q);
  }
  std::stable_sort(order.begin(), order.end());
  // The n most centred, one of each family: a real negative multiplier's family ν = σ + iπ(2k + 1)
  // is its own conjugate, so its members σ ± iπ are the same exponent (snapped to Im = ±π).
  std::vector<std::complex<double>> taken;
  for (const auto& [centroid, q] : order) {
    if (static_cast<int>(taken.size()) == n) break;
    std::complex<double> e = nu(q);
    const double half = std::remainder(e.imag() - std::numbers::pi, kTwoPi);
    if (std::abs(half) <= 1e-8 * std::max(1.0, std::abs(e))) {
      e = {e.real(), std::numbers::pi};
      bool twin = false;
      for (const auto& t : taken) twin = twin || t == e;
      if (twin) continue;
    }
    taken.push_back(e);
  }
  std::vector<std::complex<double>> mu;
  for (const auto& e : taken) {
    std::complex<double> m = std::exp(e);
    if (e.imag() == 0) m = {m.real(), 0.0};
    if (e.imag() == std::numbers::pi) m = {-std::exp(e.real()), 0.0};
    mu.push_back(m);
  }
  if (exponents) *exponents = taken;
  return ClassifyMultipliers(std::move(mu), tol);
}

HarmonicBalanceResult SolveHarmonicBalance(const PeriodicSystem& system,
                                           const HarmonicBalanceOptions& o,
                                           const Eigen::MatrixXd& guess,
                                           const Eigen::VectorXd& p_in) {
  const int n = system.size();
  o.Validate(n);
  const int h = o.harmonics, mh = 2 * h + 1;
  HarmonicBalanceResult r;
  r.parameters = ParametersOr(system, p_in);
  r.period = system.Period(r.parameters);
  if (!(r.period > 0) || !std::isfinite(r.period))
    Fail("the period T [s]", r.period, "must be > 0 and finite");
  if (system.PeriodMap(r.parameters).size() != 0)
    throw std::invalid_argument(
        "harmonic balance: the system has a period map (its orbit repeats turned, y(t + T) = "
        "S⁻¹ y(t)): it is not periodic in its own coordinates; use shooting");
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(mh, n);
  if (guess.rows() == n && guess.cols() == 1) {
    c.row(0) = guess.col(0).transpose();
  } else if (guess.rows() == mh && guess.cols() == n) {
    c = guess;
  } else {
    throw std::invalid_argument("harmonic balance: the guess is " + std::to_string(guess.rows()) +
                                " × " + std::to_string(guess.cols()) + ": must be " +
                                std::to_string(n) + " × 1 (a state) or " + std::to_string(mh) +
                                " × " + std::to_string(n) + " (coefficients)");
  }
  if (!c.allFinite()) throw std::invalid_argument("harmonic balance: the guess is not finite");
  const FourierBasis basis(h, o.SampleCount());
  const Eigen::VectorXd atol = ComponentTolerances(o.atol, n);
  const Eigen::Index m = static_cast<Eigen::Index>(n) * mh;

  Eigen::MatrixXd res, jac;
  auto evaluate = [&](const Eigen::MatrixXd& at, Eigen::MatrixXd* rr, Eigen::MatrixXd* jj) {
    r.rhs_evaluations += basis.samples;
    return HarmonicBalanceResidual(system, basis, atol, o.rtol, at, r.parameters, r.period, rr, jj,
                                   &r.message);
  };
  // |R| for the line search: R/(2π) per harmonic, as samples, over the weights.
  auto norm_of = [&](const Eigen::MatrixXd& rr, const Eigen::VectorXd& w) {
    return WeightedRms(basis.synthesis * rr / kTwoPi, w);
  };
  auto finish = [&](ShootingStatus status) {
    r.status = status;
    r.coefficients = c;
    r.initial_state = (basis.synthesis.row(0) * c).transpose();
    if (status == ShootingStatus::kConverged) r.message.clear();
    if (o.stability && status == ShootingStatus::kConverged)
      r.floquet =
          HillStability(jac, n, h, o.HillHarmonics(), o.unit_circle_tolerance, &r.exponents);
    return r;
  };
  if (!evaluate(c, &res, &jac)) return finish(ShootingStatus::kIntegrationFailed);
  Eigen::VectorXd w = Weights(basis.synthesis * c, atol, o.rtol);
  double norm = norm_of(res, w);
  for (r.iterations = 1; r.iterations <= o.max_iterations; ++r.iterations) {
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(jac);
    Eigen::VectorXd step = -lu.solve(Eigen::Map<const Eigen::VectorXd>(res.data(), m));
    if (!step.allFinite()) {
      r.message = "Newton iteration " + std::to_string(r.iterations) +
                  ": the HB Jacobian is singular (a Floquet multiplier at +1)";
      return finish(ShootingStatus::kSingularJacobian);
    }
    const Eigen::MatrixXd dc = Eigen::Map<const Eigen::MatrixXd>(step.data(), mh, n);
    r.update_norm = WeightedRms(basis.synthesis * dc, w);
    // Backtracking: halve the step until |R| decreases (Armijo with c = 1e-4), down to 1/64.
    double alpha = 1;
    Eigen::MatrixXd trial, rt, jt;
    for (;;) {
      trial = c + alpha * dc;
      if (evaluate(trial, &rt, &jt)) {
        const double nt = norm_of(rt, w);
        if (nt <= (1 - 1e-4 * alpha) * norm || alpha * r.update_norm <= o.newton_tolerance) {
          norm = nt;
          break;
        }
      }
      alpha /= 2;
      if (alpha < 1.0 / 64) {
        r.message = "Newton iteration " + std::to_string(r.iterations) +
                    ": no step down to 1/64 of the Newton step decreased |R| (weighted " +
                    Num(norm) + ")";
        return finish(ShootingStatus::kLineSearchFailed);
      }
    }
    c = trial;
    res = rt;
    jac = jt;
    r.residual_norm = norm;
    if (alpha * r.update_norm <= o.newton_tolerance) return finish(ShootingStatus::kConverged);
    w = Weights(basis.synthesis * c, atol, o.rtol);
  }
  r.iterations = o.max_iterations;
  r.message = std::to_string(o.max_iterations) +
              " Newton iterations spent; the last update (weighted) = " + Num(r.update_norm);
  return finish(ShootingStatus::kIterationLimit);
}

namespace {

using periodic_detail::ContinuationProblem;

// Harmonic balance's unknowns in scaled coordinates u = (vec C / σ, λ/Λ), C's columns (the
// components) one after the other, component i's mean over its scale σ_i and its harmonics over
// √2 σ_i: |ũ|² is then the orbit's mean square over σ² (Parseval), so that an arclength step
// moves the orbit as far as shooting's moves its state.
class HbContinuer : public ContinuationProblem {
 public:
  HbContinuer(const PeriodicSystem& system, const ContinuationOptions& c,
              const HarmonicBalanceOptions& hb, Eigen::VectorXd p, int column)
      : sys_(system),
        c_(c),
        hb_(hb),
        basis_(hb.harmonics, hb.SampleCount()),
        p_(std::move(p)),
        column_(column),
        n_(system.size()),
        mh_(2 * hb.harmonics + 1),
        atol_(ComponentTolerances(hb.atol, n_)) {
    const Eigen::VectorXd s =
        c.state_scale.size() == 1 ? Eigen::VectorXd::Constant(n_, c.state_scale(0)) : c.state_scale;
    scale_.resize(static_cast<Eigen::Index>(n_) * mh_);
    for (int i = 0; i < n_; ++i) {
      scale_.segment(i * mh_, mh_).setConstant(std::sqrt(2.0) * s(i));
      scale_(i * mh_) = s(i);
    }
    lambda_scale_ = std::abs(c.end - c.start);
  }

  int size() const override { return n_ * mh_; }
  double Lambda(const Eigen::VectorXd& u) const override { return u(size()) * lambda_scale_; }
  double LambdaScale() const override { return lambda_scale_; }
  Eigen::MatrixXd C(const Eigen::VectorXd& u) const {
    const Eigen::VectorXd x = u.head(size()).cwiseProduct(scale_);
    return Eigen::Map<const Eigen::MatrixXd>(x.data(), mh_, n_);
  }
  Eigen::VectorXd Scaled(const Eigen::MatrixXd& c, double lambda) const {
    return periodic_detail::ScaledPoint(Eigen::Map<const Eigen::VectorXd>(c.data(), size()),
                                        scale_, lambda, lambda_scale_);
  }
  Eigen::VectorXd P(double lambda) const {
    return periodic_detail::WithParameter(p_, column_, lambda);
  }
  double Period(double lambda) const override {
    const double t = sys_.Period(P(lambda));
    if (!(t > 0) || !std::isfinite(t)) Fail("the period T [s]", t, "must be > 0 and finite");
    return t;
  }

  bool Residual(const Eigen::VectorXd& u, Eigen::VectorXd* r, Point* at) override {
    ++plain_integrations;
    return Evaluate(u, r, nullptr, at);
  }

  bool Linearise(const Eigen::VectorXd& u, Eigen::VectorXd* r, Point* at) override {
    ++integrations;
    Eigen::MatrixXd jac;
    if (!Evaluate(u, r, &jac, at)) return false;
    const int m = size();
    at->jacobian.resize(m, m + 1);
    // R̃ = R/σ: ∂R̃/∂C̃ = diag(1/σ) ∂R/∂C diag(σ); ∂R̃/∂λ̃ by a forward difference in λ.
    at->jacobian.leftCols(m) = scale_.cwiseInverse().asDiagonal() * jac * scale_.asDiagonal();
    const double lambda = Lambda(u);
    const double h =
        std::sqrt(std::numeric_limits<double>::epsilon()) * std::max(std::abs(lambda), lambda_scale_);
    Eigen::VectorXd uh = u, rh;
    uh(m) = (lambda + h) / lambda_scale_;
    Point ph;
    try {
      if (!Evaluate(uh, &rh, nullptr, &ph)) {
        at->message = ph.message;
        return false;
      }
    } catch (const std::invalid_argument& e) {
      at->message = c_.parameter + " = " + Num(lambda + h) + ": " + e.what();
      return false;
    }
    at->jacobian.col(m) = (rh - *r) / (uh(m) - u(m));
    return at->jacobian.allFinite();
  }

  double tolerance() const override { return hb_.newton_tolerance; }
  bool UpdateConverged(const Eigen::VectorXd& u, const Eigen::VectorXd& du) const override {
    const Eigen::MatrixXd c = C(u);
    const Eigen::VectorXd w = Weights(basis_.synthesis * c, atol_, hb_.rtol);
    return WeightedRms(basis_.synthesis * C(du), w) <= hb_.newton_tolerance &&
           std::abs(du(size()) * lambda_scale_) <=
               hb_.newton_tolerance * hb_.rtol * (std::abs(Lambda(u)) + lambda_scale_);
  }
  FloquetReport Stability(const Point& at) const override {
    return HillStability(at.jacobian.leftCols(size()), n_, hb_.harmonics, hb_.HillHarmonics(),
                         c_.shooting.unit_circle_tolerance);
  }
  Eigen::MatrixXd Coefficients(const Eigen::VectorXd& u) const override { return C(u); }
  Eigen::VectorXd State(const Eigen::VectorXd& u) const override {
    return (basis_.synthesis.row(0) * C(u)).transpose();
  }
  double Amplitude(const Eigen::VectorXd& u) const override {
    if (c_.amplitude_samples == 0) return 0;
    const Eigen::VectorXd s =
        Eigen::VectorXd::LinSpaced(c_.amplitude_samples + 1, 0.0, 1.0);
    const Eigen::VectorXd y = basis_.Evaluate(C(u), s).col(c_.amplitude_component);
    return (y.maxCoeff() - y.minCoeff()) / 2;
  }

 private:
  // R̃ at u into *r; with `jac`, the unscaled ∂R/∂C. The corrector's norm: R/(2π) as samples over
  // the weights (as SolveHarmonicBalance's line search).
  bool Evaluate(const Eigen::VectorXd& u, Eigen::VectorXd* r, Eigen::MatrixXd* jac, Point* at) {
    const double lambda = Lambda(u);
    const Eigen::MatrixXd c = C(u);
    Eigen::MatrixXd res;
    double period = 0;
    // A corrector's iterate may leave the parameter's domain (a speed through zero): the system
    // refuses it, and the step fails and is retried shorter.
    try {
      period = Period(lambda);
      steps += basis_.samples;
      if (!HarmonicBalanceResidual(sys_, basis_, atol_, hb_.rtol, c, P(lambda), period, &res, jac,
                                   &at->message))
        return false;
    } catch (const std::invalid_argument& e) {
      at->message = c_.parameter + " = " + Num(lambda) + ": " + e.what();
      return false;
    }
    *r = Eigen::Map<const Eigen::VectorXd>(res.data(), size()).cwiseQuotient(scale_);
    const Eigen::VectorXd w = Weights(basis_.synthesis * c, atol_, hb_.rtol);
    at->residual = WeightedRms(basis_.synthesis * res / kTwoPi, w);
    at->u = u;
    return r->allFinite();
  }

  const PeriodicSystem& sys_;
  const ContinuationOptions& c_;
  const HarmonicBalanceOptions& hb_;
  FourierBasis basis_;
  Eigen::VectorXd p_;
  int column_, n_, mh_;
  Eigen::VectorXd atol_, scale_;
  double lambda_scale_ = 1;
};

}  // namespace

ContinuationResult ContinueHarmonicBalance(
    const PeriodicSystem& system, const ContinuationOptions& options,
    const HarmonicBalanceOptions& hb, const Eigen::MatrixXd& guess, const Eigen::VectorXd& p_in,
    const std::function<void(const ContinuationResult&)>& on_point) {
  const int n = system.size();
  options.Validate(n);
  hb.Validate(n);
  int column = 0;
  Eigen::VectorXd p;
  ContinuationResult result = periodic_detail::NamedResult(system, options, p_in, &column, &p);
  HbContinuer c(system, options, hb, p, column);

  // The first point: harmonic balance at λ = start (without Hill's method: the loop's first point
  // takes its stability from the linearisation below).
  HarmonicBalanceOptions first = hb;
  first.stability = false;
  const HarmonicBalanceResult start = SolveHarmonicBalance(system, first, guess, p);
  result.start.status = start.status;
  result.start.message = start.message;
  result.start.initial_state = start.initial_state;
  result.start.parameters = start.parameters;
  result.start.period = start.period;
  result.start.residual_norm = start.residual_norm;
  result.start.iterations = start.iterations;
  result.start.integrations = start.iterations + 1;
  result.start.rhs_evaluations = start.rhs_evaluations;
  result.integrations = result.start.integrations;
  result.steps = start.rhs_evaluations;
  if (start.status != ShootingStatus::kConverged) {
    result.status = ContinuationStatus::kStartFailed;
    result.message = "continuation: the first orbit, at " + options.parameter + " = " +
                     Num(options.start) + " " + result.unit +
                     ", was not found by harmonic balance: " + start.message;
    return result;
  }
  ContinuationProblem::Point here;
  Eigen::VectorXd r;
  if (!c.Linearise(c.Scaled(start.coefficients, options.start), &r, &here)) {
    result.status = ContinuationStatus::kStartFailed;
    result.message = "continuation: the first orbit's parameter derivative: " + here.message;
    return result;
  }
  periodic_detail::Continue(c, options, std::move(here), &result, on_point);
  if (!result.points.empty()) result.start.floquet = result.points.front().floquet;
  return result;
}

}  // namespace epicycle::dynamics
