#include "epicycle/transmission/geometric_iteration.hpp"

#include <stdexcept>
#include <string>
#include <vector>

#include "epicycle/io/number_format.hpp"
#include "epicycle/solvers/contact_problem.hpp"

namespace epicycle::transmission {

GeometricIterationResult IterateGeometry(
    const std::function<StageOutcome(solvers::ContactProblemData*)>& build,
    const std::function<double(const Eigen::VectorXd&)>& move, solvers::ContactSolver& solver,
    const solvers::ContactOptions& contact, const GeometricIterationOptions& options,
    const GeometricIterationStart& start, const ForceFixedPoint& forces) {
  GeometricIterationResult r;
  std::vector<std::string> previous_labels;
  for (int it = 1; it <= options.max_iterations; ++it) {
    r.iterations = it;
    solvers::ContactProblemData data;
    if (StageOutcome o = build(&data); !o.ok()) {
      r.status = o.status;
      r.message = "geometric iteration " + std::to_string(it) + ": " + o.message;
      return r;
    }
    if (it == 1) {
      r.total = Eigen::VectorXd::Zero(data.equality_rhs.size());
      if (start.displacements.size() > 0) {
        if (start.displacements.size() != r.total.size())
          throw std::invalid_argument(
              "geometric iteration: the start has " + std::to_string(start.displacements.size()) +
              " displacements for " + std::to_string(r.total.size()) + " DOFs");
        r.total = start.displacements;
      }
    }
    // Elastic supports carry the deflection of the earlier iterations: G F + K (λ + λ_prev) = W.
    if (data.support_stiffness.size() > 0) data.equality_rhs -= data.support_stiffness * r.total;
    r.rhs = data.equality_rhs;
    const solvers::ContactProblem problem(std::move(data));
    solvers::ContactOptions opt = contact;
    if (options.warm_start && it > 1 && problem.data().contact_labels == previous_labels &&
        r.solution.force.size() == problem.num_contacts()) {
      opt.warm_start = true;
      r.solution.multiplier.setZero(problem.num_equalities());
    } else if (it == 1 && start.forces && start.forces(problem.num_contacts(), &r.solution.force) &&
               r.solution.force.size() == problem.num_contacts()) {
      // A neighbour's forces: the members already carry its displacements, so λ starts from 0.
      opt.warm_start = true;
      r.solution.multiplier.setZero(problem.num_equalities());
    } else {
      r.solution = {};
    }
    previous_labels = problem.data().contact_labels;
    r.report = solver.Solve(problem, opt, &r.solution);
    r.contact_iterations += r.report.iterations;
    const bool inaccurate = r.report.status == solvers::ContactStatus::kConvergedInaccurate;
    if (inaccurate && options.accept_inaccurate) {
      r.message = "accepted converged-inaccurate contact solves (residual " +
                  std::to_string(r.report.residual.total) + ")";
    } else if (r.report.status != solvers::ContactStatus::kConverged) {
      r.status = StageStatus::kContactSolveFailed;
      r.message = "contact solve at geometric iteration " + std::to_string(it) + ": " +
                  solvers::StatusName(r.report.status) + " (" + r.report.message + ")";
      return r;
    }
    r.total += r.solution.multiplier;
    const double step = move(r.solution.multiplier);
    if (forces.update) r.force_change = forces.update(r.solution.force);
    if (step <= options.tolerance && r.force_change <= forces.tolerance) {
      r.converged = true;
      return r;
    }
    if (it == options.max_iterations && r.force_change > forces.tolerance) {
      r.status = StageStatus::kFrictionNotSettled;
      r.message = "the friction fixed point did not settle in " + std::to_string(it) +
                  " iterations: last relative force change " + io::Num(r.force_change) +
                  " (tolerance " + io::Num(forces.tolerance) + "), last displacement increment " +
                  io::Num(step) + " m";
    } else if (it == options.max_iterations) {
      r.status = StageStatus::kNotSettled;
      r.message = "geometric iterations did not settle: last displacement increment " +
                  std::to_string(step) + " m";
    }
  }
  return r;
}

}  // namespace epicycle::transmission
