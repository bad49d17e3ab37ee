// A stage's mesh stiffness from its quasi-static solutions (stage_mesh_stiffness.hpp;
// docs/model.md §10).
#include "epicycle/transmission/stage_mesh_stiffness.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "epicycle/solvers/local_term.hpp"

namespace epicycle::transmission {

MeshStiffnessAt MeshStiffnessOf(const geometry::Stage& stage, const PositionResult& r, int planet,
                                bool ring) {
  if (!r.converged)
    throw std::invalid_argument("MeshStiffnessOf: the position at carrier " +
                                std::to_string(geometry::Deg(r.carrier_angle)) +
                                " deg did not converge");
  if (planet < 0 || planet >= stage.planets())
    throw std::invalid_argument("MeshStiffnessOf: planet = " + std::to_string(planet) +
                                ": must lie in [0, " + std::to_string(stage.planets()) + ")");
  const geometry::MeshKind kind =
      ring ? geometry::MeshKind::kPlanetRing : geometry::MeshKind::kSunPlanet;
  const double rb = stage.planet(planet).base_radius();
  const solvers::ContactProblemData& data = r.problem.data;
  std::vector<int> active;
  for (std::size_t j = 0; j < r.problem.contacts.size(); ++j) {
    const StageContact& c = r.problem.contacts[j];
    if (c.planet == planet && c.mesh == kind && c.loaded &&
        r.solution.force(static_cast<Eigen::Index>(j)) > 0)
      active.push_back(static_cast<int>(j));
  }
  MeshStiffnessAt out;
  const auto n = static_cast<Eigen::Index>(active.size());
  if (n == 0) return out;
  Eigen::MatrixXd secant(n, n), tangent(n, n);
  Eigen::VectorXd g(n), f(n);
  for (Eigen::Index a = 0; a < n; ++a) {
    const int j = active[static_cast<std::size_t>(a)];
    const StageContact& c = r.problem.contacts[static_cast<std::size_t>(j)];
    // The planet is body B of its sun mesh and body A of its ring mesh.
    g(a) = std::abs(ring ? c.contact.lever_a : c.contact.lever_b) / rb;
    f(a) = r.solution.force(j);
    for (Eigen::Index b = 0; b < n; ++b)
      secant(a, b) = data.compliance(j, active[static_cast<std::size_t>(b)]);
  }
  tangent = secant;
  Eigen::VectorXd approach = secant * f;  // (C_AA F_A)_j, then + u_j(F_j)
  for (Eigen::Index a = 0; a < n && !data.local.empty(); ++a) {
    const solvers::LocalTermParameters& p = data.local[static_cast<std::size_t>(active[a])];
    if (!p.enabled) continue;
    approach(a) += solvers::LocalApproach(p, f(a));
    tangent(a, a) += solvers::LocalApproachDerivative(p, f(a));
  }
  out.force = g.dot(f);
  for (Eigen::Index a = 0; a < n; ++a)
    if (g(a) > 0) out.approach = std::max(out.approach, approach(a) / g(a));
  out.secant = out.approach > 0 ? out.force / out.approach : 0.0;
  out.tangent = g.dot(tangent.ldlt().solve(g));
  return out;
}

StageMeshStiffness ComputeStageMeshStiffness(const StageModel& model, const StageLoads& loads,
                                             int positions) {
  if (positions < 2)
    throw std::invalid_argument("stage mesh stiffness: positions = " + std::to_string(positions) +
                                ": must be >= 2");
  QuasiStaticOptions options;
  options.threads = 1;  // warm-started in order: the same means on every machine
  StageMeshStiffness out;
  std::string failure;
  SweepEach(
      model, loads, positions,
      [&](int k) { return SweepAngle(0.0, model.stage().mesh_cycle(), k, positions); }, options,
      [&](const PositionResult& r, int) {
        if (!r.converged) {
          if (failure.empty()) failure = r.message;
          return;
        }
        ++out.positions;
        for (const bool ring : {false, true}) {
          const MeshStiffnessAt k = MeshStiffnessOf(model.stage(), r, 0, ring);
          out.secant[ring ? 1 : 0] += k.secant;
          out.tangent[ring ? 1 : 0] += k.tangent;
        }
      });
  if (out.positions == 0)
    throw std::runtime_error("stage mesh stiffness of " + model.name() + ": no position of " +
                             std::to_string(positions) + " over a mesh cycle converged (" +
                             failure + ")");
  for (int m = 0; m < 2; ++m) {
    out.secant[static_cast<std::size_t>(m)] /= out.positions;
    out.tangent[static_cast<std::size_t>(m)] /= out.positions;
  }
  return out;
}

}  // namespace epicycle::transmission
