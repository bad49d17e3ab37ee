// The vibration signature of a healthy stage (dynamics/vibration.hpp, dynamics/spectrum.hpp,
// docs/spectra.md): the spectra of a dynamic run of the paper stage against the
// kinematics and the planet phasing worked out from its tooth numbers (docs/model.md §9 "Fault
// frequencies"), which share nothing with the integration.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "dynamics_fixtures.hpp"
#include "epicycle/dynamics/spectrum.hpp"
#include "epicycle/dynamics/vibration.hpp"
#include "epicycle/io/units.hpp"
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

// One Hann segment of `cycles` mesh cycles of the output times, after `skip` cycles.
dynamics::SpectrumOptions OneSegment(const std::vector<double>& times, int per_cycle, int skip,
                                     int cycles) {
  dynamics::SpectrumOptions so;
  so.sample_interval = times[1] - times[0];
  so.segment = cycles * per_cycle;
  so.start_time = times[static_cast<std::size_t>(skip * per_cycle - 1)];
  return so;
}

// The spectra of a run at 1500 rpm, one Hann segment of `cycles` mesh cycles after 4 (24 outputs
// per cycle), for the fault lines: its characteristic frequencies in *f, the run's wall time in
// *wall, the channels' names in *names.
constexpr int kFaultCycles = 48;

std::vector<std::vector<double>> FaultRun(const std::string& text, const std::string& file,
                                          dynamics::StageFrequencies* f, double* wall,
                                          std::vector<std::string>* names,
                                          int cycles = kFaultCycles) {
  const int per_cycle = 24, skip = 4;
  test::RigOptions ro;
  ro.edit = [](transmission::DynamicSettings& s) { s.sun_speed = io::RpmToRadPerSecond(1500); };
  test::DynamicRig rig = test::MakeRig(text, file, ro);
  const dynamics::DynamicModel& model = *rig.model;
  *f = dynamics::CharacteristicFrequencies(*rig.stage, model.sun_speed());
  const std::vector<double> times = test::Times(model, *rig.stage, skip + cycles, per_cycle);
  const std::vector<dynamics::VibrationChannel> channels = dynamics::VibrationChannels(model);
  const dynamics::SpectrumOptions so = OneSegment(times, per_cycle, skip, cycles);
  dynamics::WelchSpectrum spectrum(static_cast<int>(channels.size()), so);
  std::vector<double> values;
  dynamics::SimulationOptions opt;
  const dynamics::SimulationResult run = dynamics::Simulate(
      model, opt, model.QuasiStaticStart(opt.contact, opt.backend),
      Eigen::VectorXd::Zero(model.size()), times, [&](const dynamics::DynamicSample& s) {
        dynamics::VibrationValues(model, s, &values);
        spectrum.Add(s.time, values);
      });
  REQUIRE(run.completed());
  REQUIRE(spectrum.segments() == 1);
  *wall = run.stats.wall_seconds;
  std::vector<std::vector<double>> out;
  names->clear();
  for (std::size_t c = 0; c < channels.size(); ++c) {
    out.push_back(spectrum.Amplitudes(static_cast<int>(c)));
    names->push_back(channels[c].name);
  }
  return out;
}

// The amplitudes of channel `name` of a FaultRun.
const std::vector<double>& Channel(const std::vector<std::vector<double>>& run,
                                   const std::vector<std::string>& names, const std::string& name) {
  const auto it = std::find(names.begin(), names.end(), name);
  REQUIRE(it != names.end());
  return run[static_cast<std::size_t>(it - names.begin())];
}

std::vector<double> FaultRunTe(const std::string& text, const std::string& file,
                               dynamics::StageFrequencies* f, double* wall) {
  std::vector<std::string> names;
  return Channel(FaultRun(text, file, f, wall, &names), names, "te");
}

// The healthy paper stage's, computed once for the fault tests.
const std::vector<double>& HealthyFaultRunTe(dynamics::StageFrequencies* f, double* wall) {
  static dynamics::StageFrequencies sf;
  static double sw = 0;
  static const std::vector<double> te =
      FaultRunTe(test::SceneText("paper_stage.toml"), "paper_stage.toml", &sf, &sw);
  *f = sf;
  *wall = sw;
  return te;
}

// The largest peaks of `a` off the mesh harmonics (bins kFaultCycles h and their two neighbours,
// where the window spreads a mesh line).
std::vector<int> LargestOffMesh(const std::vector<double>& a, std::size_t count) {
  std::vector<double> off = a;
  for (std::size_t j = 0; j < off.size(); ++j) {
    const std::size_t r = j % kFaultCycles;
    if (r == 0 || r == 1 || r == kFaultCycles - 1) off[j] = 0;
  }
  return LargestPeaks(off, count);
}

// The three largest peaks of a damaged run's TE off the mesh harmonics, each checked to lie on a
// multiple of the fault's `line` [Hz] (`name` for messages) and to exceed the healthy run's TE
// there by more than 100: whether all lie on the lines, the smallest ratio and the peaks listed.
struct FaultPeaks {
  bool on_lines = true;
  double least_ratio = 1e300;
  std::string peaks;
};

FaultPeaks CheckFaultPeaks(const std::vector<double>& damaged, const std::vector<double>& healthy,
                           double resolution, double line, const std::string& name) {
  FaultPeaks r;
  for (int j : LargestOffMesh(damaged, 3)) {
    const double a = damaged[static_cast<std::size_t>(j)];
    const double hz = j * resolution, k = hz / line;
    const bool on = std::abs(k - std::round(k)) < 1e-9;
    const double ratio = a / std::max(healthy[static_cast<std::size_t>(j)], 1e-300);
    INFO("peak at " << hz << " Hz = " << k << " " << name << ", " << a << " rad, " << ratio
                    << " x the healthy stage's");
    CHECK(on);
    CHECK(ratio > 100);
    r.on_lines = r.on_lines && on;
    r.least_ratio = std::min(r.least_ratio, ratio);
    r.peaks += (r.peaks.empty() ? "" : ", ") + Fixed(k, 0) + " " + name + " (" +
               test::Sci(a * 1e6, 2) + " urad)";
  }
  return r;
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
  // at rtol 1e-6: ≤ 7e-5 of the response, docs/dynamic_cost.md, "Error against run time"), the start
  // transient left after the skip (e^{−10} = 4.5e-5 of its initial size, at most the response's
  // size) and the contact solve's tolerance (1e-10 relative): together ≤ 1.2e-4, asserted with a
  // margin of 8 for the transient's and the error's spread into single bins, not their sum over
  // bins.
  test::RigOptions ro;
  ro.edit = [](transmission::DynamicSettings& s) { s.sun_speed = io::RpmToRadPerSecond(1500); };
  test::DynamicRig rig = test::MakeRig(test::SceneText("paper_stage.toml"), "paper stage", ro);
  const dynamics::DynamicModel& model = *rig.model;
  const dynamics::StageFrequencies f =
      dynamics::CharacteristicFrequencies(*rig.stage, model.sun_speed());
  const int per_cycle = 24, skip = 4, z_r = 65;
  const std::vector<double> times = test::Times(model, *rig.stage, skip + z_r, per_cycle);
  const std::vector<dynamics::VibrationChannel> channels = dynamics::VibrationChannels(model);
  const dynamics::SpectrumOptions so = OneSegment(times, per_cycle, skip, z_r);
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
  REQUIRE(run.completed());
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
      // A peak at the numerical floor (below 1e-3 of the largest allowed line, the bound derived
      // above) is noise, not a line: the TE has three allowed lines below Nyquist (3, 6, 9 f_m),
      // so its fourth-largest local maximum is one.
      if (a[static_cast<std::size_t>(j)] < 1e-3 * largest) {
        peaks += (peaks.empty() ? "" : ", ") + std::string("floor");
        continue;
      }
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

TEST_CASE(
    "spectrum of a paper stage with a spall on a planet tooth: the TE gains the planet tooth's "
    "lines k f_m/z_p, at the kinematic frequencies",
    "[crosscheck][dynamics][spectrum]") {
  // scenes/paper_stage_spall.toml: the paper stage with a spall on one flank of planet 1's tooth
  // 13 (half the face width, 30 um deep). The spalled tooth meets its mate once per turn of the
  // planet relative to the carrier, every z_p = 24 mesh cycles: its lines are k f_m/z_p
  // (docs/model.md §9 "Fault frequencies"), by hand f_m/24 = 13.37 Hz at 1500 rpm. Segment: 48
  // mesh cycles (two planet turns), so f_m/z_p is bin 2 and every planet-tooth line and mesh
  // harmonic lies on a bin (Δf = f_m/48 = 6.69 Hz); the healthy stage's TE holds h f_m only
  // (bins 48 h). Asserted: in the spalled run, the three largest peaks off the healthy stage's
  // mesh harmonics lie on multiples of f_m/z_p (even bins), and there the spalled TE exceeds the
  // healthy one by more than 100 (the healthy run holds only the numerical floor of the test
  // above, ≤ 1e-3 of its mesh lines, at these bins).
  const int cycles = kFaultCycles;
  dynamics::StageFrequencies f, fh;
  double wall = 0, wall_h = 0;
  const std::vector<double> spalled =
      FaultRunTe(test::SceneText("paper_stage_spall.toml"), "paper_stage_spall.toml", &f, &wall);
  const std::vector<double>& healthy = HealthyFaultRunTe(&fh, &wall_h);
  REQUIRE(f.planet_relative == Approx(f.mesh / 24).epsilon(1e-12));
  const double resolution = f.mesh / cycles;
  CHECK(f.planet_relative / resolution == Approx(2.0).epsilon(1e-9));
  const FaultPeaks r = CheckFaultPeaks(spalled, healthy, resolution, f.planet_relative, "f_m/z_p");
  test::Figure("spectrum, spalled planet tooth, 1500 rpm: " + Fixed(wall, 2) + " s wall (" +
               Fixed(wall_h, 2) + " s healthy)");
  test::VerifyRow(
      "spectrum, paper stage with a spall on planet 1's tooth 13 (1500 rpm, 48 mesh cycles): the "
      "TE's three largest peaks off the mesh harmonics",
      "k f_m/z_p, by hand f_m/24 = " + Fixed(f.planet_relative, 2) + " Hz", r.peaks,
      "smallest " + test::Sci(r.least_ratio, 2) + " x the healthy TE there",
      "on the lines (bins of " + Fixed(resolution, 2) + " Hz); > 100 x healthy",
      r.on_lines && r.least_ratio > 100);
}

TEST_CASE(
    "spectrum of a paper stage with a cracked sun tooth: the TE gains the sun tooth's lines "
    "k n (f_s - f_c) at the kinematic frequencies, rising with the depth",
    "[crosscheck][dynamics][spectrum][crack]") {
  // The paper stage with a 2 mm crack (about a quarter of the root chord) at the largest root
  // tension of sun tooth 0's loaded side. The tooth meets the n = 3 equally spaced planets at
  // equal intervals, n times per turn of the sun relative to the carrier: its lines are
  // k n (f_s − f_c) (docs/model.md §9 "Fault frequencies"), by hand f_s − f_c = f_m/z_s =
  // f_m/16, so n (f_s − f_c) = 3 f_m/16 = 60.2 Hz at 1500 rpm (beside f_m = 16 (f_s − f_c), with
  // 16 ≢ 0 mod 3, the comb's lines are 15 and 18 (f_s − f_c), not f_m ± n (f_s − f_c):
  // docs/damage.md "Which lines a tooth fault puts into which signal"). The segment of 48 mesh
  // cycles (three relative turns) puts f_m/16 on bin 3 and 3 f_m/16 on bin 9 (Δf = f_m/48).
  // Asserted: the three largest peaks off the mesh harmonics lie on multiples of n (f_s − f_c)
  // (bins 9 k), none on a planet tooth's comb alone (bins 2 k, the spall's) and, there, the cracked
  // TE exceeds the healthy one by more than 100 (the healthy run's floor, ≤ 1e-3 of its mesh
  // lines).
  const int cycles = kFaultCycles;
  auto run = [&](double depth_mm, dynamics::StageFrequencies* f, double* wall) {
    const std::string crack =
        "\n[[damage.crack]]\ngear = \"sun\"\ntooth = 0\nside = \"-\"\ndepth_mm = " +
        Fixed(depth_mm, 2) + "\nangle_deg = 45\n";
    return FaultRunTe(test::SceneText("paper_stage.toml") + crack, "cracked_sun.toml", f, wall);
  };
  dynamics::StageFrequencies f, fh;
  double wall = 0, wall_h = 0;
  const std::vector<double> cracked = run(2.0, &f, &wall);
  const std::vector<double>& healthy = HealthyFaultRunTe(&fh, &wall_h);
  const double tooth_line = f.planets * f.sun_relative;  // n (f_s − f_c)
  REQUIRE(f.sun_relative == Approx(f.mesh / 16).epsilon(1e-12));
  const double resolution = f.mesh / cycles;
  CHECK(tooth_line / resolution == Approx(9.0).epsilon(1e-9));
  const FaultPeaks r = CheckFaultPeaks(cracked, healthy, resolution, tooth_line, "n(f_s-f_c)");
  test::Figure("spectrum, cracked sun tooth, 1500 rpm: " + Fixed(wall, 2) + " s wall (" +
               Fixed(wall_h, 2) + " s healthy)");
  // The amplitudes against the crack's depth: the line n (f_s − f_c) (bin 9) grows with the
  // depth, as the cracked tooth's compliance does (docs/model.md §9, "Root crack": monotone at
  // every flank point); beside it 2 n (f_s − f_c) (bin 18), the comb's line below f_m,
  // 5 n (f_s − f_c) = f_m − (f_s − f_c) (bin 45), and f_m − n (f_s − f_c) (bin 39), which the
  // phasing keeps out of the TE (13 ≢ 0 mod 3).
  std::string table;
  double previous = 0;
  bool rising = true;
  for (double depth : {0.5, 1.0, 2.0, 3.0}) {
    dynamics::StageFrequencies fd;
    double w = 0;
    const std::vector<double> te = depth == 2.0 ? cracked : run(depth, &fd, &w);
    rising = rising && te[9] > previous;
    previous = te[9];
    table += (table.empty() ? "" : ", ") + Fixed(depth, 1) + " mm: " + test::Sci(te[9] * 1e6, 3) +
             " / " + test::Sci(te[18] * 1e6, 3) + " / " +
             test::Sci(te[static_cast<std::size_t>(cycles) - 3] * 1e6, 3) + " / " +
             test::Sci(te[static_cast<std::size_t>(cycles) - 9] * 1e6, 3);
  }
  test::VerifyRow(
      "spectrum, paper stage with a crack in sun tooth 0 (1500 rpm): the TE at n (f_s - f_c), "
      "2 n (f_s - f_c), 5 n (f_s - f_c) = f_m - (f_s - f_c) (the comb beside f_m) and "
      "f_m - n (f_s - f_c) (off the comb) against the crack depth [urad]",
      "rises with the depth (the cracked tooth's compliance does)", table,
      rising ? "rising" : "not rising", "rising", rising);
  CHECK(rising);
  test::VerifyRow(
      "spectrum, paper stage with a 2 mm crack in sun tooth 0 (1500 rpm, 48 mesh cycles): the TE's "
      "three largest peaks off the mesh harmonics",
      "k n (f_s - f_c), by hand 3 f_m/16 = " + Fixed(tooth_line, 2) + " Hz", r.peaks,
      "smallest " + test::Sci(r.least_ratio, 2) + " x the healthy TE there",
      "on the lines (bins of " + Fixed(resolution, 2) + " Hz); > 100 x healthy",
      r.on_lines && r.least_ratio > 100);
}

TEST_CASE(
    "spectrum of a paper stage with a cracked planet tooth: the TE keeps the odd multiples of "
    "f_m/z_p beside the even ones",
    "[crosscheck][dynamics][spectrum][crack]") {
  // A 2 mm crack at the largest root tension of planet 1's tooth 0 (fillet "-"): the tooth meets
  // the sun on one flank and, half a planet turn later, the ring on the other (docs/damage.md
  // "Which lines a tooth fault puts into which signal"). Two meetings per turn of the planet
  // relative to the carrier put their weight on the even multiples of f_m/z_p; the odd ones would
  // cancel only if the two meetings were alike, and they are not (another mate, another flank).
  // Segment of 48 mesh cycles: f_m/z_p on bin 2, every multiple on a bin (Δf = f_m/48). Asserted:
  // at k f_m/z_p, k = 1 … 4 (bins 2 k), the cracked TE exceeds the healthy one by more than 100
  // (the healthy run's floor, ≤ 1e-3 of its mesh lines, test above), odd k included.
  const std::string crack =
      "\n[[damage.crack]]\ngear = \"planet1\"\ntooth = 0\nside = \"-\"\ndepth_mm = 2.0\n"
      "angle_deg = 45\n";
  dynamics::StageFrequencies f, fh;
  double wall = 0, wall_h = 0;
  const std::vector<double> cracked =
      FaultRunTe(test::SceneText("paper_stage.toml") + crack, "cracked_planet.toml", &f, &wall);
  const std::vector<double>& healthy = HealthyFaultRunTe(&fh, &wall_h);
  REQUIRE(f.planet_relative / (f.mesh / kFaultCycles) == Approx(2.0).epsilon(1e-9));
  std::string table;
  double least = 1e300;
  for (int k = 1; k <= 4; ++k) {
    const auto j = static_cast<std::size_t>(2 * k);
    const double ratio = cracked[j] / std::max(healthy[j], 1e-300);
    INFO(k << " f_m/z_p: " << cracked[j] << " rad, " << ratio << " x the healthy TE");
    CHECK(ratio > 100);
    least = std::min(least, ratio);
    table +=
        (table.empty() ? "" : ", ") + std::to_string(k) + ": " + test::Sci(cracked[j] * 1e6, 2);
  }
  test::Figure("spectrum, cracked planet tooth, 1500 rpm: " + Fixed(wall, 2) + " s wall");
  test::VerifyRow(
      "spectrum, paper stage with a 2 mm crack in planet 1's tooth 0 (1500 rpm, 48 mesh cycles): "
      "the TE at k f_m/z_p, k = 1 .. 4 [urad]",
      "every k, odd ones too (two unlike meetings per planet turn)", table,
      "smallest " + test::Sci(least, 2) + " x the healthy TE there", "> 100 x healthy",
      least > 100);
}

TEST_CASE(
    "spectrum of a 4-planet stage with a spall on a sun tooth: the TE holds k n (f_s - f_c), the "
    "housing signals k n (f_s - f_c) +- f_s, nothing at k n (f_s - f_c) +- f_c",
    "[crosscheck][dynamics][spectrum]") {
  // A stage other than the paper's: its tools and body sizes with 21/21/63 teeth and 4 equally
  // spaced planets ((21 + 63)/4 = 21 whole; carrier radius m (z_r − z_p)/2 = 88.83 mm), sun fixed,
  // 1500 rpm, and a spall on one sun tooth's loaded flank (r 44 … 46.5 mm of the active 42.3 …
  // 49.8 mm, half the face width, 30 um deep). By hand (docs/damage.md "Which lines a tooth
  // fault puts into which signal"), in carrier orders: f_c = 25·21/84 = 6.25 Hz, f_s = 4 f_c,
  // f_s − f_c = f_m/z_s = 3 f_c, f_m = 63 f_c. A term of order m of the sun's turn relative to
  // the carrier from planet i carries e^{−i m ψ_i}, a housing-fixed component e^{±i(φ_c + ψ_i)};
  // the sum over the 4 planets keeps m ≡ 0 (TE) or m ≡ ±1 (mod 4) (housing): the TE's lines
  // 12 k, the ring's mounting and the sun's bearing 12 k ± 4 (k n (f_s − f_c) ± f_s); the lines
  // k n (f_s − f_c) ± f_c, which only unlike planets add, are 12 k ± 1. One Hann segment of a
  // carrier revolution (63 mesh cycles after 4; 24 outputs per cycle): every line on a bin (bin j =
  // order j), spreading to its two neighbours only, so lines 3 bins apart do not touch.
  // Asserted below f_m (bins 2 … 59; f_m's own spread reaches 62): (1) the largest local maxima,
  // as many as the rule has lines there (TE 4, housing 10), each on a line of the rule; (2) at the
  // orders the rule excludes (TE 12 k ± 4; housing 12 k ± 1 and 12 k) below 1e-3 of the channel's
  // largest line: the bound of the healthy stage's phasing test above (a symmetric model keeps
  // the symmetry; the integrator, the start transient and the contact solve break it by ≤ 1.2e-4,
  // margin 8); (3) every sun-tooth line the spectrum markers list there
  // (dynamics::CharacteristicLines) on a line of the rule, reading 100 times the excluded ones.
  const std::string paper = test::SceneText("paper_stage.toml");
  std::string text = paper;
  for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
           {"[sun]\nteeth = 16", "[sun]\nteeth = 21"},
           {"[planet]\nteeth = 24", "[planet]\nteeth = 21"},
           {"[ring]\nteeth = 65", "[ring]\nteeth = 63"},
           {"radius_mm = 86.715               # m (z_r - z_p)/2\nplanets = 3",
            "radius_mm = 88.83\nplanets = 4"},
           {"rim_radius_mm = 156.4", "rim_radius_mm = 160.0"},
           {"mass_kg = 1.19\ninertia_kgm2 = 9.92e-4", "mass_kg = 2.0\ninertia_kgm2 = 1.9e-3"},
           {"mass_kg = 1.23\ninertia_kgm2 = 24e-4", "mass_kg = 0.94\ninertia_kgm2 = 1.4e-3"}}) {
    REQUIRE(text.find(from) != std::string::npos);
    text = test::Replace(text, from, to);
  }
  text +=
      "\n[[damage.pit]]\ngear = \"sun\"\ntooth = 0\nflank = \"-\"\nradius_from_mm = 44.0\n"
      "radius_to_mm = 46.5\nwidth_fraction = 0.5\ndepth_um = 30.0\n";
  dynamics::StageFrequencies f;
  double wall = 0;
  std::vector<std::string> names;
  const int z_r = 63;
  const auto run = FaultRun(text, "four_planets_sun_spall.toml", &f, &wall, &names, z_r);
  REQUIRE(f.planets == 4);
  REQUIRE(f.symmetric);
  REQUIRE(f.carrier == Approx(6.25).epsilon(1e-12));
  REQUIRE(f.sun_relative == Approx(3 * f.carrier).epsilon(1e-12));
  REQUIRE(f.sun == Approx(4 * f.carrier).epsilon(1e-12));
  test::Figure(
      "spectrum, 4-planet 21/21/63 stage with a sun-tooth spall, 1500 rpm, 67 mesh "
      "cycles: " +
      Fixed(wall, 2) + " s wall");
  const int last = 59;
  for (const std::string channel : {"te", "ring_force_x", "sun_force_x"}) {
    const bool torsional = channel == "te";
    const std::vector<double>& a = Channel(run, names, channel);
    auto on_rule = [&](int j) { return torsional ? j % 12 == 0 : j % 12 == 4 || j % 12 == 8; };
    auto excluded = [&](int j) {
      return torsional ? j % 12 == 4 || j % 12 == 8 : j % 12 == 1 || j % 12 == 11 || j % 12 == 0;
    };
    int rule_lines = 0;
    for (int j = 2; j <= last; ++j) rule_lines += on_rule(j) ? 1 : 0;
    const double largest = *std::max_element(a.begin() + 1, a.end());
    std::vector<double> region(a.begin(), a.begin() + last + 2);
    region[static_cast<std::size_t>(last + 1)] = 0;
    std::string peaks;
    bool on = true;
    double least = 1e300, worst = 0;
    int worst_order = 0;
    for (int j : LargestPeaks(region, static_cast<std::size_t>(rule_lines))) {
      INFO(channel << ": peak at carrier order " << j << ", " << a[static_cast<std::size_t>(j)]);
      CHECK(on_rule(j));
      on = on && on_rule(j);
      least = std::min(least, a[static_cast<std::size_t>(j)]);
      if (!peaks.empty()) peaks += " ";
      peaks += std::to_string(j);
    }
    for (int j = 2; j <= last; ++j)
      if (excluded(j) && a[static_cast<std::size_t>(j)] > worst) {
        worst = a[static_cast<std::size_t>(j)];
        worst_order = j;
      }
    INFO(channel << ": largest at an excluded order " << worst << " (order " << worst_order
                 << "), channel's largest line " << largest);
    CHECK(worst < 1e-3 * largest);
    // The markers' sun-tooth lines below bin 59.
    bool markers = true;
    for (const auto& l : dynamics::CharacteristicLines(
             f, torsional ? dynamics::SignalKind::kTorsional : dynamics::SignalKind::kHousing,
             last * f.carrier, 1, 3)) {
      if (l.kind != dynamics::LineKind::kSunTooth) continue;
      const int j = static_cast<int>(std::lround(l.carrier_order));
      const bool good = std::abs(l.carrier_order - j) < 1e-9 && on_rule(j) &&
                        a[static_cast<std::size_t>(j)] > 100 * worst;
      INFO(channel << ": marker " << l.name << " at carrier order " << l.carrier_order);
      CHECK(good);
      markers = markers && good;
    }
    const std::string unit = torsional ? " rad" : " N";
    test::VerifyRow(
        "spectrum, 4-planet 21/21/63 stage with a spall on a sun tooth (1500 rpm, one carrier "
        "revolution): " +
            channel + ", the " + std::to_string(rule_lines) +
            " largest peaks below f_m [carrier orders]",
        torsional ? "k n (f_s - f_c) = 12 k, by hand"
                  : "k n (f_s - f_c) +- f_s = 12 k +- 4, by hand",
        peaks, "smallest " + test::Sci(least, 3) + unit, "on the rule's lines (bins of f_c)", on);
    test::VerifyRow(
        "spectrum, the same: " + channel + " at the orders the rule excludes (" +
            (torsional ? "12 k +- 4" : "12 k +- 1 = k n (f_s - f_c) +- f_c, and 12 k") + ")",
        "0 (a symmetric stage); the markers' sun-tooth lines all on the rule",
        test::Sci(worst, 2) + unit + " (order " + std::to_string(worst_order) + ")",
        test::Sci(worst / largest, 2) + " of the largest line; " +
            test::Sci(least / std::max(worst, 1e-300), 2) + " x below the rule's",
        "1e-3 (integrator, start transient, contact solve)", worst < 1e-3 * largest && markers);
  }
}
