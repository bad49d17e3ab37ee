#include "epicycle/transmission/quasistatic.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "epicycle/solvers/contact_problem.hpp"
#include "epicycle/transmission/geometric_iteration.hpp"
#include "ordered_chunks.hpp"

namespace epicycle::transmission {

void QuasiStaticOptions::Validate() const {
  if (max_geometric_iterations < 1)
    throw std::invalid_argument("quasistatic: max_geometric_iterations = " +
                                std::to_string(max_geometric_iterations) + ": must be at least 1");
  if (!(geometric_tolerance > 0) || !std::isfinite(geometric_tolerance))
    throw std::invalid_argument("quasistatic: geometric_tolerance = " +
                                std::to_string(geometric_tolerance) + " m: must be finite and > 0");
  if (threads < 0)
    throw std::invalid_argument("quasistatic: threads = " + std::to_string(threads) +
                                ": must be >= 0 (0: one per core)");
  contact.Validate();
}

namespace {

// One position with the caller's solver (a sweep's worker keeps one for its chunk).
PositionResult Solve(const StageModel& model, double carrier_angle, const StageLoads& loads,
                     const QuasiStaticOptions& options, const PositionResult* neighbour,
                     solvers::ContactSolver& solver) {
  PositionResult r;
  r.carrier_angle = carrier_angle;
  const std::vector<StageDof>& dofs = model.dofs();
  geometry::StagePoses poses = model.KinematicPoses(carrier_angle);
  GeometricIterationOptions iteration;
  iteration.max_iterations = options.max_geometric_iterations;
  iteration.tolerance = options.geometric_tolerance;
  iteration.accept_inaccurate = options.accept_inaccurate;
  GeometricIterationStart start;
  if (neighbour != nullptr && neighbour->converged &&
      neighbour->displacements.size() == static_cast<Eigen::Index>(dofs.size()) &&
      neighbour->solution.force.size() ==
          static_cast<Eigen::Index>(neighbour->problem.contacts.size())) {
    // What carries over is the deviation from the kinematic motion (the loaded TE, the planets'
    // rotations, the floating sun's and elastic pins' deflections); the kinematic poses are those
    // of the new angle. The forces start the first contact solve where the contacts match.
    r.warm_started = true;
    start.displacements = neighbour->displacements;
    poses = StageModel::Displace(poses, dofs, start.displacements);
    start.forces = [&](int, Eigen::VectorXd* force) {
      return CarryForces(neighbour->problem.contacts, neighbour->solution.force, r.problem.contacts,
                         force) > 0;
    };
  }
  const bool root_stress = model.compliance().has_root_stress();
  geometry::StagePoses problem_poses;  // where the last contact problem was built (root stress)
  GeometricIterationResult g = IterateGeometry(
      [&](solvers::ContactProblemData* data) {
        if (root_stress) problem_poses = poses;
        StageOutcome o = model.Problem(poses, loads, &r.problem);
        if (o.ok()) *data = r.problem.data;
        return o;
      },
      [&](const Eigen::VectorXd& lambda) {
        poses = StageModel::Displace(poses, dofs, lambda);
        return model.DisplacementSize(dofs, lambda);
      },
      solver, options.contact, iteration, start);
  r.converged = g.converged;
  r.status = g.status;
  r.message = std::move(g.message);
  r.geometric_iterations = g.iterations;
  r.contact_iterations = g.contact_iterations;
  r.solution = std::move(g.solution);
  r.report = g.report;
  r.poses = poses;
  r.displacements = g.total;
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
  if (r.converged && root_stress)
    r.fillet_stress = model.compliance().FilletStresses(model.stage(), problem_poses,
                                                        r.problem.contacts, r.solution.force);
  return r;
}

}  // namespace

PositionResult SolvePosition(const StageModel& model, double carrier_angle, const StageLoads& loads,
                             const QuasiStaticOptions& options) {
  return SolvePosition(model, carrier_angle, loads, options, nullptr);
}

PositionResult SolvePosition(const StageModel& model, double carrier_angle, const StageLoads& loads,
                             const QuasiStaticOptions& options, const PositionResult* neighbour) {
  options.Validate();
  auto solver = solvers::MakeContactSolver(options.backend);
  return Solve(model, carrier_angle, loads, options, neighbour, *solver);
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

std::size_t ResultBytes(const PositionResult& r) {
  const solvers::ContactProblemData& d = r.problem.data;
  auto strings = [](const std::vector<std::string>& v) {
    std::size_t b = v.capacity() * sizeof(std::string);
    for (const std::string& s : v) b += s.capacity() + 1;
    return b;
  };
  auto matrix = [](const auto& m) { return static_cast<std::size_t>(m.size()) * sizeof(double); };
  return sizeof(PositionResult) + r.message.capacity() +
         (r.load_sharing.capacity() + r.planet_rotations.capacity()) * sizeof(double) +
         r.planet_displacements.capacity() * sizeof(geometry::Vec2) +
         r.problem.contacts.capacity() * sizeof(StageContact) +
         r.problem.dofs.capacity() * sizeof(StageDof) + matrix(d.compliance) + matrix(d.overlap) +
         d.local.capacity() * sizeof(solvers::LocalTermParameters) + matrix(d.equality_matrix) +
         matrix(d.equality_rhs) + matrix(d.support_stiffness) + strings(d.contact_labels) +
         strings(d.multiplier_labels) + d.name.capacity() + matrix(r.solution.force) +
         matrix(r.solution.multiplier) + r.poses.planets.capacity() * sizeof(geometry::GearPose) +
         matrix(r.displacements);
}

void CheckSweepMemory(const PositionResult& sample, std::size_t positions,
                      std::size_t memory_bytes) {
  const double each = static_cast<double>(ResultBytes(sample));
  const double total = each * static_cast<double>(positions),
               limit = 0.5 * static_cast<double>(memory_bytes);
  if (memory_bytes == 0 || total <= limit) return;
  char text[400];
  std::snprintf(text, sizeof text,
                "a sweep of %zu positions keeps about %.1f GB of results in memory (%.1f kB per "
                "position: %zu potential contacts), more than half of the %.1f GB available: at "
                "most %.0f positions",
                positions, total / 1e9, each / 1e3, sample.problem.contacts.size(),
                static_cast<double>(memory_bytes) / 1e9, std::floor(limit / each));
  throw std::invalid_argument(text);
}

std::size_t AvailableMemoryBytes() {
  if (std::FILE* f = std::fopen("/proc/meminfo", "r")) {
    char line[256];
    unsigned long long kb = 0;
    bool found = false;
    while (!found && std::fgets(line, sizeof line, f) != nullptr)
      found = std::sscanf(line, "MemAvailable: %llu kB", &kb) == 1;
    std::fclose(f);
    if (found) return static_cast<std::size_t>(kb) * 1024;
  }
  const long pages = ::sysconf(_SC_PHYS_PAGES), size = ::sysconf(_SC_PAGE_SIZE);
  return pages > 0 && size > 0 ? static_cast<std::size_t>(pages) * static_cast<std::size_t>(size)
                               : 0;
}

std::vector<PositionResult> Sweep(
    const StageModel& model, const StageLoads& loads, const std::vector<double>& carrier_angles,
    const QuasiStaticOptions& options,
    const std::function<void(const PositionResult&, int)>& on_result) {
  options.Validate();
  std::vector<PositionResult> out(carrier_angles.size());
  internal::RunOrderedChunks(
      static_cast<int>(carrier_angles.size()), options.threads, options.backend,
      [&](int k, bool chunk_first, solvers::ContactSolver& solver) {
        // A chunk's first position cold, each next one from its neighbour.
        const std::size_t i = static_cast<std::size_t>(k);
        const PositionResult* neighbour =
            options.warm_start && !chunk_first ? &out[i - 1] : nullptr;
        out[i] = Solve(model, carrier_angles[i], loads, options, neighbour, solver);
      },
      [&](int k) {
        if (on_result) on_result(out[static_cast<std::size_t>(k)], k);
      });
  return out;
}

}  // namespace epicycle::transmission
