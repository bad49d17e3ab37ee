#include "epicycle/dynamics/spectrum.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>

#include <unsupported/Eigen/FFT>

#include "epicycle/dynamics/speed_sweep.hpp"
#include "epicycle/io/number_format.hpp"

namespace epicycle::dynamics {

using io::Num;

namespace {
// A time in a message, to 12 digits (a sample off the grid may differ in the 7th).
std::string Seconds(double t) {
  char b[40];
  std::snprintf(b, sizeof b, "%.12g", t);
  return b;
}
}  // namespace

void SpectrumOptions::Validate() const {
  auto bad = [](const std::string& field, const std::string& value, const std::string& rule) {
    throw std::invalid_argument("spectrum: " + field + " = " + value + ": " + rule);
  };
  if (!(sample_interval > 0) || !std::isfinite(sample_interval))
    bad("sample_interval", Num(sample_interval), "must be finite and > 0 [s]");
  if (segment < 8) bad("segment", std::to_string(segment), "must be >= 8 samples");
  if (hop < 0 || hop > segment)
    bad("hop", std::to_string(hop),
        "must be in [1, segment = " + std::to_string(segment) + "] samples (0: segment/2)");
  if (!std::isfinite(start_time)) bad("start_time", Num(start_time), "must be finite [s]");
  if (!(time_tolerance > 0 && time_tolerance < 0.5))
    bad("time_tolerance", Num(time_tolerance), "must be in (0, 0.5) sample intervals");
}

WelchSpectrum::WelchSpectrum(int channels, const SpectrumOptions& options)
    : channels_(channels), options_(options), t0_(std::numeric_limits<double>::quiet_NaN()) {
  options_.Validate();
  if (channels < 1)
    throw std::invalid_argument("spectrum: channels = " + std::to_string(channels) +
                                ": must be >= 1");
  if (options_.hop == 0) options_.hop = std::max(1, options_.segment / 2);
  const int n = options_.segment;
  window_.resize(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k)
    window_[static_cast<std::size_t>(k)] = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * k / n);
  buffer_.assign(static_cast<std::size_t>(channels) * static_cast<std::size_t>(n), 0.0);
  power_.assign(static_cast<std::size_t>(channels) * static_cast<std::size_t>(bins()), 0.0);
  mean_.assign(static_cast<std::size_t>(channels), 0.0);
}

void WelchSpectrum::Add(double time, std::span<const double> values) {
  if (static_cast<int>(values.size()) != channels_)
    throw std::invalid_argument("spectrum: a sample of " + std::to_string(values.size()) +
                                " values for " + std::to_string(channels_) + " channels");
  if (!std::isfinite(time))
    throw std::invalid_argument("spectrum: sample time = " + Num(time) + ": must be finite");
  const double dt = options_.sample_interval;
  if (std::isnan(t0_)) {
    if (time < options_.start_time - options_.time_tolerance * dt) return;
    t0_ = time;
  } else {
    const double expected = t0_ + static_cast<double>(samples_) * dt;
    if (!(std::abs(time - expected) <= options_.time_tolerance * dt))
      throw std::invalid_argument(
          "spectrum: sample time = " + Seconds(time) + " s, expected " + Seconds(expected) +
          " s: the samples must be uniformly spaced by " + Num(dt) + " s (within " +
          Num(options_.time_tolerance) + " of it), none missing or repeated");
  }
  for (int c = 0; c < channels_; ++c) {
    const double v = values[static_cast<std::size_t>(c)];
    if (!std::isfinite(v))
      throw std::invalid_argument("spectrum: channel " + std::to_string(c) +
                                  " at t = " + Num(time) + " s is " + Num(v) + ": must be finite");
    buffer_[static_cast<std::size_t>(c) * static_cast<std::size_t>(options_.segment) +
            static_cast<std::size_t>(fill_)] = v;
  }
  ++samples_;
  if (++fill_ == options_.segment) Segment();
}

void WelchSpectrum::Segment() {
  const int n = options_.segment, nb = bins(), hop = options_.hop;
  Eigen::FFT<double> fft;
  fft.SetFlag(Eigen::FFT<double>::HalfSpectrum);
  std::vector<double> x(static_cast<std::size_t>(n));
  std::vector<std::complex<double>> spectrum;
  const double sum_w = 0.5 * n;  // Σ w_k of the periodic Hann window, exactly
  for (int c = 0; c < channels_; ++c) {
    double* seg = buffer_.data() + static_cast<std::size_t>(c) * static_cast<std::size_t>(n);
    double mean = 0;
    for (int k = 0; k < n; ++k) mean += seg[k];
    mean /= n;
    mean_[static_cast<std::size_t>(c)] += mean;
    for (int k = 0; k < n; ++k)
      x[static_cast<std::size_t>(k)] = window_[static_cast<std::size_t>(k)] * (seg[k] - mean);
    fft.fwd(spectrum, x);
    double* p = power_.data() + static_cast<std::size_t>(c) * static_cast<std::size_t>(nb);
    for (int j = 1; j < nb; ++j) {
      const double scale = (2 * j == n ? 1.0 : 2.0) / sum_w;
      p[j] += std::norm(scale * spectrum[static_cast<std::size_t>(j)]);
    }
    // Keep the overlap: the last n − hop samples start the next segment.
    std::copy(seg + hop, seg + n, seg);
  }
  fill_ = n - hop;
  ++segments_;
}

std::vector<double> WelchSpectrum::Amplitudes(int channel) const {
  if (channel < 0 || channel >= channels_)
    throw std::out_of_range("spectrum: channel " + std::to_string(channel) + " of " +
                            std::to_string(channels_));
  if (segments_ == 0)
    throw std::logic_error("spectrum: no complete segment yet (" + std::to_string(samples_) +
                           " of " + std::to_string(options_.segment) + " samples)");
  const int nb = bins();
  std::vector<double> a(static_cast<std::size_t>(nb));
  const double* p =
      power_.data() + static_cast<std::size_t>(channel) * static_cast<std::size_t>(nb);
  a[0] = std::abs(mean_[static_cast<std::size_t>(channel)]) / segments_;
  for (int j = 1; j < nb; ++j) a[static_cast<std::size_t>(j)] = std::sqrt(p[j] / segments_);
  return a;
}

double LineAmplitude(const std::vector<double>& amplitude, double resolution, double frequency) {
  if (!(resolution > 0) || !std::isfinite(frequency)) return 0;
  const double at = frequency / resolution;
  double best = 0;
  for (long j = std::max(0L, static_cast<long>(std::ceil(at - 1 - 1e-9)));
       j <= static_cast<long>(std::floor(at + 1 + 1e-9)) && j < static_cast<long>(amplitude.size());
       ++j)
    best = std::max(best, amplitude[static_cast<std::size_t>(j)]);
  return best;
}

StageFrequencies CharacteristicFrequencies(const geometry::Stage& stage, double sun_speed) {
  if (!(sun_speed != 0) || !std::isfinite(sun_speed))
    throw std::invalid_argument("characteristic frequencies: sun speed = " + Num(sun_speed) +
                                " rad/s: must be finite and non-zero");
  StageFrequencies f;
  f.sun_teeth = stage.sun().teeth();
  f.planet_teeth = stage.planet(0).teeth();
  f.ring_teeth = stage.ring().teeth();
  f.planets = stage.planets();
  f.symmetric = EquallySpaced(stage) && (f.sun_teeth + f.ring_teeth) % f.planets == 0;
  const geometry::StageSpec& spec = stage.spec();
  f.identical_planets =
      std::all_of(spec.pin_errors.begin(), spec.pin_errors.end(),
                  [](const geometry::PinError& e) { return e.radial == 0 && e.tangential == 0; }) &&
      std::all_of(spec.planet_runouts.begin(), spec.planet_runouts.end(),
                  [](const geometry::Runout& r) { return r.amplitude == 0; }) &&
      std::all_of(spec.planet_thickness_errors.begin(), spec.planet_thickness_errors.end(),
                  [](double e) { return e == 0; });
  // docs/model.md §9 "Fault frequencies", ring fixed.
  f.sun = std::abs(sun_speed) / (2.0 * std::numbers::pi);
  f.carrier = f.sun * f.sun_teeth / (f.sun_teeth + f.ring_teeth);
  f.mesh = f.ring_teeth * f.carrier;
  f.sun_relative = f.sun - f.carrier;
  f.planet_relative = f.mesh / f.planet_teeth;
  return f;
}

std::vector<LineKind> FaultKinds(const transmission::Damage& damage,
                                 const geometry::StageSpec& errors) {
  bool sun = errors.sun_runout.amplitude > 0, ring = errors.ring_runout.amplitude > 0;
  bool planet = std::any_of(errors.planet_runouts.begin(), errors.planet_runouts.end(),
                            [](const geometry::Runout& r) { return r.amplitude > 0; });
  auto note = [&](const std::string& gear) {
    sun = sun || gear == "sun";
    ring = ring || gear == "ring";
    planet = planet || gear.rfind("planet", 0) == 0;
  };
  for (const auto& p : damage.pits) note(p.gear);
  for (const auto& c : damage.cracks) note(c.gear);
  std::vector<LineKind> kinds;
  if (sun) kinds.push_back(LineKind::kSunTooth);
  if (planet) kinds.push_back(LineKind::kPlanetTooth);
  if (ring) kinds.push_back(LineKind::kRingTooth);
  return kinds;
}

std::string SignalKindName(SignalKind kind) {
  return kind == SignalKind::kTorsional ? "torsional" : "housing";
}

std::string LineKindName(LineKind kind) {
  switch (kind) {
    case LineKind::kMesh:
      return "mesh";
    case LineKind::kCarrierSideband:
      return "carrier sideband";
    case LineKind::kSunTooth:
      return "sun tooth";
    case LineKind::kPlanetTooth:
      return "planet tooth";
    case LineKind::kRingTooth:
      return "ring tooth";
  }
  return "?";
}

std::vector<SpectralLine> CharacteristicLines(const StageFrequencies& f, SignalKind kind,
                                              double max_frequency, int carrier_sidebands,
                                              int fault_multiples) {
  if (!(max_frequency > 0) || !std::isfinite(max_frequency))
    throw std::invalid_argument("characteristic lines: max frequency = " + Num(max_frequency) +
                                " Hz: must be finite and > 0");
  if (carrier_sidebands < 0 || fault_multiples < 0)
    throw std::invalid_argument(
        "characteristic lines: sidebands = " + std::to_string(carrier_sidebands) +
        ", fault multiples = " + std::to_string(fault_multiples) + ": must be >= 0");
  if (!(f.carrier > 0 && f.mesh > 0))
    throw std::invalid_argument("characteristic lines: the stage's frequencies are not set");
  std::vector<SpectralLine> lines;
  auto add = [&](std::string name, LineKind k, double hz, int h, int side, int multiple,
                 bool allowed) {
    if (!(hz > 0) || hz > max_frequency * (1 + 1e-12)) return;
    SpectralLine x;
    x.name = std::move(name);
    x.kind = k;
    x.frequency = hz;
    x.carrier_order = hz / f.carrier;
    x.sun_order = hz / f.sun_relative;
    x.harmonic = h;
    x.sideband = side;
    x.multiple = multiple;
    x.allowed = allowed;
    lines.push_back(std::move(x));
  };
  const int n = f.planets;
  auto times = [](int k, const std::string& what) {
    return k == 1 ? what : std::to_string(k) + " " + what;
  };
  const int harmonics = static_cast<int>(std::floor(max_frequency / f.mesh + 1e-12)) + 1;
  for (int h = 1; h <= harmonics; ++h) {
    // The planet phasing (Parker & Lin): family k = h z_s mod n of mesh harmonic h.
    const int family = PhasingFamily(h, f.sun_teeth, n);
    const double fm = h * f.mesh;
    const std::string hm = times(h, "f_m");
    add(hm, LineKind::kMesh, fm, h, 0, 1,
        !f.symmetric || (kind == SignalKind::kTorsional && family == 0));
    for (int k = 1; k <= carrier_sidebands; ++k) {
      const std::string side = times(k, "f_c");
      for (int sign : {-1, 1}) {
        // Housing: orders h z_r ± 1 that are multiples of n, i.e. h z_s ≡ ±1 (mod n).
        const bool housing =
            kind == SignalKind::kHousing && k == 1 && family == ((sign % n) + n) % n;
        add(hm + (sign < 0 ? " - " : " + ") + side, LineKind::kCarrierSideband,
            fm + sign * k * f.carrier, h, sign * k, 1, !f.symmetric || housing);
      }
    }
  }
  // The tooth faults (docs/damage.md "Which lines a tooth fault puts into which signal"): a
  // term of order m of planet i's response carries the phase of planet i (sun tooth: e^{−i m ψ_i}
  // in the sun's turn relative to the carrier; ring tooth: e^{i m ψ_i} in the carrier's turn) and
  // a housing-fixed component of a vector adds e^{±i(φ_c + ψ_i)}; the sum over n equally spaced
  // identical planets keeps the orders whose total phase is a multiple of 2π for every i. A
  // planet tooth's lines come from one planet: nothing cancels.
  std::vector<double> healthy;
  for (const SpectralLine& x : lines)
    if (x.allowed) healthy.push_back(x.frequency);
  auto same = [](double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(a, b); };
  const bool phased = f.symmetric && f.identical_planets;
  struct Comb {
    LineKind kind;
    double spacing;            // F [Hz]
    std::string spacing_name;  // "n (f_s - f_c)"
    double shift;              // g [Hz]: the housing frame's, 0 for none
    std::string shift_name;
  };
  const bool housing = kind == SignalKind::kHousing;
  const Comb combs[] = {
      phased ? Comb{LineKind::kSunTooth, n * f.sun_relative, "n (f_s - f_c)", housing ? f.sun : 0,
                    "f_s"}
             : Comb{LineKind::kSunTooth, f.sun_relative, "(f_s - f_c)", housing ? f.carrier : 0,
                    "f_c"},
      Comb{LineKind::kPlanetTooth, f.planet_relative, "f_m/z_p", housing ? f.carrier : 0, "f_c"},
      phased ? Comb{LineKind::kRingTooth, n * f.carrier, "n f_c", 0, ""}
             : Comb{LineKind::kRingTooth, f.carrier, "f_c", 0, ""},
  };
  for (const Comb& c : combs) {
    const std::vector<int> shifts = c.shift > 0 ? std::vector<int>{-1, 1} : std::vector<int>{0};
    // "n (f_s - f_c)", "2 x n (f_s - f_c) + f_s", "f_s - f_c", "(f_s - f_c) + f_c", "f_c".
    auto name = [&](int k, int s) {
      const std::string& sp = c.spacing_name;
      std::string out = k == 0                        ? ""
                        : k > 1                       ? std::to_string(k) + " x " + sp
                        : s != 0 || sp.front() != '(' ? sp
                                                      : sp.substr(1, sp.size() - 2);
      if (s != 0) out += k == 0 ? c.shift_name : (s < 0 ? " - " : " + ") + c.shift_name;
      return out;
    };
    auto hz = [&](int k, int s) { return k * c.spacing + s * c.shift; };
    std::vector<double> listed;
    for (int k = 0; k <= fault_multiples; ++k)
      for (int s : shifts)
        if (hz(k, s) > 0) {
          add(name(k, s), c.kind, hz(k, s), 0, s, k, false);
          listed.push_back(hz(k, s));
        }
    if (fault_multiples == 0) continue;
    // Beside each mesh harmonic: the comb's nearest line below and above that is neither the
    // harmonic, nor a healthy stage's line, nor listed above.
    for (int h = 1; h <= harmonics; ++h) {
      const double fm = h * f.mesh;
      struct Near {
        int k = -1, s = 0;
        double d = 0;
      } below, above;
      for (int s : shifts) {
        const int k0 = static_cast<int>(std::floor((fm - s * c.shift) / c.spacing));
        for (int k = std::max(0, k0 - 3); k <= k0 + 4; ++k) {
          const double x = hz(k, s);
          if (!(x > 0) || same(x, fm) ||
              std::any_of(healthy.begin(), healthy.end(), [&](double y) { return same(x, y); }) ||
              std::any_of(listed.begin(), listed.end(), [&](double y) { return same(x, y); }))
            continue;
          Near& side = x < fm ? below : above;
          if (side.k < 0 || std::abs(x - fm) < side.d) side = {k, s, std::abs(x - fm)};
        }
      }
      for (const Near* side : {&below, &above})
        if (side->k >= 0)
          add(name(side->k, side->s), c.kind, hz(side->k, side->s), h, side->s, side->k, false);
    }
  }
  std::stable_sort(lines.begin(), lines.end(), [](const SpectralLine& a, const SpectralLine& b) {
    return a.frequency < b.frequency;
  });
  return lines;
}

}  // namespace epicycle::dynamics
