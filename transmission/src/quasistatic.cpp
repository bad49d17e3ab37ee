#include "epicycle/transmission/quasistatic.hpp"

#include <cmath>
#include <stdexcept>

#include "epicycle/solvers/contact_problem.hpp"

namespace epicycle::transmission {

namespace {

// Largest rigid displacement of an increment, rotations measured at the base circles.
double DisplacementSize(const geometry::Stage& stage, const std::vector<StageDof>& dofs,
                        const Eigen::VectorXd& lambda) {
  double worst = 0;
  for (std::size_t k = 0; k < dofs.size(); ++k) {
    double scale = 1.0;
    if (dofs[k].kind == StageDof::kSunRotation) scale = stage.sun().base_radius();
    if (dofs[k].kind == StageDof::kPlanetRotation)
      scale = stage.planet(dofs[k].planet).base_radius();
    worst = std::max(worst, std::abs(lambda(static_cast<Eigen::Index>(k))) * scale);
  }
  return worst;
}

}  // namespace

PositionResult SolvePosition(const Scene& scene, const geometry::Stage& stage,
                             const StageCompliance& compliance, double carrier_angle,
                             const QuasiStaticOptions& options) {
  PositionResult r;
  r.carrier_angle = carrier_angle;
  const geometry::StagePoses kinematic = stage.Poses(carrier_angle);
  std::vector<StageDof> dofs;
  Eigen::VectorXd total;  // accumulated rigid displacements, per DOF
  geometry::StagePoses poses = kinematic;
  auto solver = solvers::MakeContactSolver(options.backend);
  std::vector<std::string> previous_labels;
  for (int it = 1; it <= options.max_geometric_iterations; ++it) {
    r.geometric_iterations = it;
    r.problem = BuildStageProblem(scene, stage, poses, compliance, options.setup);
    if (dofs.empty()) {
      dofs = r.problem.dofs;
      total = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(dofs.size()));
    }
    // Elastic supports carry the deflection of the earlier iterations: G F + K (λ + λ_prev) = W.
    if (r.problem.data.support_stiffness.size() > 0)
      r.problem.data.equality_rhs -= r.problem.data.support_stiffness * total;
    const solvers::ContactProblem problem(r.problem.data);
    // The same potential contacts as the previous geometric iteration: start from its forces
    // (the members have moved by its displacements, so the new multipliers start at zero).
    solvers::ContactOptions contact = options.contact;
    if (it > 1 && r.problem.data.contact_labels == previous_labels &&
        r.solution.force.size() == problem.num_contacts()) {
      contact.warm_start = true;
      r.solution.multiplier.setZero(problem.num_equalities());
    } else {
      r.solution = {};
    }
    previous_labels = r.problem.data.contact_labels;
    r.report = solver->Solve(problem, contact, &r.solution);
    const bool inaccurate = r.report.status == solvers::ContactStatus::kConvergedInaccurate;
    if (inaccurate && options.accept_inaccurate) {
      r.message = "accepted converged-inaccurate contact solves (residual " +
                  std::to_string(r.report.residual.total) + ")";
    } else if (r.report.status != solvers::ContactStatus::kConverged) {
      r.message = "contact solve at geometric iteration " + std::to_string(it) + ": " +
                  solvers::StatusName(r.report.status) + " (" + r.report.message + ")";
      break;
    }
    total += r.solution.multiplier;
    const double step = DisplacementSize(stage, dofs, r.solution.multiplier);
    poses = Displace(poses, dofs, r.solution.multiplier);
    if (step <= options.geometric_tolerance) {
      r.converged = true;
      break;
    }
    if (it == options.max_geometric_iterations) {
      r.message = "geometric iterations did not settle: last displacement increment " +
                  std::to_string(step) + " m";
    }
  }
  r.poses = poses;
  // Outputs from the last contact problem (solved at the poses before its own small increment).
  const int n = stage.planets();
  r.load_sharing.assign(n, 0.0);
  for (std::size_t j = 0; j < r.problem.contacts.size() && r.solution.force.size() > 0; ++j) {
    const StageContact& s = r.problem.contacts[j];
    if (s.body_a != kSunBody) continue;
    // Moment of the contact on the sun over the input torque it balances.
    r.load_sharing[s.planet] +=
        s.contact.lever_a * r.solution.force(static_cast<Eigen::Index>(j)) / -scene.sun_torque;
  }
  r.planet_rotations.assign(n, 0.0);
  r.planet_displacements.assign(n, geometry::Vec2::Zero());
  for (std::size_t k = 0; k < dofs.size(); ++k) {
    const double v = total(static_cast<Eigen::Index>(k));
    switch (dofs[k].kind) {
      case StageDof::kSunRotation:
        r.transmission_error = v;
        break;
      case StageDof::kSunX:
        r.sun_displacement.x() = v;
        break;
      case StageDof::kSunY:
        r.sun_displacement.y() = v;
        break;
      case StageDof::kPlanetRotation:
        r.planet_rotations[dofs[k].planet] = v;
        break;
      case StageDof::kPlanetX:
        r.planet_displacements[dofs[k].planet].x() = v;
        break;
      case StageDof::kPlanetY:
        r.planet_displacements[dofs[k].planet].y() = v;
        break;
    }
  }
  return r;
}

std::vector<double> LoadSharingFactors(const PositionResult& r) {
  std::vector<double> l;
  const double n = static_cast<double>(r.load_sharing.size());
  for (double v : r.load_sharing) l.push_back(n * v);
  return l;
}

double MeshLoadFactor(const PositionResult& r) {
  double k = 0.0;
  for (double v : LoadSharingFactors(r)) k = std::max(k, v);
  return k;
}

std::vector<double> SweepAngles(double start, double span, int count) {
  if (count < 1)
    throw std::invalid_argument("sweep: positions = " + std::to_string(count) +
                                ": must be at least 1");
  std::vector<double> a;
  for (int k = 0; k < count; ++k) a.push_back(start + span * k / count);
  return a;
}

std::vector<PositionResult> Sweep(
    const Scene& scene, const geometry::Stage& stage, const StageCompliance& compliance,
    const std::vector<double>& carrier_angles, const QuasiStaticOptions& options,
    const std::function<void(const PositionResult&, int)>& on_result) {
  std::vector<PositionResult> out;
  out.reserve(carrier_angles.size());
  for (std::size_t k = 0; k < carrier_angles.size(); ++k) {
    PositionResult r;
    try {
      r = SolvePosition(scene, stage, compliance, carrier_angles[k], options);
    } catch (const std::invalid_argument& e) {
      r = PositionResult{};
      r.carrier_angle = carrier_angles[k];
      r.converged = false;
      r.message = e.what();
      r.load_sharing.assign(stage.planets(), 0.0);
      r.planet_rotations.assign(stage.planets(), 0.0);
      r.planet_displacements.assign(stage.planets(), geometry::Vec2::Zero());
    }
    if (on_result) on_result(r, static_cast<int>(k));
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace epicycle::transmission
