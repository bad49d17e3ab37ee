#include "epicycle/dynamics/periodic.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_band.h>
#include <sunmatrix/sunmatrix_band.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <exception>
#include <limits>
#include <stdexcept>

#include "epicycle/io/number_format.hpp"

namespace epicycle::dynamics {

bool PeriodicSystem::Jacobian(double, const Eigen::VectorXd&, const Eigen::VectorXd&,
                              Eigen::MatrixXd*) const {
  throw std::logic_error("PeriodicSystem::Jacobian called on a system without one");
}

int PeriodicSystem::ParameterIndex(const std::string& name) const {
  const std::vector<PeriodicParameter> all = parameters();
  std::string names;
  for (std::size_t k = 0; k < all.size(); ++k) {
    if (all[k].name == name) return static_cast<int>(k);
    names += (k ? ", " : "") + all[k].name;
  }
  throw std::invalid_argument("continuation: parameter = '" + name +
                              "': not a parameter of the system (its parameters: " +
                              (names.empty() ? "none" : names) + ")");
}

Eigen::VectorXd PeriodicSystem::DefaultParameters() const {
  const std::vector<PeriodicParameter> all = parameters();
  Eigen::VectorXd p(static_cast<Eigen::Index>(all.size()));
  for (std::size_t k = 0; k < all.size(); ++k) p(static_cast<Eigen::Index>(k)) = all[k].value;
  return p;
}

namespace {

using io::Num;

[[noreturn]] void Fail(const std::string& where, const std::string& field, double value,
                       const std::string& rule) {
  throw std::invalid_argument(where + ": " + field + " = " + Num(value) + ": " + rule);
}

}  // namespace

void ShootingOptions::Validate(int n) const {
  const std::string w = "shooting";
  if (!(rtol > 0 && rtol <= 0.1)) Fail(w, "rtol", rtol, "must lie in (0, 0.1]");
  if (atol.size() != 1 && atol.size() != n)
    Fail(w, "atol's size", static_cast<double>(atol.size()),
         "must be 1 or the state's size " + std::to_string(n));
  for (Eigen::Index k = 0; k < atol.size(); ++k)
    if (!(atol(k) > 0) || !std::isfinite(atol(k)))
      Fail(w, "atol[" + std::to_string(k) + "]", atol(k), "must be > 0 and finite");
  if (!(newton_tolerance > 0) || !std::isfinite(newton_tolerance))
    Fail(w, "newton_tolerance", newton_tolerance, "must be > 0 and finite");
  if (max_iterations < 1) Fail(w, "max_iterations", max_iterations, "must be >= 1");
  if (max_steps < 1) Fail(w, "max_steps", static_cast<double>(max_steps), "must be >= 1");
  if (!(unit_circle_tolerance >= 0 && unit_circle_tolerance < 1))
    Fail(w, "unit_circle_tolerance", unit_circle_tolerance, "must lie in [0, 1)");
}

void ContinuationOptions::Validate(int n) const {
  const std::string w = "continuation";
  if (!std::isfinite(start)) Fail(w, "start", start, "must be finite");
  if (!std::isfinite(end)) Fail(w, "end", end, "must be finite");
  if (end == start)
    Fail(w, "end", end, "equals start = " + Num(start) + ": the range must have non-zero width");
  if (!(min_step > 0) || !std::isfinite(min_step)) Fail(w, "min_step", min_step, "must be > 0");
  if (!(max_step >= min_step) || !std::isfinite(max_step))
    Fail(w, "max_step", max_step, "must be >= min_step = " + Num(min_step));
  if (!(initial_step >= min_step && initial_step <= max_step))
    Fail(w, "initial_step", initial_step,
         "must lie in [min_step, max_step] = [" + Num(min_step) + ", " + Num(max_step) + "]");
  if (state_scale.size() != 1 && state_scale.size() != n)
    Fail(w, "state_scale's size", static_cast<double>(state_scale.size()),
         "must be 1 or the state's size " + std::to_string(n));
  for (Eigen::Index k = 0; k < state_scale.size(); ++k)
    if (!(state_scale(k) > 0) || !std::isfinite(state_scale(k)))
      Fail(w, "state_scale[" + std::to_string(k) + "]", state_scale(k), "must be > 0 and finite");
  if (max_points < 2) Fail(w, "max_points", max_points, "must be >= 2");
  if (max_corrector_iterations < 1)
    Fail(w, "max_corrector_iterations", max_corrector_iterations, "must be >= 1");
  if (fast_iterations < 0) Fail(w, "fast_iterations", fast_iterations, "must be >= 0");
  if (fold_refinements < 0) Fail(w, "fold_refinements", fold_refinements, "must be >= 0");
  if (amplitude_component < 0 || amplitude_component >= n)
    Fail(w, "amplitude_component", amplitude_component,
         "must lie in [0, " + std::to_string(n - 1) + "]");
  if (amplitude_samples < 4 && amplitude_samples != 0)
    Fail(w, "amplitude_samples", amplitude_samples, "must be >= 4, or 0 (no amplitude)");
  shooting.Validate(n);
}

std::string ShootingStatusName(ShootingStatus status) {
  switch (status) {
    case ShootingStatus::kConverged:
      return "converged";
    case ShootingStatus::kIterationLimit:
      return "iteration-limit";
    case ShootingStatus::kLineSearchFailed:
      return "line-search-failed";
    case ShootingStatus::kSingularJacobian:
      return "singular-jacobian";
    case ShootingStatus::kIntegrationFailed:
      return "integration-failed";
  }
  return "?";
}

std::string StabilityName(Stability stability) {
  switch (stability) {
    case Stability::kStable:
      return "stable";
    case Stability::kMarginal:
      return "marginal";
    case Stability::kUnstable:
      return "unstable";
  }
  return "?";
}

std::string ContinuationStatusName(ContinuationStatus status) {
  switch (status) {
    case ContinuationStatus::kCompleted:
      return "completed";
    case ContinuationStatus::kPointLimit:
      return "point-limit";
    case ContinuationStatus::kStartFailed:
      return "start-failed";
    case ContinuationStatus::kStepTooSmall:
      return "step-too-small";
  }
  return "?";
}

std::string BifurcationKindName(BifurcationKind kind) {
  switch (kind) {
    case BifurcationKind::kFold:
      return "fold";
    case BifurcationKind::kPeriodDoubling:
      return "period-doubling";
    case BifurcationKind::kNeimarkSacker:
      return "neimark-sacker";
  }
  return "?";
}

FloquetReport FloquetMultipliers(const Eigen::MatrixXd& monodromy, double tol) {
  FloquetReport r;
  if (monodromy.size() == 0) return r;
  const Eigen::VectorXcd mu = Eigen::EigenSolver<Eigen::MatrixXd>(monodromy, false).eigenvalues();
  r.multipliers.assign(mu.data(), mu.data() + mu.size());
  std::sort(r.multipliers.begin(), r.multipliers.end(),
            [](auto a, auto b) { return std::abs(a) > std::abs(b); });
  bool on_circle = false;
  for (const std::complex<double> m : r.multipliers) {
    const double a = std::abs(m);
    r.spectral_radius = std::max(r.spectral_radius, a);
    // Real: the imaginary part below the eigensolver's round-off relative to |μ|.
    const bool real = std::abs(m.imag()) <= 1e-12 * std::max(1.0, a);
    if (a > 1 + tol) {
      if (!real)
        ++r.complex_outside;
      else if (m.real() > 0)
        ++r.real_above_one;
      else
        ++r.real_below_minus_one;
    } else if (a >= 1 - tol) {
      on_circle = true;
    }
  }
  r.stability = r.spectral_radius > 1 + tol ? Stability::kUnstable
                : on_circle                 ? Stability::kMarginal
                                            : Stability::kStable;
  return r;
}

namespace {

// What one integration over the period gives.
struct Flow {
  bool ok = false;
  std::string message;
  Eigen::VectorXd end;  // φ(1; y0, p)
  Eigen::MatrixXd phi;  // ∂φ/∂y0 (with variational equations)
  Eigen::VectorXd psi;  // ∂φ/∂λ (with the parameter column)
  long steps = 0, rhs = 0;
};

// RAII owners of the SUNDIALS objects.
struct Sundials {
  SUNContext ctx = nullptr;
  N_Vector z = nullptr, atol = nullptr;
  SUNMatrix a = nullptr;
  SUNLinearSolver ls = nullptr;
  void* cvode = nullptr;
  ~Sundials() {
    if (cvode) CVodeFree(&cvode);
    if (ls) SUNLinSolFree(ls);
    if (a) SUNMatDestroy(a);
    if (z) N_VDestroy(z);
    if (atol) N_VDestroy(atol);
    if (ctx) SUNContext_Free(&ctx);
  }
};

std::vector<double> EndOnly() { return {1.0}; }

void Check(int flag, const char* what) {
  if (flag < 0)
    throw std::runtime_error(std::string("SUNDIALS: ") + what + " returned " +
                             std::to_string(flag));
}

// Integrates the scaled system dy/ds = T f(T s, y; p) over s ∈ [0, s_end], optionally with the
// variational equations Φ' = T J Φ (Φ(0) = I) and the parameter column ψ' = T J ψ + ∂g/∂λ
// (ψ(0) = 0, g = T(λ) f(T(λ) s, y; λ)). The augmented state is [y, Φ column by column, ψ]; its
// Newton matrix is block-diagonal with blocks I − γ T J (the coupling ∂(JΦ)/∂y, a second
// derivative of f, is left out: CVODE's Newton iteration only needs an approximate matrix, and it
// is exact for f linear or piecewise linear in y), hence a band matrix of half-bandwidth n − 1.
class PeriodIntegrator {
 public:
  PeriodIntegrator(const PeriodicSystem& system, const ShootingOptions& options, Eigen::VectorXd p,
                   bool variational, int parameter_column, double parameter_scale)
      : sys_(system),
        p_(std::move(p)),
        n_(system.size()),
        variational_(variational),
        column_(parameter_column),
        lambda_scale_(parameter_scale),
        rtol_(options.rtol),
        max_steps_(options.max_steps) {
    atol_ =
        options.atol.size() == 1 ? Eigen::VectorXd::Constant(n_, options.atol(0)) : options.atol;
    period_ = PeriodOf(p_);
    size_ = n_ + (variational_ ? n_ * n_ : 0) + (column_ >= 0 ? n_ : 0);
    f_.resize(n_);
    fp_.resize(n_);
    fm_.resize(n_);
    jac_.resize(n_, n_);
  }

  double PeriodOf(const Eigen::VectorXd& p) const {
    const double t = sys_.Period(p);
    if (!(t > 0) || !std::isfinite(t)) {
      std::string at;
      const auto names = sys_.parameters();
      for (std::size_t k = 0; k < names.size(); ++k)
        at += (k ? ", " : " at ") + names[k].name + " = " + Num(p(static_cast<Eigen::Index>(k))) +
              " " + names[k].unit;
      throw std::invalid_argument("periodic system: period T = " + Num(t) + " s" + at +
                                  ": must be > 0 and finite");
    }
    return t;
  }
  double period() const { return period_; }

  // One period for the shooting: Run to s = 1, then the system's period map S applied to the end
  // state and its derivatives (docs/periodic.md §1, "Symmetry"): the periodicity condition is
  // S φ(1; y0) = y0 and the monodromy matrix S Φ(1).
  Flow Shoot(const Eigen::VectorXd& y0) {
    Flow f = Run(y0, EndOnly(), nullptr);
    if (!f.ok) return f;
    const Eigen::MatrixXd map = sys_.PeriodMap(p_);
    if (map.size() == 0) return f;
    f.end = map * f.end;
    if (variational_) f.phi = map * f.phi;
    if (column_ >= 0) f.psi = map * f.psi;
    return f;
  }

  // y(s_k) at the increasing scaled times s_out (the last is the end); with the variational
  // parts at the end in *flow.
  Flow Run(const Eigen::VectorXd& y0, const std::vector<double>& s_out,
           std::vector<Eigen::VectorXd>* samples) {
    Flow flow;
    Sundials s;
    error_ = nullptr;
    message_.clear();
    rhs_ = 0;
    Check(SUNContext_Create(nullptr, &s.ctx), "SUNContext_Create");
    s.z = N_VNew_Serial(size_, s.ctx);
    s.atol = N_VNew_Serial(size_, s.ctx);
    if (!s.z || !s.atol) throw std::runtime_error("SUNDIALS: cannot allocate vectors");
    double* z = N_VGetArrayPointer(s.z);
    double* at = N_VGetArrayPointer(s.atol);
    std::fill(z, z + size_, 0.0);
    for (int i = 0; i < n_; ++i) {
      z[i] = y0(i);
      at[i] = atol_(i);
    }
    int off = n_;
    if (variational_) {
      // Column j answers a perturbation δ_j = atol_j/rtol of y0_j (the size below which y_j is
      // noise to the integrator): its response δ_j Φ_ij is held to atol_i.
      for (int j = 0; j < n_; ++j) {
        z[off + j * n_ + j] = 1.0;
        for (int i = 0; i < n_; ++i) at[off + j * n_ + i] = atol_(i) * rtol_ / atol_(j);
      }
      off += n_ * n_;
    }
    if (column_ >= 0)
      for (int i = 0; i < n_; ++i) at[off + i] = atol_(i) / lambda_scale_;

    s.cvode = CVodeCreate(CV_BDF, s.ctx);
    if (!s.cvode) throw std::runtime_error("SUNDIALS: CVodeCreate failed");
    Check(CVodeInit(s.cvode, RhsCallback, 0.0, s.z), "CVodeInit");
    Check(CVodeSVtolerances(s.cvode, rtol_, s.atol), "CVodeSVtolerances");
    Check(CVodeSetUserData(s.cvode, this), "CVodeSetUserData");
    Check(CVodeSetErrHandlerFn(s.cvode, ErrorHandler, this), "CVodeSetErrHandlerFn");
    Check(CVodeSetMaxNumSteps(s.cvode, max_steps_), "CVodeSetMaxNumSteps");
    Check(CVodeSetMaxErrTestFails(s.cvode, 20), "CVodeSetMaxErrTestFails");
    Check(CVodeSetMaxConvFails(s.cvode, 50), "CVodeSetMaxConvFails");
    Check(CVodeSetStabLimDet(s.cvode, SUNTRUE), "CVodeSetStabLimDet");
    Check(CVodeSetStopTime(s.cvode, s_out.back()), "CVodeSetStopTime");
    s.a = SUNBandMatrix(size_, n_ - 1, n_ - 1, s.ctx);
    s.ls = SUNLinSol_Band(s.z, s.a, s.ctx);
    if (!s.a || !s.ls) throw std::runtime_error("SUNDIALS: cannot create the band solver");
    Check(CVodeSetLinearSolver(s.cvode, s.ls, s.a), "CVodeSetLinearSolver");
    Check(CVodeSetJacFn(s.cvode, JacCallback), "CVodeSetJacFn");

    double t = 0;
    for (const double tout : s_out) {
      const int flag = CVode(s.cvode, tout, s.z, &t, CV_NORMAL);
      if (error_) std::rethrow_exception(error_);
      if (flag < 0) {
        flow.message = "the integration stopped at t = " + Num(t * period_) + " s (s = " + Num(t) +
                       " of the period): " + CVodeGetReturnFlagName(flag) +
                       (message_.empty() ? "" : "; " + message_);
        long v = 0;
        CVodeGetNumSteps(s.cvode, &v);
        flow.steps = v;
        flow.rhs = rhs_;
        return flow;
      }
      if (samples) samples->push_back(Eigen::Map<Eigen::VectorXd>(z, n_));
    }
    long v = 0;
    CVodeGetNumSteps(s.cvode, &v);
    flow.steps = v;
    flow.rhs = rhs_;
    flow.ok = true;
    flow.end = Eigen::Map<Eigen::VectorXd>(z, n_);
    if (variational_) flow.phi = Eigen::Map<Eigen::MatrixXd>(z + n_, n_, n_);
    if (column_ >= 0) flow.psi = Eigen::Map<Eigen::VectorXd>(z + off, n_);
    return flow;
  }

 private:
  static void ErrorHandler(int code, const char* module, const char* function, char* msg,
                           void* user) {
    static_cast<PeriodIntegrator*>(user)->message_ =
        std::string(module) + " " + function + " (" + std::to_string(code) + "): " + msg;
  }

  // g(s, y; p) = T(p) f(T(p) s, y; p).
  bool G(double s, const Eigen::VectorXd& y, const Eigen::VectorXd& p, double period,
         Eigen::VectorXd* g) {
    ++rhs_;
    if (!sys_.Rhs(period * s, y, p, g)) return false;
    *g *= period;
    return g->allFinite();
  }

  // T J(T s, y; p) into jac_: the system's own, or forward differences of f.
  bool ScaledJacobian(double s, const Eigen::VectorXd& y) {
    const double t = period_ * s;
    if (sys_.has_jacobian()) {
      if (!sys_.Jacobian(t, y, p_, &jac_)) return false;
      jac_ *= period_;
      return jac_.allFinite();
    }
    if (!G(s, y, p_, period_, &f_)) return false;
    Eigen::VectorXd yh = y;
    const double root_eps = std::sqrt(std::numeric_limits<double>::epsilon());
    for (int j = 0; j < n_; ++j) {
      const double h = root_eps * std::max(std::abs(y(j)), atol_(j) / rtol_);
      yh(j) = y(j) + h;
      if (!G(s, yh, p_, period_, &fp_)) return false;
      jac_.col(j) = (fp_ - f_) / (yh(j) - y(j));
      yh(j) = y(j);
    }
    return true;
  }

  static int RhsCallback(sunrealtype s, N_Vector zv, N_Vector zdot, void* user) {
    auto& c = *static_cast<PeriodIntegrator*>(user);
    try {
      const double* z = N_VGetArrayPointer(zv);
      double* out = N_VGetArrayPointer(zdot);
      const int n = c.n_;
      const Eigen::Map<const Eigen::VectorXd> y(z, n);
      c.y_ = y;
      if (!c.G(s, c.y_, c.p_, c.period_, &c.f_)) return 1;
      Eigen::Map<Eigen::VectorXd>(out, n) = c.f_;
      if (!c.variational_ && c.column_ < 0) return 0;
      if (!c.ScaledJacobian(s, c.y_)) return 1;
      int off = n;
      if (c.variational_) {
        Eigen::Map<Eigen::MatrixXd>(out + off, n, n) =
            c.jac_ * Eigen::Map<const Eigen::MatrixXd>(z + off, n, n);
        off += n * n;
      }
      if (c.column_ >= 0) {
        // ∂g/∂λ by central differences, step cbrt(ε) of λ's scale (truncation and round-off
        // balanced for a smooth dependence on λ).
        const double lambda = c.p_(c.column_);
        const double h = std::cbrt(std::numeric_limits<double>::epsilon()) *
                         std::max(std::abs(lambda), c.lambda_scale_);
        Eigen::VectorXd pp = c.p_, pm = c.p_;
        pp(c.column_) = lambda + h;
        pm(c.column_) = lambda - h;
        if (!c.G(s, c.y_, pp, c.PeriodOf(pp), &c.fp_)) return 1;
        if (!c.G(s, c.y_, pm, c.PeriodOf(pm), &c.fm_)) return 1;
        Eigen::Map<Eigen::VectorXd>(out + off, n) =
            c.jac_ * Eigen::Map<const Eigen::VectorXd>(z + off, n) +
            (c.fp_ - c.fm_) / (pp(c.column_) - pm(c.column_));
      }
      return 0;
    } catch (...) {
      c.error_ = std::current_exception();
      return -1;
    }
  }

  static int JacCallback(sunrealtype s, N_Vector zv, N_Vector, SUNMatrix a, void* user, N_Vector,
                         N_Vector, N_Vector) {
    auto& c = *static_cast<PeriodIntegrator*>(user);
    try {
      const int n = c.n_;
      c.y_ = Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(zv), n);
      if (!c.ScaledJacobian(s, c.y_)) return 1;
      SUNMatZero(a);
      for (int b = 0; b < c.size_ / n; ++b)
        for (int i = 0; i < n; ++i)
          for (int j = 0; j < n; ++j) SM_ELEMENT_B(a, b * n + i, b * n + j) = c.jac_(i, j);
      return 0;
    } catch (...) {
      c.error_ = std::current_exception();
      return -1;
    }
  }

  const PeriodicSystem& sys_;
  Eigen::VectorXd p_;
  int n_;
  bool variational_;
  int column_;
  double lambda_scale_;
  double rtol_;
  long max_steps_;
  Eigen::VectorXd atol_;
  double period_ = 0;
  int size_ = 0;
  Eigen::VectorXd y_, f_, fp_, fm_;
  Eigen::MatrixXd jac_;
  long rhs_ = 0;
  std::exception_ptr error_;
  std::string message_;
};

Eigen::VectorXd ParametersOr(const PeriodicSystem& system, const Eigen::VectorXd& p) {
  const Eigen::VectorXd defaults = system.DefaultParameters();
  if (p.size() == 0) return defaults;
  if (p.size() != defaults.size())
    throw std::invalid_argument("periodic system: " + std::to_string(p.size()) +
                                " parameter values given, the system has " +
                                std::to_string(defaults.size()));
  return p;
}

void CheckState(const PeriodicSystem& system, const Eigen::VectorXd& y0, const char* where) {
  if (y0.size() != system.size())
    throw std::invalid_argument(std::string(where) + ": the initial state has " +
                                std::to_string(y0.size()) + " entries, the system " +
                                std::to_string(system.size()));
  if (!y0.allFinite())
    throw std::invalid_argument(std::string(where) + ": the initial state is not finite");
}

// The weighted RMS norm of r with weights 1/(rtol |y_i| + atol_i) (CVODE's error norm).
double Wrms(const Eigen::VectorXd& r, const Eigen::VectorXd& y, const ShootingOptions& o) {
  double sum = 0;
  for (Eigen::Index i = 0; i < r.size(); ++i) {
    const double a = o.atol.size() == 1 ? o.atol(0) : o.atol(i);
    const double w = r(i) / (o.rtol * std::abs(y(i)) + a);
    sum += w * w;
  }
  return std::sqrt(sum / static_cast<double>(std::max<Eigen::Index>(r.size(), 1)));
}

}  // namespace

ShootingResult SolvePeriodicOrbit(const PeriodicSystem& system, const ShootingOptions& options,
                                  const Eigen::VectorXd& y0, const Eigen::VectorXd& p_in) {
  const int n = system.size();
  options.Validate(n);
  CheckState(system, y0, "shooting");
  ShootingResult r;
  r.parameters = ParametersOr(system, p_in);
  PeriodIntegrator integrator(system, options, r.parameters, true, -1, 1.0);
  r.period = integrator.period();
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(n, n);

  Eigen::VectorXd y = y0;
  auto integrate = [&](const Eigen::VectorXd& from) {
    Flow f = integrator.Shoot(from);
    ++r.integrations;
    r.steps += f.steps;
    r.rhs_evaluations += f.rhs;
    return f;
  };
  Flow flow = integrate(y);
  r.initial_state = y;
  if (!flow.ok) {
    r.status = ShootingStatus::kIntegrationFailed;
    r.message = "shooting from the initial guess: " + flow.message;
    return r;
  }
  Eigen::VectorXd res = flow.end - y;
  double norm = Wrms(res, y, options);
  auto finish = [&](ShootingStatus status, const std::string& message) {
    r.status = status;
    r.message = message;
    r.initial_state = y;
    r.monodromy = flow.phi;
    r.floquet = FloquetMultipliers(flow.phi, options.unit_circle_tolerance);
    r.residual_norm = norm;
    return r;
  };
  for (r.iterations = 0; r.iterations < options.max_iterations;) {
    if (norm <= options.newton_tolerance) return finish(ShootingStatus::kConverged, "");
    ++r.iterations;
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(flow.phi - identity);
    if (!lu.isInvertible())
      return finish(ShootingStatus::kSingularJacobian,
                    "Newton iteration " + std::to_string(r.iterations) +
                        ": M − I is singular (a Floquet multiplier at +1)");
    const Eigen::VectorXd step = -lu.solve(res);
    // The update is below the integrator's tolerance: y is the orbit as far as it can tell.
    if (Wrms(step, y, options) <= options.newton_tolerance)
      return finish(ShootingStatus::kConverged, "");
    // Backtracking: halve the step until |R| decreases (Armijo with c = 1e-4).
    double alpha = 1;
    for (;;) {
      const Eigen::VectorXd trial = y + alpha * step;
      Flow f = integrate(trial);
      if (f.ok) {
        const Eigen::VectorXd rt = f.end - trial;
        const double nt = Wrms(rt, trial, options);
        if (nt <= (1 - 1e-4 * alpha) * norm || nt <= options.newton_tolerance) {
          y = trial;
          flow = std::move(f);
          res = rt;
          norm = nt;
          break;
        }
      }
      alpha /= 2;
      if (alpha < 1.0 / 64)
        return finish(ShootingStatus::kLineSearchFailed,
                      "Newton iteration " + std::to_string(r.iterations) +
                          ": no step down to 1/64 of the Newton step decreased |R| (weighted " +
                          Num(norm) + ")" + (f.ok ? "" : "; " + f.message));
    }
  }
  if (norm <= options.newton_tolerance) return finish(ShootingStatus::kConverged, "");
  return finish(ShootingStatus::kIterationLimit,
                std::to_string(options.max_iterations) +
                    " Newton iterations spent; |φ_T(y0) − y0| (weighted) = " + Num(norm));
}

Eigen::MatrixXd SampleOrbit(const PeriodicSystem& system, const ShootingOptions& options,
                            const Eigen::VectorXd& y0, const Eigen::VectorXd& p_in, int samples) {
  const int n = system.size();
  options.Validate(n);
  CheckState(system, y0, "orbit samples");
  if (samples < 1)
    throw std::invalid_argument("orbit samples: samples = " + std::to_string(samples) +
                                ": must be >= 1");
  PeriodIntegrator integrator(system, options, ParametersOr(system, p_in), false, -1, 1.0);
  std::vector<double> s_out;
  for (int k = 1; k <= samples; ++k) s_out.push_back(static_cast<double>(k) / samples);
  std::vector<Eigen::VectorXd> ys;
  const Flow f = integrator.Run(y0, s_out, &ys);
  if (!f.ok) throw std::runtime_error("orbit samples: " + f.message);
  Eigen::MatrixXd out(samples + 1, n);
  out.row(0) = y0.transpose();
  for (int k = 0; k < samples; ++k) out.row(k + 1) = ys[static_cast<std::size_t>(k)].transpose();
  return out;
}

Eigen::VectorXd IntegratePeriods(const PeriodicSystem& system, const ShootingOptions& options,
                                 const Eigen::VectorXd& y0, const Eigen::VectorXd& p_in,
                                 int periods) {
  const int n = system.size();
  options.Validate(n);
  CheckState(system, y0, "time integration");
  if (periods < 1)
    throw std::invalid_argument("time integration: periods = " + std::to_string(periods) +
                                ": must be >= 1");
  PeriodIntegrator integrator(system, options, ParametersOr(system, p_in), false, -1, 1.0);
  std::vector<double> s_out;
  for (int k = 1; k <= periods; ++k) s_out.push_back(k);
  const Flow f = integrator.Run(y0, s_out, nullptr);
  if (!f.ok) throw std::runtime_error("time integration: " + f.message);
  return f.end;
}

namespace {

// The continuation's unknowns in scaled coordinates u = (y/state_scale, λ/Λ).
class Continuer {
 public:
  Continuer(const PeriodicSystem& system, const ContinuationOptions& options, Eigen::VectorXd p,
            int column)
      : sys_(system), o_(options), p_(std::move(p)), column_(column), n_(system.size()) {
    scale_ = o_.state_scale.size() == 1 ? Eigen::VectorXd::Constant(n_, o_.state_scale(0))
                                        : o_.state_scale;
    lambda_scale_ = std::abs(o_.end - o_.start);
  }

  struct Point {
    bool ok = false;
    std::string message;
    Eigen::VectorXd u;         // scaled (y, λ)
    Eigen::MatrixXd jacobian;  // scaled [M − I, ψ]: n × (n + 1)
    Eigen::MatrixXd monodromy;
    double residual = 0;  // weighted RMS of R
    int iterations = 0;
  };

  Eigen::VectorXd Y(const Eigen::VectorXd& u) const { return u.head(n_).cwiseProduct(scale_); }
  double Lambda(const Eigen::VectorXd& u) const { return u(n_) * lambda_scale_; }
  Eigen::VectorXd Scaled(const Eigen::VectorXd& y, double lambda) const {
    Eigen::VectorXd u(n_ + 1);
    u.head(n_) = y.cwiseQuotient(scale_);
    u(n_) = lambda / lambda_scale_;
    return u;
  }
  Eigen::VectorXd P(double lambda) const {
    Eigen::VectorXd p = p_;
    p(column_) = lambda;
    return p;
  }
  double PeriodAt(double lambda) const {
    return PeriodIntegrator(sys_, o_.shooting, P(lambda), false, -1, lambda_scale_).period();
  }

  // R and its scaled Jacobian at u (one integration with the variational equations).
  bool Evaluate(const Eigen::VectorXd& u, Eigen::VectorXd* r, Point* at) {
    const double lambda = Lambda(u);
    const Eigen::VectorXd y = Y(u);
    Flow f;
    // A corrector's iterate may leave the parameter's domain (a speed through zero): the system
    // refuses it, and the step fails and is retried shorter, as a failed integration is.
    try {
      PeriodIntegrator integrator(sys_, o_.shooting, P(lambda), true, column_, lambda_scale_);
      f = integrator.Shoot(y);
    } catch (const std::invalid_argument& e) {
      at->message = o_.parameter + " = " + Num(lambda) + ": " + e.what();
      return false;
    }
    ++integrations_;
    steps_ += f.steps;
    if (!f.ok) {
      at->message = f.message;
      return false;
    }
    *r = f.end - y;
    at->residual = Wrms(*r, y, o_.shooting);
    at->monodromy = f.phi;
    at->jacobian.resize(n_, n_ + 1);
    // R̃ = R/scale: ∂R̃/∂ỹ = diag(1/scale)(M − I) diag(scale), ∂R̃/∂λ̃ = ψ Λ/scale.
    at->jacobian.leftCols(n_) = scale_.cwiseInverse().asDiagonal() *
                                (f.phi - Eigen::MatrixXd::Identity(n_, n_)) * scale_.asDiagonal();
    at->jacobian.col(n_) = f.psi.cwiseQuotient(scale_) * lambda_scale_;
    at->u = u;
    return true;
  }

  // Corrector: Newton on [R̃(u); τ·(u − u0) − ds] = 0 from u0 + ds τ.
  Point Correct(const Eigen::VectorXd& u0, const Eigen::VectorXd& tangent, double ds) {
    Point at;
    Eigen::VectorXd u = u0 + ds * tangent;
    Eigen::VectorXd r;
    double previous = std::numeric_limits<double>::infinity();
    for (at.iterations = 1; at.iterations <= o_.max_corrector_iterations; ++at.iterations) {
      if (!Evaluate(u, &r, &at)) return at;
      if (at.residual <= o_.shooting.newton_tolerance) {
        at.ok = true;
        return at;
      }
      if (at.residual > 2 * previous && at.iterations > 2) {
        at.message = "the corrector diverged (weighted |R| " + Num(previous) + " -> " +
                     Num(at.residual) + ")";
        return at;
      }
      previous = at.residual;
      Eigen::MatrixXd a(n_ + 1, n_ + 1);
      a.topRows(n_) = at.jacobian;
      a.row(n_) = tangent.transpose();
      Eigen::VectorXd g(n_ + 1);
      g.head(n_) = r.cwiseQuotient(scale_);
      g(n_) = tangent.dot(u - u0) - ds;
      const Eigen::FullPivLU<Eigen::MatrixXd> lu(a);
      if (!lu.isInvertible()) {
        at.message = "the bordered Jacobian is singular";
        return at;
      }
      const Eigen::VectorXd du = -lu.solve(g);
      const Eigen::VectorXd dy = du.head(n_).cwiseProduct(scale_);
      // The update below the integrator's tolerance in y and in λ: converged.
      const double lambda = Lambda(u);
      if (Wrms(dy, Y(u), o_.shooting) <= o_.shooting.newton_tolerance &&
          std::abs(du(n_) * lambda_scale_) <= o_.shooting.newton_tolerance * o_.shooting.rtol *
                                                  (std::abs(lambda) + lambda_scale_)) {
        at.ok = true;
        return at;
      }
      u += du;
    }
    at.iterations = o_.max_corrector_iterations;
    at.message = "the corrector did not converge in " +
                 std::to_string(o_.max_corrector_iterations) + " iterations (weighted |R| " +
                 Num(at.residual) + ")";
    return at;
  }

  // The unit tangent: the null vector of the scaled Jacobian, oriented along `previous`.
  Eigen::VectorXd Tangent(const Eigen::MatrixXd& jacobian, const Eigen::VectorXd& previous) const {
    Eigen::MatrixXd a(n_ + 1, n_ + 1);
    a.topRows(n_) = jacobian;
    a.row(n_) = previous.transpose();
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n_ + 1);
    rhs(n_) = 1;
    Eigen::VectorXd t = a.fullPivLu().solve(rhs);
    t.normalize();
    if (t.dot(previous) < 0) t = -t;
    return t;
  }

  double Amplitude(const Eigen::VectorXd& u) const {
    if (o_.amplitude_samples == 0) return 0;
    const Eigen::MatrixXd orbit =
        SampleOrbit(sys_, o_.shooting, Y(u), P(Lambda(u)), o_.amplitude_samples);
    const Eigen::VectorXd c = orbit.col(o_.amplitude_component);
    return (c.maxCoeff() - c.minCoeff()) / 2;
  }

  long integrations_ = 0, steps_ = 0;

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

}  // namespace

ContinuationResult ContinuePeriodicOrbit(
    const PeriodicSystem& system, const ContinuationOptions& options, const Eigen::VectorXd& y0,
    const Eigen::VectorXd& p_in, const std::function<void(const ContinuationResult&)>& on_point) {
  const int n = system.size();
  options.Validate(n);
  CheckState(system, y0, "continuation");
  const int column = system.ParameterIndex(options.parameter);
  ContinuationResult result;
  result.parameter = options.parameter;
  result.unit = system.parameters()[static_cast<std::size_t>(column)].unit;
  Eigen::VectorXd p = ParametersOr(system, p_in);
  p(column) = options.start;
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
  const double direction = options.end > options.start ? 1.0 : -1.0;
  const double lo = std::min(options.start, options.end), hi = std::max(options.start, options.end);
  Eigen::VectorXd u = c.Scaled(result.start.initial_state, options.start);
  Continuer::Point here;
  Eigen::VectorXd r;
  if (!c.Evaluate(u, &r, &here)) {
    result.status = ContinuationStatus::kStartFailed;
    result.message = "continuation: the first orbit's parameter derivative: " + here.message;
    return result;
  }
  Eigen::VectorXd axis = Eigen::VectorXd::Zero(n + 1);
  axis(n) = direction;
  Eigen::VectorXd tangent = c.Tangent(here.jacobian, axis);

  auto add_point = [&](const Continuer::Point& at, const Eigen::VectorXd& t, double s) {
    BranchPoint b;
    b.state = c.Y(at.u);
    b.parameter = c.Lambda(at.u);
    b.period = c.PeriodAt(b.parameter);
    b.floquet = FloquetMultipliers(at.monodromy, options.shooting.unit_circle_tolerance);
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
    result.integrations += c.integrations_;
    result.steps += c.steps_;
    return result;
  };
  while (static_cast<int>(result.points.size()) < options.max_points) {
    Continuer::Point next = c.Correct(u, tangent, ds);
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
    const Eigen::VectorXd new_tangent = c.Tangent(next.jacobian, tangent);
    // A fold: dλ/ds changes sign between the two points. Locate it by the secant method on
    // h(σ) = dλ/ds of the point σ along the previous tangent's corrector.
    if (new_tangent(n) * tangent(n) < 0) {
      double a = 0, ha = tangent(n), b = ds, hb = new_tangent(n);
      Continuer::Point best = next;
      for (int k = 0; k < options.fold_refinements; ++k) {
        const double sigma = a - ha * (b - a) / (hb - ha);
        if (!(sigma > a && sigma < b)) break;
        const Continuer::Point mid = c.Correct(u, tangent, sigma);
        if (!mid.ok) break;
        const double h = c.Tangent(mid.jacobian, tangent)(n);
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
      fold.state = c.Y(best.u);
      fold.after_point = static_cast<int>(result.points.size());
      fold.multiplier =
          NearestToOne(FloquetMultipliers(best.monodromy, options.shooting.unit_circle_tolerance));
      result.bifurcations.push_back(std::move(fold));
    }
    s += ds;
    u = next.u;
    tangent = new_tangent;
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
  return stop(ContinuationStatus::kPointLimit,
              "continuation: " + std::to_string(options.max_points) + " points reached at " +
                  options.parameter + " = " + Num(result.points.back().parameter) + " " +
                  result.unit + " before the end " + Num(options.end));
}

}  // namespace epicycle::dynamics
