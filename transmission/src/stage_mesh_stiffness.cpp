// A stage's mesh stiffness from its quasi-static solutions (stage_mesh_stiffness.hpp;
// docs/model.md §10).
#include "epicycle/transmission/stage_mesh_stiffness.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
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
  // The approach at the stage's poses: the rigid overlap of the mesh's contact that touches first.
  double touch = -std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j < r.problem.contacts.size(); ++j) {
    const StageContact& c = r.problem.contacts[j];
    if (c.planet != planet || c.mesh != kind || !c.loaded) continue;
    const double lever = std::abs(ring ? c.contact.lever_a : c.contact.lever_b) / rb;
    if (lever > 0) touch = std::max(touch, data.overlap(static_cast<Eigen::Index>(j)) / lever);
    if (r.solution.force(static_cast<Eigen::Index>(j)) > 0) active.push_back(static_cast<int>(j));
  }
  MeshStiffnessAt out;
  const auto n = static_cast<Eigen::Index>(active.size());
  if (n == 0) return out;
  Eigen::MatrixXd block(n, n);
  Eigen::VectorXd g(n), f(n);
  for (Eigen::Index a = 0; a < n; ++a) {
    const int j = active[static_cast<std::size_t>(a)];
    const StageContact& c = r.problem.contacts[static_cast<std::size_t>(j)];
    // The planet is body B of its sun mesh and body A of its ring mesh.
    g(a) = std::abs(ring ? c.contact.lever_a : c.contact.lever_b) / rb;
    f(a) = r.solution.force(j);
    for (Eigen::Index b = 0; b < n; ++b)
      block(a, b) = data.compliance(j, active[static_cast<std::size_t>(b)]);
  }
  // u_j(F) and u_j'(F) of contact a of A (0 without a local term).
  auto local = [&](Eigen::Index a, double force, double* slope) {
    if (data.local.empty()) return 0.0;
    const solvers::LocalTermParameters& p = data.local[static_cast<std::size_t>(active[a])];
    if (!p.enabled) return 0.0;
    if (slope) *slope += solvers::LocalApproachDerivative(p, force);
    return solvers::LocalApproach(p, force);
  };
  out.force = g.dot(f);
  // The pair's state at F_m (header) by Newton from the stage's forces and shift 0, on the
  // contacts `on` that keep a force: a step that would take a force to zero stops short of it,
  // and a contact whose force the steps drive to zero leaves the set (the pair would open it).
  std::vector<Eigen::Index> on;
  for (Eigen::Index a = 0; a < n; ++a) on.push_back(a);
  Eigen::VectorXd overlap(n);
  for (Eigen::Index a = 0; a < n; ++a) overlap(a) = data.overlap(active[static_cast<std::size_t>(a)]);
  double delta = 0;  // the shift s along the line of action
  Eigen::MatrixXd jacobian, tangent;
  Eigen::VectorXd residual, gs;
  for (int iteration = 0; iteration < 100; ++iteration) {
    const auto m = static_cast<Eigen::Index>(on.size());
    jacobian.setZero(m + 1, m + 1);
    residual.resize(m + 1);
    gs.resize(m);
    for (Eigen::Index i = 0; i < m; ++i) {
      gs(i) = g(on[static_cast<std::size_t>(i)]);
      for (Eigen::Index k = 0; k < m; ++k)
        jacobian(i, k) = block(on[static_cast<std::size_t>(i)], on[static_cast<std::size_t>(k)]);
    }
    Eigen::VectorXd fs(m);
    for (Eigen::Index i = 0; i < m; ++i) fs(i) = f(on[static_cast<std::size_t>(i)]);
    residual.head(m) = jacobian.topLeftCorner(m, m) * fs - gs * delta;
    for (Eigen::Index i = 0; i < m; ++i) residual(i) -= overlap(on[static_cast<std::size_t>(i)]);
    for (Eigen::Index i = 0; i < m; ++i)
      residual(i) += local(on[static_cast<std::size_t>(i)], fs(i), &jacobian(i, i));
    residual(m) = gs.dot(fs) - out.force;
    tangent = jacobian.topLeftCorner(m, m);
    jacobian.block(0, m, m, 1) = -gs;
    jacobian.block(m, 0, 1, m) = gs.transpose();
    if (residual.head(m).norm() <= 1e-13 * std::abs(touch) * std::sqrt(static_cast<double>(m)) &&
        std::abs(residual(m)) <= 1e-13 * out.force)
      break;
    const Eigen::VectorXd step = jacobian.partialPivLu().solve(-residual);
    double t = 1;
    Eigen::Index first = -1;
    for (Eigen::Index i = 0; i < m; ++i)
      if (step(i) < 0 && -fs(i) / step(i) < t) {
        t = -fs(i) / step(i);
        first = i;
      }
    if (first >= 0 && t < 1e-3) {  // driven to zero: it leaves the set
      f(on[static_cast<std::size_t>(first)]) = 0;
      on.erase(on.begin() + first);
      if (on.empty()) return out;
      continue;
    }
    if (first >= 0) t *= 0.5;
    for (Eigen::Index i = 0; i < m; ++i) f(on[static_cast<std::size_t>(i)]) += t * step(i);
    delta += t * step(m);
  }
  out.approach = touch + delta;
  out.secant = out.approach > 0 ? out.force / out.approach : 0.0;
  out.tangent = gs.dot(tangent.ldlt().solve(gs));
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
