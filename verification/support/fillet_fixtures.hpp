// The root stress of a gear body solved directly, for checking the influence tables' fillet
// stresses (docs/model.md §9): σ_tt at a fillet node from a displacement field, and the bound
// the table's interpolation over the flank grid is held to.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include "epicycle/compliance/elastic_model.hpp"
#include "epicycle/compliance/influence_table.hpp"

namespace epicycle::test {

/// σ_tt [Pa] at the node of `set` at x (body frame), averaged over the fillet edges that share it
/// (the definition of the table's read-out at a node), from a displacement field u solved directly.
inline double NodeStress(const compliance::LinearElasticModel& model, const Eigen::VectorXd& u,
                         const std::string& set, const Eigen::Vector2d& x, double tol) {
  const auto& edges = model.mesh().EdgeSet(set);
  double sum = 0.0;
  int count = 0;
  for (int e = 0; e < static_cast<int>(edges.size()); ++e)
    for (int a = 0; a < 3; ++a)
      if ((model.mesh().nodes[edges[e].nodes[a]] - x).norm() <= tol) {
        sum += model.SurfaceStress(u, set, compliance::EdgePoint{e, a - 1.0});
        ++count;
      }
  REQUIRE(count > 0);
  return sum / count;
}

/// The bound of a table's fillet stress at point m of (tooth k, side) under a load of size
/// `force` [N] (any direction) at flank position `at`, against the FE solved directly: the FE
/// answer to a consistent point force is the quadratic (3-node) interpolation of its nodes'
/// answers, the table's the 4-point Hermite interpolant; both reproduce quadratics, so each
/// differs from the smooth S(s) by a fraction of its third difference Δ³S on the grid: the
/// quadratic by max_t |t(t−1)(t−2)|/6 = 0.064, the Hermite with parabola slopes by at most 0.05
/// (h10/h11 ≤ 4/27 times two slopes' error Δ³S/3, rounded up). Returns (0.064 + 0.05) F max|Δ³S|
/// over the load's stencil and both load axes [Pa].
inline double FilletInterpolationBound(const compliance::InfluenceTable& table,
                                       const compliance::FlankPosition& at, double force,
                                       int tooth, int side, int m) {
  const int z = table.teeth(), n = table.grid().num_points();
  const auto node = table.Prepare(at);
  const int fl = at.flank > 0 ? 0 : 1;
  const int kr = ((tooth - at.tooth) % z + z) % z;
  double d3 = 0.0;
  for (int c = 0; c < 2; ++c)
    for (int i = std::max(0, node.first - 1); i + 3 < n && i <= node.first + 1; ++i) {
      const auto S = [&](int j) { return table.FilletGridValue(fl, j, c, kr, side, m); };
      d3 = std::max(d3, std::abs(S(i + 3) - 3 * S(i + 2) + 3 * S(i + 1) - S(i)));
    }
  return (0.064 + 0.05) * std::abs(force) * d3;
}

}  // namespace epicycle::test
