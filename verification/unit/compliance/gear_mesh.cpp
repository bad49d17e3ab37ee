// The mapped mesh of a whole gear body from its generated profile (sun, planet and ring of the
// paper's stage): valid elements, flank-grid nodes on the profile, area of the outline, and an
// exactly cyclic response.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include <Eigen/Geometry>

#include "epicycle/compliance/elastic_model.hpp"
#include "epicycle/compliance/gear_mesh.hpp"
#include "stage_fixtures.hpp"
#include "test_meshes.hpp"

using namespace epicycle;
using namespace epicycle::compliance;

namespace {

geometry::GearSpec Spec(const transmission::Scene& scene, const std::string& which) {
  if (which == "sun") return scene.stage.sun;
  if (which == "planet") return scene.stage.planet;
  return scene.stage.ring;
}

// Distance from x to the exact profile (σ = ±1 flank of tooth k), by projection on the
// generated half profile.
double DistanceToProfile(const ProfilePath& path, const Eigen::Vector2d& x) {
  double d = 0.0;
  path.Project(x, 0.0, path.length(), &d);
  return d;
}

}  // namespace

TEST_CASE("Gear body mesh: valid elements, grid nodes on the profile, outline area",
          "[unit][gear]") {
  const transmission::Scene scene = test::PaperScene();
  const std::string which = GENERATE(as<std::string>{}, "sun", "planet", "ring");
  const geometry::Gear gear(Spec(scene, which));
  const GearBodyMesh body = BuildGearMesh(gear);
  // Mesh::Validate (called by the mesher) has already checked every element's Jacobian at the
  // Gauss points and corners; the quality figure is reported.
  CHECK(body.min_jacobian_ratio > 0.0);
  testing::Figure(which + " mesh: " + std::to_string(body.mesh.num_nodes()) + " nodes, " +
                  std::to_string(body.mesh.num_elements()) + " elements, " +
                  std::to_string(body.grid.num_points()) +
                  " grid points per flank, min/max det J " + testing::Sci(body.min_jacobian_ratio));
  REQUIRE(body.grid.num_points() >= 30);
  REQUIRE(body.grid.num_points() <= 60);

  // Grid nodes of every tooth and flank lie on the rotated / mirrored profile.
  const ProfilePath path(gear);
  double worst = 0.0;
  for (int k = 0; k < gear.teeth(); ++k) {
    const Eigen::Matrix2d back = Eigen::Rotation2Dd(-k * gear.pitch_angle()).toRotationMatrix();
    for (int f = 0; f < 2; ++f) {
      for (int v : body.grid_nodes[k][f]) {
        Eigen::Vector2d x = back * body.mesh.nodes[v];
        if (f == 1) x.y() = -x.y();
        worst = std::max(worst, DistanceToProfile(path, x));
      }
    }
  }
  CHECK(worst <= 1e-12);
  testing::Figure(which + " mesh: grid nodes off the profile by at most " + testing::Sci(worst) +
                  " m");

  // Area: the mesh against the shoelace area of a fine outline (its chord error, measured by
  // doubling the points, is 3e-9 relative). The mesh's quadratic edges through three profile
  // points cut the curved boundary with an area error O(ℓ⁴) (see the refinement case below);
  // at the default density it is 1e-6 relative on the sun's fillet.
  const double mesh_area = MeshArea(body.mesh);
  const double outline_area = OutlineArea(gear, 4000);
  const double rel = std::abs(mesh_area - outline_area) / outline_area;
  CHECK(rel < 1e-5);
  testing::Figure(which + " mesh: area " + testing::Sci(mesh_area) + " m^2, outline " +
                  testing::Sci(outline_area) + " m^2, relative difference " + testing::Sci(rel));
}

TEST_CASE("Gear body mesh: the area error vanishes at the rate of quadratic edges",
          "[unit][gear]") {
  // Three-point quadratic interpolation of a smooth curve errs by O(ℓ³) with an odd leading
  // term, so the area per edge errs by O(ℓ⁵) and the total by O(ℓ⁴): halving every element
  // must divide the error by about 16 (asserted: more than 8, an order above 3).
  const transmission::Scene scene = test::PaperScene();
  const geometry::Gear gear(scene.stage.sun);
  const double reference = OutlineArea(gear, 8000);
  double error[2];
  for (int r : {1, 2}) {
    GearMeshOptions o;
    o.refinement = r;
    error[r - 1] = std::abs(MeshArea(BuildGearMesh(gear, o).mesh) - reference) / reference;
  }
  const double order = std::log2(error[0] / error[1]);
  CHECK(order > 3.0);
  testing::Figure("sun mesh area error " + testing::Sci(error[0]) + " -> " +
                  testing::Sci(error[1]) + ", observed order " + testing::Sci(order));
}
