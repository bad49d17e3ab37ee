// Speed sweeps of the dynamic model (dynamics/speed_sweep.hpp, docs/speed_sweeps.md)
// against references that do not come from the sweep: the resonance speeds predicted by the
// linearised natural frequencies (SolveModes) and the mesh stiffness driver's range of the
// instantaneous mesh stiffness, and the quasi-static limit of the dynamic factor.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "dynamics_fixtures.hpp"
#include "epicycle/dynamics/speed_sweep.hpp"
#include "epicycle/io/units.hpp"
#include "epicycle/transmission/mesh_stiffness.hpp"
#include "figures.hpp"

using namespace epicycle;
using test::Figure;
using test::RigOptions;
using test::Sci;
using test::VerifyRow;

namespace {

std::string Fixed(double x, int digits = 0) {
  char b[40];
  std::snprintf(b, sizeof b, "%.*f", digits, x);
  return b;
}

// The paper's stage without errors, sun fixed, friction off (not the subject here; it costs
// evaluations), mesh damping ζ = 0.05.
test::DynamicRig PaperRig(bool local_terms) {
  RigOptions o;
  o.local_terms = local_terms;
  o.edit = [](transmission::DynamicSettings& s) {
    s.sun_speed = io::RpmToRadPerSecond(1000);
    s.friction.law = transmission::FrictionLaw::kOff;
  };
  return test::MakeRig(test::SceneText("paper_stage.toml"), "paper stage", o);
}

// Non-rigid natural frequencies [Hz] of `rig`'s linearisation with the mesh stiffnesses k.
std::vector<double> Frequencies(const test::DynamicRig& rig, const std::array<double, 2>& k) {
  dynamics::DynamicModel m = *rig.model;
  m.SetMeshStiffness(k[0], k[1]);
  Eigen::MatrixXd mm, kk;
  m.Linearise(0.0, &mm, &kk);
  std::vector<double> f;
  for (const dynamics::Mode& x : dynamics::SolveModes(mm, kk, m.ModeLayout()))
    if (!x.rigid) f.push_back(x.frequency);
  return f;
}

}  // namespace

TEST_CASE(
    "speed sweep: the TE amplitude and K_gamma peak where a mesh harmonic meets a linearised "
    "natural frequency, within the sweep's resolution",
    "[crosscheck][slow][dynamics][sweep]") {
  // The paper's stage (FE compliance with the local terms, as the mean mesh stiffness of the
  // modes), sun fixed, no errors: its modes are a rotational one (family k = 0, 3.03 kHz), a
  // double one whose planets move out of phase (k = ±1, 4.80 kHz: the translational family with
  // the sun held) and a second rotational one (6.74 kHz). Planet phasing (16 sun teeth, 3
  // planets) sends mesh harmonic 3 to k = 0 only and harmonics 4 and 5 to k = ±1 only. So the
  // sun's rotation (TE) must peak where harmonic 3 meets the first mode, and the load sharing
  // (K_γ: the out-of-phase planets) where harmonic 4 or 5 meets the k = ±1 mode.
  //
  // The coincidences are those of the linearisation with the mean *tangent* mesh stiffness
  // dF/dδ (MeanTangentMeshStiffness; the secant F/δ of MeanMeshStiffness is 6 % softer on this
  // stage and puts them 3.5 % too low). Resolution, derived: (1) the grid, ±Δn/2; (2) damping
  // moves an amplitude peak down by the factor √(1 − 2ζ_j²) (ζ_j the modal damping ratio, < 0.08
  // here: < 0.6 %). That is the first-order statement (the averaged system resonates at the
  // natural frequency of its mean stiffness). A bound that needs no averaging argument: over a
  // mesh cycle each mesh's stiffness runs between k_min and k_max, so K(t) lies between K(k_min)
  // and K(k_max) in the positive-semidefinite order (K = Σ k_m g gᵀ + bearings) and, by Weyl's
  // monotonicity, every frozen-time natural frequency lies between those of the two extreme
  // linearisations; both checks are made. The window: the plan's start-transient skip, then 3 mesh
  // cycles (the excitation of a perfect stage repeats every mesh cycle) at 64 samples (harmonic 6
  // at 10.7 samples per period: a sampled peak is within 1 − cos(π/10.7) = 4 % of the true one).
  const auto rig = PaperRig(true);
  // The mesh stiffness at each of 48 positions of a mesh cycle, tangent dF/dδ by a central
  // difference over ±5 % of the load (the local term's deflection grows less than linearly with
  // the load: small vibrations see the tangent, not the secant F/δ of MeanMeshStiffness).
  std::array<double, 2> kmin{INFINITY, INFINITY}, kmax{0, 0}, ktan{0, 0};
  const char* meshes[2] = {"sun-planet1", "planet1-ring"};
  for (int m = 0; m < 2; ++m) {
    const auto setup = transmission::MakeMeshPair(rig.scene, rig.stage.get(), meshes[m]);
    const geometry::GearPair pair(setup.spec);
    const transmission::FePairCompliance compliance(rig.scene, pair, test::SuiteTables());
    transmission::MeshStiffnessOptions opt;
    opt.positions = 48;
    transmission::MeshPairSetup up = setup, down = setup;
    up.torque *= 1.05;
    down.torque *= 0.95;
    const auto ru = transmission::ComputeMeshStiffness(up, pair, compliance, opt);
    const auto rd = transmission::ComputeMeshStiffness(down, pair, compliance, opt);
    REQUIRE(ru.failed + rd.failed == 0);
    for (std::size_t i = 0; i < ru.samples.size(); ++i) {
      const double k = (ru.samples[i].total_force - rd.samples[i].total_force) /
                       (ru.samples[i].approach - rd.samples[i].approach);
      kmin[m] = std::min(kmin[m], k);
      kmax[m] = std::max(kmax[m], k);
      ktan[m] += k / static_cast<double>(ru.samples.size());
    }
  }
  const std::vector<double> f_lo = Frequencies(rig, kmin), f_hi = Frequencies(rig, kmax),
                            f_sec = Frequencies(rig, {rig.model->sun_mesh_stiffness(),
                                                      rig.model->ring_mesh_stiffness()});
  Figure("mean mesh stiffness secant " + Sci(rig.model->sun_mesh_stiffness()) + ", " +
         Sci(rig.model->ring_mesh_stiffness()) + " N/m; tangent " + Sci(ktan[0]) + ", " +
         Sci(ktan[1]) + " N/m (range " + Sci(kmin[0]) + " .. " + Sci(kmax[0]) + ", " +
         Sci(kmin[1]) + " .. " + Sci(kmax[1]) + ")");

  dynamics::SpeedSweepOptions so;
  so.sun_speeds_rpm = dynamics::SpeedGrid(3600, 6600, 31);
  const double step = 100;
  so.threads = 2;
  so.window_cycles = 3;
  so.outputs_per_cycle = 64;
  const transmission::StageMeshPairs modal_pairs(
      rig.scene, *rig.stage, dynamic_cast<const transmission::FeStageCompliance&>(*rig.compliance));
  so.modal_mesh_stiffness = dynamics::MeanTangentMeshStiffness(modal_pairs, 48, 0.05);
  // The library's tangent stiffness against the one above (same driver, own arrangement).
  CHECK(std::abs(so.modal_mesh_stiffness[0] / ktan[0] - 1) < 1e-12);
  CHECK(std::abs(so.modal_mesh_stiffness[1] / ktan[1] - 1) < 1e-12);
  const dynamics::SpeedSweepPlan plan = dynamics::PlanSpeedSweep(*rig.model, so);
  REQUIRE(plan.modes.size() == 3);
  REQUIRE(f_lo.size() == 3);
  REQUIRE(f_hi.size() == 3);
  // The modes' families, read from their shapes (what the coincidences' phasing flags use).
  CHECK(plan.modes[0].families == std::vector<int>{0});
  CHECK(plan.modes[1].families == std::vector<int>{1});
  CHECK(plan.modes[2].families == std::vector<int>{0});

  std::vector<dynamics::SpeedResult> rows;
  const auto result = dynamics::SweepSpeeds(
      *rig.model, so, plan, [&](const dynamics::SpeedResult& r) { rows.push_back(r); });
  REQUIRE(rows.size() == so.sun_speeds_rpm.size());  // every speed handed back
  REQUIRE(result.failed() == 0);
  const auto& sp = result.speeds;
  auto argmax = [&](auto field) {
    std::size_t best = 0;
    for (std::size_t i = 1; i < sp.size(); ++i)
      if (field(sp[i]) > field(sp[best])) best = i;
    return best;
  };
  const double per_rpm = plan.mesh_hz_per_rpm;
  struct Peak {
    std::string what;
    std::size_t at;
    int mode, harmonic;
  };
  const Peak peaks[2] = {
      {"TE amplitude", argmax([](const auto& r) { return r.te_amplitude; }), 0, 3},
      {"K_gamma", argmax([](const auto& r) { return r.k_gamma; }), 1, 4}};
  for (const Peak& p : peaks) {
    const auto j = static_cast<std::size_t>(p.mode);
    const double zeta = plan.modes[j].damping_ratio;
    const double n_c = plan.modes[j].mode.frequency / (p.harmonic * per_rpm);  // tangent
    const double n_sec = f_sec[j] / (p.harmonic * per_rpm);
    const double lo = f_lo[j] / (p.harmonic * per_rpm) * std::sqrt(1 - 2 * zeta * zeta) - step / 2;
    const double hi = f_hi[j] / (p.harmonic * per_rpm) + step / 2;
    const double n_peak = sp[p.at].sun_speed_rpm;
    const bool interior = p.at > 0 && p.at + 1 < sp.size();
    const bool in_bracket = interior && n_peak >= lo && n_peak <= hi;
    // First order (the averaged system resonates at its mean stiffness' frequency): the grid and
    // the damping's shift of an amplitude peak, n_c (1 − √(1 − 2ζ²)).
    const double bound = step / 2 + n_c * (1 - std::sqrt(1 - 2 * zeta * zeta));
    const bool at_coincidence = interior && std::abs(n_peak - n_c) <= bound;
    const std::string name = "harmonic " + std::to_string(p.harmonic) + " x mode " +
                             std::to_string(p.mode + 1) + " (" +
                             Fixed(plan.modes[j].mode.frequency) + " Hz)";
    Figure(p.what + " peak at " + Fixed(n_peak) + " rpm; " + name + " at " + Fixed(n_c) +
           " rpm (tangent mesh stiffness), " + Fixed(n_sec) + " rpm (secant); bracket " +
           Fixed(lo) + " .. " + Fixed(hi));
    VerifyRow("speed sweep, paper stage, sun fixed: " + p.what + " peak (3600..6600 rpm, step 100)",
              name + ", tangent mesh stiffness: " + Fixed(n_c) + " rpm",
              "peak at " + Fixed(n_peak) + " rpm", Fixed(n_peak - n_c) + " rpm",
              Fixed(bound) + " rpm (grid step/2 + damping shift)", at_coincidence);
    VerifyRow("speed sweep, same peak against the stiffness range",
              name + " with every mesh at its k_min .. k_max over a cycle",
              "peak at " + Fixed(n_peak) + " rpm (secant coincidence " + Fixed(n_sec) + " rpm)", "",
              "inside " + Fixed(lo) + " .. " + Fixed(hi) + " rpm", in_bracket);
    CHECK(interior);
    CHECK(std::abs(n_peak - n_c) <= bound);
    CHECK(n_peak >= lo);
    CHECK(n_peak <= hi);
  }
  double cpu = 0;
  for (const auto& r : sp) cpu += r.cpu_seconds;
  Figure("speed sweep of 31 speeds: " + Fixed(cpu, 2) + " s CPU in the speeds, " +
         Fixed(result.wall_seconds, 2) + " s wall on 2 threads; plan " + Fixed(plan.seconds, 2) +
         " s");
}

TEST_CASE("speed sweep: far below the coincidences the dynamic factor tends to 1",
          "[crosscheck][dynamics][sweep]") {
  // FE structural compliance without the local term, as the quasi-static-limit test and for its
  // reason: the local term's force steps where an involute meets a tip round are steps of the
  // quasi-static equilibrium itself, which ring at the mesh modes at any speed (with them the
  // factor stays about 1 % above 1 down to 125 rpm: docs/dynamic.md). What separates the
  // dynamic from the quasi-static mesh force at low speed are then the velocity terms: damping
  // forces of contacts whose overlap changes under the rigid motion and the ringing after a kink
  // of the quasi-static deflection (both ∝ speed), and inertia (∝ speed²). Halving the speed must
  // at least halve |K_v − 1| (ratio ≥ 2, tested ≥ 2/1.25 as the quasi-static-limit test for the
  // peak sampling), above the floor of the tolerances (rtol 1e-6: 100 rtol = 1e-4 on a force
  // ratio, the bound of the tolerance-halving check).
  const auto rig = PaperRig(false);
  dynamics::SpeedSweepOptions so;
  so.sun_speeds_rpm = {125, 250, 500};
  so.threads = 2;
  so.window_cycles = 3;
  so.outputs_per_cycle = 64;
  const auto result = dynamics::SweepSpeeds(*rig.model, so);
  REQUIRE(result.failed() == 0);
  const double first = result.plan.modes.front().mode.frequency / (6 * result.plan.mesh_hz_per_rpm);
  double dev[3];
  for (int k = 0; k < 3; ++k)
    dev[k] = std::abs(result.speeds[static_cast<std::size_t>(k)].dynamic_factor - 1);
  const double floor = 1e-4;
  const bool pass = dev[0] <= dev[1] / 2 * 1.25 + floor && dev[1] <= dev[2] / 2 * 1.25 + floor;
  VerifyRow(
      "speed sweep: dynamic factor -> 1 far below the coincidences (125, 250, 500 rpm; "
      "lowest coincidence of harmonics 1-6: " +
          Fixed(first) + " rpm)",
      "quasi-static mesh force at the same carrier angles (K_v = 1)",
      "|K_v - 1| = " + Sci(dev[0], 2) + ", " + Sci(dev[1], 2) + ", " + Sci(dev[2], 2),
      "ratios " + Sci(dev[1] / dev[0], 2) + ", " + Sci(dev[2] / dev[1], 2),
      "each ratio >= 2/1.25 (above 1e-4)", pass);
  CHECK(dev[0] <= dev[1] / 2 * 1.25 + floor);
  CHECK(dev[1] <= dev[2] / 2 * 1.25 + floor);
  CHECK(result.speeds[2].sun_speed_rpm < first / 4);
}

TEST_CASE("speed sweep: a failed speed is a result with its message, never left out",
          "[crosscheck][dynamics][sweep]") {
  // Spring contacts (cheap); at most 20 steps per output interval cannot reach the first output
  // (a mesh cycle takes thousands of steps), so every speed fails in Simulate.
  RigOptions o;
  o.spring = 1e-9;
  o.spring_mesh_stiffness = 1.5e9;
  o.edit = [](transmission::DynamicSettings& s) { s.sun_speed = io::RpmToRadPerSecond(1000); };
  const auto rig = test::MakeRig(test::SceneText("paper_stage.toml"), "springs", o);
  dynamics::SpeedSweepOptions so;
  so.sun_speeds_rpm = {1000, 2000, 3000};
  so.threads = 2;
  so.window_cycles = 1;
  so.simulation.max_steps = 20;
  int seen = 0;
  const auto result =
      dynamics::SweepSpeeds(*rig.model, so, [&](const dynamics::SpeedResult&) { ++seen; });
  CHECK(seen == 3);
  REQUIRE(result.speeds.size() == 3);
  CHECK(result.failed() == 3);
  for (std::size_t k = 0; k < 3; ++k) {
    CHECK(result.speeds[k].sun_speed_rpm == so.sun_speeds_rpm[k]);
    CHECK_FALSE(result.speeds[k].ok());
    // CVODE stops at max_steps per output interval (CV_TOO_MUCH_WORK): the integrator's own failure.
    CHECK(result.speeds[k].status == transmission::RunStatus::kIntegratorFailure);
    CHECK_FALSE(result.speeds[k].message.empty());
  }
}

TEST_CASE("speed sweep: bad speed lists and options are named with value and rule",
          "[unit][dynamics][sweep]") {
  auto message = [](auto f) {
    try {
      f();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  CHECK(message([] { dynamics::SpeedGrid(0, 100, 3); }) ==
        "first sun speed [rpm] = 0: must be > 0");
  CHECK(message([] { dynamics::SpeedGrid(500, 100, 3); }) ==
        "last sun speed [rpm] = 100: must be finite and >= the first (500)");
  CHECK(message([] { dynamics::SpeedGrid(100, 500, 0); }) == "number of speeds = 0: must be >= 1");
  CHECK(message([] { dynamics::SpeedGrid(100, 500, 1); }) ==
        "number of speeds = 1: must be >= 2 when the last speed differs from the first");
  CHECK(dynamics::SpeedGrid(100, 500, 5) == std::vector<double>{100, 200, 300, 400, 500});
  CHECK(dynamics::SpeedGrid(250, 250, 1) == std::vector<double>{250});
  dynamics::SpeedSweepOptions o;
  o.sun_speeds_rpm = {100, 100};
  CHECK(message([&] { o.Validate(); }) ==
        "speed sweep: sun_speeds_rpm[1] = 100: must exceed the speed before it");
  o.sun_speeds_rpm = {100};
  o.transient_fraction = 1;
  CHECK(message([&] { o.Validate(); }) ==
        "speed sweep: transient_fraction = 1: must lie in (0, 1)");
  // A sun speed by the rule of every run's (transmission/run_arguments.hpp, --speed-rpm's).
  dynamics::SpeedSweepOptions slow;
  slow.sun_speeds_rpm = {0.5};
  CHECK(message([&] { slow.Validate(); }) ==
        "speed sweep: sun_speeds_rpm[0] = 0.5: must be finite and in [1, 100000] [rpm] (slower "
        "runs are quasi-static: epicycle quasistatic; faster ones are past any gear's pitch-line "
        "speed)");
}

TEST_CASE(
    "coincidences: every mesh harmonic that meets a mode in the speed range, beyond harmonic 3, "
    "at the kinematic speed and marked by the planet-phasing rule",
    "[crosscheck][dynamics][sweep]") {
  // The paper's stage with a floating sun (no errors: equally spaced, symmetric): its first
  // translational mode near 2.5 kHz meets mesh harmonic 8 near 1470 rpm, just below the main
  // job's 1500 rpm. References that do not come from the library: the sun speed where harmonic h
  // meets f, n_s = 60 f (1 + z_r/z_s)/(h z_r) (the mesh frequency z_r ω_c/2π with
  // ω_c = ω_s z_s/(z_s + z_r)), and Parker & Lin's rule for 3 planets and 16 sun teeth: a
  // translational mode is excited at h when (16 h − 1)/3 or (16 h + 1)/3 is whole (h = 7, 8: yes;
  // h = 9: 143/3, 145/3: no), a rotational one when 16 h/3 is whole (h = 9: yes).
  RigOptions o;
  o.sun = transmission::SunSupport::kFloating;
  const auto rig = test::MakeRig(test::SceneText("paper_stage.toml"), "paper stage", o);
  Eigen::MatrixXd m, k;
  rig.model->Linearise(0.0, &m, &k);
  const auto modes = dynamics::SolveModes(m, k, rig.model->ModeLayout());
  const auto found = dynamics::FindCoincidences(*rig.model, modes, 750, 3000);
  const double zs = rig.stage->sun().teeth(), zr = rig.stage->ring().teeth();
  auto speed = [&](double f, int h) { return 60 * f * (1 + zr / zs) / (h * zr); };
  int beyond_three = 0, checked = 0;
  for (std::size_t j = 0; j < modes.size(); ++j) {
    const dynamics::Mode& x = modes[j];
    if (x.rigid) continue;
    for (int h = 1; h <= 64; ++h) {
      const double n = speed(x.frequency, h);
      const auto it = std::find_if(found.begin(), found.end(), [&](const dynamics::Coincidence& c) {
        return c.mode == static_cast<int>(j) && c.harmonic == h;
      });
      // Every coincidence in the range is listed, and none outside it.
      CHECK((it != found.end()) == (n >= 750 && n <= 3000));
      if (it == found.end()) continue;
      ++checked;
      if (h > 3) ++beyond_three;
      CHECK(std::abs(it->sun_speed_rpm / n - 1) < 1e-12);
      const long hz = 16L * h;
      if (x.type == dynamics::ModeType::kTranslational)
        CHECK(it->phasing_excited == ((hz - 1) % 3 == 0 || (hz + 1) % 3 == 0));
      if (x.type == dynamics::ModeType::kRotational) CHECK(it->phasing_excited == (hz % 3 == 0));
    }
  }
  // The harmonic-8 coincidence of the first translational mode, excited.
  const auto h8 = std::find_if(found.begin(), found.end(), [&](const dynamics::Coincidence& c) {
    return c.harmonic == 8 &&
           modes[static_cast<std::size_t>(c.mode)].type == dynamics::ModeType::kTranslational;
  });
  REQUIRE(h8 != found.end());
  CHECK(h8->phasing_excited);
  CHECK(h8->sun_speed_rpm > 1400);
  CHECK(h8->sun_speed_rpm < 1500);
  Figure("coincidences 750-3000 rpm, floating sun: " + std::to_string(checked) + " (" +
         std::to_string(beyond_three) + " beyond harmonic 3); harmonic 8 x " +
         Fixed(h8->frequency, 1) + " Hz at " + Fixed(h8->sun_speed_rpm, 1) + " rpm");
  CHECK(static_cast<int>(found.size()) == checked);
  CHECK(beyond_three > 0);
}
