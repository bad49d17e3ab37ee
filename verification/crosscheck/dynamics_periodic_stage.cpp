// The periodic solver on the paper's stage (docs/periodic.md §3): a perfect stage (no errors) with
// spring contacts and the sun fixed, whose response repeats with the mesh cycle; the shooting
// orbit against the state a long time integration settles into.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "dynamics_fixtures.hpp"
#include "epicycle/dynamics/periodic.hpp"
#include "epicycle/dynamics/stage_periodic.hpp"
#include "epicycle/io/units.hpp"
#include "figures.hpp"

using namespace epicycle;

TEST_CASE(
    "paper stage, perfect, springs: the shooting orbit is the state a long time integration "
    "settles into",
    "[crosscheck][dynamics][periodic]") {
  test::RigOptions o;
  o.spring = 1e-9;
  o.spring_mesh_stiffness = 1.5e9;
  o.edit = [](transmission::DynamicSettings& s) { s.sun_speed = io::RpmToRadPerSecond(1000); };
  const auto rig = test::MakeRig(test::SceneText("paper_stage.toml"), "springs", o);
  const dynamics::DynamicModel& m = *rig.model;
  std::string dofs;
  for (int k = 0; k < m.size(); ++k) dofs += m.dofs()[k].Label() + "; ";
  test::Figure("stage DOFs: " + dofs);
  const dynamics::StagePeriodicSystem system(m, solvers::Backend::kActiveSetNewton, {});
  const int n = m.size();
  dynamics::ShootingOptions so;
  so.rtol = 1e-8;
  Eigen::VectorXd atol(2 * n);
  for (int k = 0; k < n; ++k) {
    atol(k) = m.dofs()[k].axis == dynamics::MotionDof::kRotation ? 1e-11 : 1e-12;
    atol(n + k) = atol(k) * 1e4;
  }
  so.atol = atol;
  Eigen::VectorXd y0 = Eigen::VectorXd::Zero(2 * n);
  y0.head(n) = m.QuasiStaticStart({}, solvers::Backend::kActiveSetNewton);
  const auto clock = std::chrono::steady_clock::now();
  const dynamics::ShootingResult r = dynamics::SolvePeriodicOrbit(system, so, y0);
  test::FigureValue("stage shooting wall time",
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - clock).count(),
                    "s");
  INFO(r.message);
  REQUIRE(r.status == dynamics::ShootingStatus::kConverged);
  test::FigureValue("stage shooting iterations", r.iterations, "-");
  test::FigureValue("stage shooting steps", static_cast<double>(r.steps), "-");
  test::FigureValue("stage spectral radius", r.floquet.spectral_radius, "-");
  // The project's time integration (dynamics::Simulate, CVODE on the stage's own right-hand
  // side) from the same start over 60 mesh cycles, at the same tolerances.
  const int cycles = 60;
  dynamics::SimulationOptions sim;
  sim.rtol = so.rtol;
  sim.atol_angle = 1e-11;
  sim.atol_length = 1e-12;
  sim.rate_scale = 1e4;
  const dynamics::SimulationResult run =
      dynamics::Simulate(m, sim, y0.head(n), y0.tail(n), {cycles * r.period});
  REQUIRE(run.completed());
  test::FigureValue("stage Simulate 60 cycles wall time", run.stats.wall_seconds, "s");
  test::FigureValue("stage Simulate steps", static_cast<double>(run.stats.steps), "-");
  Eigen::VectorXd settled(2 * n);
  settled << run.samples.back().d, run.samples.back().v;
  // Weighted by the integrator's tolerance per component, rtol |y_k| + atol_k.
  auto weighted = [&](const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
    double worst = 0;
    for (int k = 0; k < 2 * n; ++k)
      worst = std::max(worst, std::abs(a(k) - b(k)) / (so.rtol * std::abs(b(k)) + atol(k)));
    return worst;
  };
  // Tolerance (weighted): what is left of the transient, ρ^cycles times the start's distance
  // (ρ ≈ 1e-3: nothing), plus the integration's error, one local tolerance a step contracted by ρ
  // each cycle (steps a cycle/(1 − ρ)), plus the shooting's own R to newton_tolerance over
  // (1 − ρ).
  const double rho = r.floquet.spectral_radius;
  const double steps = static_cast<double>(r.steps) / static_cast<double>(r.integrations);
  const double tol = std::pow(rho, cycles) * weighted(y0, r.initial_state) +
                     (steps + so.newton_tolerance) / (1 - rho);
  const double settled_error = weighted(settled, r.initial_state);
  test::FigureValue("stage settled - orbit (weighted)", settled_error, "-");
  test::FigureValue("stage settled tolerance (weighted)", tol, "-");
  CHECK(settled_error <= tol);
  CHECK(r.floquet.stability == dynamics::Stability::kStable);

  // Started elsewhere (the quasi-static start with its deviations halved: a different transient),
  // the same orbit: both shootings stop with R to newton_tolerance, each an orbit error of at most
  // newton_tolerance/(1 − ρ).
  Eigen::VectorXd other = y0;
  other.head(n) *= 0.5;
  const dynamics::ShootingResult r2 = dynamics::SolvePeriodicOrbit(system, so, other);
  REQUIRE(r2.status == dynamics::ShootingStatus::kConverged);
  const double other_error = weighted(r2.initial_state, r.initial_state);
  test::FigureValue("stage second start - orbit (weighted)", other_error, "-");
  CHECK(other_error <= 2 * (so.newton_tolerance + steps) / (1 - rho));
}
