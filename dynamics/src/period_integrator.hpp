// The periodic solver's integrator (docs/periodic.md §2, "Integrator"): one period of the
// scaled system with its variational equations and parameter column by CVODE, and the helpers
// that shooting (periodic.cpp) and continuation (periodic_continuation.cpp) share. Private to
// dynamics/src: SUNDIALS stays out of the public headers.
#pragma once

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_band.h>
#include <sunmatrix/sunmatrix_band.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "epicycle/dynamics/periodic.hpp"
#include "epicycle/io/number_format.hpp"

namespace epicycle::dynamics::periodic_detail {

using io::Num;


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

inline std::vector<double> EndOnly() { return {1.0}; }

inline void Check(int flag, const char* what) {
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
        // ∂g/∂λ by forward differences from g at λ (out's first n entries), step √ε of λ's
        // scale (truncation and round-off balanced for a one-sided difference): one evaluation
        // of the system a step. ∂φ/∂λ steers the predictor and the corrector's Newton; where
        // the corrector converges is set by R alone (docs/periodic.md §2).
        const double lambda = c.p_(c.column_);
        const double h = std::sqrt(std::numeric_limits<double>::epsilon()) *
                         std::max(std::abs(lambda), c.lambda_scale_);
        Eigen::VectorXd pp = c.p_;
        pp(c.column_) = lambda + h;
        if (!c.G(s, c.y_, pp, c.PeriodOf(pp), &c.fp_)) return 1;
        Eigen::Map<Eigen::VectorXd>(out + off, n) =
            c.jac_ * Eigen::Map<const Eigen::VectorXd>(z + off, n) +
            (c.fp_ - Eigen::Map<const Eigen::VectorXd>(out, n)) / (pp(c.column_) - lambda);
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
  Eigen::VectorXd y_, f_, fp_;
  Eigen::MatrixXd jac_;
  long rhs_ = 0;
  std::exception_ptr error_;
  std::string message_;
};

inline Eigen::VectorXd ParametersOr(const PeriodicSystem& system, const Eigen::VectorXd& p) {
  const Eigen::VectorXd defaults = system.DefaultParameters();
  if (p.size() == 0) return defaults;
  if (p.size() != defaults.size())
    throw std::invalid_argument("periodic system: " + std::to_string(p.size()) +
                                " parameter values given, the system has " +
                                std::to_string(defaults.size()));
  return p;
}

inline void CheckState(const PeriodicSystem& system, const Eigen::VectorXd& y0, const char* where) {
  if (y0.size() != system.size())
    throw std::invalid_argument(std::string(where) + ": the initial state has " +
                                std::to_string(y0.size()) + " entries, the system " +
                                std::to_string(system.size()));
  if (!y0.allFinite())
    throw std::invalid_argument(std::string(where) + ": the initial state is not finite");
}

// The weighted RMS norm of r with weights 1/(rtol |y_i| + atol_i) (CVODE's error norm).
inline double Wrms(const Eigen::VectorXd& r, const Eigen::VectorXd& y, const ShootingOptions& o) {
  double sum = 0;
  for (Eigen::Index i = 0; i < r.size(); ++i) {
    const double a = o.atol.size() == 1 ? o.atol(0) : o.atol(i);
    const double w = r(i) / (o.rtol * std::abs(y(i)) + a);
    sum += w * w;
  }
  return std::sqrt(sum / static_cast<double>(std::max<Eigen::Index>(r.size(), 1)));
}


}  // namespace epicycle::dynamics::periodic_detail
