// The vibration signature of a healthy stage (dynamics/vibration.hpp, dynamics/spectrum.hpp,
// docs/dynamic.md "Spectra"): the spectra of a dynamic run of the paper stage against the
// kinematics and the planet phasing worked out from its tooth numbers (docs/model.md §9 "Fault
// frequencies"), which share nothing with the integration.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "dynamics_fixtures.hpp"
#include "epicycle/dynamics/spectrum.hpp"
#include "epicycle/dynamics/vibration.hpp"
#include "figures.hpp"
#include "stage_fixtures.hpp"

using namespace epicycle;

namespace {

std::string Fixed(double x, int digits) {
  char b[40];
  std::snprintf(b, sizeof b, "%.*f", digits, x);
  return b;
}

// Local maxima of a (from bin 2: bin 1 is where a segment's mean would sit), largest first.
std::vector<int> LargestPeaks(const std::vector<double>& a, std::size_t count) {
  std::vector<int> p;
  for (std::size_t j = 2; j + 1 < a.size(); ++j)
    if (a[j] > a[j - 1] && a[j] >= a[j + 1]) p.push_back(static_cast<int>(j));
  std::sort(p.begin(), p.end(), [&](int x, int y) {
    return a[static_cast<std::size_t>(x)] > a[static_cast<std::size_t>(y)];
  });
  if (p.size() > count) p.resize(count);
  return p;
}

}  // namespace

TEST_CASE(
    "spectrum of a healthy paper stage: the TE holds only the mesh harmonics the planet phasing "
    "allows, the ring's mounting force only the carrier-order lines h f_m +- f_c it allows",
    "[crosscheck][dynamics][spectrum]") {
  // The paper stage (16/24/65, 3 equally spaced identical planets, no errors), sun fixed, the
  // scene's Xu & Kahraman friction and ζ = 0.05, 1500 rpm: f_c = 4.938 Hz, f_m = 65 f_c =
  // 320.99 Hz. Reference, by hand from the teeth (docs/model.md §9): every planet's forces are a
  // function of its angle θ_i = φ_c + ψ_i alone, of period 2π/65 (the mesh) and, summed over the
  // three planets 120° apart, only carrier orders that are multiples of 3 survive. A torque (the
  // sun's rotation, the TE, the ring's moment) has orders 65h: multiples of 3 for h = 3, 6, ...;
  // a force component in a fixed direction (the ring's mounting, the sun's bearing) has orders
  // 65h ± 1: 66 (f_m + f_c), 129 (2 f_m − f_c), 261 (4 f_m + f_c), 324 (5 f_m − f_c), ...
  //
  // Sampling: 24 outputs per mesh cycle (Nyquist 12 f_m); the outputs are instantaneous values,
  // so content above the Nyquist frequency folds back, order o onto 65·24 − o: with 24 a
  // multiple of 3 a fold of a multiple of 3 is one, so the folds cannot put a forbidden line
  // where the phasing allows none. The window: 4 mesh cycles left out (the start transient
  // decays as e^{−ζω t}, ζω ≥ 800 1/s here: e^{−10}), then one carrier revolution, 65·24 = 1560
  // samples in one Hann segment: every kinematic line is a whole carrier order, on a bin
  // (Δf = f_c), so a line reads its amplitude and spreads to its two neighbours only.
  //
  // Asserted: (1) the four largest peaks of the TE, the ring torque, the ring's x force and the
  // sun's x force each lie within one bin (the resolution) of a line the phasing allows;
  // (2) at the mesh harmonics the phasing forbids (TE: f_m, 2 f_m, 4 f_m, 5 f_m; force: h f_m
  // and h f_m ± f_c on the forbidden side, except where one bin from an allowed line) the amplitude
  // is below 1e-3 of the channel's largest line. Why 1e-3: a symmetric model's response keeps the
  // symmetry exactly; what breaks it is numerical: the integrator's global error (LSR 20–70 × rtol
  // at rtol 1e-6: ≤ 7e-5 of the response, docs/dynamic.md "Error against run time"), the start
  // transient left after the skip (e^{−10} = 4.5e-5 of its initial size, at most the response's
  // size) and the contact solve's tolerance (1e-10 relative): together ≤ 1.2e-4, asserted with a
  // margin of 8 for the transient's and the error's spread into single bins, not their sum over
  // bins.
  test::RigOptions ro;
  ro.edit = [](transmission::DynamicSettings& s) { s.sun_speed = 1500 * test::kRpm; };
  test::DynamicRig rig = test::MakeRig(test::SceneText("paper_stage.toml"), "paper stage", ro);
  const dynamics::DynamicModel& model = *rig.model;
  const dynamics::StageFrequencies f =
      dynamics::CharacteristicFrequencies(*rig.stage, model.sun_speed());
  const int per_cycle = 24, skip = 4, z_r = 65;
  const std::vector<double> times = test::Times(model, *rig.stage, skip + z_r, per_cycle);
  const std::vector<dynamics::VibrationChannel> channels = dynamics::VibrationChannels(model);
  dynamics::SpectrumOptions so;
  so.sample_interval = times[1] - times[0];
  so.segment = z_r * per_cycle;
  so.start_time = times[static_cast<std::size_t>(skip * per_cycle - 1)];
  dynamics::WelchSpectrum spectrum(static_cast<int>(channels.size()), so);
  std::vector<double> values;
  double ring_torque = 0, balance = 0;  // over the samples the spectrum uses
  int used = 0;
  dynamics::SimulationOptions opt;
  const Eigen::VectorXd d0 = model.QuasiStaticStart(opt.contact, opt.backend);
  const dynamics::SimulationResult run =
      dynamics::Simulate(model, opt, d0, Eigen::VectorXd::Zero(model.size()), times,
                         [&](const dynamics::DynamicSample& s) {
                           dynamics::VibrationValues(model, s, &values);
                           spectrum.Add(s.time, values);
                           if (s.time < so.start_time - 0.5 * so.sample_interval) return;
                           ring_torque += values[3];
                           // The balance of angular momentum about the centre (below).
                           const dynamics::Evaluation& e = s.evaluation;
                           double moment = model.sun_torque();
                           for (std::size_t i = 0; i < e.planet_bearing_force.size(); ++i) {
                             const Eigen::Vector2d c = e.poses.planets[i].rotation_centre;
                             const Eigen::Vector2d q = e.planet_bearing_force[i];
                             moment += c.x() * q.y() - c.y() * q.x();
                           }
                           for (int k = 0; k < model.size(); ++k)
                             if (model.dofs()[k].axis == dynamics::MotionDof::kRotation)
                               moment -= model.mass()(k) * e.acceleration(k);
                           balance = std::max(balance, std::abs(values[3] - moment));
                           ++used;
                         });
  REQUIRE(run.completed);
  REQUIRE(spectrum.segments() == 1);
  CHECK(spectrum.resolution() == Approx(f.carrier).epsilon(1e-9));
  test::Figure("spectrum, healthy paper stage, 1500 rpm, " + std::to_string(times.size()) +
               " outputs: " + Fixed(run.stats.wall_seconds, 2) + " s wall, " +
               std::to_string(run.stats.steps) + " steps");

  // The ring's moment on its mounting, read from the ring's contacts, against the balance of
  // angular momentum about the centre of sun, planets and ring, from the input torque, the
  // pins' forces on the planets (Evaluation::planet_bearing_force) and the members' angular
  // accelerations: −T_mount = T_s + Σ_i c_i × F_pin,i − Σ_k J_k θ̈_k at every sample (the fixed
  // sun's bearing acts at the centre; the planets' orbital momentum is constant on rigid pins at
  // a constant carrier speed). Every contact force acts on both its bodies at one point, so the
  // balance holds to round-off (~30 terms ≲ 1e4 N m: ~1e-11 N m); asserted 1e-9 of the moment. Its
  // mean: friction only lowers it below the lossless T_s (1 − ω_s/ω_c) = T_s (1 − 81/16) = 2437.5 N
  // m, by the meshes' loss, which for μ ≤ 0.08 (Xu & Kahraman on this mesh, docs/dynamic.md
  // "Friction") is a few per cent of the power: required within (0.95, 1) of it. (The samples' mean
  // is not compared with the inertia-free balance: the accelerations' harmonics at 24 f_m and up
  // fold onto 0 Hz at 24 samples per cycle and leave ~15 N m in their mean.)
  const double lossless = model.sun_torque() * (1 - model.sun_speed() / model.carrier_speed());
  const double mean = ring_torque / used;
  INFO("ring moment: mean " << mean << " N m (lossless " << lossless << "), largest imbalance "
                            << balance << " N m");
  CHECK(balance < 1e-9 * std::abs(lossless));
  CHECK(mean / lossless > 0.95);
  CHECK(mean / lossless < 1.0);
  test::VerifyRow(
      "spectrum run, healthy paper stage: the ring's moment on its mounting",
      "T_s + sum c_i x F_pin,i - sum J theta'' at every sample; mean below the "
      "lossless " +
          Fixed(lossless, 1) + " N m",
      "mean " + Fixed(mean, 1) + " N m", test::Sci(balance, 2) + " N m",
      "1e-9 of the moment; mean in (0.95, 1) of lossless",
      balance < 1e-9 * std::abs(lossless) && mean / lossless > 0.95 && mean / lossless < 1.0);

  const double nyquist = spectrum.Frequency(spectrum.bins() - 1);
  for (std::size_t c = 0; c < channels.size(); ++c) {
    const dynamics::VibrationChannel& ch = channels[c];
    if (ch.name != "te" && ch.name != "ring_torque" && ch.name != "ring_force_x" &&
        ch.name != "sun_force_x")
      continue;
    const std::vector<double> a = spectrum.Amplitudes(static_cast<int>(c));
    const auto lines = dynamics::CharacteristicLines(f, ch.kind, nyquist, 1, 0);
    double largest = 0;
    for (const auto& l : lines)
      if (l.allowed)
        largest = std::max(largest, dynamics::LineAmplitude(a, spectrum.resolution(), l.frequency));
    std::string peaks;
    bool on_lines = true;
    for (int j : LargestPeaks(a, 4)) {
      const double hz = spectrum.Frequency(j);
      std::string near;
      for (const auto& l : lines)
        if (l.allowed && std::abs(l.frequency - hz) <= spectrum.resolution() * (1 + 1e-9))
          near = l.name;
      peaks += (peaks.empty() ? "" : ", ") + (near.empty() ? Fixed(hz, 1) + " Hz" : near);
      INFO(ch.name << ": peak at " << hz << " Hz, carrier order " << j);
      CHECK_FALSE(near.empty());
      on_lines = on_lines && !near.empty();
    }
    double worst = 0;
    std::string worst_name;
    for (const auto& l : lines) {
      // A forbidden line one bin from an allowed one holds half of it (the window's spread):
      // h f_m beside h f_m ± f_c in a force; its other side, two bins away, is clean.
      bool beside = l.allowed;
      for (const auto& m : lines)
        beside = beside || (m.allowed && std::abs(m.frequency - l.frequency) < 1.5 * f.carrier);
      if (beside) continue;
      const double v = a[static_cast<std::size_t>(std::lround(l.frequency / f.carrier))];
      if (v > worst) {
        worst = v;
        worst_name = l.name;
      }
    }
    test::VerifyRow("spectrum, healthy paper stage (1500 rpm, one carrier revolution): " + ch.name +
                        ", the four largest peaks",
                    "lines the planet phasing allows, by hand from 16/65 teeth and 3 planets",
                    peaks, "", "each within one bin (" + Fixed(f.carrier, 2) + " Hz)", on_lines);
    test::VerifyRow("spectrum, healthy paper stage: " + ch.name + ", the lines the phasing forbids",
                    "0 (a symmetric stage)",
                    test::Sci(worst, 2) + " " + ch.unit + " (" + worst_name + ")",
                    test::Sci(worst / largest, 2) + " of the largest allowed line",
                    "1e-3 (integrator, start transient, contact solve)", worst < 1e-3 * largest);
    INFO(ch.name << ": forbidden line " << worst_name << " at " << worst / largest
                 << " of the largest allowed");
    CHECK(worst < 1e-3 * largest);
  }
}
