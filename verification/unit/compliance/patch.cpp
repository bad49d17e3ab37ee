// Constant-stress patch tests: a linear displacement field is reproduced to round-off by distorted
// Q8 patches, in plane stress and plane strain, under prescribed displacements and under the
// consistent loads of the constant traction.
#include <catch2/catch.hpp>

#include <cmath>

#include "epicycle/compliance/elastic_model.hpp"
#include "epicycle/compliance/mesher.hpp"
#include "test_meshes.hpp"

using namespace epicycle::compliance;

namespace {

// u = a0 + A x: a general linear field (stretch, shear and rotation).
const Eigen::Vector2d kA0(1.0e-4, 2.0e-4);
Eigen::Matrix2d Gradient() {
  Eigen::Matrix2d a;
  a << 2.0e-3, 1.0e-3,  //
      -1.0e-3, 3.0e-3;
  return a;
}
Eigen::Vector2d Exact(const Eigen::Vector2d& x) { return kA0 + Gradient() * x; }
Eigen::Vector3d ExactStress(const ElasticMaterial& m) {
  const Eigen::Matrix2d g = Gradient();
  return m.ElasticityMatrix() * Eigen::Vector3d(g(0, 0), g(1, 1), g(0, 1) + g(1, 0));
}

// Round-off bound: ε_machine × a condition-number allowance of ~10⁴ for these small systems.
constexpr double kRoundOff = 1e-12;

double MaxNodeError(const LinearElasticModel& model, const Eigen::VectorXd& u) {
  double err = 0.0, scale = 0.0;
  for (int v = 0; v < model.mesh().num_nodes(); ++v) {
    const Eigen::Vector2d exact = Exact(model.mesh().nodes[v]);
    err = std::max(err, (model.NodeDisplacement(u, v) - exact).norm());
    scale = std::max(scale, exact.norm());
  }
  return err / scale;
}

double MaxStressError(const LinearElasticModel& model, const Eigen::VectorXd& u) {
  const Eigen::Vector3d s = ExactStress(model.material());
  double err = 0.0;
  const GaussRule g = GaussLegendre(3);
  for (int e = 0; e < model.mesh().num_elements(); ++e) {
    for (int i = 0; i < 3; ++i) {
      for (int k = 0; k < 3; ++k) {
        err = std::max(err, (model.Stress(u, {e, g.points[i], g.points[k]}) - s).norm());
      }
    }
  }
  return err / s.norm();
}

}  // namespace

TEST_CASE("Patch test, distorted Q8 patch: displacement and traction forms", "[unit]") {
  const auto plane = GENERATE(PlaneAssumption::kPlaneStress, PlaneAssumption::kPlaneStrain);
  const double bulge = GENERATE(0.0, 0.08);
  const ElasticMaterial mat{210e9, 0.3, 0.025, plane};
  INFO(ToString(plane) << ", interior sides bulged by " << bulge);
  LinearElasticModel model(testing::DistortedPatch(bulge), mat);

  SECTION("displacements prescribed on the boundary") {
    model.PrescribeNodeSet("boundary", Exact);
    model.Factorize();
    const Eigen::VectorXd u = model.Solve(model.ZeroLoads());
    CHECK(MaxNodeError(model, u) < kRoundOff);
    CHECK(MaxStressError(model, u) < kRoundOff);
    testing::Figure("patch displacement-form " + ToString(plane) + " bulge " +
                    std::to_string(bulge) + ": u " + testing::Sci(MaxNodeError(model, u)) +
                    " sigma " + testing::Sci(MaxStressError(model, u)));
  }
  SECTION("constant traction sigma.n on the boundary, three DOFs fixed") {
    const Eigen::Vector3d s = ExactStress(mat);
    Eigen::Matrix2d sigma;
    sigma << s(0), s(2), s(2), s(1);
    Eigen::VectorXd f = model.ZeroLoads();
    model.AddEdgeTraction(
        "outer",
        [&](const Eigen::Vector2d&, const Eigen::Vector2d& n) { return (sigma * n).eval(); }, &f);
    // Node 0 at (0, 0) fully, node 1 at (0.24, 0) in y: rigid motion fixed at the exact values.
    model.PrescribeDof(0, 0, Exact(model.mesh().nodes[0]).x());
    model.PrescribeDof(0, 1, Exact(model.mesh().nodes[0]).y());
    model.PrescribeDof(1, 1, Exact(model.mesh().nodes[1]).y());
    model.Factorize();
    const Eigen::VectorXd u = model.Solve(f);
    CHECK(MaxNodeError(model, u) < kRoundOff);
    CHECK(MaxStressError(model, u) < kRoundOff);
    // The consistent loads are self-equilibrated, so the reactions vanish.
    CHECK(model.Reactions(u, f).norm() < kRoundOff * f.norm());
    testing::Figure("patch traction-form " + ToString(plane) + " bulge " + std::to_string(bulge) +
                    ": u " + testing::Sci(MaxNodeError(model, u)) + " sigma " +
                    testing::Sci(MaxStressError(model, u)));
  }
}

TEST_CASE("Patch test on a mapped mesh with curved, graded patches", "[unit]") {
  const auto plane = GENERATE(PlaneAssumption::kPlaneStress, PlaneAssumption::kPlaneStrain);
  const ElasticMaterial mat{70e9, 0.33, 0.01, plane};
  // Two patches sharing a wavy side; the outer sides are curved too.
  const Mesh mesh = MappedMesher().BuildMesh(testing::TwoCurvedPatches());
  LinearElasticModel model(mesh, mat);
  model.PrescribeNodeSet("outer", Exact);
  model.Factorize();
  const Eigen::VectorXd u = model.Solve(model.ZeroLoads());
  CHECK(MaxNodeError(model, u) < kRoundOff);
  CHECK(MaxStressError(model, u) < kRoundOff);
  testing::Figure("patch mapped-mesh " + ToString(plane) + ": u " +
                  testing::Sci(MaxNodeError(model, u)) + " sigma " +
                  testing::Sci(MaxStressError(model, u)));
}
