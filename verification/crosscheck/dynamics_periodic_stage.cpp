// The periodic solver on the paper's stage (docs/periodic.md §3): a perfect stage (no errors) with
// spring contacts, whose response repeats with the mesh cycle; the shooting orbit against the
// state a long time integration (dynamics::Simulate, the project's own) settles into, at one
// speed, with a floating sun (the period map turns its centre back by the carrier's advance), and
// along a branch continued over the sun speed; a branch continued over a pin error against
// independent shooting runs of scenes with each value written in.
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
#include "periodic_fixtures.hpp"

using namespace epicycle;

namespace {

// The suite's spring rig of the paper stage at `rpm`, with the sun held as `sun` says.
test::DynamicRig SpringRig(double rpm, transmission::SunSupport sun) {
  test::RigOptions o;
  o.spring = 1e-9;
  o.spring_mesh_stiffness = 1.5e9;
  o.sun = sun;
  o.edit = [rpm](transmission::DynamicSettings& s) { s.sun_speed = io::RpmToRadPerSecond(rpm); };
  return test::MakeRig(test::SceneText("paper_stage.toml"), "springs", o);
}

// The integration's tolerances of the tests: rtol 1e-8, 1e-11 rad and 1e-12 m, rates × 1e4.
constexpr double kRtol = 1e-8, kAtolAngle = 1e-11, kAtolLength = 1e-12, kRateScale = 1e4;

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
  Eigen::VectorXd atol(2 * n);
  for (int k = 0; k < n; ++k) {
    atol(k) = m.dofs()[k].axis == dynamics::MotionDof::kRotation ? kAtolAngle : kAtolLength;
    atol(n + k) = atol(k) * kRateScale;
  }
  so.atol = atol;
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

// The quasi-static start of m's state y = (d, ḋ): d from the quasi-static solve, ḋ = 0.
Eigen::VectorXd QuasiStaticState(const dynamics::DynamicModel& m) {
  Eigen::VectorXd y0 = Eigen::VectorXd::Zero(2 * m.size());
  y0.head(m.size()) = m.QuasiStaticStart({}, solvers::Backend::kActiveSetNewton);
  return y0;
}

// Shooting on m's stage from its quasi-static start (the suite's tolerances), converged.
dynamics::ShootingResult ShootFromQuasiStatic(const dynamics::DynamicModel& m,
                                              const dynamics::PeriodicSystem& system) {
  const dynamics::ShootingResult r =
      dynamics::SolvePeriodicOrbit(system, Shooting(m), QuasiStaticState(m));
  INFO(r.message);
  REQUIRE(r.status == dynamics::ShootingStatus::kConverged);
  return r;
}

// The state Simulate reaches after `cycles` periods and `fraction` of one more from y0 (the raw
// state: a stage with translations has it turned by the carrier's advance).
Eigen::VectorXd Settle(const dynamics::DynamicModel& m, const Eigen::VectorXd& y0, double period,
                       int cycles, double fraction = 0) {
  const int n = m.size();
  const dynamics::SimulationResult run = dynamics::Simulate(
      m, Integration(), y0.head(n), y0.tail(n), {(cycles + fraction) * period});
  REQUIRE(run.completed());
  Eigen::VectorXd settled(2 * n);
  settled << run.samples.back().d, run.samples.back().v;
  return settled;
}

// Tolerance (weighted) of a settled state against the shooting orbit: what is left of the
// transient, ρ^cycles times the start's distance, plus the integration's error, one local
// tolerance a step contracted by ρ each cycle (steps a cycle/(1 − ρ)), plus the shooting's own R
// to newton_tolerance over (1 − ρ).
double SettledTolerance(double rho, int cycles, double start_distance, double steps_per_period,
                        double newton_tolerance) {
  return std::pow(rho, cycles) * start_distance + (steps_per_period + newton_tolerance) / (1 - rho);
}

// A branch over an error amplitude (docs/periodic.md §3, "Continued scene numbers"): planet 2's
// tangential pin error by its scene key path.
const char* const kKey = "errors.pin.planet2.tangential_um";

// SpringRig's stage (its damping's mesh stiffness given, so that every rig has the same c_m
// whatever its errors) at 1000 rpm, the sun held, with `extra` appended to the scene's text.
test::DynamicRig RigOfText(const std::string& scene_text) {
  test::RigOptions o;
  o.spring = 1e-9;
  o.spring_mesh_stiffness = 1.5e9;
  o.edit = [](transmission::DynamicSettings& s) { s.sun_speed = io::RpmToRadPerSecond(1000); };
  return test::MakeRig(scene_text, "pin", o);
}

test::DynamicRig Rig(const std::string& extra) {
  return RigOfText(test::SceneText("paper_stage.toml") + "\n" + extra);
}

// A number to 17 digits (read back exactly).
std::string Exact(double value) {
  char text[64];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

// The scene's own [[errors.pin]] entry for planet 2 with the tangential error written in [µm], to
// 17 digits (the value the branch's point carries, read back exactly).
std::string PinEntry(double tangential_um) {
  return "[[errors.pin]]\ngear = \"planet2\"\ntangential_um = " + Exact(tangential_um) + "\n";
}

// Shooting on `rig`'s own stage from its quasi-static start against the branch point `q` (the
// same orbit): the weighted distance, and the tolerance. Both stop with R ≤ newton_tolerance
// (weighted) and an integration error of at most one local tolerance a step; each is within
// (newton_tolerance + steps)/(1 − ρ) of the exact orbit, the two within twice that (the same bound
// as two shootings from different starts, CheckOrbitAgainstSettled).
struct IndependentShooting {
  double error = 0, tolerance = 0;
  dynamics::Stability stability = dynamics::Stability::kStable;
};
IndependentShooting ShootAgainstPoint(const test::DynamicRig& rig,
                                      const dynamics::StageBranchPoint& q, double steps) {
  const dynamics::DynamicModel& m = *rig.model;
  const dynamics::StagePeriodicSystem system(m, solvers::Backend::kActiveSetNewton, {});
  const dynamics::ShootingOptions so = Shooting(m);
  const dynamics::ShootingResult r = ShootFromQuasiStatic(m, system);
  const double rho = std::max(q.spectral_radius, r.floquet.spectral_radius);
  return {Weighted(so, r.initial_state, q.state), 2 * (so.newton_tolerance + steps) / (1 - rho),
          r.floquet.stability};
}

// The shooting orbit of `rig`'s stage against the state a long time integration settles into
// (figures named by `name`), and against the orbit shot from another start.
void CheckOrbitAgainstSettled(const test::DynamicRig& rig, const std::string& name) {
  const dynamics::DynamicModel& m = *rig.model;
  std::string dofs;
  for (int k = 0; k < m.size(); ++k) dofs += m.dofs()[k].Label() + "; ";
  test::Figure(name + " DOFs: " + dofs);
  const dynamics::StagePeriodicSystem system(m, solvers::Backend::kActiveSetNewton, {});
  const int n = m.size();
  const dynamics::ShootingOptions so = Shooting(m);
  const Eigen::VectorXd y0 = QuasiStaticState(m);
  const auto clock = std::chrono::steady_clock::now();
  const dynamics::ShootingResult r = dynamics::SolvePeriodicOrbit(system, so, y0);
  test::FigureValue(name + " shooting wall time",
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - clock).count(),
                    "s");
  INFO(r.message);
  REQUIRE(r.status == dynamics::ShootingStatus::kConverged);
  test::FigureValue(name + " shooting iterations", r.iterations, "-");
  test::FigureValue(name + " shooting steps", static_cast<double>(r.steps), "-");
  test::FigureValue(name + " spectral radius", r.floquet.spectral_radius, "-");
  const int cycles = 60;
  const Eigen::VectorXd settled = Settle(m, y0, r.period, cycles);
  const double rho = r.floquet.spectral_radius;
  const double steps = static_cast<double>(r.steps) / static_cast<double>(r.integrations);
  const double tol =
      SettledTolerance(rho, cycles, Weighted(so, y0, r.initial_state), steps, so.newton_tolerance);
  const double settled_error = Weighted(so, settled, r.initial_state);
  test::FigureValue(name + " settled - orbit (weighted)", settled_error, "-");
  test::FigureValue(name + " settled tolerance (weighted)", tol, "-");
  CHECK(settled_error <= tol);
  CHECK(r.floquet.stability == dynamics::Stability::kStable);

  // Started elsewhere (the quasi-static start with its deviations halved: a different transient),
  // the same orbit: both shootings stop with R to newton_tolerance, each an orbit error of at most
  // newton_tolerance/(1 − ρ).
  Eigen::VectorXd other = y0;
  other.head(n) *= 0.5;
  const dynamics::ShootingResult r2 = dynamics::SolvePeriodicOrbit(system, so, other);
  REQUIRE(r2.status == dynamics::ShootingStatus::kConverged);
  const double other_error = Weighted(so, r2.initial_state, r.initial_state);
  test::FigureValue(name + " second start - orbit (weighted)", other_error, "-");
  CHECK(other_error <= 2 * (so.newton_tolerance + steps) / (1 - rho));
}

}  // namespace

TEST_CASE(
    "paper stage, perfect, springs: the shooting orbit is the state a long time integration "
    "settles into",
    "[crosscheck][dynamics][periodic]") {
  CheckOrbitAgainstSettled(SpringRig(1000, transmission::SunSupport::kFixed), "stage");
}

// Another point of the orbit (docs/periodic.md §3, "Another point of the orbit"): the stage's
// orbit is pinned to the mesh's phase, so the other point is the section at t = T/3. Shooting the
// stage on a clock started there, from the phase-0 orbit's state (a point of the orbit, at the
// wrong phase for this section), must find the state a long time integration from the
// quasi-static start reaches at (60 + 1/3) T.
TEST_CASE(
    "paper stage, perfect, springs: shooting started at another phase of the mesh period (T/3) "
    "finds the state a long time integration reaches there",
    "[crosscheck][dynamics][periodic]") {
  const auto rig = SpringRig(1000, transmission::SunSupport::kFixed);
  const dynamics::StagePeriodicSystem system(*rig.model, solvers::Backend::kActiveSetNewton, {});
  const dynamics::ShootingResult r = ShootFromQuasiStatic(*rig.model, system);
  const dynamics::DynamicModel& m = *rig.model;
  const dynamics::ShootingOptions so = Shooting(m);
  const Eigen::VectorXd y0 = QuasiStaticState(m);
  const test::PhaseShifted shifted(system, 1.0 / 3);
  const dynamics::ShootingResult b = dynamics::SolvePeriodicOrbit(shifted, so, r.initial_state);
  INFO(b.message);
  REQUIRE(b.status == dynamics::ShootingStatus::kConverged);
  const int cycles = 60;
  const Eigen::VectorXd settled = Settle(m, y0, r.period, cycles, 1.0 / 3);
  // Tolerance: SettledTolerance (the transient's remainder from the start's distance to the
  // phase-0 orbit, the integration's and the shooting's errors over (1 − ρ)), ρ the larger of the
  // two sections' spectral radii (their monodromies are similar: the same multipliers).
  const double rho = std::max(r.floquet.spectral_radius, b.floquet.spectral_radius);
  const double steps = std::max(static_cast<double>(r.steps) / static_cast<double>(r.integrations),
                                static_cast<double>(b.steps) / static_cast<double>(b.integrations));
  const double tol =
      SettledTolerance(rho, cycles, Weighted(so, y0, r.initial_state), steps, so.newton_tolerance);
  const double error = Weighted(so, settled, b.initial_state);
  const double guess = Weighted(so, r.initial_state, b.initial_state);
  test::FigureValue("stage phase T/3: Newton iterations", b.iterations, "-");
  test::FigureValue("stage phase T/3: guess - answer (weighted)", guess, "-");
  test::FigureValue("stage phase T/3: settled - shifted orbit (weighted)", error, "-");
  test::FigureValue("stage phase T/3: tolerance (weighted)", tol, "-");
  test::FigureValue("stage phase T/3: spectral radius phase 0", r.floquet.spectral_radius, "-");
  test::FigureValue("stage phase T/3: spectral radius shifted", b.floquet.spectral_radius, "-");
  CHECK(error <= tol);
  CHECK(guess > tol);  // the guess was not already the answer
  CHECK(b.floquet.stability == r.floquet.stability);
}

// The helical paper stage (β = 15°) in 5 slices (docs/model.md §10; the orbit's cost grows with
// the slices, dynamics_helical.cpp), the same springs per slice contact: its state is the planar
// one (the axial and tilting motions held), so the shooting is the spur stage's on the sliced
// meshes, with the same tolerance.
TEST_CASE(
    "helical paper stage, perfect, springs, 5 slices: the shooting orbit is the state a long time "
    "integration settles into",
    "[crosscheck][dynamics][periodic][helical][slow]") {
  test::RigOptions o;
  o.spring = 1e-9;
  o.spring_mesh_stiffness = 1.5e9;
  o.edit = [](transmission::DynamicSettings& s) { s.sun_speed = io::RpmToRadPerSecond(1000); };
  const auto rig = test::MakeRig(
      test::Replace(test::SceneText("paper_stage_helical.toml"), "slices = 20", "slices = 5"),
      "helical springs", o);
  REQUIRE(rig.stage_model->helical());
  CheckOrbitAgainstSettled(rig, "helical stage");
}

TEST_CASE(
    "paper stage, floating sun: the orbit repeats turned by the carrier's advance, and is the "
    "state a long time integration settles into",
    "[crosscheck][dynamics][periodic][slow]") {
  const auto rig = SpringRig(1000, transmission::SunSupport::kFloating);
  const dynamics::DynamicModel& m = *rig.model;
  const int n = m.size();
  REQUIRE(m.Find(dynamics::MotionDof::kSun, dynamics::MotionDof::kX) >= 0);
  const dynamics::StagePeriodicSystem system(m, solvers::Backend::kActiveSetNewton, {});
  const dynamics::ShootingOptions so = Shooting(m);
  // The period map is orthogonal and turns (x, y) by −Δφ_c = −sign(ω_c) 2π/z_r.
  const Eigen::MatrixXd map = system.PeriodMap(system.DefaultParameters());
  REQUIRE(map.rows() == 2 * n);
  CHECK((map.transpose() * map - Eigen::MatrixXd::Identity(2 * n, 2 * n)).norm() < 1e-14);
  const int kx = m.Find(dynamics::MotionDof::kSun, dynamics::MotionDof::kX);
  const int ky = m.Find(dynamics::MotionDof::kSun, dynamics::MotionDof::kY);
  const double advance = std::copysign(rig.stage->mesh_cycle(), m.carrier_speed());
  CHECK(std::atan2(map(ky, kx), map(kx, kx)) == Approx(-advance).margin(1e-14));

  const Eigen::VectorXd y0 = QuasiStaticState(m);
  const dynamics::ShootingResult r = dynamics::SolvePeriodicOrbit(system, so, y0);
  INFO(r.message);
  REQUIRE(r.status == dynamics::ShootingStatus::kConverged);
  test::FigureValue("floating sun: shooting iterations", r.iterations, "-");
  test::FigureValue("floating sun: spectral radius", r.floquet.spectral_radius, "-");
  const int cycles = 60;
  const Eigen::VectorXd settled = Settle(m, y0, r.period, cycles);
  // After `cycles` periods the orbit's state is S^−cycles y_orbit (turned by cycles Δφ_c).
  Eigen::MatrixXd turn = Eigen::MatrixXd::Identity(2 * n, 2 * n);
  for (int k = 0; k < cycles; ++k) turn = map.transpose() * turn;
  const Eigen::VectorXd expected = turn * r.initial_state;
  const double rho = r.floquet.spectral_radius;
  const double steps = static_cast<double>(r.steps) / static_cast<double>(r.integrations);
  const double tol =
      SettledTolerance(rho, cycles, Weighted(so, y0, r.initial_state), steps, so.newton_tolerance);
  const double error = Weighted(so, settled, expected);
  test::FigureValue("floating sun: settled - turned orbit (weighted)", error, "-");
  test::FigureValue("floating sun: tolerance (weighted)", tol, "-");
  CHECK(r.floquet.stability == dynamics::Stability::kStable);
  CHECK(error <= tol);
  // Without the turn the settled state is not the orbit: the period map is needed.
  const double unturned = Weighted(so, settled, r.initial_state);
  test::FigureValue("floating sun: settled - unturned orbit (weighted)", unturned, "-");
  CHECK(unturned > tol);
}

TEST_CASE(
    "paper stage, springs: the branch continued over the sun speed is, at each of several "
    "speeds, the state a long time integration settles into",
    "[crosscheck][dynamics][periodic][slow]") {
  const auto rig = SpringRig(1000, transmission::SunSupport::kFixed);
  const dynamics::DynamicModel& base = *rig.model;
  dynamics::StageBranchOptions o;
  o.start = 1000;
  o.end = 1250;
  o.simulation = Integration();
  o.max_step = 0.2;
  int streamed = 0;
  const dynamics::StageBranchRecord rec =
      dynamics::ContinueStageBranch(base, o, [&](const dynamics::StageBranchRecord& so_far) {
        CHECK(static_cast<int>(so_far.points.size()) == streamed + 1);
        streamed = static_cast<int>(so_far.points.size());
      });
  INFO(rec.message + rec.figures_message);
  REQUIRE(rec.ok());
  CHECK(streamed == static_cast<int>(rec.points.size()));
  test::FigureValue("speed branch points", static_cast<double>(rec.points.size()), "-");
  test::FigureValue("speed branch CPU", rec.cpu_seconds, "s");
  test::FigureValue("speed branch steps", static_cast<double>(rec.steps), "-");
  REQUIRE(rec.points.size() >= 3);
  CHECK(rec.points.front().sun_speed_rpm == Approx(1000).epsilon(1e-12));
  CHECK(rec.points.back().sun_speed_rpm >= o.end);
  const dynamics::ShootingOptions so = Shooting(base);
  const dynamics::StagePeriodicSystem system(base, solvers::Backend::kActiveSetNewton, {});
  for (const std::size_t i : {std::size_t{0}, rec.points.size() / 2, rec.points.size() - 2}) {
    const dynamics::StageBranchPoint& q = rec.points[i];
    Eigen::VectorXd p = system.DefaultParameters();
    p(0) = q.sun_speed_rpm;
    const dynamics::DynamicModel& m = system.ModelAt(p);
    // T = 2π/(z_r |ω_c|) at this speed: the speed entered the period.
    CHECK(q.period == Approx(rig.stage->mesh_cycle() / std::abs(m.carrier_speed())).epsilon(1e-14));
    const Eigen::VectorXd y0 = QuasiStaticState(m);
    const int cycles = 60;
    const Eigen::VectorXd settled = Settle(m, y0, q.period, cycles);
    // The corrector's orbit: R to newton_tolerance (weighted) like the shooting's; steps per
    // period from the branch's own count, an upper bound of one period's (the mean over every
    // integration, each a period).
    const double steps = static_cast<double>(rec.steps) /
                         static_cast<double>(rec.integrations + rec.plain_integrations);
    const double rho = q.spectral_radius;
    const double tol =
        SettledTolerance(rho, cycles, Weighted(so, y0, q.state), steps, 100.0);
    const double error = Weighted(so, settled, q.state);
    test::FigureValue("speed branch at " + std::to_string(q.sun_speed_rpm) +
                          " rpm: settled - orbit (weighted)",
                      error, "-");
    CHECK(error <= tol);
    CHECK(q.stability == dynamics::Stability::kStable);
  }
}

TEST_CASE("stage branch: bad input names the field, its value and the rule",
          "[crosscheck][dynamics][periodic]") {
  const auto rig = SpringRig(1000, transmission::SunSupport::kFixed);
  dynamics::StageBranchOptions o;
  o.simulation = Integration();
  o.start = 1000;
  o.end = 1000;
  CHECK_THROWS_WITH(dynamics::ContinueStageBranch(*rig.model, o),
                    "stage branch: end = 1000: equals start = 1000: the range must have non-zero "
                    "width");
  o.end = 2000;
  o.parameter = "speed";
  CHECK_THROWS_WITH(dynamics::ContinueStageBranch(*rig.model, o),
                    Catch::StartsWith("stage branch: parameter = 'speed': not a parameter of "
                                      "the stage (its parameters: sun_speed_rpm, sun_torque_Nm, "
                                      "mesh_damping_ratio, errors.pin.planetK.radial_um"));
  o.parameter = dynamics::StagePeriodicSystem::kSunSpeed;
  o.period.mesh_cycles = 24;
  o.period.reasons = {"planet1 run-out: 24 mesh cycles"};
  CHECK_THROWS_WITH(dynamics::ContinueStageBranch(*rig.model, o),
                    Catch::Contains("the stage's period = 24 mesh cycles (planet1 run-out: 24 "
                                    "mesh cycles): must be <= max_period_mesh_cycles = 4"));
}

TEST_CASE("the stage's period: the common period of the mesh and the rotations its errors need",
          "[crosscheck][dynamics][periodic]") {
  const auto rig = SpringRig(1000, transmission::SunSupport::kFixed);
  geometry::StageSpec spec = rig.stage->spec();
  CHECK(dynamics::StagePeriodMeshCycles(geometry::Stage(spec), {}).mesh_cycles == 1);
  // 16/24/65: a planet's run-out repeats after z_p = 24 cycles, the sun's after z_s = 16, both
  // after lcm = 48; the ring's (held) after a carrier turn, z_r = 65 cycles.
  spec.planet_runouts.assign(3, {});
  spec.planet_runouts[0].amplitude = 20e-6;
  CHECK(dynamics::StagePeriodMeshCycles(geometry::Stage(spec), {}).mesh_cycles == 24);
  spec.sun_runout.amplitude = 10e-6;
  const dynamics::StagePeriod both = dynamics::StagePeriodMeshCycles(geometry::Stage(spec), {});
  CHECK(both.mesh_cycles == 48);
  CHECK(both.reasons.size() == 2);
  spec.ring_runout.amplitude = 10e-6;
  CHECK(dynamics::StagePeriodMeshCycles(geometry::Stage(spec), {}).mesh_cycles == 48 * 65);
}

TEST_CASE(
    "paper stage, springs: a branch over planet 2's pin error at fixed speed equals, point by "
    "point, independent shooting runs of scenes with that error written in",
    "[crosscheck][dynamics][periodic][slow]") {
  const auto base = Rig("");
  dynamics::StageBranchOptions o;
  o.parameter = kKey;
  o.start = 0;
  o.end = 2;
  o.max_step = 0.5;
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
  // The speed stays the scene's (rpm → rad/s → rpm: round-off only).
  for (const dynamics::StageBranchPoint& q : rec.points)
    CHECK(q.sun_speed_rpm == Approx(1000).epsilon(1e-14));

  // Steps per period: the branch's mean over every period it integrated.
  const double steps = static_cast<double>(rec.steps) /
                       static_cast<double>(rec.integrations + rec.plain_integrations);
  double k_gamma_first = 0;
  for (const std::size_t i : {std::size_t{1}, rec.points.size() / 2, rec.points.size() - 1}) {
    const dynamics::StageBranchPoint& q = rec.points[i];
    const auto rig = Rig(PinEntry(q.parameter));
    REQUIRE(rig.scene.stage.pin_errors.at(1).tangential == q.parameter * 1e-6);
    const IndependentShooting shot = ShootAgainstPoint(rig, q, steps);
    test::FigureValue("pin-error branch at " + std::to_string(q.parameter) +
                          " um: independent shooting - point (weighted)",
                      shot.error, "-");
    CHECK(shot.error <= shot.tolerance);
    CHECK(shot.stability == q.stability);
    if (i == 1) k_gamma_first = q.k_gamma;
  }
  // A pin error moves load between the planets: the largest share K_γ grows with its size.
  CHECK(rec.points.back().k_gamma > k_gamma_first);
}

TEST_CASE(
    "paper stage, springs: short branches over the sun torque and over the mesh damping ratio at "
    "1000 rpm: a point of each is the orbit an independent shooting finds with that value in the "
    "scene",
    "[crosscheck][dynamics][periodic]") {
  struct Case {
    const char* parameter;   // the scene's key, also the line that writes it
    const char* scene_line;  // the scene's line with the base value
    double start, end;
  };
  // From the scene's own values: the torque 10 % up (its sign the scene's), the damping doubled.
  const Case cases[] = {{"sun_torque_Nm", "sun_torque_Nm = -600.0", -600, -660},
                        {"mesh_damping_ratio", "mesh_damping_ratio = 0.05", 0.05, 0.1}};
  const std::string base_text = test::SceneText("paper_stage.toml");
  const auto base = RigOfText(base_text);
  for (const Case& c : cases) {
    dynamics::StageBranchOptions o;
    o.parameter = c.parameter;
    o.start = c.start;
    o.end = c.end;
    o.initial_step = 0.35;  // three or four points over the range
    o.max_step = 0.35;
    o.simulation = Integration();
    const dynamics::StageBranchRecord rec = dynamics::ContinueStageBranch(*base.model, o);
    INFO(c.parameter << ": " << rec.message << rec.figures_message);
    REQUIRE(rec.ok());
    test::FigureValue(std::string(c.parameter) + " branch points",
                      static_cast<double>(rec.points.size()), "-");
    test::FigureValue(std::string(c.parameter) + " branch CPU", rec.cpu_seconds, "s");
    REQUIRE(rec.points.size() >= 3);
    CHECK(rec.points.front().parameter == c.start);
    CHECK(std::abs(rec.points.back().parameter - c.start) >= std::abs(c.end - c.start));
    // The speed stays the scene's (rpm → rad/s → rpm: round-off only).
    for (const dynamics::StageBranchPoint& q : rec.points)
      CHECK(q.sun_speed_rpm == Approx(1000).epsilon(1e-14));
    // The point inside the range nearest its middle, against shooting on a scene with its value
    // written in place of the scene's (its own rig: the stage, the model, the quasi-static start).
    const dynamics::StageBranchPoint& q = rec.points[rec.points.size() / 2];
    REQUIRE(base_text.find(c.scene_line) != std::string::npos);
    const auto rig = RigOfText(test::Replace(
        base_text, c.scene_line, std::string(c.parameter) + " = " + Exact(q.parameter)));
    const double steps = static_cast<double>(rec.steps) /
                         static_cast<double>(rec.integrations + rec.plain_integrations);
    const IndependentShooting shot = ShootAgainstPoint(rig, q, steps);
    test::FigureValue(std::string(c.parameter) + " branch at " + Exact(q.parameter) +
                          ": independent shooting - point (weighted)",
                      shot.error, "-");
    test::FigureValue(std::string(c.parameter) + " branch: tolerance (weighted)", shot.tolerance,
                      "-");
    CHECK(shot.error <= shot.tolerance);
    CHECK(shot.stability == q.stability);
    // And the start's value is not the point's: the branch moved the orbit by more than the
    // tolerance (else the check above would not tell a continued parameter from a fixed one).
    const IndependentShooting at_start = ShootAgainstPoint(base, q, steps);
    test::FigureValue(std::string(c.parameter) + " branch: base scene's orbit - point (weighted)",
                      at_start.error, "-");
    CHECK(at_start.error > shot.tolerance);
  }
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
