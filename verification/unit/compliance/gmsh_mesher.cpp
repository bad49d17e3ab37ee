// gmsh mesher (EPICYCLE_WITH_GMSH): unstructured Q8 meshes of the same regions as the mapped
// mesher, with the same boundary nodes on named sides: exact areas, the patch test, clear
// messages, and the real point — the tooth compliance of a gear does not depend on the mesher.
// In a build without gmsh the tests check the clear "not built with gmsh" error instead.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "epicycle/compliance/elastic_model.hpp"
#include "epicycle/compliance/gear_mesh.hpp"
#include "epicycle/compliance/gmsh_mesher.hpp"
#include "epicycle/compliance/influence_cache.hpp"
#include "epicycle/compliance/influence_table.hpp"
#include "epicycle/config.h"
#include "stage_fixtures.hpp"
#include "test_meshes.hpp"

using namespace epicycle;
using namespace epicycle::compliance;
using Catch::Matchers::Contains;

namespace {

// Area between the origin and the quadratic (mid-angle node) interpolant of a circular arc of
// radius r and angle 2h (see mesher.cpp): A = r² sin h (4 − cos h)/3.
double QuadraticArcSectorArea(double r, double h) {
  return r * r * std::sin(h) * (4.0 - std::cos(h)) / 3.0;
}

// Corner nodes inside the region (on no free element side) shared by other than 4 elements: 0
// for a structured mesh.
int IrregularInteriorNodes(const Mesh& m) {
  std::map<std::pair<int, int>, int> sides;
  std::vector<int> valence(m.num_nodes(), 0);
  for (const auto& el : m.elements) {
    for (int a = 0; a < 4; ++a) {
      ++valence[el[a]];
      const int b = el[(a + 1) % 4];
      ++sides[{std::min(el[a], b), std::max(el[a], b)}];
    }
  }
  std::vector<bool> on_boundary(m.num_nodes(), false);
  for (const auto& [key, count] : sides) {
    if (count == 1) on_boundary[key.first] = on_boundary[key.second] = true;
  }
  int irregular = 0;
  for (int v = 0; v < m.num_nodes(); ++v) {
    if (valence[v] > 0 && !on_boundary[v] && valence[v] != 4) ++irregular;
  }
  return irregular;
}

Region Square() {
  Patch p;
  p.name = "square";
  p.sides = {StraightLine({0.0, 0.0}, {0.1, 0.0}), StraightLine({0.1, 0.0}, {0.1, 0.1}),
             StraightLine({0.0, 0.1}, {0.1, 0.1}), StraightLine({0.0, 0.0}, {0.0, 0.1})};
  p.side_names = {"bottom", "right", "top", "left"};
  p.u = Distribution::Geometric(6, 1.3);
  p.v = Distribution::Graded(5, 4.0);
  return Region{{p}};
}

// The ring a ≤ r ≤ b, 0 ≤ θ ≤ π/2 as two patches that share the ray θ = π/4 (u radial, v
// angular, uniform in angle); named arcs "inner" and "outer".
Region AnnulusSector(double a, double b) {
  Region region;
  for (int k = 0; k < 2; ++k) {
    const double t0 = k * std::numbers::pi / 4, t1 = (k + 1) * std::numbers::pi / 4;
    Patch p;
    p.name = k == 0 ? "lower" : "upper";
    p.sides = {StraightLine(a * Eigen::Vector2d(std::cos(t0), std::sin(t0)),
                            b * Eigen::Vector2d(std::cos(t0), std::sin(t0))),
               CircularArc({0.0, 0.0}, b, t0, t1),
               StraightLine(a * Eigen::Vector2d(std::cos(t1), std::sin(t1)),
                            b * Eigen::Vector2d(std::cos(t1), std::sin(t1))),
               CircularArc({0.0, 0.0}, a, t0, t1)};
    p.side_names = {"", "outer", "", "inner"};
    p.u = Distribution::Geometric(4, 1.4);
    p.v = Distribution::Uniform(5);
    region.patches.push_back(p);
  }
  return region;
}

ElasticMaterial Steel(const transmission::Scene& scene, const geometry::GearSpec& spec) {
  return ElasticMaterial{scene.material.youngs_modulus, scene.material.poisson_ratio,
                         spec.face_width, PlaneAssumption::kPlaneStrain};
}

}  // namespace

TEST_CASE("gmsh mesher: availability follows the build option", "[unit][gmsh]") {
  CHECK(GmshMesher::Available() == (EPICYCLE_HAVE_GMSH == 1));
  CHECK(GmshMesher().name() == "gmsh");
  CHECK_THROWS_WITH(GmshMesher(GmshMesherOptions{8}),
                    Contains("GmshMesherOptions.algorithm = 8") && Contains("must be 6"));
  GearMeshOptions options;
  options.mesher = "delaunay";
  CHECK_THROWS_WITH(options.Validate(), Contains("GearMeshOptions.mesher = 'delaunay'") &&
                                            Contains("\"mapped\" or \"gmsh\""));
  options.mesher = "gmsh";
  if (GmshMesher::Available()) {
    CHECK_NOTHROW(options.Validate());
    CHECK(GmshMesher::LibraryVersion() != "");
    // A table of a gmsh mesh is another table: the mesher enters the cache key.
    const transmission::Scene scene = test::PaperScene();
    InfluenceTableOptions table;
    const std::uint64_t mapped_key =
        InfluenceTableKey(scene.stage.sun, Steel(scene, scene.stage.sun), table);
    table.mesh.mesher = "gmsh";
    CHECK(InfluenceTableKey(scene.stage.sun, Steel(scene, scene.stage.sun), table) != mapped_key);
  } else {
    // The clear "not built with gmsh" errors of a build without EPICYCLE_WITH_GMSH.
    CHECK_THROWS_WITH(options.Validate(), Contains("GearMeshOptions.mesher = 'gmsh'") &&
                                              Contains("EPICYCLE_WITH_GMSH"));
    CHECK_THROWS_WITH(GmshMesher().BuildMesh(Square()), Contains("gmsh mesher:") &&
                                                            Contains("not built with gmsh") &&
                                                            Contains("EPICYCLE_WITH_GMSH"));
  }
}

TEST_CASE("gmsh mesher: square and annulus sector, exact areas, named sides as mapped",
          "[unit][gmsh]") {
  if (!GmshMesher::Available()) return;  // the availability case checks the error
  SECTION("graded square") {
    const Mesh g = GmshMesher().BuildMesh(Square());
    const Mesh m = MappedMesher().BuildMesh(Square());
    CHECK_NOTHROW(g.Validate());
    // Straight sides: the area is the square's to round-off (3×3 Gauss integrates det J exactly).
    CHECK(MeshArea(g) == Approx(0.01).epsilon(1e-13));
    CHECK(g.ElementSet("square").size() == static_cast<std::size_t>(g.num_elements()));
    // Named sides carry the mapped mesher's boundary nodes, in the same order.
    for (const char* side : {"bottom", "right", "top", "left"}) {
      const auto& a = g.NodeSet(side);
      const auto& b = m.NodeSet(side);
      REQUIRE(a.size() == b.size());
      for (std::size_t k = 0; k < a.size(); ++k) {
        CHECK((g.nodes[a[k]] - m.nodes[b[k]]).norm() <= 1e-15);
      }
      CHECK(g.EdgeSet(side).size() == m.EdgeSet(side).size());
    }
    // Genuinely unstructured (the mapped mesh has none).
    CHECK(IrregularInteriorNodes(g) > 0);
    CHECK(IrregularInteriorNodes(m) == 0);
    testing::Figure("gmsh square: " + std::to_string(g.num_elements()) + " elements (mapped " +
                    std::to_string(m.num_elements()) + "), " +
                    std::to_string(IrregularInteriorNodes(g)) + " irregular interior nodes");
  }
  SECTION("annulus sector of two patches") {
    const double a = 0.05, b = 0.1;
    const Region region = AnnulusSector(a, b);
    const Mesh g = GmshMesher().BuildMesh(region);
    const Mesh m = MappedMesher().BuildMesh(region);
    CHECK_NOTHROW(g.Validate());
    CHECK(g.ElementSet("lower").size() + g.ElementSet("upper").size() ==
          static_cast<std::size_t>(g.num_elements()));
    // The region bounded by the quadratic interpolants of the arcs (10 uniform intervals of
    // π/20 each) and the straight rays: exact in closed form.
    const double h = std::numbers::pi / 40;
    const double exact = 10 * (QuadraticArcSectorArea(b, h) - QuadraticArcSectorArea(a, h));
    CHECK(MeshArea(g) == Approx(exact).epsilon(1e-13));
    CHECK(MeshArea(m) == Approx(exact).epsilon(1e-13));
    // Arc nodes exactly on the arcs; edge normals point out of the body.
    for (int v : g.NodeSet("outer")) CHECK(g.nodes[v].norm() == Approx(b).epsilon(1e-15));
    for (int v : g.NodeSet("inner")) CHECK(g.nodes[v].norm() == Approx(a).epsilon(1e-15));
    for (int k = 0; k < static_cast<int>(g.EdgeSet("outer").size()); ++k) {
      const EdgePoint p{k, 0.3};
      CHECK(g.EdgeNormal("outer", p).dot(g.EdgePosition("outer", p).normalized()) > 0.99);
    }
    CHECK(g.NodeSet("outer").size() == m.NodeSet("outer").size());
    CHECK(IrregularInteriorNodes(g) > 0);
  }
}

TEST_CASE("gmsh mesher: the patch test on an unstructured mesh of curved patches", "[unit][gmsh]") {
  if (!GmshMesher::Available()) return;
  // The two curved, graded patches of patch.cpp ("Patch test on a mapped mesh"); a linear
  // displacement field prescribed on the boundary is reproduced to round-off inside.
  const auto plane = GENERATE(PlaneAssumption::kPlaneStress, PlaneAssumption::kPlaneStrain);
  const ElasticMaterial mat{70e9, 0.33, 0.01, plane};
  const Mesh mesh = GmshMesher().BuildMesh(testing::TwoCurvedPatches());
  const Eigen::Vector2d a0(1.0e-4, 2.0e-4);
  Eigen::Matrix2d grad;
  grad << 2.0e-3, 1.0e-3, -1.0e-3, 3.0e-3;
  auto exact = [&](const Eigen::Vector2d& x) -> Eigen::Vector2d { return a0 + grad * x; };
  LinearElasticModel model(mesh, mat);
  model.PrescribeNodeSet("outer", exact);
  model.Factorize();
  const Eigen::VectorXd u = model.Solve(model.ZeroLoads());
  double err = 0.0, scale = 0.0;
  for (int v = 0; v < mesh.num_nodes(); ++v) {
    err = std::max(err, (model.NodeDisplacement(u, v) - exact(mesh.nodes[v])).norm());
    scale = std::max(scale, exact(mesh.nodes[v]).norm());
  }
  const Eigen::Vector3d s =
      mat.ElasticityMatrix() * Eigen::Vector3d(grad(0, 0), grad(1, 1), grad(0, 1) + grad(1, 0));
  double stress_err = 0.0;
  const GaussRule gauss = GaussLegendre(3);
  for (int e = 0; e < mesh.num_elements(); ++e) {
    for (int i = 0; i < 3; ++i) {
      for (int k = 0; k < 3; ++k) {
        stress_err = std::max(stress_err,
                              (model.Stress(u, {e, gauss.points[i], gauss.points[k]}) - s).norm());
      }
    }
  }
  // Round-off bound as in patch.cpp: ε_machine × a condition-number allowance of ~10⁴.
  CHECK(err / scale < 1e-12);
  CHECK(stress_err / s.norm() < 1e-12);
  CHECK(IrregularInteriorNodes(mesh) > 0);
  testing::Figure("patch gmsh-mesh " + ToString(plane) + ": " +
                  std::to_string(mesh.num_elements()) + " elements, u " +
                  testing::Sci(err / scale) + " sigma " + testing::Sci(stress_err / s.norm()));
}

TEST_CASE("gmsh mesher: clear messages for bad regions", "[unit][gmsh]") {
  if (!GmshMesher::Available()) return;
  Patch a;
  a.name = "flank";
  a.sides = {StraightLine({0, 0}, {1, 0}), StraightLine({1, 0}, {1, 1}),
             StraightLine({0, 1}, {1, 1}), StraightLine({0, 0}, {0, 1})};
  a.u = Distribution::Uniform(2);
  a.v = Distribution::Uniform(2);
  SECTION("corners that do not meet") {
    Patch bad = a;
    bad.sides[1] = StraightLine({1, 0.01}, {1, 1});
    CHECK_THROWS_WITH(
        GmshMesher().BuildMesh(Region{{bad}}),
        Contains("gmsh mesher: patch 0 ('flank')") && Contains("corner (u, v) = (1, 0)"));
  }
  SECTION("non-conforming join") {
    Patch b = a;
    b.name = "rim";
    b.sides = {StraightLine({1, 0}, {2, 0}), StraightLine({2, 0}, {2, 1}),
               StraightLine({1, 1}, {2, 1}), StraightLine({1, 0}, {1, 1})};
    b.side_names = {"", "", "", "joint"};  // named: kept exactly as given
    b.v = Distribution::Uniform(3);
    a.side_names = {"", "joint", "", ""};
    CHECK_THROWS_WITH(GmshMesher().BuildMesh(Region{{a, b}}),
                      Contains("gmsh mesher: non-conforming join") && Contains("same divisions"));
  }
  SECTION("a folded patch") {
    Patch bad = a;  // a bow-tie: the top side runs backwards
    bad.sides = {StraightLine({0, 0}, {1, 0}), StraightLine({1, 0}, {0.2, 1}),
                 StraightLine({0.8, 1}, {0.2, 1}), StraightLine({0, 0}, {0.8, 1})};
    CHECK_THROWS_WITH(GmshMesher().BuildMesh(Region{{bad}}),
                      Contains("gmsh mesher: patch 0 ('flank')"));
  }
  SECTION("a bad distribution") {
    Patch bad = a;
    bad.u = Distribution::Uniform(0);
    CHECK_THROWS_WITH(GmshMesher().BuildMesh(Region{{bad}}),
                      Contains("gmsh mesher: patch 0 ('flank') u") && Contains("divisions = 0"));
  }
}

TEST_CASE("gmsh mesher: gear bodies, flank grid and hub exactly as with the mapped mesher",
          "[unit][gmsh][gear]") {
  if (!GmshMesher::Available()) return;
  const transmission::Scene scene = test::PaperScene();
  const std::string which = GENERATE(as<std::string>{}, "sun", "planet", "ring");
  const geometry::GearSpec& spec = which == "sun"      ? scene.stage.sun
                                   : which == "planet" ? scene.stage.planet
                                                       : scene.stage.ring;
  const geometry::Gear gear(spec);
  GearMeshOptions options;
  const GearBodyMesh mapped = BuildGearMesh(gear, options);
  options.mesher = "gmsh";
  const GearBodyMesh body = BuildGearMesh(gear, options);
  CHECK(body.min_jacobian_ratio > 0.0);
  for (const char* set : {"band", "core", "fillet", "rim"}) {
    CHECK(!body.mesh.ElementSet(set).empty());
  }
  // Grid nodes, flank sets and the hub: the very points of the mapped mesh, in the same order.
  double worst = 0.0;
  for (int k = 0; k < gear.teeth(); ++k) {
    for (int f = 0; f < 2; ++f) {
      for (int i = 0; i < body.grid.num_points(); ++i) {
        worst = std::max(worst, (body.mesh.nodes[body.grid_nodes[k][f][i]] -
                                 mapped.mesh.nodes[mapped.grid_nodes[k][f][i]])
                                    .norm());
      }
    }
  }
  CHECK(worst <= 1e-12 * gear.tip_radius());
  for (const std::string set : {"hub", "flank0+", "flank0-", "flank3+"}) {
    REQUIRE(body.mesh.NodeSet(set).size() == mapped.mesh.NodeSet(set).size());
    CHECK(body.mesh.EdgeSet(set).size() == mapped.mesh.EdgeSet(set).size());
  }
  // Area: as the mapped mesh's check in gear_mesh.cpp (quadratic edges on the outline).
  const double rel = std::abs(MeshArea(body.mesh) - OutlineArea(gear, 4000)) / MeshArea(body.mesh);
  CHECK(rel < 1e-5);
  CHECK(IrregularInteriorNodes(body.mesh) > 0);
  testing::Figure(which + " gmsh mesh: " + std::to_string(body.mesh.num_nodes()) + " nodes, " +
                  std::to_string(body.mesh.num_elements()) + " elements (mapped " +
                  std::to_string(mapped.mesh.num_elements()) + "), area vs outline " +
                  testing::Sci(rel) + ", min/max det J " + testing::Sci(body.min_jacobian_ratio));
}

TEST_CASE("gmsh mesher: the tooth compliance does not depend on the mesher",
          "[unit][slow][gmsh][gear]") {
  if (!GmshMesher::Available()) return;
  // The sun of the paper's stage, meshed by both meshers at the same flank grid (default
  // density): n·Λ·n for unit loads at five grid points of the σ = +1 flank of tooth 0 — the self
  // term (depth-h read-out), and the responses on the same tooth (both flanks) and on the
  // neighbouring tooth 1 (both flanks). The discretisation error of each mesher is measured by
  // refining it (×2: the grid points of density 1 are grid points of density 2, read at the same
  // h).
  const transmission::Scene scene = test::PaperScene();
  const geometry::Gear gear(scene.stage.sun);
  const ElasticMaterial steel = Steel(scene, scene.stage.sun);
  InfluenceTableOptions options;
  const InfluenceTable mapped = InfluenceTable::Build(gear, steel, options);
  options.mesh.mesher = "gmsh";
  const InfluenceTable gmsh = InfluenceTable::Build(gear, steel, options);
  const int n = mapped.grid().num_points();
  REQUIRE(gmsh.grid().num_points() == n);
  REQUIRE(gmsh.join_depth() == mapped.join_depth());
  // The gmsh mesh is exactly cyclic too (rotated copies of the sector's mesh): reciprocity of the
  // raw table holds to round-off, as for the mapped mesh (gear_influence.cpp).
  CHECK(gmsh.raw_asymmetry() < 1e-9);

  const std::vector<int> points = {n / 10, n / 4, n / 2, 3 * n / 4, 9 * n / 10};
  const Eigen::Matrix2d r1 = Eigen::Rotation2Dd(gear.pitch_angle()).toRotationMatrix();
  auto mirror = [](const Eigen::Vector2d& v) { return Eigen::Vector2d(v.x(), -v.y()); };
  // Quantities per load point i: 0 self (depth-h read-out); surface responses (normals of the
  // grid, mirrored for σ = −1, rotated for tooth 1) at 1 the same flank a quarter of the flank
  // away (j = i ± n/4, away from the point load's singular surface value), 2 the other flank of
  // the same tooth, 3 tooth 1 flank −, 4 tooth 1 flank +.
  constexpr int kKinds = 5;
  const char* kind_name[kKinds] = {"self", "same flank", "other flank", "tooth 1 flank -",
                                   "tooth 1 flank +"};
  auto other = [&](int i) { return i < n / 2 ? i + n / 4 : i - n / 4; };
  auto from_table = [&](const InfluenceTable& t, int i, int kind) {
    const Eigen::Vector2d nl = t.grid().normal[i];
    switch (kind) {
      case 0:  // the FE read-out at h alone (the self block less its layer term)
        return nl.dot(t.SelfBlock(0, i) * nl) - t.LayerCompliance(0, i);
      case 1:
        return t.grid().normal[other(i)].dot(t.GridValue(0, i, 0, 0, other(i)) * nl);
      case 2:
        return mirror(nl).dot(t.GridValue(0, i, 0, 1, i) * nl);
      case 3:
        return (r1 * mirror(nl)).dot(t.GridValue(0, i, 1, 1, i) * nl);
      default:
        return (r1 * nl).dot(t.GridValue(0, i, 1, 0, i) * nl);
    }
  };
  // The same quantities by a direct solve on the refined mesh (refinement 2: grid index 2i).
  auto refined = [&](const std::string& mesher) {
    GearMeshOptions o;
    o.mesher = mesher;
    o.refinement = 2;
    const GearBodyMesh body = BuildGearMesh(gear, o);
    LinearElasticModel model(body.mesh, steel);
    model.FixNodeSet("hub");
    model.Factorize();
    Eigen::MatrixXd f = Eigen::MatrixXd::Zero(model.num_dofs(), points.size());
    for (std::size_t q = 0; q < points.size(); ++q) {
      const Eigen::Vector2d nl = body.grid.normal[2 * points[q]];
      const int node = body.grid_nodes[0][0][2 * points[q]];
      f(2 * node, q) = nl.x();
      f(2 * node + 1, q) = nl.y();
    }
    const Eigen::MatrixXd u = model.SolveMany(f);
    std::vector<std::array<double, kKinds>> out(points.size());
    for (std::size_t q = 0; q < points.size(); ++q) {
      const int i = 2 * points[q];
      const Eigen::Vector2d nl = body.grid.normal[i];
      // The table's depth read-out: the edge point at the node, minus h times the edge normal.
      const Eigen::Vector2d x = model.mesh().nodes[body.grid_nodes[0][0][i]];
      const EdgePoint ep = model.mesh().LocateOnEdgeSet("flank0+", x);
      const Eigen::Vector2d xd = model.mesh().EdgePosition("flank0+", ep) -
                                 mapped.join_depth() * model.mesh().EdgeNormal("flank0+", ep);
      out[q][0] = nl.dot(model.Displacement(u.col(q), model.LocatePoint(xd)));
      auto at = [&](int k, int fl, int j) {
        return model.NodeDisplacement(u.col(q), body.grid_nodes[k][fl][j]);
      };
      out[q][1] = body.grid.normal[2 * other(points[q])].dot(at(0, 0, 2 * other(points[q])));
      out[q][2] = mirror(nl).dot(at(0, 1, i));
      out[q][3] = (r1 * mirror(nl)).dot(at(1, 1, i));
      out[q][4] = (r1 * nl).dot(at(1, 0, i));
    }
    return out;
  };
  const auto mapped_fine = refined("mapped");
  const auto gmsh_fine = refined("gmsh");

  // Per kind of quantity, the largest relative change under refinement of each mesher, Δ_m and
  // Δ_g. With a convergence order p ≥ 1 the error of the coarse value is Δ 2^p/(2^p − 1) ≤ 2Δ,
  // so the two meshers may differ by up to 2(Δ_m + Δ_g): the tolerance, measured, not guessed.
  for (int kind = 0; kind < kKinds; ++kind) {
    double change_m = 0.0, change_g = 0.0, diff = 0.0, diff_fine = 0.0;
    for (std::size_t q = 0; q < points.size(); ++q) {
      const double cm = from_table(mapped, points[q], kind);
      const double cg = from_table(gmsh, points[q], kind);
      const double fm = mapped_fine[q][kind], fg = gmsh_fine[q][kind];
      change_m = std::max(change_m, std::abs(fm - cm) / std::abs(fm));
      change_g = std::max(change_g, std::abs(fg - cg) / std::abs(fg));
      diff = std::max(diff, std::abs(cg - cm) / std::abs(cm));
      diff_fine = std::max(diff_fine, std::abs(fg - fm) / std::abs(fm));
      testing::Figure(std::string("sun compliance ") + kind_name[kind] +
                      " at s = " + testing::Sci(mapped.grid().arc_length[points[q]]) +
                      " m: mapped " + testing::Sci(cm) + " -> " + testing::Sci(fm) + ", gmsh " +
                      testing::Sci(cg) + " -> " + testing::Sci(fg) + " m/N");
    }
    INFO(kind_name[kind] << ": refinement changes mapped " << change_m << ", gmsh " << change_g
                         << "; mapped vs gmsh " << diff << " (refined: " << diff_fine << ")");
    CHECK(diff <= 2.0 * (change_m + change_g));
    CHECK(diff_fine <= 2.0 * (change_m + change_g));
    // And in absolute terms: within 2 % (self) or 0.2 % (the other teeth).
    CHECK(diff <= (kind == 0 ? 0.02 : 0.002));
    testing::Figure(std::string("sun compliance ") + kind_name[kind] +
                    ": largest relative refinement change mapped " + testing::Sci(change_m) +
                    ", gmsh " + testing::Sci(change_g) + "; mapped vs gmsh " + testing::Sci(diff) +
                    " (refined " + testing::Sci(diff_fine) + ")");
  }
  testing::Figure("sun tables: mapped " + std::to_string(mapped.num_elements()) +
                  " elements, gmsh " + std::to_string(gmsh.num_elements()) +
                  " elements; gmsh raw Maxwell-Betti asymmetry " +
                  testing::Sci(gmsh.raw_asymmetry()));
}
