// A branch continued over an error amplitude of the scene (docs/periodic.md §3, "Continued scene
// numbers"): the paper stage with spring contacts, planet 2's pin-hole error continued at a fixed
// sun speed; each point against an independent shooting run of a scene with that amplitude
// written in (its own rig: the scene read from text, its stage, stage model and dynamic model),
// and the names a branch refuses.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "dynamics_fixtures.hpp"
#include "epicycle/dynamics/branch_run.hpp"
#include "epicycle/dynamics/periodic.hpp"
#include "epicycle/dynamics/stage_branch.hpp"
#include "epicycle/dynamics/stage_periodic.hpp"
#include "epicycle/io/units.hpp"
#include "epicycle/transmission/scene_keys.hpp"
#include "figures.hpp"

using namespace epicycle;

namespace {

constexpr double kRpm = 1000;
constexpr double kRtol = 1e-8, kAtolAngle = 1e-11, kAtolLength = 1e-12, kRateScale = 1e4;
const char* const kKey = "errors.pin.planet2.tangential_um";

// The paper stage with spring contacts (1e-9 m/N, the damping's mesh stiffness 1.5e9 N/m given,
// so that every rig has the same c_m whatever its errors) at kRpm, the sun held; `extra` appended
// to the scene's text.
test::DynamicRig Rig(const std::string& extra) {
  test::RigOptions o;
  o.spring = 1e-9;
  o.spring_mesh_stiffness = 1.5e9;
  o.edit = [](transmission::DynamicSettings& s) { s.sun_speed = io::RpmToRadPerSecond(kRpm); };
  return test::MakeRig(test::SceneText("paper_stage.toml") + "\n" + extra, "pin", o);
}

// The scene's own [[errors.pin]] entry for planet 2 with the tangential error written in [µm], to
// 17 digits (the value the branch's point carries, read back exactly).
std::string PinEntry(double tangential_um) {
  char text[64];
  std::snprintf(text, sizeof text, "%.17g", tangential_um);
  return "[[errors.pin]]\ngear = \"planet2\"\ntangential_um = " + std::string(text) + "\n";
}

dynamics::SimulationOptions Integration() {
  dynamics::SimulationOptions sim;
  sim.rtol = kRtol;
  sim.atol_angle = kAtolAngle;
  sim.atol_length = kAtolLength;
  sim.rate_scale = kRateScale;
  return sim;
}

dynamics::ShootingOptions Shooting(const dynamics::DynamicModel& m) {
  const int n = m.size();
  dynamics::ShootingOptions so;
  so.rtol = kRtol;
  so.atol.resize(2 * n);
  for (int k = 0; k < n; ++k) {
    so.atol(k) = m.dofs()[k].axis == dynamics::MotionDof::kRotation ? kAtolAngle : kAtolLength;
    so.atol(n + k) = so.atol(k) * kRateScale;
  }
  return so;
}

// max_k |a_k − b_k| / (rtol |b_k| + atol_k): in integrator tolerances per component.
double Weighted(const dynamics::ShootingOptions& so, const Eigen::VectorXd& a,
                const Eigen::VectorXd& b) {
  double worst = 0;
  for (Eigen::Index k = 0; k < a.size(); ++k)
    worst = std::max(worst, std::abs(a(k) - b(k)) / (so.rtol * std::abs(b(k)) + so.atol(k)));
  return worst;
}

}  // namespace

TEST_CASE(
    "paper stage, springs: a branch over planet 2's pin error at fixed speed equals, point by "
    "point, independent shooting runs of scenes with that error written in",
    "[crosscheck][dynamics][periodic][slow]") {
  const auto base = Rig("");
  dynamics::StageBranchOptions o;
  o.parameter = kKey;
  o.start = 0;
  o.end = 4;
  o.max_step = 0.25;
  o.simulation = Integration();
  const dynamics::StageBranchRecord rec = dynamics::ContinueStageBranch(*base.model, o);
  INFO(rec.message + rec.figures_message);
  REQUIRE(rec.ok());
  CHECK(rec.unit == "µm");
  test::FigureValue("pin-error branch points", static_cast<double>(rec.points.size()), "-");
  test::FigureValue("pin-error branch stage rebuilds", static_cast<double>(rec.rebuilds), "-");
  test::FigureValue("pin-error branch CPU", rec.cpu_seconds, "s");
  REQUIRE(rec.points.size() >= 3);
  CHECK(rec.points.front().parameter == 0.0);
  CHECK(rec.points.back().parameter >= o.end);
  // The stage is rebuilt only for an error value other than the scene's, once per value the
  // continuation evaluated (predictor, corrector iterates, the parameter derivative's λ + h):
  // at least one per point after the first.
  CHECK(rec.rebuilds >= static_cast<long>(rec.points.size()) - 1);
  for (const dynamics::StageBranchPoint& q : rec.points) CHECK(q.sun_speed_rpm == kRpm);

  const dynamics::ShootingOptions so = Shooting(*base.model);
  // Steps per period: the branch's mean over every period it integrated.
  const double steps = static_cast<double>(rec.steps) /
                       static_cast<double>(rec.integrations + rec.plain_integrations);
  double k_gamma_first = 0;
  for (const std::size_t i : {std::size_t{1}, rec.points.size() / 2, rec.points.size() - 1}) {
    const dynamics::StageBranchPoint& q = rec.points[i];
    const auto rig = Rig(PinEntry(q.parameter));
    REQUIRE(rig.scene.stage.pin_errors.at(1).tangential == q.parameter * 1e-6);
    const dynamics::DynamicModel& m = *rig.model;
    const dynamics::StagePeriodicSystem system(m, solvers::Backend::kActiveSetNewton, {});
    Eigen::VectorXd y0 = Eigen::VectorXd::Zero(2 * m.size());
    y0.head(m.size()) = m.QuasiStaticStart({}, solvers::Backend::kActiveSetNewton);
    const dynamics::ShootingResult r = dynamics::SolvePeriodicOrbit(system, so, y0);
    INFO(r.message);
    REQUIRE(r.status == dynamics::ShootingStatus::kConverged);
    // Both stop with R ≤ newton_tolerance (weighted) and an integration error of at most one
    // local tolerance a step; each is within (newton_tolerance + steps)/(1 − ρ) of the exact
    // orbit, the two within twice that (the same bound as two shootings from different starts,
    // crosscheck/dynamics_periodic_stage.cpp).
    const double rho = std::max(q.spectral_radius, r.floquet.spectral_radius);
    const double tol = 2 * (so.newton_tolerance + steps) / (1 - rho);
    const double error = Weighted(so, r.initial_state, q.state);
    test::FigureValue("pin-error branch at " + std::to_string(q.parameter) +
                          " um: independent shooting - point (weighted)",
                      error, "-");
    CHECK(error <= tol);
    CHECK(r.floquet.stability == q.stability);
    if (i == 1) k_gamma_first = q.k_gamma;
  }
  // A pin error moves load between the planets: the largest share K_γ grows with its size.
  CHECK(rec.points.back().k_gamma > k_gamma_first);
}

TEST_CASE("stage branch: the names of the scene's numbers a branch continues, and why not",
          "[crosscheck][dynamics][periodic]") {
  const auto rig = Rig(PinEntry(2.0));
  const transmission::Scene& scene = rig.scene;
  dynamics::StagePeriod period;
  // The model's parameters, by name or by their key paths; an error amplitude of a planet's pin.
  CHECK(dynamics::ResolveBranchParameter(scene, "load.sun_torque_Nm", "NAME", 4, &period) ==
        "sun_torque_Nm");
  CHECK(dynamics::ResolveBranchParameter(scene, kKey, "NAME", 4, &period) == kKey);
  CHECK(period.mesh_cycles == 1);
  const auto key = dynamics::ParseStageErrorKey(kKey, 3);
  REQUIRE(key);
  CHECK(key->Value(scene.stage) == Approx(2.0).epsilon(1e-15));
  CHECK_FALSE(dynamics::ParseStageErrorKey("errors.pin.planet4.tangential_um", 3));
  CHECK_FALSE(dynamics::ParseStageErrorKey("errors.pin.sun.tangential_um", 3));
  // Keys in the scene's text: a number, something else, nothing.
  CHECK(transmission::FindSceneKey(scene, "sun.teeth") == transmission::SceneKeyKind::kNumber);
  CHECK(transmission::FindSceneKey(scene, "errors.pin.planet2.gear") ==
        transmission::SceneKeyKind::kOther);
  CHECK(transmission::FindSceneKey(scene, "scene.name") == transmission::SceneKeyKind::kOther);
  CHECK(transmission::FindSceneKey(scene, "sun.teeths") == transmission::SceneKeyKind::kAbsent);
  CHECK_THROWS_WITH(
      dynamics::ResolveBranchParameter(scene, "sun.teeth", "NAME", 4, &period),
      Catch::StartsWith("NAME = 'sun.teeth': a number of the scene that a branch cannot continue"));
  CHECK_THROWS_WITH(dynamics::ResolveBranchParameter(scene, "scene.name", "NAME", 4, &period),
                    Catch::StartsWith("NAME = 'scene.name': not a number in the scene"));
  CHECK_THROWS_WITH(dynamics::ResolveBranchParameter(scene, "speed", "NAME", 4, &period),
                    Catch::StartsWith("NAME = 'speed': not a key of the scene"));
  // A run-out turns with its gear: planet 1's makes the period z_p = 24 mesh cycles.
  CHECK_THROWS_WITH(
      dynamics::ResolveBranchParameter(scene, "errors.runout.planet1.amplitude_um", "NAME", 4,
                                       &period),
      Catch::Contains("the stage's period with it = 24 mesh cycles (planet1 run-out: 24 mesh "
                      "cycles): must be <= max_period_mesh_cycles = 4"));
  // With a longer limit it is continued, over that period.
  CHECK(dynamics::ResolveBranchParameter(scene, "errors.runout.planet1.amplitude_um", "NAME", 24,
                                         &period) == "errors.runout.planet1.amplitude_um");
  CHECK(period.mesh_cycles == 24);

  // The system's fourth parameter: each new value rebuilds the stage, whose pin then sits off its
  // nominal place by the value, tangentially (geometry::Stage::Pin, the scene's meaning of the key).
  const dynamics::StagePeriodicSystem system(*rig.model, solvers::Backend::kActiveSetNewton, {}, 1,
                                             key);
  REQUIRE(system.parameters().size() == 4);
  CHECK(system.parameters()[3].name == kKey);
  CHECK(system.parameters()[3].value == Approx(2.0).epsilon(1e-15));
  Eigen::VectorXd p = system.DefaultParameters();
  CHECK(&system.ModelAt(p) == rig.model.get());  // the scene's own value: no rebuild
  const auto clock = std::chrono::steady_clock::now();
  const int values = 5;
  for (int k = 1; k <= values; ++k) {
    p(3) = 2.0 + 0.5 * k;
    const geometry::Stage& stage = system.ModelAt(p).stage_model().stage();
    const double at = geometry::kPi / 7;  // any carrier angle
    const geometry::Vec2 nominal = stage.Pin(1, at, false);
    const geometry::Vec2 off = stage.Pin(1, at, true) - nominal;
    // Tangential: perpendicular to the pin's radius at ψ_2 + φ_c, |off| = the value in m. The
    // difference of two positions of size R = a_c carries a round-off of a few ε R per component:
    // 8 ε R on its length, 8 ε R² on its dot product with the radius.
    const double round_off = 8 * std::numeric_limits<double>::epsilon() * nominal.norm();
    CHECK(std::abs(off.norm() - p(3) * 1e-6) <= round_off);
    CHECK(std::abs(off.dot(nominal)) <= round_off * nominal.norm());
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - clock).count();
  test::FigureValue("stage rebuild (geometry::Stage, stage model, dynamic model)",
                    seconds / values, "s");
  CHECK(system.rebuilds() == values);
}
