// Amplitude spectra and the stage's characteristic frequencies (dynamics/spectrum.hpp,
// docs/spectra.md, docs/model.md §9 "Fault frequencies") against closed forms: the
// periodic Hann window's transform, the statistics of white noise, and frequencies worked out by
// hand from the paper stage's tooth numbers.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <numbers>
#include <random>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "epicycle/dynamics/spectrum.hpp"
#include "epicycle/dynamics/speed_sweep.hpp"
#include "epicycle/dynamics/vibration.hpp"
#include "epicycle/io/units.hpp"
#include "spectrum_fixtures.hpp"
#include "stage_fixtures.hpp"

using namespace epicycle;
using dynamics::SpectrumOptions;
using dynamics::WelchSpectrum;

namespace {

constexpr double kPi = std::numbers::pi;

// The spectrum of x(t_k), t_k = k dt, k = 0..samples−1, in segments of n with hop n/2.
std::vector<double> Spectrum(const std::function<double(double)>& x, int n, int samples,
                             double dt = 1e-3, int* segments = nullptr) {
  SpectrumOptions o;
  o.sample_interval = dt;
  o.segment = n;
  WelchSpectrum w(1, o);
  for (int k = 0; k < samples; ++k) {
    const double v = x(k * dt);
    w.Add(k * dt, std::span<const double>(&v, 1));
  }
  if (segments) *segments = w.segments();
  return w.Amplitudes(0);
}

// The window's response |W(δ)|/W(0) = |sinc δ|/(1 − δ²) of the periodic Hann window, N → ∞.
double HannResponse(double delta) {
  if (delta == 0) return 1;
  return std::abs(std::sin(kPi * delta) / (kPi * delta)) / (1 - delta * delta);
}

}  // namespace

TEST_CASE("spectrum: sinusoids on bins read their amplitudes, the mean stays out of bin 1",
          "[unit][dynamics][spectrum]") {
  // The periodic Hann window's DFT is exactly ½, −¼, −¼ at bins 0, ±1 and 0 elsewhere, so a
  // sinusoid on bin j reads A there and A/2 at j ± 1, and nothing else: round-off only (an FFT
  // of N = 1024 points, relative ~ε log2 N; asserted to 1e-12 of the largest amplitude).
  const int n = 1024;
  const double dt = 1e-3, df = 1.0 / (n * dt);
  auto x = [&](double t) {
    return 2.5 + 3.0 * std::cos(2 * kPi * 100 * df * t + 0.3) +
           0.5 * std::sin(2 * kPi * 300 * df * t);
  };
  int segments = 0;
  const std::vector<double> a = Spectrum(x, n, n, dt, &segments);
  REQUIRE(segments == 1);
  REQUIRE(a.size() == static_cast<std::size_t>(n / 2 + 1));
  const double tol = 1e-12 * 3.0;
  CHECK(std::abs(a[100] - 3.0) < tol);
  CHECK(std::abs(a[99] - 1.5) < tol);
  CHECK(std::abs(a[101] - 1.5) < tol);
  CHECK(std::abs(a[300] - 0.5) < tol);
  CHECK(std::abs(a[299] - 0.25) < tol);
  CHECK(std::abs(a[0] - 2.5) < tol);  // the mean, reported at bin 0
  CHECK(a[1] < tol);                  // removed before the window: no line at Δf
  for (int j = 2; j <= n / 2; ++j)
    if (std::abs(j - 100) > 1 && std::abs(j - 300) > 1) CHECK(a[static_cast<std::size_t>(j)] < tol);
}

TEST_CASE("spectrum: a sinusoid between bins peaks on the nearest bin within the scalloping bound",
          "[unit][dynamics][spectrum]") {
  // At δ bins off its nearest bin a line reads |sinc δ|/(1 − δ²) of its amplitude (N → ∞),
  // least 8/(3π) half a bin off. Finite N changes the ratio by O((πδ/N)²) (< 1e-5 at N = 1024)
  // and the negative frequency's image, ≥ 200 bins away, leaks < 1/(π·200³) = 4e-8 through the
  // window's sidelobes: 1e-4 covers both with a margin.
  const int n = 1024;
  const double dt = 1e-3, df = 1.0 / (n * dt);
  for (double delta : {0.1, 0.25, 0.4, 0.5}) {
    const double f = (100 + delta) * df, amplitude = 2.0;
    const std::vector<double> a =
        Spectrum([&](double t) { return amplitude * std::cos(2 * kPi * f * t + 1.0); }, n, n, dt);
    int peak = 1;
    for (int j = 1; j <= n / 2; ++j)
      if (a[static_cast<std::size_t>(j)] > a[static_cast<std::size_t>(peak)]) peak = j;
    INFO("delta = " << delta << " bins, peak at bin " << peak);
    // The frequency to the resolution: the peak is the nearest bin (a tie at δ = ½).
    CHECK(std::abs(peak * df - f) <= 0.5 * df * (1 + 1e-12));
    const double read = a[static_cast<std::size_t>(peak)] / amplitude;
    CHECK(read >= dynamics::kHannScallopLoss * (1 - 1e-4));
    CHECK(read <= 1 + 1e-12);
    CHECK(std::abs(read - HannResponse(std::abs(peak - 100 - delta))) < 1e-4);
    // The reading of the line at its true frequency: the same peak.
    CHECK(dynamics::LineAmplitude(a, df, f) == a[static_cast<std::size_t>(peak)]);
  }
  CHECK(dynamics::kHannScallopLoss == Approx(8 / (3 * kPi)).epsilon(1e-15));
}

TEST_CASE("spectrum: Welch over several segments agrees with one segment within the noise's bound",
          "[unit][dynamics][spectrum]") {
  // A stationary signal: lines on bins 50, 120, 200 of N = 512 plus white noise of σ = 0.05.
  // Per bin the noise adds a complex term of mean square (2/Σw)² σ² Σw² = 6σ²/N in amplitude
  // units (Σw = N/2, Σw² = 3N/8), half of it along the line's phase: one segment reads a line's
  // amplitude A to a standard deviation σ√(3/N), and so does the Welch average (with a smaller
  // deviation; its power average adds the bias 3σ²/(N A)). Asserted: each within 5 standard
  // deviations of A, so the two within 10 of each other (a fixed seed: deterministic).
  // The noise floor: the mean of a_j² over the noise-only bins is 6σ²/N; a bin's power is an
  // exponential variable averaged over K_eff ≈ K segments (half-overlapping Hann segments are
  // correlated by 0.17² = 0.03 in power), so over M bins its relative deviation is 1/√(M K_eff):
  // asserted within 5 of those (and 5/√M for one segment). The scatter over the bins, std/mean
  // of a_j², is 1 for one segment and ≈ 1/√K_eff = 0.26 for Welch (K = 15): asserted > 0.7 and
  // < 0.4 (the estimate of a std over M = 480 bins is good to about 1/√(2M) = 3 %).
  const int n = 512, segments_expected = 15;
  const double dt = 1e-3, df = 1.0 / (n * dt), sigma = 0.05;
  const double lines[3][2] = {{50, 1.0}, {120, 0.4}, {200, 2.0}};
  std::mt19937_64 rng(12345);
  std::normal_distribution<double> noise(0.0, sigma);
  const int samples = n / 2 * (segments_expected + 1);
  std::vector<double> x(static_cast<std::size_t>(samples));
  for (int k = 0; k < samples; ++k) {
    double v = noise(rng);
    for (const auto& l : lines) v += l[1] * std::cos(2 * kPi * l[0] * df * k * dt + l[0]);
    x[static_cast<std::size_t>(k)] = v;
  }
  auto from = [&](double t) { return x[static_cast<std::size_t>(std::lround(t / dt))]; };
  int k1 = 0, kw = 0;
  const std::vector<double> one = Spectrum(from, n, n, dt, &k1);
  const std::vector<double> welch = Spectrum(from, n, samples, dt, &kw);
  REQUIRE(k1 == 1);
  REQUIRE(kw == segments_expected);
  const double sd = sigma * std::sqrt(3.0 / n);
  for (const auto& l : lines) {
    const auto j = static_cast<std::size_t>(l[0]);
    INFO("line at bin " << j << ": one segment " << one[j] << ", Welch " << welch[j]);
    CHECK(std::abs(one[j] - l[1]) < 5 * sd);
    CHECK(std::abs(welch[j] - l[1]) < 5 * sd + 3 * sigma * sigma / (n * l[1]));
    CHECK(std::abs(welch[j] - one[j]) < 10 * sd + 3 * sigma * sigma / (n * l[1]));
  }
  auto floor_stats = [&](const std::vector<double>& a, double* mean, double* scatter) {
    double s = 0, s2 = 0;
    int m = 0;
    for (int j = 3; j < n / 2 - 1; ++j) {
      bool near = false;
      for (const auto& l : lines) near = near || std::abs(j - l[0]) <= 1;
      if (near) continue;
      const double p = a[static_cast<std::size_t>(j)] * a[static_cast<std::size_t>(j)];
      s += p;
      s2 += p * p;
      ++m;
    }
    *mean = s / m;
    *scatter = std::sqrt(s2 / m - *mean * *mean) / *mean;
    return m;
  };
  double mean1 = 0, scatter1 = 0, meanw = 0, scatterw = 0;
  const int m = floor_stats(one, &mean1, &scatter1);
  floor_stats(welch, &meanw, &scatterw);
  const double expected = 6 * sigma * sigma / n;
  INFO("noise floor: expected " << expected << ", one segment " << mean1 << " (scatter " << scatter1
                                << "), Welch " << meanw << " (scatter " << scatterw << "), " << m
                                << " bins");
  CHECK(std::abs(mean1 / expected - 1) < 5 / std::sqrt(m));
  CHECK(std::abs(meanw / expected - 1) < 5 / std::sqrt(m * segments_expected / 1.1));
  CHECK(scatter1 > 0.7);
  CHECK(scatterw < 0.4);
}

TEST_CASE("spectrum: samples off the uniform grid, bad values and bad options are refused",
          "[unit][dynamics][spectrum]") {
  SpectrumOptions o;
  o.sample_interval = 1e-3;
  o.segment = 16;
  o.start_time = 5e-3;
  WelchSpectrum w(2, o);
  const double v[2] = {1.0, 2.0};
  // Before start_time: skipped, not counted.
  for (int k = 0; k < 5; ++k) w.Add(k * 1e-3, v);
  CHECK(w.samples() == 0);
  for (int k = 5; k < 8; ++k) w.Add(k * 1e-3, v);
  CHECK(w.samples() == 3);
  CHECK(w.first_time() == 5e-3);
  // A late sample (half an interval), a missing one and a repeated one.
  for (double t : {8.5e-3, 9e-3, 7e-3})
    CHECK_THROWS_WITH(w.Add(t, v), Catch::Contains("expected 0.008 s: the samples must be "
                                                   "uniformly spaced by 0.001 s"));
  // Within the tolerance (1e-6 of an interval): accepted.
  w.Add(8e-3 + 1e-10, v);
  const double nan[2] = {1.0, std::nan("")};
  CHECK_THROWS_WITH(w.Add(9e-3, nan), Catch::Contains("channel 1 at t = 0.009 s is"));
  CHECK_THROWS_WITH(w.Add(9e-3, std::span<const double>(v, 1)),
                    Catch::Contains("a sample of 1 values for 2 channels"));
  CHECK_THROWS_WITH(w.Amplitudes(0), Catch::Contains("no complete segment yet (4 of 16 samples)"));
  SpectrumOptions bad = o;
  bad.segment = 4;
  CHECK_THROWS_WITH(WelchSpectrum(1, bad), "spectrum: segment = 4: must be >= 8 samples");
  bad = o;
  bad.sample_interval = 0;
  CHECK_THROWS_WITH(WelchSpectrum(1, bad),
                    "spectrum: sample_interval = 0: must be finite and > 0 [s]");
  bad = o;
  bad.hop = 17;
  CHECK_THROWS_WITH(WelchSpectrum(1, bad), Catch::Contains("spectrum: hop = 17: must be in [1, "
                                                           "segment = 16]"));
}

TEST_CASE("stage frequencies: the paper stage's mesh, fault and sideband lines from its teeth",
          "[unit][dynamics][spectrum]") {
  // By hand, 16/24/65 teeth, 3 planets, ring fixed, sun at 1500 rpm: f_s = 25 Hz,
  // f_c = 25·16/81 = 4.9382716 Hz, f_m = 65 f_c = 16 (f_s − f_c) = 320.98765 Hz,
  // f_s − f_c = 20.061728 Hz; sun tooth 3·20.061728 = 60.185185 Hz; planet tooth
  // f_m/24 = 13.374486 Hz (both flanks 26.748971 Hz); ring tooth 3 f_c = 14.814815 Hz.
  const geometry::Stage stage(test::PaperScene().stage);
  const double ws = io::RpmToRadPerSecond(1500);
  const dynamics::StageFrequencies f = dynamics::CharacteristicFrequencies(stage, -ws);
  CHECK(f.symmetric);
  CHECK(f.sun == Approx(25.0).epsilon(1e-14));
  CHECK(f.carrier == Approx(400.0 / 81).epsilon(1e-14));
  CHECK(f.mesh == Approx(26000.0 / 81).epsilon(1e-14));
  CHECK(f.sun_relative == Approx(1625.0 / 81).epsilon(1e-14));
  CHECK(f.planet_relative == Approx(26000.0 / 81 / 24).epsilon(1e-14));

  // The planet phasing, by hand (16 ≡ 1 mod 3): h z_s mod 3 = 1, 2, 0, 1, 2, 0 for h = 1..6.
  const int family[6] = {1, 2, 0, 1, 2, 0};
  for (int h = 1; h <= 6; ++h) CHECK(dynamics::PhasingFamily(h, 16, 3) == family[h - 1]);
  const double fmax = 6.5 * f.mesh;
  // Torsional: only 3 f_m and 6 f_m (carrier orders 195, 390).
  std::vector<double> allowed;
  for (const auto& l : dynamics::CharacteristicLines(f, dynamics::SignalKind::kTorsional, fmax))
    if (l.allowed) allowed.push_back(l.carrier_order);
  REQUIRE(allowed.size() == 2);
  CHECK(allowed[0] == Approx(195).epsilon(1e-13));
  CHECK(allowed[1] == Approx(390).epsilon(1e-13));
  // Housing-fixed: carrier orders 65h ± 1 that are multiples of 3;
  // h = 1: 66 (f_m + f_c); 2: 129 (2 f_m − f_c); 3: none (194, 196); 4: 261; 5: 324; 6: none.
  allowed.clear();
  std::vector<std::string> names;
  for (const auto& l : dynamics::CharacteristicLines(f, dynamics::SignalKind::kHousing, fmax))
    if (l.allowed) {
      allowed.push_back(l.carrier_order);
      names.push_back(l.name);
    }
  REQUIRE(allowed.size() == 4);
  const double orders[4] = {66, 129, 261, 324};
  for (int k = 0; k < 4; ++k)
    CHECK(allowed[static_cast<std::size_t>(k)] == Approx(orders[k]).epsilon(1e-13));
  CHECK(names[0] == "f_m + f_c");
  CHECK(names[1] == "2 f_m - f_c");
  // The fault lines (not lines of a healthy stage), by hand: a sun tooth k n (f_s − f_c) in a
  // torsional signal and k n (f_s − f_c) ± f_s in a housing one (3 · 1625/81 ± 25 Hz).
  auto find = [&](dynamics::SignalKind kind, const std::string& name) {
    for (const auto& l : dynamics::CharacteristicLines(f, kind, fmax))
      if (l.name == name) return l;
    FAIL("no line " << name);
    return dynamics::SpectralLine{};
  };
  const auto housing = dynamics::SignalKind::kHousing, torsional = dynamics::SignalKind::kTorsional;
  CHECK(find(torsional, "n (f_s - f_c)").frequency == Approx(3 * 1625.0 / 81).epsilon(1e-14));
  CHECK(find(torsional, "n (f_s - f_c)").sun_order == Approx(3).epsilon(1e-14));
  CHECK(find(housing, "n (f_s - f_c) + f_s").frequency ==
        Approx(3 * 1625.0 / 81 + 25).epsilon(1e-14));
  CHECK(find(housing, "2 x n (f_s - f_c) - f_s").frequency ==
        Approx(6 * 1625.0 / 81 - 25).epsilon(1e-14));
  CHECK(find(housing, "f_s").frequency == Approx(25).epsilon(1e-14));
  CHECK(find(torsional, "f_m/z_p").frequency == Approx(26000.0 / 81 / 24).epsilon(1e-14));
  CHECK(find(housing, "f_m/z_p + f_c").frequency ==
        Approx(26000.0 / 81 / 24 + 400.0 / 81).epsilon(1e-14));
  CHECK(find(housing, "n f_c").carrier_order == Approx(3).epsilon(1e-14));
  CHECK(find(torsional, "2 x n f_c").carrier_order == Approx(6).epsilon(1e-14));
  // Beside f_m = 16 (f_s − f_c) in the TE: the comb's 15 and 18 (f_s − f_c).
  CHECK(find(torsional, "5 x n (f_s - f_c)").sun_order == Approx(15).epsilon(1e-14));
  CHECK(find(torsional, "5 x n (f_s - f_c)").harmonic == 1);
  CHECK_FALSE(find(housing, "n (f_s - f_c) + f_s").allowed);
  CHECK_THROWS_WITH(dynamics::CharacteristicFrequencies(stage, 0.0),
                    Catch::Contains("sun speed = 0 rad/s: must be finite and non-zero"));
}

TEST_CASE(
    "fault lines: the orders the planets' phasing keeps for each tooth fault and kind of signal, "
    "by hand on a 4-planet 21/21/63 stage",
    "[unit][dynamics][spectrum]") {
  // docs/damage.md "Which lines a tooth fault puts into which signal". The stage: z_s = 21,
  // z_p = 21, z_r = 63, n = 4 equally spaced ((21 + 63)/4 = 21), frequencies in units of f_c:
  // f_s − f_c = f_m/z_s = 63/21 = 3, f_s = 4, f_m = 63, f_m/z_p = 3. By hand, orders m of the
  // fault's own period kept when m ≡ s (mod n) (sun tooth; s = 0 torsional, ±1 housing) or
  // m + s ≡ 0 (ring tooth); a planet tooth's, all:
  //   sun tooth, torsional: 12 k;            housing: 12 k ± 4 (orders ≡ ±4 mod 12)
  //   planet tooth, torsional: 3 k;          housing: 3 k ± 1
  //   ring tooth, either: 4 k
  // and with a planet carrying its own error (no cancellation) the sun's housing lines 3 k ± 1.
  // Listed up to 70 f_c: multiples k ≤ 3 and, beside f_m = 63, the comb's nearest lines on either
  // side that are not f_m and, in a housing signal, not the healthy stage's f_m + f_c = 64
  // (21 ≡ 1 mod 4; a torsional signal's healthy lines are h f_m with 21 h ≡ 0 mod 4: none here).
  dynamics::StageFrequencies f = test::KinematicFrequencies(21, 21, 63, 4, 4.0);
  REQUIRE(f.symmetric);
  REQUIRE(f.carrier == 1);
  REQUIRE(f.sun_relative == 3);
  auto orders = [&](dynamics::SignalKind kind, dynamics::LineKind fault) {
    std::vector<double> o;
    for (const auto& l : dynamics::CharacteristicLines(f, kind, 70, 1, 3))
      if (l.kind == fault) o.push_back(l.carrier_order);
    return o;
  };
  using V = std::vector<double>;
  const auto torsional = dynamics::SignalKind::kTorsional, housing = dynamics::SignalKind::kHousing;
  CHECK(orders(torsional, dynamics::LineKind::kSunTooth) == V{12, 24, 36, 60});
  CHECK(orders(housing, dynamics::LineKind::kSunTooth) == V{4, 8, 16, 20, 28, 32, 40, 56, 68});
  CHECK(orders(torsional, dynamics::LineKind::kPlanetTooth) == V{3, 6, 9, 60, 66});
  CHECK(orders(housing, dynamics::LineKind::kPlanetTooth) == V{1, 2, 4, 5, 7, 8, 10, 62, 65});
  CHECK(orders(torsional, dynamics::LineKind::kRingTooth) == V{4, 8, 12, 60, 64});
  CHECK(orders(housing, dynamics::LineKind::kRingTooth) == V{4, 8, 12, 60, 68});
  // The housing lines the sun tooth does not put there: k n (f_s − f_c) ± f_c (12 k ± 1) and
  // k n (f_s − f_c) (12 k).
  for (double o : orders(housing, dynamics::LineKind::kSunTooth)) {
    const double r = std::fmod(o, 12.0);
    CHECK(r != 1);
    CHECK(r != 11);
    CHECK(r != 0);
  }
  // A planet with an error of its own: every order m (f_s − f_c) ± f_c, 3 k ± 1.
  f.identical_planets = false;
  CHECK(orders(housing, dynamics::LineKind::kSunTooth) == V{1, 2, 4, 5, 7, 8, 10, 62, 65});
  CHECK(orders(torsional, dynamics::LineKind::kSunTooth) == V{3, 6, 9, 60, 66});
}

TEST_CASE("fault lines of a scene: a damaged or run-out gear's comb, each once",
          "[unit][dynamics][spectrum]") {
  // dynamics::FaultKinds: a pit or crack on a gear, or its run-out, repeats with that gear's turn
  // (docs/damage.md "Which lines a tooth fault puts into which signal"); pin-hole and thickness
  // errors repeat with nothing and add no comb.
  using K = dynamics::LineKind;
  transmission::Damage damage;
  geometry::StageSpec errors;
  CHECK(dynamics::FaultKinds(damage, errors).empty());
  errors.pin_errors = {{5e-6, 0}, {}, {}};
  errors.planet_thickness_errors = {0, 5e-6, 0};
  CHECK(dynamics::FaultKinds(damage, errors).empty());
  damage.pits.push_back({});
  damage.pits.back().gear = "planet2";
  damage.cracks.push_back({});
  damage.cracks.back().gear = "sun";
  damage.pits.push_back({});
  damage.pits.back().gear = "planet3";
  CHECK(dynamics::FaultKinds(damage, errors) == std::vector<K>{K::kSunTooth, K::kPlanetTooth});
  errors.ring_runout.amplitude = 10e-6;
  CHECK(dynamics::FaultKinds(damage, errors) ==
        std::vector<K>{K::kSunTooth, K::kPlanetTooth, K::kRingTooth});
  errors.planet_runouts = {{20e-6, 0}, {}, {}};
  CHECK(dynamics::FaultKinds({}, errors) == std::vector<K>{K::kPlanetTooth, K::kRingTooth});
}

TEST_CASE(
    "spectrum of a run: the skip, the segment of one carrier revolution or of whole mesh "
    "cycles, and a run too short",
    "[unit][dynamics][spectrum]") {
  // The paper stage at ω_c = 2π·100/65 rad/s: a mesh cycle lasts 10 ms, a carrier revolution
  // 0.65 s = 65 cycles; 24 outputs per cycle, Δt = 10 ms/24.
  const geometry::Stage stage(test::PaperScene().stage);
  const double wc = 2 * kPi * 100.0 / 65.0;
  const dynamics::StageFrequencies f = dynamics::CharacteristicFrequencies(stage, wc * 81 / 16);
  REQUIRE(f.carrier == Approx(100.0 / 65).epsilon(1e-14));
  const double dt = 0.01 / 24;
  // 4 cycles of skip and two carrier revolutions: 134 cycles, 3216 outputs.
  const auto run =
      dynamics::MakeRunSpan(stage, wc, transmission::RunRange::kCarrierRevolution, 1.34, 24);
  REQUIRE(run.outputs == 3216);
  const SpectrumOptions o = dynamics::RunSpectrumOptions(run, f, 0, 4);
  CHECK(o.sample_interval == Approx(dt).epsilon(1e-14));
  CHECK(o.segment == 65 * 24);
  CHECK(o.hop == 65 * 12);
  CHECK(o.start_time == Approx(0.04).epsilon(1e-14));  // output 96 of 3216
  CHECK(o.resolution() == Approx(f.carrier).epsilon(1e-12));
  // Shorter than a revolution (one planet revolution, 24 cycles, 576 outputs): the rest after
  // the skip, outputs 96..576 (481), in whole mesh cycles: 20 cycles, 480 samples.
  const auto planet =
      dynamics::MakeRunSpan(stage, wc, transmission::RunRange::kPlanetRevolution, 0, 24);
  CHECK(dynamics::RunSpectrumOptions(planet, f, 0, 4).segment == 480);
  // A resolution given: N = round(1/(Δf Δt)) = round(24/(10 ms · 20 Hz)) = 120.
  CHECK(dynamics::RunSpectrumOptions(planet, f, 20, 4).segment == 120);
  const dynamics::SpectrumInputs given{"--res", true, "--skip", true, "--range planet"};
  // Outside [1/(481 Δt), 1/(8 Δt)] = [4.99, 300] Hz: named with the rule, before any count.
  CHECK_THROWS_WITH(dynamics::RunSpectrumOptions(planet, f, 1, 4, given),
                    Catch::Contains("--res = 1 Hz: must be in [4.99, 300] Hz here") &&
                        Catch::Contains("leaves 481 of them (0.2004 s) after --skip = 4 mesh"));
  CHECK_THROWS_WITH(dynamics::RunSpectrumOptions(planet, f, 1e-300, 4, given),
                    Catch::Contains("--res = 1e-300 Hz: must be in [4.99, 300] Hz here") &&
                        !Catch::Contains("-9223372036854775808"));
  // A run shorter than the skip: the message names what set the run and the default skip, not
  // an option that was not given.
  const auto cycle = dynamics::MakeRunSpan(stage, wc, transmission::RunRange::kMeshCycle, 0, 24);
  CHECK_THROWS_WITH(
      dynamics::RunSpectrumOptions(cycle, f, 0, 4,
                                   {"--res", false, "--skip", false, "--range cycle"}),
      Catch::StartsWith("spectrum: --range cycle runs 0.01 s in 24 output steps") &&
          Catch::Contains("leaves 0 of them (0 s) after the first 4 mesh cycles (the start "
                          "transient; --skip changes it)") &&
          !Catch::Contains("--res"));
  CHECK_THROWS_WITH(dynamics::RunSpectrumOptions(planet, f, 0, -1, given),
                    "--skip = -1: must be finite and >= 0 [mesh cycles]");
}
