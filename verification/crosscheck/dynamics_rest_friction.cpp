// The quasi-static driver with friction at rest (docs/model.md §9, docs/quasistatic.md
// "Friction at rest") against the dynamic model with the same friction at low speed (issue 25,
// must-show 2 and 3): the dynamic model is the reference, an independent computation (an
// integrated motion with masses, damping and friction evaluated at the motion's own velocities).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "dynamics_fixtures.hpp"
#include "epicycle/dynamics/simulation.hpp"
#include "epicycle/io/units.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "figures.hpp"
#include "tolerance_floor.hpp"

using namespace epicycle;
using test::Figure;
using test::RigOptions;
using test::Run;
using test::Sci;
using test::Times;
using test::VerifyRow;
using test::WithRunout;
using transmission::SunSupport;

namespace {

// The gap between a dynamic run and the quasi-static solver with friction at rest at the same
// carrier angles, split as the velocity terms split it: `motion` the dynamic model as integrated
// (its deviation rates in the damping and in the friction's sliding and rolling speeds), `rest`
// the same model at the same positions with the deviation rates set to 0 (no damping; friction of
// the rigid kinematics, as the quasi-static model has it): what is left is the inertial terms.
struct FrictionGap {
  double motion = 0;         // largest |LSR_dyn − LSR_qs| [-]
  double rest = 0;           // largest |LSR_dyn(v = 0) − LSR_qs| [-]
  double power_motion = 0;   // mean P_f of the dynamic samples [W]
  double power_rest = 0;     // mean P_f of the dynamic model at v = 0 [W]
  double power_qs = 0;       // mean P_f of the quasi-static positions [W]
  int compared = 0;          // samples whose quasi-static position converged
  int skipped = 0;  // positions whose friction fixed point did not settle, or within 10 v_ε of a pitch point
};

FrictionGap RestFrictionGap(const test::DynamicRig& rig, transmission::FrictionLaw law,
                            const dynamics::SimulationOptions& so,
                            const std::vector<dynamics::DynamicSample>& samples) {
  FrictionGap g;
  transmission::QuasiStaticOptions qo;
  qo.friction = rig.model->settings().friction;
  qo.sun_speed = rig.model->settings().sun_speed;
  auto solver = solvers::MakeContactSolver(so.backend);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(rig.model->size());
  for (const dynamics::DynamicSample& s : samples) {
    const auto q =
        transmission::SolvePosition(*rig.stage_model, s.carrier_angle, rig.scene.loads, qo);
    if (q.status == transmission::StageStatus::kFrictionNotSettled) {
      ++g.skipped;
      continue;
    }
    bool zone = false;
    for (Eigen::Index j = 0; j < q.sliding_velocity.size(); ++j)
      zone = zone || (q.solution.force(j) > 0 &&
                      std::abs(q.sliding_velocity(j)) < 10 * qo.friction.smoothing_velocity);
    if (zone) {
      ++g.skipped;
      continue;
    }
    REQUIRE(q.converged);
    REQUIRE(q.friction == (law != transmission::FrictionLaw::kOff));
    dynamics::Evaluation e;
    rig.model->Evaluate(s.time, s.d, zero, *solver, so.contact, &s.evaluation, &e);
    REQUIRE(e.ok);
    ++g.compared;
    for (std::size_t i = 0; i < q.load_sharing.size(); ++i) {
      g.motion = std::max(g.motion, std::abs(s.load_sharing[i] - q.load_sharing[i]));
      const double rest = e.sun_mesh_torque[i] / -rig.scene.loads.sun_torque;
      g.rest = std::max(g.rest, std::abs(rest - q.load_sharing[i]));
    }
    g.power_motion += s.evaluation.friction_power;
    g.power_rest += e.friction_power;
    g.power_qs += q.friction_power;
  }
  const double n = std::max(g.compared, 1);
  g.power_motion /= n;
  g.power_rest /= n;
  g.power_qs /= n;
  return g;
}

}  // namespace

TEST_CASE(
    "quasi-static limit with friction: the dynamic run with friction tends to the quasi-static "
    "friction at rest with the speed, fixed and floating sun",
    "[crosscheck][slow][dynamics][friction]") {
  // As the friction-off limit ("quasi-static limit: the dynamic LSR tends to the quasi-static
  // sweep with the speed"): FE structural compliance without the local term, planet 1 with 20 um
  // run-out; a short window of 6 mesh cycles, 2 outputs each, at 60 and 30 rpm. The quasi-static
  // solution with friction at rest is the dynamic model's with its velocity terms dropped but the
  // rigid kinematics that set the sliding. What separates them at low speed: the mesh damping
  // (∝ speed), the inertial terms (∝ speed²), and friction's response to the deviation rates in
  // the sliding and rolling speeds. The rates are ∝ speed as the rigid speeds are, so a law of the
  // speeds' ratio (Xu & Kahraman: μ ∝ SR^1.036) keeps a gap that does not fall with the speed
  // (docs/quasistatic.md, "Friction at rest": 5e-5 with the sun fixed, 4e-3 floating, in LSR at
  // 30 rpm on this case): the quasi-static model leaves the rates out by definition. The law whose
  // μ does not depend on the speeds is the constant one away from the pitch point: μ_s = μ
  // tanh(v_s/v_ε) with v_ε = 1e-5 m/s, and positions where a loaded contact slides slower than 10
  // v_ε at rest left out (tanh 10 = 1 − 4e-9). There friction adds no velocity term and the
  // friction-off derivation carries over: halving the speed must at least halve the gap (tested ≥
  // 2/1.25, that test's allowance for the mix of the two terms and the output sampling), down to
  // the floor of the tolerances: what the integrator's error test lets through in LSR at each run's
  // samples (ToleranceFloor, from rtol 1e-8 and the default absolute tolerances), the contact
  // solves' 1e-10 below it.
  const SunSupport sun = GENERATE(SunSupport::kFixed, SunSupport::kFloating);
  const transmission::FrictionLaw law = transmission::FrictionLaw::kConstant;
  const char* sun_name = sun == SunSupport::kFixed ? "fixed" : "floating";
  const std::string name = transmission::FrictionLawName(law) + ", sun " + sun_name;
  const double speeds[2] = {60.0, 30.0};
  FrictionGap gap[2];
  double tolerance_floor[2];
  for (int k = 0; k < 2; ++k) {
    RigOptions o;
    o.sun = sun;
    o.local_terms = false;
    o.edit = [&](transmission::DynamicSettings& s) {
      s.sun_speed = io::RpmToRadPerSecond(speeds[k]);
      s.friction.law = law;
      s.friction.smoothing_velocity = 1e-5;
    };
    const auto rig = test::MakeRig(WithRunout(test::SceneText("paper_stage.toml")), "runout", o);
    dynamics::SimulationOptions so;
    so.rtol = 1e-8;
    const auto r = Run(rig, Times(*rig.model, *rig.stage, 6, 2), so);
    REQUIRE(r.completed());
    gap[k] = RestFrictionGap(rig, law, so, r.samples);
    tolerance_floor[k] =
        test::ToleranceFloor(rig, so, r.stats.rate_scale, r.samples,
                             [&](const dynamics::Evaluation& e, std::vector<double>& out) {
                               for (double t : e.sun_mesh_torque)  // LSR_i = T_i/(−T_s) [-]
                                 out.push_back(t / -rig.scene.loads.sun_torque);
                             });
    Figure("friction at rest, " + name + ", " + std::to_string(speeds[k]) +
           " rpm: largest |LSR - LSR_qs| " + Sci(gap[k].rest) +
           " at the run's positions without "
           "its rates, " +
           Sci(gap[k].motion) + " as integrated, over " + std::to_string(gap[k].compared) +
           " samples (" + std::to_string(gap[k].skipped) + " left out); mean friction power " +
           Sci(gap[k].power_qs, 6) + " W at rest, " + Sci(gap[k].power_rest, 6) +
           " W without the rates, " + Sci(gap[k].power_motion, 6) + " W as integrated; " +
           std::to_string(r.stats.steps) +
           " steps; the tolerances "
           "allow " +
           Sci(tolerance_floor[k]) + " in LSR");
  }
  REQUIRE(gap[1].compared >= 10);
  // The floor: each run's LSR may be off by what its tolerances let through (ToleranceFloor), the
  // 60 rpm run's share halved with its gap.
  const double floor = tolerance_floor[1] + tolerance_floor[0] / 2 * 1.25;
  const bool pass = gap[1].motion <= gap[0].motion / 2 * 1.25 + floor;
  VerifyRow(
      "dynamic LSR with friction -> quasi-static friction at rest, " + name +
          " (60, 30 rpm; 6 mesh cycles; run-out)",
      "dynamic model with the same friction law",
      "largest gap " + Sci(gap[0].motion) + " at 60 rpm, " + Sci(gap[1].motion) + " at 30 rpm",
      "ratio " + Sci(gap[0].motion / gap[1].motion, 2),
      "ratio >= 2/1.25 (gap <= the tolerances' floor " + Sci(floor) + ")", pass);
  CHECK(pass);
  // Must-show 3: the friction power P_f = Σ μ_s F v_s. In motion v_s carries the deviation rates,
  // ∝ speed as the rigid sliding is: a relative part that does not fall with the speed (1.2e-3
  // here, reported). Without the rates, at the run's own positions (the dynamic model evaluated
  // with ḋ = 0), the forces differ from the quasi-static ones by the positional terms above only:
  // the relative gap of the mean power follows the same speed law.
  double rel[2];
  for (int k = 0; k < 2; ++k)
    rel[k] = std::abs(gap[k].power_rest - gap[k].power_qs) / gap[k].power_qs;
  const double power_floor = 1e-6;
  const bool power = rel[1] <= rel[0] / 2 * 1.25 + power_floor;
  VerifyRow("mean friction power, dynamic vs quasi-static at rest, " + name + " (60, 30 rpm)",
            "dynamic model's friction power (steps CSV friction_power_W) at the run's positions",
            Sci(gap[1].power_qs, 6) + " W at rest, " + Sci(gap[1].power_rest, 6) +
                " W without the rates, " + Sci(gap[1].power_motion, 6) +
                " W as integrated (30 rpm)",
            "relative " + Sci(rel[0]) + " at 60 rpm, " + Sci(rel[1]) + " at 30 rpm",
            "ratio >= 2/1.25 (<= 1e-6 floor)", power);
  CHECK(power);
}
