// Linear elastic model: constraints, singular systems, consistent point loads, many right-hand
// sides, evaluation on edges and inside elements, reciprocity.
#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>

#include "epicycle/compliance/elastic_model.hpp"
#include "epicycle/compliance/mesher.hpp"
#include "test_meshes.hpp"

using namespace epicycle::compliance;
using Catch::Matchers::Contains;

namespace {
const ElasticMaterial kSteel{210e9, 0.3, 0.025, PlaneAssumption::kPlaneStrain};
}

TEST_CASE("Model: bad input and misuse give clear messages", "[unit]") {
  const Mesh mesh = MappedMesher().BuildMesh(testing::CantileverRegion(0.1, 0.02, 5, 2));
  ElasticMaterial bad = kSteel;
  bad.thickness = -0.01;
  CHECK_THROWS_WITH(LinearElasticModel(mesh, bad), Contains("thickness") && Contains("-0.01"));
  bad = kSteel;
  bad.youngs_modulus = 0.0;
  CHECK_THROWS_WITH(LinearElasticModel(mesh, bad), Contains("youngs_modulus = 0"));
  bad = kSteel;
  bad.poisson_ratio = 0.7;
  CHECK_THROWS_WITH(LinearElasticModel(mesh, bad),
                    Contains("poisson_ratio = 0.7") && Contains("[0, 0.5)"));

  Mesh inverted = mesh;  // swap two corners of element 3: clockwise, inverted
  std::swap(inverted.elements[3][1], inverted.elements[3][3]);
  std::swap(inverted.elements[3][4], inverted.elements[3][7]);
  std::swap(inverted.elements[3][5], inverted.elements[3][6]);
  CHECK_THROWS_WITH(LinearElasticModel(inverted, kSteel), Contains("element 3") &&
                                                              Contains("Jacobian determinant") &&
                                                              Contains("inverted"));
  Mesh dangling = mesh;
  dangling.nodes.push_back({1.0, 1.0});
  CHECK_THROWS_WITH(LinearElasticModel(dangling, kSteel), Contains("belongs to no element"));

  LinearElasticModel model(mesh, kSteel);
  CHECK_THROWS_WITH(model.FixNodeSet("hub"), Contains("node set 'hub' does not exist") &&
                                                 Contains("'root'") && Contains("'tip'"));
  CHECK_THROWS_WITH(model.Solve(model.ZeroLoads()), Contains("not factorised"));
  // No constraint: three rigid-body modes; only x fixed at the root: one mode (y translation).
  CHECK_THROWS_WITH(model.Factorize(), Contains("singular") && Contains("rigid-body"));
  model.FixNodeSet("root", Components::kX);
  CHECK_THROWS_WITH(model.Factorize(), Contains("singular") && Contains("node"));
  model.FixNodeSet("root", Components::kXY);
  CHECK_NOTHROW(model.Factorize());
  CHECK_THROWS_WITH(model.Solve(Eigen::VectorXd::Zero(3)), Contains("num_dofs()"));
  CHECK_THROWS_WITH(model.PrescribeDof(10000, 0, 0.0), Contains("node 10000"));
  CHECK_THROWS_WITH(model.EdgeDisplacement(model.ZeroLoads(), "tip", {99, 0.0}),
                    Contains("edge 99") && Contains("'tip'"));
  CHECK_THROWS_WITH(model.LocatePoint({1.0, 1.0}), Contains("lies in no element"));
  CHECK_THROWS_WITH(model.DisplacementAtDepth(model.ZeroLoads(), "tip", {0, 0.0}, -1e-3),
                    Contains("depth = -0.001") && Contains(">= 0"));
}

TEST_CASE("Model: consistent point loads on edges and evaluation on edges", "[unit]") {
  const Mesh mesh = MappedMesher().BuildMesh(testing::QuarterRingRegion(0.05, 0.1, 4, 6));
  LinearElasticModel model(mesh, kSteel);
  model.FixNodeSet("inner");
  model.Factorize();
  const Eigen::Vector2d force(120.0, -340.0);
  // A point force at ξ on a curved edge: total force and moment about the origin preserved
  // (Σ N_a = 1 and Σ N_a x_a = x(ξ) for the isoparametric edge).
  const EdgePoint at{2, 0.37};
  Eigen::VectorXd f = model.ZeroLoads();
  model.AddEdgePointForce("outer", at, force, &f);
  Eigen::Vector2d total = Eigen::Vector2d::Zero();
  double moment = 0.0;
  for (int v = 0; v < mesh.num_nodes(); ++v) {
    const Eigen::Vector2d fv(f(2 * v), f(2 * v + 1));
    total += fv;
    moment += mesh.nodes[v].x() * fv.y() - mesh.nodes[v].y() * fv.x();
  }
  const Eigen::Vector2d x = mesh.EdgePosition("outer", at);
  CHECK((total - force).norm() < 1e-12 * force.norm());
  CHECK(moment == Approx(x.x() * force.y() - x.y() * force.x()).epsilon(1e-12));
  // At ξ = +1 the load is the nodal load of the edge's last node.
  Eigen::VectorXd g = model.ZeroLoads();
  model.AddEdgePointForce("outer", {2, 1.0}, force, &g);
  Eigen::VectorXd h = model.ZeroLoads();
  model.AddNodalForce(mesh.EdgeSet("outer")[2].nodes[2], force, &h);
  CHECK((g - h).norm() == 0.0);

  // Many right-hand sides at once equal the one-at-a-time solutions.
  Eigen::MatrixXd loads(model.num_dofs(), 3);
  loads.col(0) = f;
  loads.col(1) = g;
  loads.col(2) = f - 2.0 * g;
  const Eigen::MatrixXd u = model.SolveMany(loads);
  for (int j = 0; j < 3; ++j) {
    CHECK((u.col(j) - model.Solve(loads.col(j))).norm() <= 1e-13 * u.col(j).norm());
  }
  // Edge displacement at a node equals the node's; inside an element equals the interpolation.
  const BoundaryEdge& e = mesh.EdgeSet("outer")[3];
  CHECK((model.EdgeDisplacement(u.col(0), "outer", {3, -1.0}) -
         model.NodeDisplacement(u.col(0), e.nodes[0]))
            .norm() == 0.0);
  CHECK((model.EdgeDisplacement(u.col(0), "outer", {3, 0.0}) -
         model.NodeDisplacement(u.col(0), e.nodes[1]))
            .norm() == 0.0);
  const EdgePoint q{3, -0.41};
  const ElementPoint inside = model.LocatePoint(mesh.EdgePosition("outer", q));
  CHECK((model.Displacement(u.col(0), inside) - model.EdgeDisplacement(u.col(0), "outer", q))
            .norm() <= 1e-9 * u.col(0).norm());
  // At depth: the point x − d·n inside the body, here on the radius through the edge point.
  const double depth = 0.004;
  const Eigen::Vector2d below = mesh.EdgePosition("outer", q) - depth * mesh.EdgeNormal("outer", q);
  CHECK((model.DisplacementAtDepth(u.col(0), "outer", q, depth) -
         model.Displacement(u.col(0), model.LocatePoint(below)))
            .norm() == 0.0);
  CHECK(below.norm() == Approx(mesh.EdgePosition("outer", q).norm() - depth).epsilon(1e-3));
  // Reactions balance the applied load: Σ reactions = −Σ loads.
  const Eigen::VectorXd r = model.Reactions(u.col(0), f);
  Eigen::Vector2d sum_r = Eigen::Vector2d::Zero();
  for (int v = 0; v < mesh.num_nodes(); ++v) sum_r += Eigen::Vector2d(r(2 * v), r(2 * v + 1));
  CHECK((sum_r + force).norm() < 1e-9 * force.norm());
}

TEST_CASE("Model: Maxwell-Betti reciprocity of edge-point loads", "[unit]") {
  // Symmetric K gives a symmetric flexibility: the displacement at B along d_B from a unit load
  // at A along d_A equals the displacement at A along d_A from a unit load at B along d_B.
  const Mesh mesh = MappedMesher().BuildMesh(testing::QuarterRingRegion(0.03, 0.08, 6, 12));
  LinearElasticModel model(mesh, kSteel);
  model.FixNodeSet("inner");
  model.Factorize();
  const EdgePoint a{1, 0.3}, b{9, -0.7};
  const Eigen::Vector2d da(0.6, 0.8), db(-1.0, 0.0);
  Eigen::MatrixXd loads = Eigen::MatrixXd::Zero(model.num_dofs(), 2);
  Eigen::VectorXd fa = model.ZeroLoads(), fb = model.ZeroLoads();
  model.AddEdgePointForce("outer", a, da, &fa);
  model.AddEdgePointForce("outer", b, db, &fb);
  loads << fa, fb;
  const Eigen::MatrixXd u = model.SolveMany(loads);
  const double ab = db.dot(model.EdgeDisplacement(u.col(0), "outer", b));
  const double ba = da.dot(model.EdgeDisplacement(u.col(1), "outer", a));
  // Round-off of the factorisation: ε × cond(K_ff) allowance of 1e-10 relative.
  CHECK(ab == Approx(ba).epsilon(1e-10));
}
