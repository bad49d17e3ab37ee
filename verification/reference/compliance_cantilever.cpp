// Cantilever under a parabolic tip shear: Q8 FE against the exact plane-elasticity solution of
// Timoshenko & Goodier (Theory of Elasticity, §21), whose tip deflection is Timoshenko's beam
// formula with its shear term; and the observed order of convergence.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "../unit/compliance/test_meshes.hpp"
#include "epicycle/compliance/elastic_model.hpp"
#include "epicycle/compliance/mesher.hpp"

using namespace epicycle::compliance;

namespace {

// Strip [0, L] × [−D/2, D/2], thickness b, root x = 0, tip shear force P (+y) at x = L, I = bD³/12.
// With the plane-stress-equivalent E', ν' (plane strain: E/(1−ν²), ν/(1−ν)):
//   u_x = −P y/(6E'I) [ (6L − 3x) x + (2 + ν')(y² − D²/4) ]
//   u_y =  P/(6E'I) [ 3ν' y² (L − x) + (4 + 5ν') D² x/4 + (3L − x) x² ]
//   σxx = −P (L − x) y / I,  σyy = 0,  τxy = P/(2I) (D²/4 − y²)
// so the tip deflection is  δ = P L³/(3E'I) + (4 + 5ν') P D² L/(24 E'I)  (bending + shear). The
// root is held at the exact displacements and the tip carries the exact parabolic shear.
struct Beam {
  double length, height, force;
  ElasticMaterial material;
  double I() const { return material.thickness * std::pow(height, 3) / 12.0; }
  Eigen::Vector2d Exact(const Eigen::Vector2d& p) const {
    const double e = material.EffectiveModulus(), nu = material.EffectivePoissonRatio();
    const double x = p.x(), y = p.y(), l = length, d = height, c = force / (6.0 * e * I());
    return {-c * y * ((6 * l - 3 * x) * x + (2 + nu) * (y * y - d * d / 4)),
            c * (3 * nu * y * y * (l - x) + (4 + 5 * nu) * d * d * x / 4 + (3 * l - x) * x * x)};
  }
  double TipDeflection() const { return Exact({length, 0.0}).y(); }
  // Timoshenko beam with shear coefficient κ = 5/6 (for comparison only; its end conditions are
  // those of beam theory, not the elasticity solution's).
  double TimoshenkoBeamKappa() const {
    const double e = material.EffectiveModulus(), nu = material.EffectivePoissonRatio();
    const double g = e / (2 * (1 + nu));
    return force * std::pow(length, 3) / (3 * e * I()) +
           force * length / (5.0 / 6.0 * g * material.thickness * height);
  }
};

struct Result {
  double tip_error;    // |δ_FE − δ| / δ
  double field_error;  // max over nodes |u_FE − u| / max |u|
};

Result Solve(const Beam& beam, int nx, int ny) {
  LinearElasticModel model(
      MappedMesher().BuildMesh(testing::CantileverRegion(beam.length, beam.height, nx, ny)),
      beam.material);
  model.PrescribeNodeSet("root", [&](const Eigen::Vector2d& x) { return beam.Exact(x); });
  model.Factorize();
  Eigen::VectorXd f = model.ZeroLoads();
  const double d = beam.height;
  model.AddEdgeTraction(
      "tip",
      [&](const Eigen::Vector2d& x, const Eigen::Vector2d&) {
        return Eigen::Vector2d(0.0, beam.force / (2 * beam.I()) * (d * d / 4 - x.y() * x.y()));
      },
      &f);
  const Eigen::VectorXd u = model.Solve(f);
  const EdgePoint tip = model.mesh().LocateOnEdgeSet("tip", {beam.length, 0.0});
  const double delta = model.EdgeDisplacement(u, "tip", tip).y();
  double err = 0.0, scale = 0.0;
  for (int v = 0; v < model.mesh().num_nodes(); ++v) {
    const Eigen::Vector2d exact = beam.Exact(model.mesh().nodes[v]);
    err = std::max(err, (model.NodeDisplacement(u, v) - exact).norm());
    scale = std::max(scale, exact.norm());
  }
  return {std::abs(delta - beam.TipDeflection()) / beam.TipDeflection(), err / scale};
}

// The practical variant: root fully clamped (u = 0 on x = 0), tip shear as above. Its deflection
// differs from the elasticity solution by the root's local flexibility (not a discretisation
// error); reported, not asserted.
double ClampedTipDeflection(const Beam& beam, int nx, int ny) {
  LinearElasticModel model(
      MappedMesher().BuildMesh(testing::CantileverRegion(beam.length, beam.height, nx, ny)),
      beam.material);
  model.FixNodeSet("root");
  model.Factorize();
  Eigen::VectorXd f = model.ZeroLoads();
  const double d = beam.height;
  model.AddEdgeTraction(
      "tip",
      [&](const Eigen::Vector2d& x, const Eigen::Vector2d&) {
        return Eigen::Vector2d(0.0, beam.force / (2 * beam.I()) * (d * d / 4 - x.y() * x.y()));
      },
      &f);
  const Eigen::VectorXd u = model.Solve(f);
  return model.EdgeDisplacement(u, "tip", model.mesh().LocateOnEdgeSet("tip", {beam.length, 0.0}))
      .y();
}

}  // namespace

TEST_CASE("Cantilever tip deflection within 1% of Timoshenko's solution, convergence order",
          "[reference]") {
  const auto plane = GENERATE(PlaneAssumption::kPlaneStress, PlaneAssumption::kPlaneStrain);
  const double slenderness = GENERATE(10.0, 4.0);
  const double height = 0.02;
  const Beam beam{slenderness * height, height, 1000.0, ElasticMaterial{210e9, 0.3, 0.025, plane}};
  INFO(ToString(plane) << ", L/D = " << slenderness);
  // Mesh sequence: ny = 1, 2, 4, 8 elements through the height, aspect ratio L/D·ny/nx = 1.
  const int base = static_cast<int>(slenderness);
  std::vector<Result> results;
  for (int ny : {1, 2, 4, 8}) results.push_back(Solve(beam, base * ny, ny));
  const Result& refined = results[2];  // the suite's refined mesh: 4 elements through the height
  CHECK(refined.tip_error < 0.01);
  for (std::size_t k = 0; k < results.size(); ++k) {
    testing::Figure("cantilever " + ToString(plane) + " L/D " + std::to_string(base) + " ny " +
                    std::to_string(1 << k) + ": tip error " + testing::Sci(results[k].tip_error) +
                    " field error " + testing::Sci(results[k].field_error));
  }
  // Observed order of the nodal displacement error (Q8: complete quadratics, O(h³) in the
  // displacement; nodal values may superconverge). Measured between the two middle meshes,
  // before round-off dominates.
  const double order = std::log2(results[1].field_error / results[2].field_error);
  testing::Figure("cantilever " + ToString(plane) + " L/D " + std::to_string(base) +
                  ": observed order " + std::to_string(order) + ", beam (kappa 5/6) differs by " +
                  testing::Sci(beam.TimoshenkoBeamKappa() / beam.TipDeflection() - 1.0));
  CHECK(order > 2.5);
  const double clamped = ClampedTipDeflection(beam, base * 8, 8);
  testing::Figure("cantilever " + ToString(plane) + " L/D " + std::to_string(base) +
                  ": fully clamped root / elasticity solution - 1 = " +
                  testing::Sci(clamped / beam.TipDeflection() - 1.0) + ", / beam kappa 5/6 - 1 = " +
                  testing::Sci(clamped / beam.TimoshenkoBeamKappa() - 1.0));
  // Errors decrease monotonically along the sequence (until round-off).
  CHECK(results[1].field_error < results[0].field_error);
  CHECK(results[2].field_error < results[1].field_error);
}
