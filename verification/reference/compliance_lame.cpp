// Thick cylinder under internal pressure: Q8 FE on a quarter model with symmetry conditions
// against Lamé's solution, plane strain and plane stress; observed order of convergence.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "../unit/compliance/test_meshes.hpp"
#include "epicycle/compliance/elastic_model.hpp"
#include "epicycle/compliance/mesher.hpp"

using namespace epicycle::compliance;

namespace {

// Lamé, internal pressure p on a ≤ r ≤ b, free outer surface:
//   plane strain: u_r = (1+ν) p a² / (E (b²−a²)) · [ (1−2ν) r + b²/r ]
//   plane stress: u_r = p a² / (E (b²−a²)) · [ (1−ν) r + (1+ν) b²/r ]
double LameRadialDisplacement(const ElasticMaterial& m, double p, double a, double b, double r) {
  const double e = m.youngs_modulus, nu = m.poisson_ratio, c = p * a * a / (e * (b * b - a * a));
  if (m.plane == PlaneAssumption::kPlaneStrain)
    return c * (1 + nu) * ((1 - 2 * nu) * r + b * b / r);
  return c * ((1 - nu) * r + (1 + nu) * b * b / r);
}

struct Result {
  double radial_error;      // max over nodes |u_r − Lamé| / u_r(a)
  double tangential_error;  // max over nodes |u_θ| / u_r(a)
};

Result Solve(const ElasticMaterial& m, double p, double a, double b, int nr, int nt) {
  LinearElasticModel model(MappedMesher().BuildMesh(testing::QuarterRingRegion(a, b, nr, nt)), m);
  model.FixNodeSet("x_axis", Components::kY);  // symmetry: u_y = 0 on θ = 0
  model.FixNodeSet("y_axis", Components::kX);  // symmetry: u_x = 0 on θ = π/2
  model.Factorize();
  Eigen::VectorXd f = model.ZeroLoads();
  model.AddEdgeTraction(
      "inner", [p](const Eigen::Vector2d&, const Eigen::Vector2d& n) { return (-p * n).eval(); },
      &f);
  const Eigen::VectorXd u = model.Solve(f);
  const double scale = LameRadialDisplacement(m, p, a, b, a);
  Result r{0.0, 0.0};
  for (int v = 0; v < model.mesh().num_nodes(); ++v) {
    const Eigen::Vector2d x = model.mesh().nodes[v];
    const Eigen::Vector2d er = x.normalized();
    const Eigen::Vector2d uv = model.NodeDisplacement(u, v);
    const double ur = uv.dot(er), ut = uv.x() * -er.y() + uv.y() * er.x();
    r.radial_error =
        std::max(r.radial_error, std::abs(ur - LameRadialDisplacement(m, p, a, b, x.norm())));
    r.tangential_error = std::max(r.tangential_error, std::abs(ut));
  }
  r.radial_error /= scale;
  r.tangential_error /= scale;
  return r;
}

}  // namespace

TEST_CASE("Thick cylinder: radial displacement within 0.5% of Lame, convergence order",
          "[reference]") {
  const auto plane = GENERATE(PlaneAssumption::kPlaneStrain, PlaneAssumption::kPlaneStress);
  const ElasticMaterial m{206e9, 0.3, 0.025, plane};
  const double a = 0.05, b = 0.1, p = 100e6;
  INFO(ToString(plane));
  // Sequence: nr radial × 2nr angular elements, nr = 1, 2, 4, 8.
  std::vector<Result> results;
  for (int nr : {1, 2, 4, 8}) results.push_back(Solve(m, p, a, b, nr, 2 * nr));
  for (std::size_t k = 0; k < results.size(); ++k) {
    testing::Figure("lame " + ToString(plane) + " nr " + std::to_string(1 << k) +
                    ": radial error " + testing::Sci(results[k].radial_error) + " tangential " +
                    testing::Sci(results[k].tangential_error));
  }
  const Result& refined = results[2];  // the suite's refined mesh: 4 × 8 elements
  CHECK(refined.radial_error < 0.005);
  const double order = std::log2(results[1].radial_error / results[2].radial_error);
  testing::Figure("lame " + ToString(plane) + ": observed order " + std::to_string(order));
  // Q8 on a domain whose arcs are interpolated by quadratics: O(h³) displacement error expected.
  CHECK(order > 2.5);
  CHECK(results[3].radial_error < results[2].radial_error);
}
