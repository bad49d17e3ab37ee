#include "epicycle/transmission/quasistatic.hpp"

#include <cmath>
#include <stdexcept>

#include "epicycle/solvers/contact_problem.hpp"
#include "epicycle/transmission/geometric_iteration.hpp"

namespace epicycle::transmission {

PositionResult SolvePosition(const StageModel& model, double carrier_angle, const StageLoads& loads,
                             const QuasiStaticOptions& options) {
  PositionResult r;
  r.carrier_angle = carrier_angle;
  const std::vector<StageDof>& dofs = model.dofs();
  geometry::StagePoses poses = model.KinematicPoses(carrier_angle);
  auto solver = solvers::MakeContactSolver(options.backend);
  GeometricIterationOptions iteration;
  iteration.max_iterations = options.max_geometric_iterations;
  iteration.tolerance = options.geometric_tolerance;
  iteration.accept_inaccurate = options.accept_inaccurate;
  GeometricIterationResult g = IterateGeometry(
      [&] {
        r.problem = model.Problem(poses, loads);
        return r.problem.data;
      },
      [&](const Eigen::VectorXd& lambda) {
        poses = StageModel::Displace(poses, dofs, lambda);
        return model.DisplacementSize(dofs, lambda);
      },
      *solver, options.contact, iteration);
  r.converged = g.converged;
  r.message = std::move(g.message);
  r.geometric_iterations = g.iterations;
  r.solution = std::move(g.solution);
  r.report = g.report;
  r.poses = poses;
  // The problem as solved: with elastic supports, W less the earlier iterations' deflections.
  if (g.rhs.size() > 0) r.problem.data.equality_rhs = g.rhs;
  // Outputs from the last contact problem (solved at the poses before its own small increment).
  const int n = model.planets();
  r.load_sharing = model.LoadSharing(r.problem.contacts, r.solution.force, loads.sun_torque);
  r.planet_rotations.assign(n, 0.0);
  r.planet_displacements.assign(n, geometry::Vec2::Zero());
  for (std::size_t k = 0; k < dofs.size() && g.total.size() > 0; ++k) {
    const double v = g.total(static_cast<Eigen::Index>(k));
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
      default:
        break;
    }
  }
  return r;
}

PositionResult SolvePosition(const Scene& scene, const geometry::Stage& stage,
                             const StageCompliance& compliance, double carrier_angle,
                             const QuasiStaticOptions& options) {
  const StageModel model(scene, stage, compliance, options.setup);
  return SolvePosition(model, carrier_angle, StageLoads{scene.sun_torque}, options);
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
    const StageModel& model, const StageLoads& loads, const std::vector<double>& carrier_angles,
    const QuasiStaticOptions& options,
    const std::function<void(const PositionResult&, int)>& on_result) {
  std::vector<PositionResult> out;
  out.reserve(carrier_angles.size());
  const int n = model.planets();
  for (std::size_t k = 0; k < carrier_angles.size(); ++k) {
    PositionResult r;
    try {
      r = SolvePosition(model, carrier_angles[k], loads, options);
    } catch (const std::invalid_argument& e) {
      r = PositionResult{};
      r.carrier_angle = carrier_angles[k];
      r.converged = false;
      r.message = e.what();
      r.load_sharing.assign(n, 0.0);
      r.planet_rotations.assign(n, 0.0);
      r.planet_displacements.assign(n, geometry::Vec2::Zero());
    }
    if (on_result) on_result(r, static_cast<int>(k));
    out.push_back(std::move(r));
  }
  return out;
}

std::vector<PositionResult> Sweep(
    const Scene& scene, const geometry::Stage& stage, const StageCompliance& compliance,
    const std::vector<double>& carrier_angles, const QuasiStaticOptions& options,
    const std::function<void(const PositionResult&, int)>& on_result) {
  const StageModel model(scene, stage, compliance, options.setup);
  return Sweep(model, StageLoads{scene.sun_torque}, carrier_angles, options, on_result);
}

}  // namespace epicycle::transmission
