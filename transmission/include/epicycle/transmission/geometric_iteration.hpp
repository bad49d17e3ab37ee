// The geometric iteration of docs/model.md §6, shared by every quasi-static driver (the stage's
// load sharing, a gear pair's mesh stiffness): the geometry is nonlinear in the positions (tip
// contacts, translations), so the contact problem is solved at the current poses, the members are
// moved by its rigid displacements λ, and the search is repeated until λ stops changing.
#pragma once

#include <functional>
#include <string>

#include <Eigen/Dense>

#include "epicycle/solvers/contact_solver.hpp"
#include "epicycle/transmission/stage_problem.hpp"

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

/// Where the iteration starts when it continues from a neighbouring state (a sweep's previous
/// position) instead of from the kinematic poses and zero forces.
struct GeometricIterationStart {
  /// Rigid displacements already applied to the poses that `build()` starts from, per DOF [m] or
  /// [rad]; they count in the accumulated λ (and in K·λ of elastic supports). Empty: none.
  Eigen::VectorXd displacements;
  /// Called once with the first problem's contact count; fills the forces to start its contact
  /// solve from [N] and returns true, or returns false for a cold first solve.
  std::function<bool(int contacts, Eigen::VectorXd* force)> forces;
};

/// A fixed point on the contact forces alongside the geometry's, for loads that depend on the
/// forces (the quasi-static friction, docs/model.md §9): `build` adds the loads of the forces
/// it was last given (none before the first solve, or a neighbour's), `update` gives it the new
/// ones. Empty `update`: no such loads, the iteration is the geometric one alone.
struct ForceFixedPoint {
  /// Called with the forces F [N] of every accepted contact solve (on the contacts of the problem
  /// `build` last wrote); keeps them for the next `build` and returns their change from the
  /// forces that problem's loads were computed with, ‖F − F_prev‖∞/‖F‖∞ [-].
  std::function<double(const Eigen::VectorXd& force)> update;
  double tolerance = 0;  ///< settled when the change is ≤ this [-]
};

struct GeometricIterationResult {
  bool converged = false;             ///< every contact solve converged and the increments settled
  /// kOk when converged; kContactSolveFailed, kNotSettled, or the outcome `build` returned.
  StageStatus status = StageStatus::kOk;
  std::string message;                ///< why not (or a note on accepted inaccurate solves)
  int iterations = 0;                 ///< [-]
  double force_change = 0;  ///< ForceFixedPoint: the last relative change of the forces [-]
  int contact_iterations = 0;         ///< back-end iterations summed over the contact solves [-]
  Eigen::VectorXd total;              ///< accumulated rigid displacements λ, per DOF [m] or [rad]
  solvers::ContactSolution solution;  ///< of the last contact problem
  solvers::ContactReport report;      ///< of the last contact problem
  Eigen::VectorXd rhs;  ///< W of the last contact problem as solved (less K·λ_prev) [N] or [N·m]
};

/// `build(data)` writes the contact problem at the current poses (its equality rows are the DOFs;
/// elastic supports' rows carry their stiffness K, and the loop subtracts K·λ_total of the earlier
/// iterations from W so that G F + K(λ + λ_prev) = W) or returns the geometric outcome that
/// prevents it, which ends the iteration with that status; `move(λ)` moves the poses by the
/// increment λ and returns its size [m]. `start` continues from a neighbouring state (its
/// displacements already in the poses, its forces for the first solve). Exceptions from either
/// propagate. With `forces` (ForceFixedPoint), the iteration ends when the displacement increment
/// and the relative force change have both settled; the bound on the iterations is the same
/// (options.max_iterations), and when the forces have not settled the status is
/// kFrictionNotSettled (the message gives the last force change and displacement increment).
/// @throws std::invalid_argument if start.displacements does not have one entry per DOF.
GeometricIterationResult IterateGeometry(
    const std::function<StageOutcome(solvers::ContactProblemData*)>& build,
    const std::function<double(const Eigen::VectorXd&)>& move, solvers::ContactSolver& solver,
    const solvers::ContactOptions& contact, const GeometricIterationOptions& options,
    const GeometricIterationStart& start = {}, const ForceFixedPoint& forces = {});

}  // namespace epicycle::transmission
