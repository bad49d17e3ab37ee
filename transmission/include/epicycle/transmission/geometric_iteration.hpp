// The geometric iteration of docs/model.md §5, shared by every quasi-static driver (the stage's
// load sharing, a gear pair's mesh stiffness): the geometry is nonlinear in the positions (tip
// contacts, translations), so the contact problem is solved at the current poses, the members are
// moved by its rigid displacements λ, and the search is repeated until λ stops changing.
#pragma once

#include <functional>
#include <string>

#include <Eigen/Dense>

#include "epicycle/solvers/contact_solver.hpp"

namespace epicycle::transmission {

struct GeometricIterationOptions {
  int max_iterations = 30;   ///< [-], ≥ 1
  double tolerance = 1e-11;  ///< largest rigid-displacement increment at convergence [m]
  /// Accept contact solves whose status is converged-inaccurate (the message says so).
  bool accept_inaccurate = false;
  /// When an iteration has the same potential contacts (labels) as the previous one, start the
  /// contact solve from its forces (multipliers from zero: the members have moved by them).
  bool warm_start = true;
};

struct GeometricIterationResult {
  bool converged = false;             ///< every contact solve converged and the increments settled
  std::string message;                ///< why not (or a note on accepted inaccurate solves)
  int iterations = 0;                 ///< [-]
  Eigen::VectorXd total;              ///< accumulated rigid displacements λ, per DOF [m] or [rad]
  solvers::ContactSolution solution;  ///< of the last contact problem
  solvers::ContactReport report;      ///< of the last contact problem
  Eigen::VectorXd rhs;  ///< W of the last contact problem as solved (less K·λ_prev) [N] or [N·m]
};

/// `build()` returns the contact problem at the current poses (its equality rows are the DOFs;
/// elastic supports' rows carry their stiffness K, and the loop subtracts K·λ_total of the earlier
/// iterations from W so that G F + K(λ + λ_prev) = W); `move(λ)` moves the poses by the increment
/// λ and returns its size [m]. Exceptions from either propagate.
GeometricIterationResult IterateGeometry(const std::function<solvers::ContactProblemData()>& build,
                                         const std::function<double(const Eigen::VectorXd&)>& move,
                                         solvers::ContactSolver& solver,
                                         const solvers::ContactOptions& contact,
                                         const GeometricIterationOptions& options);

}  // namespace epicycle::transmission
