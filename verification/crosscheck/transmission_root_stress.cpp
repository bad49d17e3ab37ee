// Root stresses in the quasi-static driver (docs/model.md §9, docs/stresses.md): switching them on
// changes no force, and over a planet revolution a planet's fillets bend both ways (the idler's
// reversed bending); with friction at rest the friction forces load the fillets too, checked
// against the sun's body solved directly. The stresses themselves are checked against the FE
// solved directly and against ISO 6336-3 in the compliance suite ("[stress]").
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "epicycle/compliance/elastic_model.hpp"
#include "epicycle/compliance/gear_mesh.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "epicycle/transmission/root_stress.hpp"
#include "epicycle/transmission/run_range.hpp"
#include "epicycle/transmission/sweep_summary.hpp"
#include "fe_fixtures.hpp"
#include "figures.hpp"
#include "fillet_fixtures.hpp"
#include "stage_fixtures.hpp"
#include "epicycle/io/units.hpp"

using namespace epicycle;
using namespace epicycle::transmission;

namespace {

struct Run {
  std::vector<PositionResult> results;
  SweepSummary summary;
};

// The run-out scene, fixed sun, root stresses on or off, with its tables from the suite's cache.
struct RunOutStage {
  Scene scene;
  geometry::Stage stage;
  FeStageCompliance compliance;
  StageModel model;
  explicit RunOutStage(bool root_stress)
      : scene(Read(root_stress)),
        stage(scene.stage),
        compliance(scene, stage, test::CachedTables()),
        model(stage, compliance, SetupFromScene(scene)) {}
  static Scene Read(bool root_stress) {
    Scene s = ParseScene(test::SceneText("paper_stage_runout.toml"), "paper_stage_runout.toml");
    s.model.stresses = root_stress;
    return s;
  }
};

// The run-out scene over one planet revolution (the period of everything that happens to a
// planet tooth), `positions` positions, fixed sun, root stresses on or off.
Run RunOut(bool root_stress, int positions) {
  const RunOutStage rig(root_stress);
  const geometry::Stage& stage = rig.stage;
  const StageModel& model = rig.model;
  const Scene& scene = rig.scene;
  QuasiStaticOptions options;
  options.threads = 1;
  const std::vector<double> angles =
      SweepAngles(0.0, CarrierSpan(stage, RunRange::kPlanetRevolution), positions);
  Run run;
  run.results = Sweep(model, scene.loads, angles, options);
  run.summary = SummariseSweep(run.results, stage.planets());
  return run;
}

}  // namespace

TEST_CASE("root stress: on, the forces are those of a run without it, to the bit",
          "[crosscheck][transmission][stress]") {
  // The stress tables come from the same unit-load solves as the compliance, whose values they
  // do not touch: every contact force and rigid displacement must be identical.
  const Run off = RunOut(false, 36), on = RunOut(true, 36);
  REQUIRE(off.results.size() == on.results.size());
  for (std::size_t k = 0; k < off.results.size(); ++k) {
    REQUIRE(off.results[k].converged);
    REQUIRE(on.results[k].converged);
    CHECK(off.results[k].fillet_stress.empty());
    CHECK_FALSE(on.results[k].fillet_stress.empty());
    CHECK(off.results[k].solution.force == on.results[k].solution.force);
    CHECK(off.results[k].displacements == on.results[k].displacements);
  }
  CHECK(off.summary.root_stress.empty());
  CHECK(on.summary.root_stress.size() == 5);
}

TEST_CASE("root stress: a planet bends both ways over its revolution",
          "[crosscheck][transmission][stress]") {
  const Run on = RunOut(true, 360);
  REQUIRE(on.summary.converged == 360);
  const auto& rs = on.summary.root_stress;
  // Every gear's loaded fillets: tension on the loaded side, compression on the other.
  for (const auto& g : rs) {
    INFO(BodyName(g.extremes.body));
    CHECK(g.extremes.tension > 50e6);
    CHECK(g.extremes.compression < -50e6);
  }
  // A planet tooth is driven on one flank by the sun and loads the ring with the other: at the
  // fillet point of its largest range it sees tension in one mesh and compression in the other,
  // each a sizeable part of the planet's extremes (ISO 6336-5's reversed bending of idlers).
  for (int i = 0; i < 3; ++i) {
    const auto& p = rs[static_cast<std::size_t>(PlanetBody(i))];
    INFO("planet " << i + 1 << ": range " << p.range.range / 1e6 << " MPa between "
                   << p.range.max / 1e6 << " and " << p.range.min / 1e6 << " MPa");
    CHECK(p.range.max > 0.25 * p.extremes.tension);
    CHECK(p.range.min < 0.25 * p.extremes.compression);
    CHECK(p.range.range > p.extremes.tension);
  }
  // Planet 1 (run-out 20 µm, K_γ 2.17) carries the most: its root stress exceeds the others'.
  CHECK(rs[PlanetBody(0)].extremes.tension > 1.2 * rs[PlanetBody(1)].extremes.tension);
  CHECK(rs[PlanetBody(0)].extremes.tension > 1.2 * rs[PlanetBody(2)].extremes.tension);
}

TEST_CASE("root stress with friction at rest: the sun's fillets against its body solved directly",
          "[crosscheck][transmission][stress][friction]") {
  // The run-out stage at one position with friction at rest (constant μ = 0.1, a large one, so
  // that friction's part is well above the comparison's bound), fixed sun. The reference: the
  // sun's FE body (the table's mesh) solved directly under every sun contact's force on the sun,
  // −F_j n_j − φ_j t_j (contact_kinematics.hpp: the normal force and the friction force on body
  // A), applied as consistent point forces; its fillet stresses against the driver's, within
  // the table interpolation's bound per load (test::FilletInterpolationBound with the load's
  // size) plus round-off (1e-9 of the largest stress).
  const RunOutStage rig(true);
  const Scene& scene = rig.scene;
  const geometry::Stage& stage = rig.stage;
  const FeStageCompliance& compliance = rig.compliance;
  const StageModel& model = rig.model;
  QuasiStaticOptions options;
  options.friction.law = FrictionLaw::kConstant;
  options.friction.coefficient = 0.1;
  options.friction.smoothing_velocity = 1e-5;
  options.sun_speed = io::RpmToRadPerSecond(1500.0);
  const PositionResult r =
      SolvePosition(model, 0.3 * stage.mesh_cycle(), scene.loads, options);
  REQUIRE(r.converged);
  REQUIRE(r.friction);
  REQUIRE(r.friction_tangent.size() == r.problem.contacts.size());

  const geometry::Gear& gear = stage.sun();
  const compliance::InfluenceTable& table = compliance.tables().Table(kSunBody);
  compliance::GearMeshOptions mesh;
  mesh.refinement = scene.model.mesh_refinement;
  compliance::LinearElasticModel fe(
      compliance::BuildGearMesh(gear, mesh).mesh,
      compliance::ElasticMaterial{scene.material.youngs_modulus, scene.material.poisson_ratio,
                                  gear.spec().face_width, compliance::PlaneAssumption::kPlaneStrain});
  fe.FixNodeSet("hub");
  fe.Factorize();
  const geometry::GearPose& pose = r.poses.sun;
  const Eigen::Matrix2d to_body = Eigen::Rotation2Dd(-pose.rotation).toRotationMatrix();
  struct Load {
    compliance::FlankPosition at;
    double size;
  };
  std::vector<Load> loads;
  Eigen::VectorXd f = fe.ZeroLoads();
  double friction_size = 0;
  for (std::size_t j = 0; j < r.problem.contacts.size(); ++j) {
    const StageContact& s = r.problem.contacts[j];
    const double force = r.solution.force(static_cast<Eigen::Index>(j));
    if (s.body_a != kSunBody || !(force > 0)) continue;
    const double phi = r.friction_force(static_cast<Eigen::Index>(j));
    friction_size = std::max(friction_size, std::abs(phi));
    const Eigen::Vector2d on_sun = -force * s.contact.normal - phi * r.friction_tangent[j];
    const Eigen::Vector2d x = to_body * (s.contact.surface_a - pose.geometric_centre);
    const std::string set =
        "flank" + std::to_string(s.contact.tooth_a) + (s.contact.side_a > 0 ? "+" : "-");
    double distance = 0;
    const compliance::EdgePoint ep = fe.mesh().LocateOnEdgeSet(set, x, &distance);
    REQUIRE(distance < 1e-5 * gear.module());  // the quadratic edge on the generated profile
    fe.AddEdgePointForce(set, ep, to_body * on_sun, &f);
    loads.push_back({table.Locate(x, s.contact.tooth_a, s.contact.side_a), on_sun.norm()});
  }
  REQUIRE(loads.size() >= 3);      // every planet's mesh loads the sun
  CHECK(friction_size > 100);      // μ F of a few kN: friction's part is not a rounding
  const Eigen::VectorXd u = fe.Solve(f);

  const auto& points = table.fillet_points();
  const double tol_node = 1e-9 * gear.tip_radius();
  double worst = 0, bound = 0, largest = 0, share = 0;
  int compared = 0;
  bool within = true;
  // The normal forces alone, for friction's share.
  const auto normal_only =
      compliance.FilletStresses(stage, r.poses, r.problem.contacts, r.solution.force);
  for (std::size_t q = 0; q < r.fillet_stress.size(); ++q) {
    const compliance::FilletStress& fs = r.fillet_stress[q];
    if (fs.body != kSunBody) continue;
    for (int m = 0; m < static_cast<int>(points.size()); ++m) {
      const std::string set = "fillet" + std::to_string(fs.tooth) + (fs.side == 0 ? "+" : "-");
      const Eigen::Vector2d x = Eigen::Rotation2Dd(fs.tooth * gear.pitch_angle()) *
                                (fs.side == 1 ? Eigen::Vector2d(points[m].position.x(),
                                                                -points[m].position.y())
                                              : points[m].position);
      const double direct = test::NodeStress(fe, u, set, x, tol_node);
      double b = 0;
      for (const Load& l : loads)
        b += test::FilletInterpolationBound(table, l.at, l.size, fs.tooth, fs.side, m);
      largest = std::max(largest, std::abs(direct));
      worst = std::max(worst, std::abs(fs.sigma[m] - direct));
      bound = std::max(bound, b);
      share = std::max(share, std::abs(fs.sigma[m] - normal_only[q].sigma[m]));
      const bool ok = std::abs(fs.sigma[m] - direct) <= b + 1e-9 * largest;
      INFO("tooth " << fs.tooth << " side " << fs.side << " point " << m << ": driver "
                    << fs.sigma[m] << " Pa, direct " << direct << " Pa, bound " << b);
      CHECK(ok);
      within = within && ok;
      ++compared;
    }
  }
  CHECK(compared > 0);
  CHECK(largest > 1e7);
  // Friction's part is resolved: larger than what the comparison allows.
  CHECK(share > 10 * bound);
  test::VerifyRow(
      "root stress with friction at rest (mu 0.1): the paper sun's fillets in the stage",
      "the sun's FE body solved directly under the normal and friction forces",
      "largest stress " + test::Sci(largest / 1e6) + " MPa, friction's part up to " +
          test::Sci(share / 1e6) + " MPa",
      test::Sci(worst / 1e6) + " MPa",
      "per point 0.114 |F| |third difference| (up to " + test::Sci(bound / 1e6) + " MPa)",
      compared > 0 && within);
}
