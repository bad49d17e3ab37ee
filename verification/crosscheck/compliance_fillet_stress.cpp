// Root stress from the influence table (docs/model.md §9) against the FE solved directly: two
// off-grid loads at once against the table's superposition, the mirror symmetry of the body, and
// the cache round trip of a table with stresses.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "epicycle/compliance/compliance_operator.hpp"
#include "epicycle/compliance/elastic_model.hpp"
#include "epicycle/compliance/gear_mesh.hpp"
#include "epicycle/compliance/influence_cache.hpp"
#include "epicycle/compliance/influence_table.hpp"
#include "figures.hpp"
#include "fillet_fixtures.hpp"
#include "stage_fixtures.hpp"

using namespace epicycle;
using namespace epicycle::compliance;

namespace {

// The paper stage's sun, or its ring (held on its outer rim: the ring's root land at the space
// centre line is the rim's inner surface, the first fillet point).
geometry::GearSpec Spec(const std::string& which) {
  const transmission::Scene scene = test::PaperScene();
  return which == "ring" ? scene.stage.ring : scene.stage.sun;
}

ElasticMaterial Material(const std::string& which) {
  const transmission::Scene scene = test::PaperScene();
  return ElasticMaterial{scene.material.youngs_modulus, scene.material.poisson_ratio,
                         Spec(which).face_width, PlaneAssumption::kPlaneStrain};
}

ElasticMaterial SunMaterial() { return Material("sun"); }

geometry::Gear Sun() { return geometry::Gear(Spec("sun")); }

InfluenceTableOptions WithStress() {
  InfluenceTableOptions o;
  o.fillet_stress = true;
  return o;
}

const InfluenceTable& StressTable(const std::string& which) {
  static const InfluenceTable sun = InfluenceTable::Build(Sun(), SunMaterial(), WithStress());
  if (which != "ring") return sun;
  static const InfluenceTable ring =
      InfluenceTable::Build(geometry::Gear(Spec("ring")), Material("ring"), WithStress());
  return ring;
}

const InfluenceTable& SunStressTable() { return StressTable("sun"); }

Eigen::Vector2d OnTooth(const Eigen::Vector2d& x0, double angle, bool mirrored) {
  const Eigen::Vector2d x = mirrored ? Eigen::Vector2d(x0.x(), -x0.y()) : x0;
  return Eigen::Rotation2Dd(angle).toRotationMatrix() * x;
}

using test::NodeStress;

struct Load {
  FlankPosition at;
  Eigen::Vector2d direction;  // unit, body frame
  double force;               // [N]
};

}  // namespace

TEST_CASE("fillet stress: two off-grid loads against the FE solved directly",
          "[crosscheck][slow][compliance][stress]") {
  // The table's side: FilletStresses of a state with the body rotated and moved (inertial points
  // and directions, as the stage gives them), the other side of each contact on a second body.
  // The sun, and the ring: its rim, held on the outer circle, is what a thin ring bends in; the
  // first fillet point of each side is the rim's inner surface at the space centre line.
  const std::string which = GENERATE("sun", "ring");
  INFO(which);
  const geometry::Gear gear(Spec(which));
  const InfluenceTable& table = StressTable(which);
  REQUIRE(table.has_fillet_stress());
  const auto& points = table.fillet_points();
  const int m_count = int(points.size());
  // The direct solve: the same body mesh, the loads applied as the FE applies a point force on
  // an edge (consistent nodal forces), one solve with both loads at once.
  const GearBodyMesh body = BuildGearMesh(gear);
  LinearElasticModel model(body.mesh, Material(which));
  model.FixNodeSet("hub");
  model.Factorize();
  const ProfilePath path(gear);
  const double s_max = table.arc_length_max();
  // Two loads between grid points on the involute: a mesh force into tooth 0's σ = +1 flank, and
  // one on tooth 1's σ = −1 flank with a tangential (friction-like) part.
  const std::vector<Load> loads = {
      {{0, 1, 0.37 * s_max}, Eigen::Vector2d::Zero(), 3000.0},
      {{1, -1, 0.61 * s_max}, Eigen::Vector2d::Zero(), 2000.0},
  };
  std::vector<Load> placed = loads;
  Eigen::VectorXd f = model.ZeroLoads();
  for (Load& l : placed) {
    const bool mirrored = l.at.flank < 0;
    const double angle = l.at.tooth * gear.pitch_angle();
    const double s = table.grid().form_arc + l.at.arc_length;
    const Eigen::Vector2d x = OnTooth(path.Point(s), angle, mirrored);
    const Eigen::Vector2d normal = OnTooth(path.Normal(s), angle, mirrored);
    const Eigen::Vector2d tangent(-normal.y(), normal.x());
    l.direction = (l.at.flank > 0 ? -normal : (-normal + 0.1 * tangent).normalized());
    const std::string set = "flank" + std::to_string(l.at.tooth) + (l.at.flank > 0 ? "+" : "-");
    double distance = 0.0;
    const EdgePoint ep = model.mesh().LocateOnEdgeSet(set, x, &distance);
    // Between its nodes the quadratic edge lies within nanometres of the generated profile.
    REQUIRE(distance < 1e-5 * gear.module());
    model.AddEdgePointForce(set, ep, l.force * l.direction, &f);
  }
  const Eigen::VectorXd u = model.Solve(f);

  // The bound of the comparison: the table's and the FE's interpolations of a load between grid
  // points, Σ_loads test::FilletInterpolationBound (0.114 F |Δ³S| per point), plus round-off of
  // the two solves (1e-9 of the largest stress).
  const double theta = 0.3, tol_node = 1e-9 * gear.tip_radius();
  const Eigen::Vector2d centre(0.02, -0.01);
  const Eigen::Matrix2d rot = Eigen::Rotation2Dd(theta).toRotationMatrix();
  std::vector<OperatorBody> bodies(2);
  bodies[0] = {&table, centre, theta, Eigen::Matrix2d::Zero(), which};
  bodies[1] = {&table, Eigen::Vector2d(1.0, 1.0), 0.0, Eigen::Matrix2d::Zero(), "other"};
  std::vector<OperatorContact> contacts;
  Eigen::VectorXd force(static_cast<Eigen::Index>(placed.size()));
  for (const Load& l : placed) {
    const double s = table.grid().form_arc + l.at.arc_length;
    const bool mirrored = l.at.flank < 0;
    OperatorContact c;
    c.side[0] = {0, l.at.tooth, l.at.flank,
                 centre + rot * OnTooth(path.Point(s), l.at.tooth * gear.pitch_angle(), mirrored),
                 rot * l.direction};
    c.side[1] = {1, 3, 1,
                 Eigen::Vector2d(1.0, 1.0) + OnTooth(path.Point(s), 3 * gear.pitch_angle(), false),
                 -OnTooth(path.Normal(s), 3 * gear.pitch_angle(), false)};
    force(static_cast<Eigen::Index>(contacts.size())) = l.force;
    contacts.push_back(c);
  }
  const std::vector<FilletStress> fillets = FilletStresses(bodies, contacts, force);
  double worst = 0.0, bound = 0.0, largest = 0.0, rim = 0.0;
  int compared = 0;
  bool within = true;
  for (const FilletStress& fs : fillets) {
    if (fs.body != 0) continue;
    const int k = fs.tooth, side = fs.side;
    const std::span<const double> sigma = fs.sigma;
    for (int m = 0; m < m_count; ++m) {
      const std::string set = "fillet" + std::to_string(k) + (side == 0 ? "+" : "-");
      const double direct = NodeStress(
          model, u, set, OnTooth(points[m].position, k * gear.pitch_angle(), side == 1), tol_node);
      worst = std::max(worst, std::abs(sigma[m] - direct));
      largest = std::max(largest, std::abs(direct));
      if (m == 0) rim = std::max(rim, std::abs(direct));
      double b = 0.0;
      for (const Load& l : placed)
        b += test::FilletInterpolationBound(table, l.at, l.force, k, side, m);
      bound = std::max(bound, b);
      INFO("tooth " << k << " side " << side << " point " << m << ": table " << sigma[m]
                    << " Pa, direct " << direct << " Pa, bound " << b);
      const bool ok = std::abs(sigma[m] - direct) <= b + 1e-9 * std::max(largest, 1.0);
      CHECK(ok);
      within = within && ok;
      ++compared;
    }
  }
  // Both sides of the loaded teeth 0 and 1 and of their neighbours z − 1 and 2, and nothing else.
  CHECK(compared == 8 * m_count);
  // The loaded teeth's fillets carry tens of MPa: the comparison is not between zeros; the ring's
  // rim (its inner surface at the space centre lines) carries a part of it.
  CHECK(largest > 1e7);
  if (which == "ring") CHECK(rim > 1e-2 * largest);
  test::Figure(which + ": largest |sigma_tt| at the space centre lines " + test::Sci(rim / 1e6) +
               " MPa, on the fillets " + test::Sci(largest / 1e6) + " MPa");
  test::VerifyRow("root stress of two off-grid loads from the table (paper " + which +
                      ", rotated body" + (which == "ring" ? ", the rim's inner surface among them)" : ")"),
                  "FE solved directly, same mesh",
                  "largest stress " + test::Sci(largest / 1e6) + " MPa (space centre lines " +
                      test::Sci(rim / 1e6) + " MPa)",
                  test::Sci(worst / 1e6) + " MPa",
                  "per point 0.114 F |third difference| (up to " + test::Sci(bound / 1e6) + " MPa)",
                  compared == 8 * m_count && within);
  WARN("largest |table - direct| " << worst / 1e6 << " MPa (bound up to " << bound / 1e6
                                   << " MPa) at stresses up to " << largest / 1e6 << " MPa");
}

TEST_CASE("fillet stress: a mirrored load gives the mirrored stresses",
          "[crosscheck][compliance][stress]") {
  // The body is symmetric about each tooth's centre line: a load on tooth 0's σ = −1 flank that
  // mirrors one on its σ = +1 flank gives at side 1 of tooth k what the original gives at side 0
  // of tooth −k (exactly, up to the solves' round-off).
  const InfluenceTable& table = SunStressTable();
  const int z = table.teeth(), m_count = int(table.fillet_points().size());
  const double s = 0.45 * table.arc_length_max();
  const Eigen::Vector2d d = Eigen::Vector2d(-0.8, -0.6);
  const auto plus = table.PrepareDirected({0, 1, s}, d);
  const auto minus = table.PrepareDirected({0, -1, s}, Eigen::Vector2d(d.x(), -d.y()));
  double largest = 0.0, worst = 0.0;
  for (int k = 0; k < z; ++k) {
    for (int side = 0; side < 2; ++side) {
      std::vector<double> a(static_cast<std::size_t>(m_count), 0.0), b = a;
      table.AddFilletStress(plus, 1.0, k, side, a.data());
      table.AddFilletStress(minus, 1.0, (z - k) % z, 1 - side, b.data());
      for (int m = 0; m < m_count; ++m) {
        largest = std::max(largest, std::abs(a[m]));
        worst = std::max(worst, std::abs(a[m] - b[m]));
      }
    }
  }
  CHECK(largest > 1e3);  // [Pa/N]
  CHECK(worst <= 1e-8 * largest);
}

TEST_CASE("fillet stress: loads superposed on all fillets at once are the per-node sums",
          "[crosscheck][compliance][stress]") {
  // The definition σ(k, side, m) = Σ_l Σ_pc (F_l w_lpc) S(fl_l, i_l + p, c, k − k_l, side, m),
  // summed load by load and term by term (a zero weight skipped) from the tabulated values, against
  // each load prepared once and added to every fillet of the body in one call (FilletStresses'
  // path): the same products and sums in the same order, so equal bit for bit, on the usual load
  // (8 weights) and on one along a body axis (4 weights: the other path).
  const InfluenceTable& table = SunStressTable();
  const int z = table.teeth();
  const std::size_t points = table.fillet_points().size();
  const double s_max = table.arc_length_max();
  const std::vector<std::pair<InfluenceTable::DirectedNode, double>> loads = {
      {table.PrepareDirected({0, 1, 0.45 * s_max}, Eigen::Vector2d(-0.8, -0.6)), 1234.5},
      {table.PrepareDirected({1, -1, 0.3 * s_max}, Eigen::Vector2d(0.6, -0.8)), 987.25},
      {table.PrepareDirected({0, 1, 0.7 * s_max}, Eigen::Vector2d(0.0, 1.0)), 55.5}};
  std::vector<InfluenceTable::FilletLoad> prepared;
  for (const auto& [node, force] : loads) prepared.push_back(table.PrepareFilletLoad(node, force));
  CHECK(prepared[0].count == 8);
  CHECK(prepared[2].count == 4);
  std::vector<std::vector<double>> sigma(2 * static_cast<std::size_t>(z),
                                         std::vector<double>(points, 0.0));
  std::vector<InfluenceTable::FilletTarget> targets;
  for (int k = 0; k < z; ++k)
    for (int side = 0; side < 2; ++side)
      targets.push_back({k, side, sigma[2 * static_cast<std::size_t>(k) + side].data()});
  for (const InfluenceTable::FilletLoad& l : prepared) table.AddFilletStress(l, targets);
  int differ = 0;
  double largest = 0.0;
  for (int k = 0; k < z; ++k)
    for (int side = 0; side < 2; ++side)
      for (std::size_t m = 0; m < points; ++m) {
        double expect = 0.0;
        for (const auto& [node, force] : loads) {
          const int kr = ((k - node.tooth) % z + z) % z;
          for (int p = 0; p < 4; ++p)
            for (int c = 0; c < 2; ++c) {
              const double w = force * node.load_weight[static_cast<std::size_t>(2 * p + c)];
              if (w == 0.0) continue;
              expect += w * table.FilletGridValue(node.flank_index, node.node.first + p, c, kr,
                                                  side, static_cast<int>(m));
            }
        }
        const double got = sigma[2 * static_cast<std::size_t>(k) + side][m];
        differ += got != expect;
        largest = std::max(largest, std::abs(expect));
      }
  CHECK(largest > 1e6);  // [Pa]: the loads bend the teeth
  CHECK(differ == 0);
}

TEST_CASE("fillet stress: a table with stresses survives the cache, under its own key",
          "[crosscheck][compliance][stress]") {
  const geometry::Gear gear = Sun();
  const ElasticMaterial material = SunMaterial();
  CHECK(InfluenceTableKey(gear.spec(), material, WithStress()) !=
        InfluenceTableKey(gear.spec(), material, InfluenceTableOptions{}));
  const std::string dir =
      (std::filesystem::temp_directory_path() / "epicycle-fillet-stress-cache").string();
  std::filesystem::remove_all(dir);
  CacheReport built, loaded;
  const InfluenceTable a = LoadOrBuildInfluenceTable(gear, material, WithStress(), dir, &built);
  const InfluenceTable b = LoadOrBuildInfluenceTable(gear, material, WithStress(), dir, &loaded);
  CHECK(built.outcome == CacheOutcome::kBuilt);
  CHECK(loaded.outcome == CacheOutcome::kLoaded);
  REQUIRE(b.has_fillet_stress());
  REQUIRE(b.fillet_points().size() == a.fillet_points().size());
  const int n = a.grid().num_points(), m_count = int(a.fillet_points().size());
  for (int i : {0, n / 2, n - 1})
    for (int m : {0, m_count / 2, m_count - 1})
      CHECK(b.FilletGridValue(0, i, 1, 0, 0, m) == a.FilletGridValue(0, i, 1, 0, 0, m));
  std::filesystem::remove_all(dir);
}
