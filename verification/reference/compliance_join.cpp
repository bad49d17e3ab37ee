// The join of the FE structural term with the analytic local term (docs/compliance.md, "The
// join"), checked on one tooth against a direct FE solution that needs no join at all: the ISO
// 20/40 pinion loaded at mid-involute by a Hertzian (elliptical) pressure of half-width L on a
// mesh refined until the pressure is resolved, surface displacement read at the pressure's
// centre. The hybrid model's approach of that point under the same load is
//   F · mᵀ S(h) m + u_hp(F),   S(h) = the table's self block (FE point load read at depth h, plus
// the layer term when it is on), and u_hp the half-plane's approach between the surface under the
// pressure and the depth-h point under the point load. For the half-plane, integrating the plane
// strain ε_z = [(1−ν²)σ_z − ν(1+ν)σ_x]/E along the axis (Hertz: σ_z = −p0 L/√(L²+z²),
// σ_x = −p0[(L²+2z²)/(L√(L²+z²)) − 2z/L]; Flamant: σ_z = −2F/(π b z), σ_x = 0) gives
//   u_hp = a F [ln(2h/L) − c/2],   a = 2(1−ν²)/(π E b),  c = ν/(1−ν)
// exactly, while the model's local term (solvers/local_term.hpp, surface to depth h, both under
// the pressure) is a F [asinh(h/L) − c/(1 + √(1+(L/h)²))] = u_hp + a F (1/4 + c/8)(L/h)² + ….
// The direct solution has no h: the gap to it is the join's error.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <string>

#include "epicycle/compliance/elastic_model.hpp"
#include "epicycle/compliance/gear_mesh.hpp"
#include "epicycle/compliance/influence_table.hpp"
#include "epicycle/solvers/local_term.hpp"
#include "epicycle/transmission/mesh_stiffness.hpp"
#include "figures.hpp"
#include "stage_fixtures.hpp"

using namespace epicycle;
using namespace epicycle::compliance;

TEST_CASE(
    "Join of FE and local term against a direct FE solution of a tooth under a Hertzian "
    "pressure",
    "[reference][slow][gear]") {
  const std::string name = "iso_pair_20_40";
  const transmission::Scene sc =
      transmission::ParseScene(test::SceneText(name + ".toml"), name + ".toml");
  const geometry::GearPair pair(transmission::MakeMeshPair(sc, nullptr, "").spec);
  const geometry::Gear& gear = pair.gear1();
  const ElasticMaterial m{sc.material.youngs_modulus, sc.material.poisson_ratio,
                          gear.spec().face_width, PlaneAssumption::kPlaneStrain};
  const double nu = m.poisson_ratio;
  const double a = 2 * (1 - nu * nu) / (std::numbers::pi * m.youngs_modulus * m.thickness);
  const double c = nu / (1 - nu);
  const double force = 1000.0;       // [N]; the comparison is per unit force up to the local terms
  const double half_width = 0.3e-3;  // L [m]: resolved by 4 elements at refinement 4

  // The hybrid model's side: the tables at their default density, with and without the layer.
  InfluenceTableOptions with, without;
  without.layer_term = false;
  const InfluenceTable t_with = InfluenceTable::Build(gear, m, with);
  const InfluenceTable t_without = InfluenceTable::Build(gear, m, without);
  const int j = 16;  // middle of the involute (2 × 16 grid intervals) at refinement 1
  const double h = t_with.join_depth();
  t_with.CheckHalfWidth(half_width);
  const Eigen::Vector2d n = t_with.grid().normal[j];
  const double u_hp = a * force * (std::log(2 * h / half_width) - c / 2);
  // The model's own local term, one body: half the two-body value of identical bodies, R_eq set
  // so that its half-width is L at this force.
  solvers::LocalTermParameters p;
  p.face_width = m.thickness;
  for (auto& b : p.body) b = solvers::LocalBody{m.youngs_modulus, nu, h};
  p.reduced_radius = 1.0;
  p.reduced_radius = half_width * half_width / std::pow(solvers::HertzHalfWidth(p, force), 2);
  REQUIRE(solvers::HertzHalfWidth(p, force) == Approx(half_width).epsilon(1e-12));
  const double u_model_local = 0.5 * solvers::LocalApproach(p, force);
  const double s_with = force * n.dot(t_with.SelfBlock(0, j) * n);
  const double s_without = force * n.dot(t_without.SelfBlock(0, j) * n);

  // The direct solution at two refinements.
  double direct[2] = {0, 0};
  int level = 0;
  for (int refinement : {3, 4}) {
    GearMeshOptions o;
    o.refinement = refinement;
    const GearBodyMesh body = BuildGearMesh(gear, o);
    const int i = 16 * refinement;
    REQUIRE((body.grid.position[i] - t_with.grid().position[j]).norm() < 1e-12);
    LinearElasticModel model(body.mesh, m);
    model.FixNodeSet("hub");
    model.Factorize();
    const Eigen::Vector2d x0 = body.grid.position[i];
    const double p0 = 2 * force / (std::numbers::pi * half_width * m.thickness);
    Eigen::VectorXd f = model.ZeroLoads();
    model.AddEdgeTraction(
        "flank0+",
        [&](const Eigen::Vector2d& x, const Eigen::Vector2d& normal) -> Eigen::Vector2d {
          const double d = (x - x0).norm() / half_width;  // chord ≈ arc: (L/ρ)² ~ 1e-3 apart
          return d < 1 ? Eigen::Vector2d(-p0 * std::sqrt(1 - d * d) * normal)
                       : Eigen::Vector2d::Zero();
        },
        &f, 5);
    double applied = 0;  // the applied normal resultant (the quadrature of the √ edge)
    for (int node = 0; node < static_cast<int>(body.mesh.nodes.size()); ++node)
      applied -= n.dot(Eigen::Vector2d(f(2 * node), f(2 * node + 1)));
    const Eigen::VectorXd u = model.Solve(f);
    direct[level] = -n.dot(model.NodeDisplacement(u, body.grid_nodes[0][0][i])) * force / applied;
    test::Figure("join direct: refinement " + std::to_string(refinement) + " (" +
                 std::to_string(model.num_dofs()) + " DOF), applied force " + test::Sci(applied) +
                 " N, surface approach " + test::Sci(direct[level]) + " m");
    ++level;
  }
  const double ref = direct[1];
  const double hybrid = s_with + u_hp, hybrid_paper = s_without + u_hp;
  const double model_with = s_with + u_model_local, model_without = s_without + u_model_local;
  test::Figure("join direct: h " + test::Sci(h) + " m, L " + test::Sci(half_width) + " m; direct " +
               test::Sci(ref) + " m (refinement 3: " + test::Sci(direct[0] / ref - 1) + ")");
  test::Figure("join direct: FE at h + layer + u_hp " + test::Sci(hybrid / ref - 1) +
               "; without the layer " + test::Sci(hybrid_paper / ref - 1) +
               "; the model's local term with the layer " + test::Sci(model_with / ref - 1) +
               ", without " + test::Sci(model_without / ref - 1));
  // Tolerance: the direct solution's discretisation, bounded by 3× its change from refinement 3
  // to 4 (the error left after a step of ratio 4/3 at an order ≥ 1: |Δ| / ((4/3) − 1)), plus the
  // table's (its depth read-out and layer term at refinement 1 against refinement 4 at this
  // point: 1e-4 a and 4e-4 a of the body's 16 a; 0.1 % taken).
  const double tol = 3 * std::abs(direct[1] - direct[0]) / ref + 0.001;
  CHECK(std::abs(hybrid / ref - 1) <= tol);
  CHECK(std::abs(hybrid_paper / ref - 1) > tol);  // the paper's join misses the layer
  test::VerifyRow("join of FE and local term: ISO pinion mid-flank, Hertzian pressure L = 0.3 mm",
                  "direct FE, 789k DOF " + test::Sci(ref) + " m",
                  "FE at h + layer term + half-plane " + test::Sci(hybrid) + " m",
                  test::Sci(std::abs(hybrid / ref - 1)) + " relative",
                  test::Sci(tol) + " (direct FE refinement + tables)",
                  std::abs(hybrid / ref - 1) <= tol);
  test::ReportRow("join of FE and local term: the same without the layer term (paper's join)",
                  "direct FE", test::Sci(hybrid_paper) + " m",
                  test::Sci(hybrid_paper / ref - 1) + " relative",
                  "misses the structural strain between the surface and h");
  test::ReportRow(
      "join of FE and local term: the model's local term (Hertz at depth h) in place "
      "of the half-plane's point-load read-out",
      "direct FE", test::Sci(model_with) + " m",
      test::Sci(model_with / ref - 1) + " relative (L/h = " + test::Sci(half_width / h) + ")",
      "a F (1/4 + c/8)(L/h)^2 too compliant, docs/compliance.md");
}
