#include "epicycle/dynamics/periodic.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <functional>
#include <exception>
#include <limits>
#include <stdexcept>

#include "epicycle/io/number_format.hpp"
#include "period_integrator.hpp"

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
  if (monodromy.size() == 0) return {};
  const Eigen::VectorXcd mu = Eigen::EigenSolver<Eigen::MatrixXd>(monodromy, false).eigenvalues();
  return ClassifyMultipliers({mu.data(), mu.data() + mu.size()}, tol);
}

FloquetReport ClassifyMultipliers(std::vector<std::complex<double>> multipliers, double tol) {
  FloquetReport r;
  r.multipliers = std::move(multipliers);
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

using periodic_detail::CheckState;
using periodic_detail::Flow;
using periodic_detail::ParametersOr;
using periodic_detail::PeriodIntegrator;
using periodic_detail::Wrms;

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

}  // namespace epicycle::dynamics
