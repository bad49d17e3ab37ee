// The dynamic model (docs/model.md §7, docs/dynamic.md) against references that do not come from
// it: the quasi-static solver at low speed, energy conservation with constant compliance, the
// sun's torque balance from the integrator's own interpolant, the planet-phasing rules of Parker
// (2000) on the spectrum of a perfect stage, self-consistency of the integrators, friction work
// against the efficiency at the ports, and the determinism of the right-hand side.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include "dynamics_fixtures.hpp"
#include "epicycle/dynamics/simulation.hpp"
#include "epicycle/dynamics/dynamic_summary.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "figures.hpp"
#include "lin_parker.hpp"
#include "epicycle/io/units.hpp"

using namespace epicycle;
using dynamics::DynamicSample;
using test::Figure;
using test::Harmonic;
using test::QuasiStaticGap;
using test::RigOptions;
using test::Run;
using test::Sci;
using test::Times;
using test::VerifyRow;
using test::WithRunout;

TEST_CASE("quasi-static limit: the dynamic LSR tends to the quasi-static sweep with the speed",
          "[crosscheck][slow][dynamics]") {
  // FE structural compliance without the local term (its curvature jumps where an involute meets
  // a tip round: docs/dynamic.md), friction off, planet 1 with 20 um run-out, sun fixed, one
  // planet revolution relative to the carrier (24 mesh cycles, 2 outputs each). What separates the
  // dynamic from the quasi-static solution at low speed are the velocity terms: mesh damping on
  // contacts whose overlap changes under the rigid motion (the off-line-of-action tip contacts, and
  // the run-out), proportional to the speed, and the inertial terms, proportional to its square.
  // Halving the speed must therefore at least halve the gap (ratio ≥ 2, tested ≥ 2/1.25 for the mix
  // of the two and the output sampling), down to the floor of the tolerances (integrator rtol 1e-8
  // on deflections of ~1e-3 rad, contact solver 1e-10: LSR floor below 1e-6).
  double gap[2];
  const double speeds[2] = {120.0, 60.0};
  for (int k = 0; k < 2; ++k) {
    RigOptions o;
    o.local_terms = false;
    o.edit = [&](transmission::DynamicSettings& s) {
      s.sun_speed = io::RpmToRadPerSecond(speeds[k]);
      s.friction.law = transmission::FrictionLaw::kOff;
    };
    const auto rig = test::MakeRig(WithRunout(test::SceneText("paper_stage.toml")), "runout", o);
    dynamics::SimulationOptions so;
    so.rtol = 1e-8;
    const auto r = Run(rig, Times(*rig.model, *rig.stage, 24, 2), so);
    REQUIRE(r.completed());
    gap[k] = QuasiStaticGap(rig, r.samples);
    Figure("quasi-static limit at " + std::to_string(speeds[k]) + " rpm: largest |LSR - LSR_qs| " +
           Sci(gap[k]) + ", " + std::to_string(r.stats.steps) + " steps");
  }
  const double floor = 1e-6;
  const bool pass = gap[1] <= gap[0] / 2 * 1.25 + floor;
  VerifyRow(
      "dynamic LSR -> quasi-static linearly in speed (120, 60 rpm; a planet revolution; "
      "run-out)",
      "quasi-static solver at the same carrier angles",
      "largest gap " + Sci(gap[0]) + " at 120 rpm, " + Sci(gap[1]) + " at 60 rpm",
      "ratio " + Sci(gap[0] / gap[1], 2), "ratio >= 2/1.25 (gap <= 1e-6 floor)", pass);
  CHECK(pass);
}

namespace {

// The energy balance B = E_kin + E_el − W_ext + W_diss of one output and the bound on its drift
// that CVODE's error control implies. B is a first integral of the ODE (B' = 0 on exact
// trajectories, W_ext and W_diss being states), so after N steps
//   B(y_N) − B(y_0) = Σ_n [B(y_n+1) − B(φ_h(y_n))] = Σ_n ∇B·le_n + O(le²),
// the sum of the local errors projected on ∇B, with no amplification by the dynamics. The error
// test keeps ‖le‖_WRMS ≤ 1 with weights 1/tol_i, tol_i = rtol|y_i| + atol_i, so by Cauchy–Schwarz
// |∇B·le| ≤ √n_y ‖∇B ∘ tol‖₂ per step: the drift is at most N_steps √n_y max ‖∇B ∘ tol‖₂. The
// gradient is taken at the outputs by central differences of the model's own energies (exact for
// the kinetic energy, quadratic in the rates; the springs' energy is piecewise quadratic).
double StepBound(const test::DynamicRig& rig, const dynamics::SimulationOptions& so,
                 double rate_scale, const DynamicSample& s) {
  const dynamics::DynamicModel& m = *rig.model;
  auto solver = solvers::MakeContactSolver(so.backend);
  auto energy = [&](const Eigen::VectorXd& d, const Eigen::VectorXd& v) {
    dynamics::Evaluation e;
    m.Evaluate(s.time, d, v, *solver, so.contact, &s.evaluation, &e);
    return e.kinetic_energy + e.elastic_energy;
  };
  double sum2 = 0;
  const int n = m.size();
  for (int i = 0; i < n; ++i) {
    const bool rotation = m.dofs()[i].axis == dynamics::MotionDof::kRotation;
    const double atol = rotation ? so.atol_angle : so.atol_length;
    const double h = rotation ? 1e-8 : 1e-9;  // [rad], [m]: small against the deflections
    Eigen::VectorXd dp = s.d, dm = s.d, vp = s.v, vm = s.v;
    dp(i) += h;
    dm(i) -= h;
    vp(i) += h;
    vm(i) -= h;
    const double gd = (energy(dp, s.v) - energy(dm, s.v)) / (2 * h);
    const double gv = (energy(s.d, vp) - energy(s.d, vm)) / (2 * h);
    sum2 += std::pow(gd * (so.rtol * std::abs(s.d(i)) + atol), 2) +
            std::pow(gv * (so.rtol * std::abs(s.v(i)) + atol * rate_scale), 2);
  }
  sum2 += std::pow(so.rtol * std::abs(s.external_work) + so.atol_energy, 2) +
          std::pow(so.rtol * std::abs(s.dissipated_work) + so.atol_energy, 2);
  return std::sqrt(2.0 * n + 2.0) * std::sqrt(sum2);
}

}  // namespace

TEST_CASE(
    "energy: with constant compliance, input work = kinetic + elastic energy, with damping "
    "and friction, the loss equals their integrated power",
    "[crosscheck][dynamics]") {
  // Independent linear springs (c = 1e-9 m/N, no local term, no coupling) make the contact
  // forces the gradient of the stored energy ½FᵀCF of the overlaps δ0(q): the model is then
  // conservative (the FE compliance varies with the contact's place on the flank, and the forces
  // omit ½Fᵀ(∂C/∂q)F; docs/dynamic.md). The balance E(t) − E(0) = W_ext − W_diss is exact for
  // the ODE; what remains is the integrator's error, bounded by StepBound above. The deviations
  // are small (µm, µrad), so the absolute tolerances, not rtol, set that error: an imbalance that
  // is integration error shrinks with them (checked: all tolerances / 100 must cut it ≥ 10×,
  // where a non-conservative force would leave it unchanged).
  for (const bool dissipative : {false, true}) {
    RigOptions o;
    o.spring = 1e-9;
    o.spring_mesh_stiffness = 1.5e9;
    o.edit = [&](transmission::DynamicSettings& s) {
      s.sun_speed = io::RpmToRadPerSecond(1500);
      s.mesh_damping_ratio = dissipative ? 0.05 : 0.0;
      s.friction.law =
          dissipative ? transmission::FrictionLaw::kConstant : transmission::FrictionLaw::kOff;
      s.friction.coefficient = 0.05;
    };
    const auto rig = test::MakeRig(WithRunout(test::SceneText("paper_stage.toml")), "runout", o);
    double worst[2] = {0, 0}, bound = 0, lost = 0, throughput = 0;
    long steps = 0;
    for (int tight = 0; tight < 2; ++tight) {
      dynamics::SimulationOptions so;
      so.rtol = 1e-8;
      if (tight) so = test::Tightened(so, 100);
      const auto r = Run(rig, Times(*rig.model, *rig.stage, 2, 100), so);
      REQUIRE(r.completed());
      const dynamics::Evaluation start = test::StartEvaluation(rig, so);
      const double energy0 = start.kinetic_energy + start.elastic_energy;
      for (const DynamicSample& s : r.samples) {
        const double e = s.evaluation.kinetic_energy + s.evaluation.elastic_energy;
        worst[tight] =
            std::max(worst[tight], std::abs(e - energy0 - s.external_work + s.dissipated_work));
      }
      if (!tight) {
        double per_step = 0;
        for (const DynamicSample& s : r.samples)
          per_step = std::max(per_step, StepBound(rig, so, r.stats.rate_scale, s));
        steps = r.stats.steps;
        bound = static_cast<double>(steps) * per_step;
        lost = r.samples.back().dissipated_work;
        throughput =
            std::abs(rig.scene.loads.sun_torque * rig.model->sun_speed()) * r.samples.back().time;
      }
    }
    const bool converges = worst[1] <= worst[0] / 10;
    const bool pass =
        worst[0] <= bound && converges && (dissipative ? lost > 100 * worst[0] : lost == 0.0);
    VerifyRow(std::string("energy balance, spring contacts, 2 mesh cycles at 1500 rpm, ") +
                  (dissipative ? "damping 5 % and friction 0.05" : "no damping, no friction"),
              "E(t) - E(0) = W_ext - W_diss",
              "largest imbalance " + Sci(worst[0]) + " J (" + Sci(worst[0] / throughput) +
                  " of the throughput), " + Sci(worst[1]) +
                  " J with tolerances / 100; dissipated " + Sci(lost) + " J",
              Sci(worst[0]) + " J",
              "error-control bound " + Sci(bound) + " J (" + std::to_string(steps) +
                  " steps); / 100 tolerances: >= 10x smaller",
              pass);
    CHECK(worst[0] <= bound);
    CHECK(converges);
    if (dissipative) CHECK(lost > 100 * worst[0]);  // the balance resolves the loss
    if (!dissipative) CHECK(lost == 0.0);
  }
}

TEST_CASE(
    "sun balance: the sun-mesh torques equal the input torque less J_s times the sun's "
    "acceleration from the integrator's interpolant",
    "[crosscheck][dynamics]") {
  // θ̈_s is the derivative of CVODE's interpolating polynomial of θ̇_s at the output, not the
  // right-hand side's value; its error is about the local error of θ̇_s over a step,
  // (rtol|θ̇_s| + atol_v)/h. The tolerance is 10 times that, with h the mean step.
  RigOptions o;
  o.edit = [](transmission::DynamicSettings& s) { s.sun_speed = io::RpmToRadPerSecond(1500); };
  const auto rig = test::MakeRig(WithRunout(test::SceneText("paper_stage.toml")), "runout", o);
  dynamics::SimulationOptions so;
  const auto times = Times(*rig.model, *rig.stage, 2, 20);
  const auto r = Run(rig, times, so);
  REQUIRE(r.completed());
  const double h = times.back() / static_cast<double>(r.stats.steps);
  const int ks = rig.model->Find(dynamics::MotionDof::kSun, dynamics::MotionDof::kRotation);
  const double js = rig.model->mass()(ks);
  double worst = 0, vmax = 0;
  for (const DynamicSample& s : r.samples) {
    double mesh = 0;
    for (double t : s.evaluation.sun_mesh_torque) mesh += t;
    worst = std::max(worst, std::abs(mesh + rig.scene.loads.sun_torque - js * s.sun_acceleration));
    vmax = std::max(vmax, std::abs(s.v(ks)));
  }
  const double tol = 10 * js * (so.rtol * vmax + so.atol_angle * r.stats.rate_scale) / h;
  const bool pass = worst <= tol;
  VerifyRow("sun balance at every output (run-out, friction, 1500 rpm, 40 outputs)",
            "sum of sun-mesh torques = T_in - J_s d2theta_s/dt2 (interpolant)",
            "largest residual " + Sci(worst) + " N m", Sci(worst / 600.0) + " of |T_in|",
            Sci(tol) + " N m (10 x interpolant error)", pass);
  CHECK(pass);
}

TEST_CASE(
    "perfect gears: the sun's rotation carries only mesh harmonics 3, 6 and its net mesh "
    "force (carrier frame) only 1, 2, 4, 5 (Parker 2000, 16/65, 3 planets)",
    "[crosscheck][dynamics]") {
  // Planet phasing: harmonic l of the mesh frequency acts on rotation if l z_s/n is whole and on
  // translation if (l z_s ± 1)/n is. Exactly: turning the whole stage by 22 ring pitches (121.8°)
  // and advancing time by a third of a mesh cycle maps the stage onto itself with the planets
  // renumbered, so TE has period T_m/3 and the sun's force turns by 120° in the carrier frame.
  // Steady state after 6 mesh cycles (the slowest mode, ζ ≥ 0.04 at ≥ 3 kHz, has decayed by
  // e^-14), then 3 cycles of 128 samples each: the response rings at the mesh modes (3–7 kHz,
  // harmonics 10–22) and fewer samples alias allowed high harmonics into the forbidden bins
  // (with 32 per cycle, harmonic 27 lands on bin 5). Forbidden harmonics must stay below 1 % of
  // the largest allowed one (what remains: the transient, the integrator's error at rtol 1e-6).
  RigOptions o;
  o.edit = [](transmission::DynamicSettings& s) {
    s.sun_speed = io::RpmToRadPerSecond(1500);
    s.friction.law = transmission::FrictionLaw::kOff;
  };
  const auto rig = test::MakeRig(test::SceneText("paper_stage.toml"), "perfect", o);
  auto times = Times(*rig.model, *rig.stage, 6, 4);
  for (double t : Times(*rig.model, *rig.stage, 3, 128, 6.0)) times.push_back(t);
  const auto r = Run(rig, times);
  REQUIRE(r.completed());
  std::vector<std::complex<double>> te, force;
  for (std::size_t k = 6 * 4; k < r.samples.size(); ++k) {
    const DynamicSample& s = r.samples[k];
    te.emplace_back(s.transmission_error, 0.0);
    const Eigen::Vector2d f = geometry::Rotate(s.evaluation.sun_mesh_force, -s.carrier_angle);
    force.emplace_back(f.x(), f.y());
  }
  // Over 3 cycles harmonic l of the mesh frequency is DFT bin 3l.
  auto at = [](const std::vector<std::complex<double>>& x, int l) {
    return std::max(Harmonic(x, 3 * l), Harmonic(x, -3 * l));
  };
  const double rot_allowed = std::max(at(te, 3), at(te, 6));
  double rot_forbidden = 0, tr_forbidden = 0, tr_allowed = 0;
  for (int l : {1, 2, 4, 5}) {
    rot_forbidden = std::max(rot_forbidden, at(te, l));
    tr_allowed = std::max(tr_allowed, at(force, l));
  }
  for (int l : {3, 6}) tr_forbidden = std::max(tr_forbidden, at(force, l));
  Figure("TE harmonics 1..6 [urad]: " + Sci(at(te, 1) * 1e6) + " " + Sci(at(te, 2) * 1e6) + " " +
         Sci(at(te, 3) * 1e6) + " " + Sci(at(te, 4) * 1e6) + " " + Sci(at(te, 5) * 1e6) + " " +
         Sci(at(te, 6) * 1e6));
  Figure("sun net mesh force harmonics 1..6 [N] (carrier frame): " + Sci(at(force, 1)) + " " +
         Sci(at(force, 2)) + " " + Sci(at(force, 3)) + " " + Sci(at(force, 4)) + " " +
         Sci(at(force, 5)) + " " + Sci(at(force, 6)));
  const bool rot = rot_forbidden <= 0.01 * rot_allowed;
  const bool tr = tr_forbidden <= 0.01 * tr_allowed;
  VerifyRow("perfect stage, sun rotation (TE): harmonics 1, 2, 4, 5 against 3, 6",
            "Parker (2000) phasing: only l z_s/n whole",
            "largest forbidden " + Sci(rot_forbidden * 1e6) + " urad, allowed " +
                Sci(rot_allowed * 1e6) + " urad",
            Sci(rot_forbidden / rot_allowed), "0.01", rot);
  VerifyRow("perfect stage, sun net mesh force (carrier frame): harmonics 3, 6 against 1, 2, 4, 5",
            "Parker (2000) phasing: only (l z_s +- 1)/n whole",
            "largest forbidden " + Sci(tr_forbidden) + " N, allowed " + Sci(tr_allowed) + " N",
            Sci(tr_forbidden / tr_allowed), "0.01", tr);
  CHECK(rot);
  CHECK(tr);
}

TEST_CASE(
    "integrators: halving the tolerances moves the LSR trace by less than the stated bound, "
    "and the explicit method agrees within it",
    "[crosscheck][dynamics]") {
  // Bound: the global error of a stable integration stays within a modest multiple of rtol
  // times the size of what is integrated; LSR is a ratio of forces that follow the deflections
  // with the mesh stiffness, so its error is about κ·rtol with κ = (k δ)/F ~ 1 ... stated as
  // 100 rtol (absolute, on LSR ~ 1/3): 1e-4 at rtol 1e-6.
  RigOptions o;
  o.edit = [](transmission::DynamicSettings& s) { s.sun_speed = io::RpmToRadPerSecond(1500); };
  const auto rig = test::MakeRig(WithRunout(test::SceneText("paper_stage.toml")), "runout", o);
  const auto times = Times(*rig.model, *rig.stage, 2, 20);
  dynamics::SimulationOptions a, b, c;
  b.rtol = a.rtol / 2;
  b.atol_angle = a.atol_angle / 2;
  b.atol_length = a.atol_length / 2;
  // The explicit second opinion at a tenth of the tolerances: at the same rtol its own error is
  // the larger one (measured: ERK at 1e-6 against ERK at 1e-7 1.7e-4, BDF at 1e-6 against BDF at
  // 1e-7 3.0e-5, the two at 1e-7 6.9e-6 apart), so it checks the BDF run, not itself.
  c.integrator = dynamics::Integrator::kArkodeErk;
  c.rtol = a.rtol / 10;
  c.atol_angle = a.atol_angle / 10;
  c.atol_length = a.atol_length / 10;
  const auto ra = Run(rig, times, a), rb = Run(rig, times, b), rc = Run(rig, times, c);
  REQUIRE(ra.completed());
  REQUIRE(rb.completed());
  REQUIRE(rc.completed());
  auto diff = [](const dynamics::SimulationResult& x, const dynamics::SimulationResult& y) {
    double w = 0;
    for (std::size_t k = 0; k < x.samples.size(); ++k)
      for (std::size_t i = 0; i < x.samples[k].load_sharing.size(); ++i)
        w = std::max(w, std::abs(x.samples[k].load_sharing[i] - y.samples[k].load_sharing[i]));
    return w;
  };
  const double bound = 100 * a.rtol;
  const double half = diff(ra, rb), erk = diff(ra, rc);
  Figure("CVODE steps " + std::to_string(ra.stats.steps) + ", evaluations " +
         std::to_string(ra.stats.rhs_evaluations) + "; ERK steps " +
         std::to_string(rc.stats.steps) + ", evaluations " +
         std::to_string(rc.stats.rhs_evaluations));
  VerifyRow("halving rtol and atol (CVODE BDF, 2 mesh cycles, run-out, friction, 1500 rpm)",
            "the same run at half the tolerances", "largest LSR change " + Sci(half), Sci(half),
            Sci(bound) + " (100 rtol)", half <= bound);
  VerifyRow("explicit Dormand-Prince (ARKODE ERK, rtol 1e-7) against CVODE BDF, rtol 1e-6",
            "CVODE BDF", "largest LSR difference " + Sci(erk), Sci(erk), Sci(bound) + " (100 rtol)",
            erk <= bound);
  CHECK(half <= bound);
  CHECK(erk <= bound);
}

TEST_CASE(
    "friction: over whole mesh cycles the friction power equals the drop in efficiency "
    "measured at the ports (sun torque, carrier pins)",
    "[crosscheck][dynamics][friction]") {
  // Spring contacts (conservative without friction, see the energy test), Xu & Kahraman friction,
  // no damping. The efficiency comes from the ports: input W_in = T_s (θ_s(t) − θ_s(0)), from the
  // motion; output −W_carrier = W_in − W_ext, the work of the driven carrier through the pins.
  // The friction work W_f = ∫ Σ μ_s F v_s dt comes from the contacts. Over whole cycles in steady
  // state (after 6 settling cycles) the stored energy nearly returns to its value; exactly,
  //   1 − η = W_f / W_in + ΔE / W_in   to the integrator's global error, relative to W_in,
  // a balance between work measured at the ports and friction measured at the contacts. The
  // bound on that error is √N rtol for the N steps of the run: N local errors, each within rtol
  // by CVODE's error test, of random sign (a random walk). A fixed 10 rtol, used before, sat
  // inside the scatter of the error itself: changes of the contact solve at round-off level
  // (its stopping point inside the tolerance) moved the residual between 1.2e-8 and 1.7e-7 at
  // rtol 1e-8, with about 1e4 steps.
  RigOptions o;
  o.spring = 1e-9;
  o.spring_mesh_stiffness = 1.5e9;
  o.edit = [](transmission::DynamicSettings& s) {
    s.sun_speed = io::RpmToRadPerSecond(1500);
    s.mesh_damping_ratio = 0;
    s.friction.law = transmission::FrictionLaw::kXuKahraman;
  };
  const auto rig = test::MakeRig(test::SceneText("paper_stage.toml"), "friction", o);
  dynamics::SimulationOptions so;
  so.rtol = 1e-8;
  const auto times = Times(*rig.model, *rig.stage, 9, 4);
  const auto r = Run(rig, times, so);
  REQUIRE(r.completed());
  const DynamicSample& a = r.samples[6 * 4 - 1];
  const DynamicSample& b = r.samples.back();
  const int ks = rig.model->Find(dynamics::MotionDof::kSun, dynamics::MotionDof::kRotation);
  const double t_s = rig.scene.loads.sun_torque, ws = rig.model->sun_speed();
  const double w_in = t_s * (ws * (b.time - a.time) + b.d(ks) - a.d(ks));
  const double w_ext = b.external_work - a.external_work;
  const double w_f = b.dissipated_work - a.dissipated_work;  // friction only: no damping
  const double d_e = (b.evaluation.kinetic_energy + b.evaluation.elastic_energy) -
                     (a.evaluation.kinetic_energy + a.evaluation.elastic_energy);
  const double loss = w_ext / w_in, friction = w_f / w_in;
  const double steps = static_cast<double>(r.stats.steps);
  const double residual = std::abs(loss - friction - d_e / w_in), tol = std::sqrt(steps) * so.rtol;
  Figure("efficiency over 3 mesh cycles (spring contacts, Xu & Kahraman): eta = " +
         Sci(1 - loss, 6) + ", friction work / input " + Sci(friction));
  const bool pass = residual <= tol && w_f > 0;
  VerifyRow("mesh-cycle friction power against the drop in efficiency (3 cycles, 1500 rpm)",
            "1 - eta from the port works (sun torque, carrier pins)",
            "1 - eta = " + Sci(loss, 4) + ", friction work / input = " + Sci(friction, 4) +
                ", dE / input = " + Sci(d_e / w_in, 2),
            "residual " + Sci(residual),
            Sci(tol) + " (sqrt(N) rtol, N = " + std::to_string(r.stats.steps) + " steps)", pass);
  CHECK(w_f > 0);
  CHECK(residual <= tol);
}

TEST_CASE(
    "the right-hand side is deterministic: a warm-started contact solve ends where a cold "
    "one ends, to the solver's tolerance",
    "[crosscheck][dynamics]") {
  // The paper's stage with run-out, FE compliance and local terms, friction on: the evaluation
  // at a state warm-started from a neighbouring evaluation (1 us earlier, the planets turned by
  // 1e-6 rad) against the same evaluation solved cold. The contact solver's nondimensional
  // tolerance 1e-10 bounds the difference of the forces relative to the load scale (ℓ·F* with F*
  // ~ |T|/r_bs); the accelerations follow linearly: required 1e-8 relative to their largest.
  RigOptions o;
  const auto rig = test::MakeRig(WithRunout(test::SceneText("paper_stage.toml")), "warm", o);
  const auto& m = *rig.model;
  const Eigen::VectorXd d = m.QuasiStaticStart({}, solvers::Backend::kActiveSetNewton);
  const Eigen::VectorXd v = Eigen::VectorXd::Zero(m.size());
  auto solver = solvers::MakeContactSolver(solvers::Backend::kActiveSetNewton);
  Eigen::VectorXd nearby = d;
  for (int k = 0; k < m.size(); ++k)
    if (m.dofs()[k].axis == dynamics::MotionDof::kRotation) nearby(k) += 1e-6;
  dynamics::Evaluation warm, a, b;
  m.Evaluate(-1e-6, nearby, v, *solver, {}, nullptr, &warm);
  m.Evaluate(0.0, d, v, *solver, {}, &warm, &a);
  m.Evaluate(0.0, d, v, *solver, {}, nullptr, &b);
  REQUIRE(a.ok);
  REQUIRE(b.ok);
  REQUIRE(a.force.size() == b.force.size());
  const double load = std::abs(rig.scene.loads.sun_torque) / rig.stage->sun().base_radius();
  const double df = (a.force - b.force).cwiseAbs().maxCoeff() / load;
  const double da = (a.acceleration - b.acceleration).cwiseAbs().maxCoeff() /
                    b.acceleration.cwiseAbs().maxCoeff();
  VerifyRow("warm against cold contact solve inside the right-hand side",
            "the same evaluation solved cold",
            "force " + Sci(df) + " of T/r_bs, acceleration " + Sci(da) + " relative",
            Sci(std::max(df, da)), "1e-8", df <= 1e-8 && da <= 1e-8);
  CHECK(df <= 1e-8);
  CHECK(da <= 1e-8);
}

namespace {

// ∂d̈/∂d (velocity = false) or ∂d̈/∂ḋ (true) by central differences of the whole right-hand side
// with step h per coordinate (rotations h, translations h/10: about the same motion at the flank),
// each evaluation solved cold to the contact solver's tightest tolerance.
Eigen::MatrixXd RightHandSideDifferences(const dynamics::DynamicModel& m, const Eigen::VectorXd& d,
                                         const Eigen::VectorXd& v, bool velocity, double h) {
  auto solver = solvers::MakeContactSolver(solvers::Backend::kActiveSetNewton);
  solvers::ContactOptions tight;
  tight.tolerance = 1e-14;
  Eigen::MatrixXd j(m.size(), m.size());
  for (int k = 0; k < m.size(); ++k) {
    const double hk = m.dofs()[k].axis == dynamics::MotionDof::kRotation ? h : h / 10;
    Eigen::VectorXd dp = d, dm = d, vp = v, vm = v;
    (velocity ? vp : dp)(k) += hk;
    (velocity ? vm : dm)(k) -= hk;
    dynamics::Evaluation ep, em;
    m.Evaluate(0.0, dp, vp, *solver, tight, nullptr, &ep);
    m.Evaluate(0.0, dm, vm, *solver, tight, nullptr, &em);
    REQUIRE(ep.ok);
    REQUIRE(em.ok);
    j.col(k) = (ep.acceleration - em.acceleration) / (2 * hk);
  }
  return j;
}

// Largest column error of `j` against `reference`, relative to the reference's largest column.
double ColumnError(const Eigen::MatrixXd& j, const Eigen::MatrixXd& reference) {
  double worst = 0, scale = 0;
  for (int k = 0; k < j.cols(); ++k) {
    worst = std::max(worst, (j.col(k) - reference.col(k)).norm());
    scale = std::max(scale, reference.col(k).norm());
  }
  return worst / scale;
}

}  // namespace

TEST_CASE(
    "Jacobian with friction: the velocity Jacobian equals differences of the right-hand side, "
    "friction adds no error to the position Jacobian beyond its frozen contact geometry",
    "[crosscheck][dynamics][friction]") {
  // The paper's stage with run-out at 30 rpm, floating sun, FE compliance and local terms, Xu &
  // Kahraman friction: at low speed ∂μ/∂v_s ~ μ/V_e is large, the case where leaving friction out
  // of the Jacobian costs the integrator most. At the quasi-static start (t = 0, ḋ = 0):
  // - ∂d̈/∂ḋ: the contact forces do not depend on ḋ, so differences of the whole right-hand side
  //   test friction's velocity terms and the damping directly. The differences' own error is
  //   estimated by halving the step (Richardson: |D(h) − D(h/2)| bounds the truncation of D(h/2)
  //   to within a factor 4/3); required: friction adds no more than 10 times that estimate to
  //   the error the friction-free Jacobian has against the friction-free model's differences.
  // - ∂d̈/∂d: the Jacobian freezes the contact geometry (points, normals, levers), so it differs
  //   from the differences by the geometric terms whether friction is on or off; required: with
  //   friction no more than 1.5 times the error of the friction-free Jacobian of the same state.
  auto make = [](transmission::FrictionLaw law) {
    RigOptions o;
    o.sun = transmission::SunSupport::kFloating;  // translations too
    o.edit = [law](transmission::DynamicSettings& s) {
      s.sun_speed = io::RpmToRadPerSecond(30);
      s.friction.law = law;
    };
    return test::MakeRig(WithRunout(test::SceneText("paper_stage.toml")), "jacobian", o);
  };
  const auto with = make(transmission::FrictionLaw::kXuKahraman);
  const auto without = make(transmission::FrictionLaw::kOff);
  const auto& m = *with.model;
  const Eigen::VectorXd d = m.QuasiStaticStart({}, solvers::Backend::kActiveSetNewton);
  const Eigen::VectorXd v = Eigen::VectorXd::Zero(m.size());
  auto jacobian = [&](const dynamics::DynamicModel& model, Eigen::MatrixXd* dd,
                      Eigen::MatrixXd* dv) {
    auto solver = solvers::MakeContactSolver(solvers::Backend::kActiveSetNewton);
    solvers::ContactOptions tight;
    tight.tolerance = 1e-14;
    dynamics::Evaluation at;
    model.Evaluate(0.0, d, v, *solver, tight, nullptr, &at);
    REQUIRE(at.ok);
    model.Jacobian(0.0, d, v, at, dd, dv);
  };
  Eigen::MatrixXd dd, dv, dd0, dv0;
  jacobian(m, &dd, &dv);
  jacobian(*without.model, &dd0, &dv0);

  const double hv = 1e-6;
  const Eigen::MatrixXd fd_v = RightHandSideDifferences(m, d, v, true, hv);
  const Eigen::MatrixXd fd_v2 = RightHandSideDifferences(m, d, v, true, hv / 2);
  const double v_error = ColumnError(dv, fd_v2);
  const double v_estimate = ColumnError(fd_v, fd_v2);
  const double v_without = ColumnError(dv0, fd_v2);  // the Jacobian as it was without friction
  // The friction-free Jacobian of the friction-free model: the accuracy the model had before.
  const double v_error0 =
      ColumnError(dv0, RightHandSideDifferences(*without.model, d, v, true, hv / 2));
  const double v_tol = v_error0 + 10 * v_estimate;

  const Eigen::MatrixXd fd_d = RightHandSideDifferences(m, d, v, false, 1e-9);
  const Eigen::MatrixXd fd_d0 = RightHandSideDifferences(*without.model, d, v, false, 1e-9);
  const double d_error = ColumnError(dd, fd_d), d_error0 = ColumnError(dd0, fd_d0);

  Figure("Jacobian at 30 rpm, Xu & Kahraman: velocity part " + Sci(v_error) +
         " relative (friction off " + Sci(v_error0) + ", differences' own error " +
         Sci(v_estimate) + "; without friction's terms " + Sci(v_without) + "), position part " +
         Sci(d_error) + " (friction off: " + Sci(d_error0) + ")");
  VerifyRow("Jacobian with friction, velocity part (30 rpm, run-out, Xu & Kahraman)",
            "central differences of the right-hand side",
            "relative column error " + Sci(v_error) +
                " (friction's terms left out: " + Sci(v_without) + ")",
            Sci(v_error),
            Sci(v_tol) + " (friction off " + Sci(v_error0) + " + 10 x the differences' error)",
            v_error <= v_tol);
  VerifyRow("Jacobian with friction, position part (frozen contact geometry)",
            "central differences of the right-hand side; the friction-free Jacobian's error",
            "relative column error " + Sci(d_error) + " (friction off " + Sci(d_error0) + ")",
            Sci(d_error), Sci(1.5 * d_error0) + " (1.5 x friction off)", d_error <= 1.5 * d_error0);
  CHECK(v_error <= v_tol);
  CHECK(v_without > 100 * v_tol);  // friction's terms matter here: the check can fail
  CHECK(d_error <= 1.5 * d_error0);
}
