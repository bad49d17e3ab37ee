// Mesh convergence of the root stress (docs/model.md §9, docs/stresses.md "Root stress against
// ISO 6336-3 method B"): the largest fillet tension σ_tt on the loaded side (and the largest
// compression on the other) of a gear body under the load ISO 6336-3 method B rates, for the
// influence tables' default mesh, meshes refined uniformly ([model] mesh_refinement 2, 3, 4) and
// along the fillet alone (GearMeshOptions::fillet_elements 10, 20).
//
// The load is the same on every mesh: the normal force F_n at one point of the exact flank of
// tooth 0 (σ = +1), the point where the flank crosses the diameter d_en of the outer point of
// single pair contact (ISO 6336-3: d_en = 2 √{[√(r_a² − r_b²) − p_b (ε_α − 1)]² + r_b²}, ε_α from
// the tip circles; for a ring the point the same p_b (ε_α − 1) from its tip toward its root),
// along the exact profile's inward normal there. Each mesh takes it at the point of its flank
// edges closest to that point (its distance from the exact point is printed and held to 1e-4 of
// the module: the mesh's edge interpolates the profile between nodes), distributed by the edge's
// shape functions (LinearElasticModel::AddEdgePointForce), so no refinement moves it.
// F_n = T_1/r_b1 for a pair (the full mesh load, as the ISO test), T_s/(n r_bs) for a stage (one
// planet's share); the stresses are linear in it. The fillet is read as the stress tables read
// it: σ_tt at every node of the fillet's edges, averaged over the edges that share the node.
//
// The uniform sequence h, h/2, h/3, h/4 gives the observed order p of the peak from refinements
// 2, 3, 4 ((S2 − S3)/(S3 − S4) = (2^−p − 3^−p)/(3^−p − 4^−p)) and the Richardson estimate of the
// limit S∞ = S4 + (S4 − S3)/((4/3)^p − 1); each mesh's error is printed against it. Refinements
// 1, 2, 3 give a second estimate, whose distance from the first says how well the sequence is in
// its asymptotic range. A sequence that is not monotone (the peak is read at nodes, which move
// along the fillet as the mesh refines) has no estimate: each mesh is then printed against
// refinement 4, and the spread of the refined meshes is what refining can still change.
//
//   build/benchmarks/fillet_stress_convergence SCENE [GEAR]
// SCENE a pair or stage scene; GEAR gear1 or gear2 of a pair, sun, planet (its sun mesh's point)
// or ring of a stage (default: gear1, or the sun).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "epicycle/compliance/elastic_model.hpp"
#include "epicycle/compliance/gear_mesh.hpp"
#include "epicycle/geometry/pair.hpp"
#include "epicycle/geometry/stage.hpp"
#include "epicycle/transmission/scene.hpp"

using namespace epicycle;

namespace {

// Largest (sign +1) or smallest (sign −1) node-averaged σ_tt along an edge set [Pa].
double FilletExtreme(const compliance::LinearElasticModel& model, const Eigen::VectorXd& u,
                     const std::string& set, int sign) {
  std::map<int, std::pair<double, int>> at_node;  // node → (sum, count)
  const auto& edges = model.mesh().EdgeSet(set);
  for (int e = 0; e < static_cast<int>(edges.size()); ++e)
    for (int a = 0; a < 3; ++a) {
      auto& [sum, count] = at_node[edges[static_cast<std::size_t>(e)].nodes[a]];
      sum += model.SurfaceStress(u, set, compliance::EdgePoint{e, a - 1.0});
      ++count;
    }
  double best = 0.0;
  for (const auto& [node, sc] : at_node) best = std::max(best, sign * sc.first / sc.second);
  return sign * best;
}

// The observed order p of S(h) = S∞ + C h^p from three refinements r0 < r1 < r2 (h ∝ 1/r), by
// bisection on (S0 − S1)/(S1 − S2) = (r0^−p − r1^−p)/(r1^−p − r2^−p) over p in [0.1, 12];
// nothing when the differences change sign or the ratio lies outside that range.
std::optional<double> ObservedOrder(const double r[3], const double s[3]) {
  const double d01 = s[0] - s[1], d12 = s[1] - s[2];
  if (d01 == 0.0 || d12 == 0.0 || (d01 > 0) != (d12 > 0)) return std::nullopt;
  const double target = d01 / d12;
  auto ratio = [&](double p) {
    return (std::pow(r[0], -p) - std::pow(r[1], -p)) / (std::pow(r[1], -p) - std::pow(r[2], -p));
  };
  double lo = 0.1, hi = 12.0;  // the ratio rises with p
  if (target < ratio(lo) || target > ratio(hi)) return std::nullopt;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (ratio(mid) < target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: fillet_stress_convergence SCENE [GEAR]\n");
    return 2;
  }
  const transmission::Scene scene = transmission::ReadScene(argv[1]);
  const bool stage = scene.kind == transmission::SceneKind::kStage;
  const std::string which = argc > 2 ? argv[2] : (stage ? "sun" : "gear1");
  if (!(stage && (which == "sun" || which == "planet" || which == "ring")) &&
      !(!stage && (which == "gear1" || which == "gear2"))) {
    std::fprintf(stderr, "fillet_stress_convergence: GEAR = '%s': must be %s\n", which.c_str(),
                 stage ? "sun, planet or ring" : "gear1 or gear2");
    return 2;
  }
  // The gear, its mesh's ISO contact ratio (from the tip circles) and the normal force.
  std::optional<geometry::GearPair> pair;
  std::optional<geometry::Stage> layout;
  const geometry::Gear* gear = nullptr;
  double contact_ratio = 0.0, f_n = 0.0;
  if (stage) {
    layout.emplace(scene.stage);
    gear = which == "sun" ? &layout->sun() : which == "ring" ? &layout->ring() : &layout->planet(0);
    const geometry::MeshKind kind =
        which == "ring" ? geometry::MeshKind::kPlanetRing : geometry::MeshKind::kSunPlanet;
    contact_ratio = layout->meshes()[geometry::MeshIndex(0, kind)].contact_ratio_iso;
    f_n = std::abs(scene.loads.sun_torque) / (layout->planets() * layout->sun().base_radius());
  } else {
    pair.emplace(scene.pair);
    gear = which == "gear1" ? &pair->gear1() : &pair->gear2();
    contact_ratio = pair->summary().contact_ratio_iso;
    f_n = std::abs(scene.pair_torque) / pair->gear1().base_radius();
  }
  const geometry::GearSpec& spec = gear->spec();
  const double rb = gear->base_radius(), ra = gear->tip_radius();
  const double roll = std::sqrt(ra * ra - rb * rb) +
                      (gear->internal() ? 1.0 : -1.0) * gear->base_pitch() * (contact_ratio - 1.0);
  const double r_en = std::sqrt(roll * roll + rb * rb);

  // The exact flank point at r_en: bisection on the radius along the flank grid's arc (it rises
  // from the form point on an external gear and falls on a ring).
  const compliance::ProfilePath path(*gear);
  const compliance::FlankGrid grid = compliance::MakeFlankGrid(*gear);
  const double s0 = grid.form_arc, sign = gear->internal() ? -1.0 : 1.0;
  double lo = 0.0, hi = grid.arc_length.back();
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (sign * (path.Point(s0 + mid).norm() - r_en) < 0 ? lo : hi) = mid;
  }
  const double s = 0.5 * (lo + hi);
  const Eigen::Vector2d point = path.Point(s0 + s);
  const Eigen::Vector2d force = -f_n * path.Normal(s0 + s);

  std::printf(
      "%s, gear '%s' (z = %d, m = %.3f mm), eps_alpha %.4f: F_n = %.1f N along the flank's "
      "inward normal at d_en = %.3f mm (arc %.4f mm from the form point)\n",
      scene.name.c_str(), gear->name().c_str(), gear->teeth(), gear->module() * 1e3, contact_ratio,
      f_n, 2e3 * r_en, s * 1e3);
  std::printf("%-24s %9s %9s %13s %14s %14s\n", "mesh", "elements", "nodes", "load off [m]",
              "tension [MPa]", "compr. [MPa]");
  struct Row {
    int refinement, fillet;
    double tension = 0.0, compression = 0.0;
  };
  std::vector<Row> rows = {{1, 5}, {2, 5}, {3, 5}, {4, 5}, {1, 10}, {1, 20}};
  for (Row& row : rows) {
    compliance::GearMeshOptions o;
    o.refinement = row.refinement;
    o.fillet_elements = row.fillet;
    compliance::GearBodyMesh body = compliance::BuildGearMesh(*gear, o);
    compliance::LinearElasticModel model(
        std::move(body.mesh),
        compliance::ElasticMaterial{scene.material.youngs_modulus, scene.material.poisson_ratio,
                                    spec.face_width, compliance::PlaneAssumption::kPlaneStrain});
    model.FixNodeSet("hub");
    model.Factorize();
    double off = 0.0;
    const compliance::EdgePoint at = model.mesh().LocateOnEdgeSet("flank0+", point, &off);
    // The flank edges pass through the grid nodes on the exact profile and interpolate it
    // quadratically between them (an O(h³) gap, nanometres here): a load point further off than
    // 1e-4 of the module would not be the same point on every mesh.
    if (!(off <= 1e-4 * gear->module())) {
      std::fprintf(stderr,
                   "fillet_stress_convergence: the load point is %.3g m off the exact flank on "
                   "the mesh of refinement %d, fillet %d (more than 1e-4 m_n)\n",
                   off, row.refinement, row.fillet);
      return 1;
    }
    Eigen::VectorXd f = model.ZeroLoads();
    model.AddEdgePointForce("flank0+", at, force, &f);
    const Eigen::VectorXd u = model.Solve(f);
    row.tension = FilletExtreme(model, u, "fillet0+", +1);
    row.compression = FilletExtreme(model, u, "fillet0-", -1);
    std::printf("refinement %d, fillet %2d  %9d %9d %13.1e %14.3f %14.3f\n", row.refinement,
                row.fillet, model.mesh().num_elements(), model.mesh().num_nodes(), off,
                row.tension / 1e6, row.compression / 1e6);
    std::fflush(stdout);
  }

  // Richardson over the uniform refinements (rows 0..3: r = 1..4).
  auto estimate = [&](int first, double Row::*field, const char* what) {
    const double r[3] = {first + 1.0, first + 2.0, first + 3.0};
    const double v[3] = {rows[first].*field, rows[first + 1].*field, rows[first + 2].*field};
    const std::optional<double> p = ObservedOrder(r, v);
    if (!p) {
      std::printf("%s, refinements %d-%d: not monotone, no Richardson estimate\n", what, first + 1,
                  first + 3);
      return std::optional<double>();
    }
    const double limit = v[2] + (v[2] - v[1]) / (std::pow(r[2] / r[1], *p) - 1.0);
    std::printf("%s, refinements %d-%d: observed order %.2f, limit %.3f MPa\n", what, first + 1,
                first + 3, *p, limit / 1e6);
    return std::optional<double>(limit);
  };
  for (auto [field, what] :
       {std::pair{&Row::tension, "tension"}, std::pair{&Row::compression, "compression"}}) {
    const std::optional<double> limit = estimate(1, field, what);
    estimate(0, field, what);
    // Each mesh against the limit, or against the finest mesh when the sequence is not monotone
    // (then the spread of the refined meshes bounds what the refinement can still change).
    const double reference = limit ? *limit : rows[3].*field;
    std::printf("%s against %s (+: larger in magnitude):", what,
                limit ? "the limit of refinements 2-4" : "refinement 4");
    for (const Row& row : rows)
      std::printf(" r%d/f%d %+.2f %%", row.refinement, row.fillet,
                  100.0 * ((row.*field) / reference - 1.0));
    std::printf("\n");
  }
  return 0;
}
