// The pseudo-arclength continuation loop (docs/periodic.md §1 and §2, "Continuation") over any
// periodic back end: shooting (periodic_continuation.cpp) and harmonic balance
// (harmonic_balance_continuation.cpp) give their residual, its bordered Jacobian and the
// stability of a point in scaled unknowns u = (x̃, λ/Λ); the predictor, the chord corrector, the
// step control, the fold location and the bifurcation flags are this one loop's. Private to
// dynamics/src.
#pragma once

#include <functional>
#include <string>

#include <Eigen/Dense>

#include "epicycle/dynamics/periodic.hpp"

namespace epicycle::dynamics::periodic_detail {

class ContinuationProblem {
 public:
  struct Point {
    bool ok = false;
    std::string message;
    Eigen::VectorXd u;         // scaled (x, λ)
    Eigen::MatrixXd jacobian;  // scaled [∂R̃/∂x̃, ∂R̃/∂λ̃]: m × (m + 1)
    Eigen::MatrixXd monodromy; // shooting's M (harmonic balance: empty)
    double residual = 0;       // the back end's norm of R (converged at ≤ tolerance())
    int iterations = 0;
  };
  virtual ~ContinuationProblem() = default;
  virtual int size() const = 0;  ///< m, the unknowns besides λ
  virtual double Lambda(const Eigen::VectorXd& u) const = 0;
  virtual double LambdaScale() const = 0;
  /// R̃ at u alone (the corrector's iterations): into *r, its norm and u into *at.
  virtual bool Residual(const Eigen::VectorXd& u, Eigen::VectorXd* r, Point* at) = 0;
  /// R̃ and its scaled Jacobian at u (and what Stability needs) into *at.
  virtual bool Linearise(const Eigen::VectorXd& u, Eigen::VectorXd* r, Point* at) = 0;
  /// The norm of R at or below which a corrector has converged.
  virtual double tolerance() const = 0;
  /// Whether the corrector's update du at u is below the back end's resolution.
  virtual bool UpdateConverged(const Eigen::VectorXd& u, const Eigen::VectorXd& du) const = 0;
  virtual FloquetReport Stability(const Point& at) const = 0;
  virtual Eigen::VectorXd State(const Eigen::VectorXd& u) const = 0;  ///< y(0) on the orbit
  /// The orbit's Fourier coefficients (BranchPoint::coefficients; empty: not a series).
  virtual Eigen::MatrixXd Coefficients(const Eigen::VectorXd& u) const {
    (void)u;
    return {};
  }
  virtual double Period(double lambda) const = 0;
  virtual double Amplitude(const Eigen::VectorXd& u) const = 0;
  long integrations = 0, plain_integrations = 0, steps = 0;
};

/// The scaled unknowns u = (x/scale, λ/Λ) of a point x at λ.
inline Eigen::VectorXd ScaledPoint(const Eigen::VectorXd& x, const Eigen::VectorXd& scale,
                                   double lambda, double lambda_scale) {
  Eigen::VectorXd u(x.size() + 1);
  u.head(x.size()) = x.cwiseQuotient(scale);
  u(x.size()) = lambda / lambda_scale;
  return u;
}

/// The parameters p with the continued one, p(column), at λ.
inline Eigen::VectorXd WithParameter(Eigen::VectorXd p, int column, double lambda) {
  p(column) = lambda;
  return p;
}

/// A result named for the continued parameter (its index into *column), and the parameters at
/// λ = start into *p (p_in, or the system's defaults when empty).
/// @throws std::invalid_argument for an unknown parameter or p_in of the wrong size.
ContinuationResult NamedResult(const PeriodicSystem& system, const ContinuationOptions& options,
                               const Eigen::VectorXd& p_in, int* column, Eigen::VectorXd* p);

/// The continuation from the converged, linearised first point `here` (result->start filled by
/// the caller) to options.end; the branch and its status into *result.
void Continue(ContinuationProblem& problem, const ContinuationOptions& options,
              ContinuationProblem::Point here, ContinuationResult* result,
              const std::function<void(const ContinuationResult&)>& on_point);

}  // namespace epicycle::dynamics::periodic_detail
