// The quasi-static driver on a stage whose contacts are independent linear springs (no coupling,
// no local term). For involute contacts the levers are the base radii and the overlap is linear in
// the rotations, so the closed forms of a series-spring planetary hold exactly:
//   path stiffness k_i = 1/(c/n_s,i + c/n_r,i),  F_i = k_i (r_bs θ + a_i),  Σ F_i r_bs = |T|,
// with n the loaded involute pairs of each mesh and a_i the overlap the errors add to path i.
#include <catch2/catch.hpp>

#include <cmath>

#include "epicycle/transmission/quasistatic.hpp"
#include "stage_fixtures.hpp"

using namespace epicycle;
using transmission::StageContact;

namespace {

constexpr double kSpring = 1e-9;  // c [m/N] of every contact

class SpringCompliance : public transmission::StageCompliance {
 public:
  Eigen::MatrixXd Matrix(const geometry::Stage&, const geometry::StagePoses&,
                         const std::vector<StageContact>& contacts) const override {
    const auto n = static_cast<Eigen::Index>(contacts.size());
    return kSpring * Eigen::MatrixXd::Identity(n, n);
  }
  double JoiningDepth(int) const override { return 1e-3; }
  // Springs need no material; the local terms, when a test adds them, see steel.
  const transmission::Material& material() const override { return steel_; }
  solvers::PlaneAssumption plane() const override {
    return solvers::PlaneAssumption::kPlaneStrain;
  }

 private:
  transmission::Material steel_;
};

struct PathCounts {
  std::vector<int> sun, ring;
  bool only_involute = true;
};

// Active pairs of each mesh in the solved problem (F > 0), and whether all are involute pairs.
PathCounts Active(const transmission::PositionResult& r, int planets) {
  PathCounts p{std::vector<int>(planets, 0), std::vector<int>(planets, 0), true};
  for (std::size_t j = 0; j < r.problem.contacts.size(); ++j) {
    if (r.solution.force(static_cast<Eigen::Index>(j)) <= 0) continue;
    const StageContact& s = r.problem.contacts[j];
    if (s.contact.kind != geometry::ContactKind::kInvolute || !s.loaded) p.only_involute = false;
    (s.mesh == geometry::MeshKind::kSunPlanet ? p.sun : p.ring)[s.planet]++;
  }
  return p;
}

transmission::StageSetup Setup(const transmission::Scene& scene, transmission::SunSupport sun) {
  transmission::StageSetup s = transmission::SetupFromScene(scene);
  s.sun = sun;
  s.local_terms = false;
  return s;
}

// The quasi-static solution at carrier angle φ of the stage model (stage, springs, setup).
transmission::PositionResult Solve(const transmission::Scene& scene, const geometry::Stage& stage,
                                   const transmission::StageCompliance& springs, double phi,
                                   const transmission::StageSetup& setup) {
  const transmission::StageModel model(stage, springs, setup);
  return transmission::SolvePosition(model, phi, scene.loads, {});
}

}  // namespace

TEST_CASE("fixed sun, springs: load shares follow the path stiffnesses",
          "[crosscheck][transmission]") {
  const auto scene = test::PaperScene();
  const geometry::Stage stage(scene.stage);
  const SpringCompliance springs;
  const double rbs = stage.sun().base_radius();
  int tested = 0;
  for (int k = 0; k < 16; ++k) {
    const double phi = stage.mesh_cycle() * (k + 0.5) / 16;
    const auto r = Solve(scene, stage, springs, phi, Setup(scene, transmission::SunSupport::kFixed));
    REQUIRE(r.converged);
    const PathCounts c = Active(r, 3);
    if (!c.only_involute) continue;  // a tip round carries load here: not a series-spring stage
    double ksum = 0;
    std::vector<double> kp(3);
    for (int i = 0; i < 3; ++i) {
      REQUIRE((c.sun[i] > 0 && c.ring[i] > 0));
      kp[i] = 1.0 / (kSpring / c.sun[i] + kSpring / c.ring[i]);
      ksum += kp[i];
    }
    double lsr_sum = 0;
    for (int i = 0; i < 3; ++i) {
      CHECK(r.load_sharing[i] == Approx(kp[i] / ksum).epsilon(1e-9));
      lsr_sum += r.load_sharing[i];
    }
    CHECK(lsr_sum == Approx(1.0).epsilon(1e-10));
    // The sun turns with the torque by |T|/(r_bs² Σk).
    CHECK(r.transmission_error == Approx(scene.loads.sun_torque / (rbs * rbs * ksum)).epsilon(1e-8));
    ++tested;
  }
  CHECK(tested >= 6);
}

TEST_CASE("fixed sun, springs, tangential pin error: the closed form with the error's overlap",
          "[crosscheck][transmission]") {
  auto scene = test::PaperScene();
  scene.stage.pin_errors.assign(3, {});
  scene.stage.pin_errors[0].tangential = 3e-6;
  const geometry::Stage stage(scene.stage);
  const SpringCompliance springs;
  const double rbs = stage.sun().base_radius(), torque = std::abs(scene.loads.sun_torque);
  int tested = 0;
  for (int k = 0; k < 16; ++k) {
    const double phi = stage.mesh_cycle() * (k + 0.5) / 16;
    const auto r = Solve(scene, stage, springs, phi, Setup(scene, transmission::SunSupport::kFixed));
    REQUIRE(r.converged);
    const PathCounts c = Active(r, 3);
    if (!c.only_involute) continue;
    // The error's extra overlap of each path, from the geometry at the kinematic poses.
    const auto with = stage.Poses(phi, true), without = stage.Poses(phi, false);
    std::vector<double> kp(3), a(3);
    double ksum = 0, ka = 0;
    for (int i = 0; i < 3; ++i) {
      kp[i] = 1.0 / (kSpring / c.sun[i] + kSpring / c.ring[i]);
      a[i] = geometry::NearestLoaOverlap(stage.Sun(with), stage.Planet(with, i), false,
                                         stage.sun_mesh_side()) -
             geometry::NearestLoaOverlap(stage.Sun(without), stage.Planet(without, i), false,
                                         stage.sun_mesh_side()) +
             geometry::NearestLoaOverlap(stage.Planet(with, i), stage.Ring(with), true,
                                         stage.ring_mesh_planet_side()) -
             geometry::NearestLoaOverlap(stage.Planet(without, i), stage.Ring(without), true,
                                         stage.ring_mesh_planet_side());
      ksum += kp[i];
      ka += kp[i] * a[i];
    }
    const double rot = (torque / rbs - ka) / (rbs * ksum);  // |θ| of the sun
    for (int i = 0; i < 3; ++i) {
      const double expected = kp[i] * (rbs * rot + a[i]) * rbs / torque;
      CHECK(r.load_sharing[i] == Approx(expected).epsilon(1e-7));
    }
    // The error moves planet 1's share the way its extra overlap says.
    CHECK((r.load_sharing[0] - 1.0 / 3.0) * a[0] > 0);
    ++tested;
  }
  CHECK(tested >= 6);
}

TEST_CASE(
    "floating sun, three planets, springs: equal shares up to the tilt of the lines of action",
    "[crosscheck][transmission]") {
  // Three forces on lines of action 120° apart balance only if they are equal; the sun's move s
  // and the pin error e tilt those lines by at most ~(|s| + e)/a, and the shares by as much.
  auto scene = test::PaperScene();
  const double e = 5e-6;
  scene.stage.pin_errors.assign(3, {});
  scene.stage.pin_errors[1].tangential = e;
  const geometry::Stage stage(scene.stage);
  const SpringCompliance springs;
  int tested = 0;
  for (int k = 0; k < 16; ++k) {
    const double phi = stage.mesh_cycle() * (k + 0.5) / 16;
    const auto r = Solve(scene, stage, springs, phi, Setup(scene, transmission::SunSupport::kFloating));
    const auto fixed = Solve(scene, stage, springs, phi, Setup(scene, transmission::SunSupport::kFixed));
    REQUIRE(r.converged);
    REQUIRE(fixed.converged);
    if (!Active(r, 3).only_involute) continue;
    const double bound = 3.0 * (r.sun_displacement.norm() + e) / stage.carrier_radius();
    for (int i = 0; i < 3; ++i) {
      CHECK(std::abs(r.load_sharing[i] - 1.0 / 3.0) <= bound);
      CHECK(std::abs(fixed.load_sharing[1] - 1.0 / 3.0) > 100 * bound);  // what floating removed
    }
    CHECK(r.sun_displacement.norm() > 0.5 * e);  // the sun moved to absorb the pin error
    ++tested;
  }
  CHECK(tested >= 6);
}

TEST_CASE(
    "elastic sun bearing, springs: the bearing carries the net mesh force, stiff and soft limits",
    "[crosscheck][transmission]") {
  // The sun on a bearing of stiffness k_s: its deflection s satisfies k_s s = net contact force
  // on the sun (Σ −n_j F_j over the sun's contacts), computed here from the solved forces and the
  // geometry's normals. A very stiff bearing gives the fixed sun's shares, a very soft one the
  // floating sun's: a bearing force k_s s against mesh forces F changes the shares by about
  // k_s s/F (soft: 1e3 N/m × 5 µm / 6.5 kN ≈ 1e-6), a bearing deflection s = net/k_s changes the
  // overlaps by s against the mesh deflection (stiff: 1e-11 m / 25 µm ≈ 1e-6); margin 1e-4.
  auto scene = test::PaperScene();
  scene.stage.pin_errors.assign(3, {});
  scene.stage.pin_errors[1].tangential = 5e-6;
  const geometry::Stage stage(scene.stage);
  const SpringCompliance springs;
  const double phi = stage.mesh_cycle() * 0.3;
  auto solve = [&](transmission::SunSupport sun, double k) {
    auto setup = Setup(scene, sun);
    setup.sun_stiffness = k;
    const auto r = Solve(scene, stage, springs, phi, setup);
    REQUIRE(r.converged);
    return r;
  };
  const auto fixed = solve(transmission::SunSupport::kFixed, 0.0);
  const auto floating = solve(transmission::SunSupport::kFloating, 0.0);
  for (double k : {1e3, 3e8, 1e14}) {
    const auto r = solve(transmission::SunSupport::kElastic, k);
    geometry::Vec2 net = geometry::Vec2::Zero();
    for (std::size_t j = 0; j < r.problem.contacts.size(); ++j) {
      const auto& c = r.problem.contacts[j];
      if (c.body_a == transmission::kSunBody)
        net -= c.contact.normal * r.solution.force(static_cast<Eigen::Index>(j));
    }
    INFO("k_s = " << k << " N/m");
    // The last geometric iteration solves at the poses before its own (≤ 1e-11 m) increment.
    CHECK((k * r.sun_displacement - net).norm() <= 1e-6 * net.norm() + k * 1e-10);
    const auto& limit = k > 1e12 ? fixed : (k < 1e4 ? floating : r);
    for (int i = 0; i < 3; ++i)
      CHECK(r.load_sharing[i] == Approx(limit.load_sharing[i]).margin(1e-4));
  }
}
