// A toothed ring built from rotated copies of one sector: the mesh and its response are exactly
// cyclic (what the gear influence tables rely on to store one loaded tooth only).
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <string>

#include "epicycle/compliance/elastic_model.hpp"
#include "epicycle/compliance/mesher.hpp"
#include "test_meshes.hpp"

using namespace epicycle::compliance;

namespace {

Eigen::Vector2d Polar(double r, double angle) {
  return r * Eigen::Vector2d(std::cos(angle), std::sin(angle));
}

// Sector 0 of a z-toothed ring: three body patches between the hub radius a and the root radius b
// (angles [0, φ/3], [φ/3, 2φ/3], [2φ/3, φ]), and a trapezoidal tooth on the middle one reaching
// radius c. Sides: "hub" (r = a); "flank" (the tooth's counter-clockwise side).
std::vector<Patch> Sector(int z, double a, double b, double c) {
  const double phi = 2 * std::numbers::pi / z;
  std::vector<Patch> patches;
  for (int k = 0; k < 3; ++k) {
    const double a0 = k * phi / 3, a1 = (k + 1) * phi / 3;
    Patch p;
    p.sides = {CircularArc({0, 0}, a, a0, a1), StraightLine(Polar(a, a1), Polar(b, a1)),
               CircularArc({0, 0}, b, a0, a1), StraightLine(Polar(a, a0), Polar(b, a0))};
    p.side_names = {"hub", "", "", ""};
    p.u = Distribution::Uniform(3);
    p.v = Distribution::Graded(4, 0.4);  // refined toward the root circle
    patches.push_back(p);
  }
  const double a1 = phi / 3, a2 = 2 * phi / 3, inset = phi / 12;
  Patch tooth;
  tooth.sides = {CircularArc({0, 0}, b, a1, a2), StraightLine(Polar(b, a2), Polar(c, a2 - inset)),
                 StraightLine(Polar(c, a1 + inset), Polar(c, a2 - inset)),
                 StraightLine(Polar(b, a1), Polar(c, a1 + inset))};
  tooth.side_names = {"", "flank", "", ""};
  tooth.u = Distribution::Uniform(3);
  tooth.v = Distribution::Uniform(5);
  patches.push_back(tooth);
  return patches;
}

}  // namespace

TEST_CASE("Cyclic toothed ring: mesh and response repeat from tooth to tooth", "[unit]") {
  const int z = 6;
  const double step = 2 * std::numbers::pi / z;
  Region region;
  for (int j = 0; j < z; ++j) {
    for (Patch p : Sector(z, 0.02, 0.05, 0.058)) {
      p = Rotated(p, j * step);
      if (p.side_names[1] == "flank") p.side_names[1] = "flank" + std::to_string(j);
      region.patches.push_back(p);
    }
  }
  const Mesh mesh = MappedMesher().BuildMesh(region);
  Eigen::Matrix2d r;
  r << std::cos(step), -std::sin(step), std::sin(step), std::cos(step);
  // Node positions: flank j+1 is flank j rotated by one pitch.
  for (int j = 0; j + 1 < z; ++j) {
    const auto& f0 = mesh.NodeSet("flank" + std::to_string(j));
    const auto& f1 = mesh.NodeSet("flank" + std::to_string(j + 1));
    REQUIRE(f0.size() == f1.size());
    for (std::size_t k = 0; k < f0.size(); ++k) {
      CHECK((mesh.nodes[f1[k]] - r * mesh.nodes[f0[k]]).norm() < 1e-15);
    }
  }
  LinearElasticModel model(mesh, ElasticMaterial{206e9, 0.3, 0.025, PlaneAssumption::kPlaneStrain});
  model.FixNodeSet("hub");
  model.Factorize();
  // A normal point force on tooth 0's flank and the same force, rotated, on tooth 1's flank.
  const EdgePoint at{2, 0.4};
  Eigen::MatrixXd f = Eigen::MatrixXd::Zero(model.num_dofs(), 2);
  Eigen::VectorXd f0 = model.ZeroLoads(), f1 = model.ZeroLoads();
  const Eigen::Vector2d n0 = mesh.EdgeNormal("flank0", at);
  model.AddEdgePointForce("flank0", at, -1000.0 * n0, &f0);
  model.AddEdgePointForce("flank1", at, -1000.0 * (r * n0), &f1);
  f << f0, f1;
  const Eigen::MatrixXd u = model.SolveMany(f);
  // Response of tooth j+1 to the load on tooth 1 = rotated response of tooth j to the load on
  // tooth 0, for every tooth (cyclic index), to round-off of the factorisation.
  const double scale = model.EdgeDisplacement(u.col(0), "flank0", at).norm();
  double worst = 0.0;
  for (int j = 0; j < z; ++j) {
    const std::string here = "flank" + std::to_string(j);
    const std::string next = "flank" + std::to_string((j + 1) % z);
    for (int e = 0; e < static_cast<int>(mesh.EdgeSet(here).size()); ++e) {
      for (double xi : {-1.0, 0.25}) {
        const Eigen::Vector2d a = model.EdgeDisplacement(u.col(0), here, {e, xi});
        const Eigen::Vector2d b = model.EdgeDisplacement(u.col(1), next, {e, xi});
        worst = std::max(worst, (b - r * a).norm() / scale);
      }
    }
  }
  CHECK(worst < 1e-10);
  testing::Figure("cyclic ring: worst relative deviation from cyclic response " +
                  testing::Sci(worst));
  // Positive work of the load (K positive definite): the loaded point moves along the force.
  CHECK(model.EdgeDisplacement(u.col(0), "flank0", at).dot(-n0) > 0.0);
}
