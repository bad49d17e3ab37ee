// Flamant: a point force F normal to the surface of an elastic half-plane. On the load axis
// σ_rr = −2F/(π b r), σ_θθ = 0, so ε_rr = σ_rr (1−ν²)/E (plane strain) or σ_rr/E (plane stress)
// and the approach between depths h1 < h2 on the axis is
//   Δ = 2F(1−ν²)/(π E b) · ln(h2/h1)   (plane strain),   Δ = 2F/(π E b) · ln(h2/h1)   (plane
//   stress).
// This is exactly the quantity the join of the FE structural term with the local contact term
// relies on (docs/model.md §4).
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "../unit/compliance/test_meshes.hpp"
#include "epicycle/compliance/elastic_model.hpp"
#include "epicycle/compliance/mesher.hpp"

using namespace epicycle::compliance;

namespace {

double FlamantApproach(const ElasticMaterial& m, double force, double h1, double h2) {
  const double k = m.plane == PlaneAssumption::kPlaneStrain
                       ? (1 - m.poisson_ratio * m.poisson_ratio) / m.youngs_modulus
                       : 1.0 / m.youngs_modulus;
  return 2 * force * k / (std::numbers::pi * m.thickness) * std::log(h2 / h1);
}

enum class Far { kFixedArc, kFlamantTraction };

// Half-disc of radius R around the load point (the origin), force F along −y at the origin.
double FeApproach(const ElasticMaterial& m, double force, double radius, int n, double h1,
                  double h2, Far far) {
  const double s = radius / 10.0;
  LinearElasticModel model(MappedMesher().BuildMesh(testing::HalfDiscRegion(radius, s, n, 200.0)),
                           m);
  Eigen::VectorXd f = model.ZeroLoads();
  // The load point is the corner shared by the two square patches: first node of "surface" of
  // the right square is not guaranteed, so locate it on the surface edge set.
  model.AddEdgePointForce("surface", model.mesh().LocateOnEdgeSet("surface", {0.0, 0.0}),
                          {0.0, -force}, &f);
  if (far == Far::kFixedArc) {
    model.FixNodeSet("arc");
  } else {
    // The exact Flamant stress on the arc, σ_rr = −2F cos θ/(π b R) with θ from the load axis,
    // balances F exactly; symmetry fixes u_x on the axis, one node fixes the y translation.
    model.AddEdgeTraction(
        "arc",
        [&](const Eigen::Vector2d& x, const Eigen::Vector2d&) {
          const double r = x.norm(), cos_theta = -x.y() / r;
          return (-2 * force * cos_theta / (std::numbers::pi * m.thickness * r) * x / r).eval();
        },
        &f);
    model.FixNodeSet("axis", Components::kX);
    model.FixNodeSet("axis_deep", Components::kX);
    model.PrescribeDof(model.mesh().NodeSet("axis_deep").front(), 1, 0.0);
  }
  model.Factorize();
  const Eigen::VectorXd u = model.Solve(f);
  // Read on the load axis through the join's read-out: depth below the load point along −n.
  const EdgePoint load_point = model.mesh().LocateOnEdgeSet("surface", {0.0, 0.0});
  const double u1 = model.DisplacementAtDepth(u, "surface", load_point, h1).y();
  const double u2 = model.DisplacementAtDepth(u, "surface", load_point, h2).y();
  return u2 - u1;  // the shallower point moves further down
}

}  // namespace

TEST_CASE("Flamant half-plane: approach between two depths within 2% of the closed form",
          "[reference]") {
  const auto plane = GENERATE(PlaneAssumption::kPlaneStrain, PlaneAssumption::kPlaneStress);
  const ElasticMaterial m{206e9, 0.3, 0.025, plane};
  const double force = 1000.0, h1 = 1e-3, h2 = 5e-3;
  INFO(ToString(plane));
  const double exact = FlamantApproach(m, force, h1, h2);
  SECTION("exact far-field traction: only the discretisation error remains") {
    for (int n : {8, 16, 24}) {
      const double fe = FeApproach(m, force, 0.2, n, h1, h2, Far::kFlamantTraction);
      testing::Figure("flamant traction-arc " + ToString(plane) + " n " + std::to_string(n) +
                      ": error " + testing::Sci(fe / exact - 1.0));
      if (n == 16) CHECK(std::abs(fe / exact - 1.0) < 0.02);
    }
  }
  SECTION("large model fixed on its arc") {
    for (double radius : {0.2, 1.0}) {
      const double fe = FeApproach(m, force, radius, 16, h1, h2, Far::kFixedArc);
      testing::Figure("flamant fixed-arc " + ToString(plane) + " R/h2 " +
                      std::to_string(radius / h2) + ": error " + testing::Sci(fe / exact - 1.0));
      if (radius == 1.0) CHECK(std::abs(fe / exact - 1.0) < 0.02);
    }
  }
}
