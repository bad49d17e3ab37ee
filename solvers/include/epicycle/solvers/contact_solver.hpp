// One interface, interchangeable back ends (docs/solvers.md §2–3).
#pragma once

#include <algorithm>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "epicycle/solvers/contact_problem.hpp"

namespace epicycle::solvers {

/// Outcome of a solve, decided by the driver from its own residual, never by the back end.
enum class ContactStatus {  // append only: values are written to files
  kConverged,               ///< residual ≤ tolerance
  kConvergedInaccurate,     ///< back end stopped with a usable point, residual ≤ 100·tolerance
  kIterationLimit,          ///< iteration or time limit reached
  kNumericalFailure,        ///< the back end failed (singular system, NaN, line search)
  kInfeasible,              ///< no F ≥ 0 satisfies G F = W
  kBackendUnavailable,      ///< compiled out
};

/// The back ends. Registration is this enum plus the switch in MakeContactSolver.
enum class Backend {  // append only
  kActiveSetNewton,   ///< "newton": semismooth active-set Newton, Φ-globalised, warm-startable
  kIpopt,             ///< "ipopt": interior point (TNLP, exact Hessian)
  kNloptSlsqp,        ///< "nlopt-slsqp": SLSQP with the equalities
  kNloptLbfgs,        ///< "nlopt-lbfgs": bound-constrained L-BFGS (problems without equalities)
  kNloptAuglag,       ///< "nlopt-auglag": AUGLAG (equalities) around CCSAQ (bounds)
};

std::string BackendName(Backend backend);  ///< "newton", "ipopt", ...
Backend BackendFromName(
    const std::string& name);                  ///< @throws std::invalid_argument naming the value
std::string StatusName(ContactStatus status);  ///< "converged", ...

struct ContactOptions {
  double tolerance = 1e-10;  ///< on the nondimensional residual (see ContactResiduals) [-]
  int max_iterations = 200;  ///< back-end iterations [-]
  double time_limit = 60.0;  ///< [s]
  bool warm_start = false;   ///< use the solution passed in as the starting point
  bool polish = false;       ///< after the raw solve, a labelled active-set polish step
  /// Back-end specific knobs, namespaced: "ipopt.mu_strategy", "nlopt.xtol_rel", "newton.ls_beta".
  /// Unknown keys are rejected by Validate().
  std::map<std::string, std::string> backend_options;
  void Validate() const;  ///< @throws std::invalid_argument naming the field, value and rule
};

struct ContactSolution {
  Eigen::VectorXd force;       ///< F [N], N
  Eigen::VectorXd multiplier;  ///< λ [m] or [rad], m
};

/// Nondimensional residuals: forces by the load scale, lengths by the deflection scale.
struct ContactResiduals {
  double complementarity = 0.0;  ///< ‖F − max(0, F − g)‖∞ (natural map), nondimensional
  double equilibrium = 0.0;      ///< ‖G F + S λ − W‖∞, nondimensional
  double total = 0.0;            ///< max of the two
};

struct ContactReport {
  Backend backend = Backend::kActiveSetNewton;
  ContactStatus status = ContactStatus::kNumericalFailure;
  std::string message;       ///< human-readable reason, always set
  int iterations = 0;        ///< back-end iterations
  int backend_code = 0;      ///< the back end's raw return code
  double solve_seconds = 0;  ///< [s] inside the back end
  double total_seconds = 0;  ///< [s] including scaling and residual
  ContactResiduals residual;
  int active_contacts =
      0;                  ///< contacts with F_j > g_j (nondimensional), the natural-map active set
  bool polished = false;  ///< the polish option changed the answer
};

/// A stateful, reusable solver. Solve() nondimensionalises, runs the back end, recovers the
/// multipliers it does not return, computes the residual and decides the status.
class ContactSolver {
 public:
  virtual ~ContactSolver() = default;
  virtual Backend backend() const = 0;
  virtual bool available() const = 0;  ///< false: compiled out
  /// @param in_out warm start in (if options.warm_start), answer out. Never null.
  /// @throws std::invalid_argument for a bad problem or options (not for numerical trouble).
  virtual ContactReport Solve(const class ContactProblem& problem, const ContactOptions& options,
                              ContactSolution* in_out) = 0;
  /// The same, the report written into `report` (never null), whose message's storage is
  /// reused: a warm solve on the Newton's direct path then allocates nothing (the dynamic
  /// model's right-hand side calls it on every evaluation). The default calls Solve.
  virtual void SolveInto(const class ContactProblem& problem, const ContactOptions& options,
                         ContactSolution* in_out, ContactReport* report) {
    *report = Solve(problem, options, in_out);
  }
};

std::unique_ptr<ContactSolver> MakeContactSolver(Backend backend);  ///< never null

/// The driver's nondimensionalisation (see solvers/src/backend.hpp and docs/solvers.md).
struct ContactScales {
  double force = 1.0;   ///< F* [N]
  double length = 1.0;  ///< ℓ* [m]
  Eigen::VectorXd row;  ///< r_i, m: [-] for force rows, [m] for moment rows
};
ContactScales ComputeContactScales(const ContactProblem& problem);

/// The residuals the driver judges every back end by (ContactResiduals: the natural map and the
/// equilibrium, nondimensional) of any answer (F, λ) of `problem`, e.g. one of a solver of one's
/// own, evaluated at max(F, 0). @throws std::invalid_argument unless the solution has N forces
/// and m multipliers.
ContactResiduals EvaluateResiduals(const ContactProblem& problem, const ContactSolution& solution);

/// Differences of a solution from a reference, each relative and unit-consistent:
///   force        ‖F − F_ref‖∞ / max(‖F_ref‖∞, F*)
///   multiplier   ‖r∘(λ − λ_ref)‖∞ / max(‖r∘λ_ref‖∞, ℓ*)   (r∘λ: rigid displacements [m])
///   displacement ‖Gᵀ(λ − λ_ref)‖∞ / max(‖Gᵀλ_ref‖∞, ℓ*)   (well defined even if λ is not unique)
struct SolutionDifference {
  double force = 0.0;
  double multiplier = 0.0;
  double displacement = 0.0;
  double max() const { return std::max(force, multiplier); }
};
SolutionDifference CompareSolutions(const ContactProblem& problem, const ContactSolution& solution,
                                    const ContactSolution& reference);
std::vector<Backend> AllBackends();
std::vector<Backend> AvailableBackends();

}  // namespace epicycle::solvers
