// Private interface between the contact driver and its back ends. A back end sees only the
// nondimensional problem built by the driver; the driver scales back, recovers multipliers the
// back end does not return, computes the one residual and decides the status.
#pragma once

#include <memory>
#include <string>

#include <Eigen/Dense>

#include "epicycle/solvers/contact_solver.hpp"

namespace epicycle::solvers::internal {

/// The nondimensional problem: forces in units of force_scale [N], lengths in length_scale [m]
/// (so C is in length_scale/force_scale, δ0 in length_scale, W in force_scale (force rows) or
/// force_scale·moment_arm_scale (moment rows) as chosen by the driver).
///
///   Φ(x)  = ½xᵀCx + Σ_j U_j(x_j) − δ0ᵀx,   U_j = ∫₀^{x_j} u_local,j
///   ∇Φ(x) = Cx + u(x) − δ0 = g(x) + Gᵀλ
///   ∇²Φ   = C + diag(u'(x))           (u'(0⁺) = +∞: the local term's hazard)
///   s.t. x ≥ 0,  G x + S λ = W  (S = 0: hard equalities)
struct ScaledProblem {
  Eigen::MatrixXd C;        ///< N×N, SPD
  Eigen::VectorXd delta0;   ///< N
  Eigen::MatrixXd G;        ///< m×N (m may be 0)
  Eigen::VectorXd W;        ///< m
  Eigen::MatrixXd S;        ///< m×m PSD (all zero when there are no elastic supports)
  bool has_support = false; ///< S has a non-zero entry
  bool has_local = false;   ///< any local term enabled

  int num_contacts() const { return static_cast<int>(C.rows()); }
  int num_equalities() const { return static_cast<int>(G.rows()); }

  // Implemented by the driver (scaled_problem.cpp) for every back end to use.
  double Objective(const Eigen::VectorXd& x) const;                      ///< Φ(x), x ≥ 0
  void Gradient(const Eigen::VectorXd& x, Eigen::VectorXd* grad) const;  ///< ∇Φ(x)
  void LocalValue(const Eigen::VectorXd& x, Eigen::VectorXd* u) const;   ///< u_local(x)
  void LocalDerivative(const Eigen::VectorXd& x, Eigen::VectorXd* du) const;  ///< u'(x), +inf at 0

  // Scaled local-term parameters, one per contact (filled by the driver).
  struct Local {
    bool enabled = false;
    double a[2] = {0, 0};  ///< 2k_B/(πb) in scaled units
    double c[2] = {0, 0};  ///< c_B
    double h[2] = {0, 0};  ///< h_B in scaled length
    double l2 = 0;         ///< L² = l2 · F (scaled)
  };
  std::vector<Local> local;
};

/// What a back end returns: raw, unjudged.
struct BackendResult {
  Eigen::VectorXd force;        ///< x (scaled), N
  Eigen::VectorXd multiplier;   ///< λ (scaled), m; empty if the back end does not return it
  int iterations = 0;
  int code = 0;                 ///< the back end's own return code
  std::string message;          ///< the back end's own words
  bool failed = false;          ///< the back end reports a hard failure (no usable point)
  bool limit_reached = false;   ///< iteration or time limit
};

class BackendImpl {
 public:
  virtual ~BackendImpl() = default;
  virtual bool available() const = 0;
  /// @param x0, lambda0 warm start (scaled) or nullptr.
  virtual BackendResult Run(const ScaledProblem& problem, const ContactOptions& options,
                            const Eigen::VectorXd* x0, const Eigen::VectorXd* lambda0) = 0;
  /// Back-end option keys this back end accepts (without the namespace), for Validate().
  virtual std::vector<std::string> option_keys() const { return {}; }
};

// Factories, one per source file. The Ipopt / NLopt ones are compiled from either the real file
// or its *_unavailable.cpp, whose available() is false.
std::unique_ptr<BackendImpl> MakeActiveSetNewtonBackend();  // active_set_newton.cpp
std::unique_ptr<BackendImpl> MakeIpoptBackend();            // backend_ipopt[_unavailable].cpp
std::unique_ptr<BackendImpl> MakeNloptBackend(Backend which);  // backend_nlopt[_unavailable].cpp

}  // namespace epicycle::solvers::internal
