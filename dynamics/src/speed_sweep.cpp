#include "epicycle/dynamics/speed_sweep.hpp"

#include <time.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <complex>
#include <exception>
#include <limits>
#include <mutex>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <thread>
#include <utility>

#include "epicycle/dynamics/dynamic_factor.hpp"
#include "epicycle/dynamics/dynamic_summary.hpp"
#include "epicycle/dynamics/run_span.hpp"
#include "epicycle/io/number_format.hpp"
#include "epicycle/io/units.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/mesh_stiffness.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "epicycle/transmission/run_arguments.hpp"
#include "epicycle/transmission/work_queue.hpp"

namespace epicycle::dynamics {

using io::Num;

namespace {

double ThreadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

int MeshIndex(const transmission::StageContact& c) { return geometry::MeshIndex(c.planet, c.mesh); }

// The cyclic-symmetry families k (0..n−1) present in a mode group of equally spaced planets: the
// planets' motions (rotation; centre x, y turned into the carrier frame by −ψ_i) over the planets
// have discrete Fourier components k; a family is present if it holds at least kFamilyShare of the
// planets' squared amplitude. Rotational modes are k = 0, translational k = ±1, planet modes the
// others (Lin & Parker 1999); a held sun makes the k = ±1 modes "planet" by class, so the family
// is read from the shape, not from the class. Why a share of 1 % and not round-off: an error such
// as run-out makes the linearisation slightly unsymmetric and mixes a few 1e-6 of the other
// families into every mode; phasing is about the dominant family (the mixed-in share is what the
// error's weak excitation of "forbidden" coincidences goes through).
constexpr double kFamilyShare = 1e-2;

std::vector<bool> Families(const Mode& mode, const DynamicModel& model, const geometry::Stage& st) {
  const int n = st.planets();
  // Per family k: [0] rotations [rad²], [1] translations [m²] (not added: each share is taken of
  // its own total).
  std::vector<std::array<double, 2>> energy(static_cast<std::size_t>(n), {0.0, 0.0});
  std::array<double, 2> total{0.0, 0.0};
  for (Eigen::Index col = 0; col < mode.shapes.cols(); ++col) {
    std::vector<std::complex<double>> rot(n), rad(n), tan(n);
    for (int i = 0; i < n; ++i) {
      const int kr = model.Find(MotionDof::kPlanet, MotionDof::kRotation, i);
      const int kx = model.Find(MotionDof::kPlanet, MotionDof::kX, i);
      const int ky = model.Find(MotionDof::kPlanet, MotionDof::kY, i);
      if (kr >= 0) rot[i] = mode.shapes(kr, col);
      if (kx >= 0 && ky >= 0) {
        const double c = std::cos(st.planet_angle(i)), s = std::sin(st.planet_angle(i));
        rad[i] = c * mode.shapes(kx, col) + s * mode.shapes(ky, col);
        tan[i] = -s * mode.shapes(kx, col) + c * mode.shapes(ky, col);
      }
    }
    for (int k = 0; k < n; ++k) {
      std::complex<double> a = 0, b = 0, c = 0;
      for (int i = 0; i < n; ++i) {
        const std::complex<double> w = std::polar(1.0, -2.0 * std::numbers::pi * k * i / n);
        a += rot[i] * w;
        b += rad[i] * w;
        c += tan[i] * w;
      }
      energy[static_cast<std::size_t>(k)][0] += std::norm(a);
      energy[static_cast<std::size_t>(k)][1] += std::norm(b) + std::norm(c);
      total[0] += std::norm(a);
      total[1] += std::norm(b) + std::norm(c);
    }
  }
  std::vector<bool> present(static_cast<std::size_t>(n), !(total[0] > 0 || total[1] > 0));
  for (int k = 0; k < n; ++k)
    for (int q = 0; q < 2; ++q)
      if (total[q] > 0 && energy[static_cast<std::size_t>(k)][q] >= kFamilyShare * total[q])
        present[static_cast<std::size_t>(k)] = true;
  return present;
}

// Parker & Lin (2004) for equally spaced planets: the symmetric mesh excitation at harmonic h
// loads the planets with phases e^{i h z_s ψ_i}, family k ≡ ±h z_s (mod n) (PhasingFamily).
bool PhasingExcited(const std::vector<bool>& families, int h, int sun_teeth) {
  const int n = static_cast<int>(families.size());
  const int k = PhasingFamily(h, sun_teeth, n);
  return families[static_cast<std::size_t>(k)] || families[static_cast<std::size_t>((n - k) % n)];
}

}  // namespace

CarryState ParseCarryState(const std::string& key, const std::string& name) {
  if (const std::optional<CarryState> c = io::ValueOf(kCarryStateNames, name)) return *c;
  throw std::invalid_argument(key + " = '" + name +
                              "': not a carry (give up: each speed from the previous, increasing; "
                              "down: the same, decreasing; none: each from rest)");
}

void SpeedSweepOptions::Validate() const {
  auto bad = [](const std::string& field, double value, const std::string& rule) {
    throw std::invalid_argument("speed sweep: " + field + " = " + Num(value) + ": " + rule);
  };
  if (sun_speeds_rpm.empty())
    throw std::invalid_argument("speed sweep: sun_speeds_rpm is empty: needs at least one speed");
  for (std::size_t k = 0; k < sun_speeds_rpm.size(); ++k) {
    const double s = sun_speeds_rpm[k];
    if (!transmission::kSunSpeedRpm.Holds(s))
      bad("sun_speeds_rpm[" + std::to_string(k) + "]", s, transmission::kSunSpeedRpm.Describe());
    if (k > 0 && !(s > sun_speeds_rpm[k - 1]))
      bad("sun_speeds_rpm[" + std::to_string(k) + "]", s, "must exceed the speed before it");
  }
  if (threads < 1) bad("threads", threads, "must be >= 1");
  if (!(window_cycles > 0) || !std::isfinite(window_cycles))
    bad("window_cycles", window_cycles, "must be > 0");
  if (outputs_per_cycle < 4) bad("outputs_per_cycle", outputs_per_cycle, "must be >= 4");
  // The window's samples are counted before they are made an int (1e5 cycles x 1e5 per cycle
  // would wrap).
  if (!(window_cycles * outputs_per_cycle <= kMaxRunOutputs))
    throw std::invalid_argument(
        "speed sweep: window_cycles x outputs_per_cycle = " + Num(window_cycles) + " x " +
        std::to_string(outputs_per_cycle) + " = " + Num(window_cycles * outputs_per_cycle) +
        " samples per speed: must be at most " + std::to_string(kMaxRunOutputs) +
        " (the output steps a run may have)");
  if (!std::isfinite(window_start)) bad("window_start", window_start, "must be finite");
  if (!(transient_fraction > 0 && transient_fraction < 1))
    bad("transient_fraction", transient_fraction, "must lie in (0, 1)");
  if (!(skip_time >= 0) || !std::isfinite(skip_time))
    bad("skip_time", skip_time, "must be >= 0 (0: from the modal damping)");
  if (harmonics < 0) bad("harmonics", harmonics, "must be >= 0 (0: every harmonic in range)");
  for (int m = 0; m < 2; ++m)
    if (!(modal_mesh_stiffness[m] >= 0) || !std::isfinite(modal_mesh_stiffness[m]))
      bad("modal_mesh_stiffness[" + std::to_string(m) + "]", modal_mesh_stiffness[m],
          "must be >= 0 (0: the base model's)");
  simulation.Validate();
}

std::vector<double> SpeedGrid(double from, double to, int count) {
  auto bad = [](const std::string& what, double value, const std::string& rule) {
    throw std::invalid_argument(what + " = " + Num(value) + ": " + rule);
  };
  if (!(from > 0) || !std::isfinite(from)) bad("first sun speed [rpm]", from, "must be > 0");
  if (!(to >= from) || !std::isfinite(to))
    bad("last sun speed [rpm]", to, "must be finite and >= the first (" + Num(from) + ")");
  if (count < 1) bad("number of speeds", count, "must be >= 1");
  if (count == 1 && to != from)
    bad("number of speeds", count, "must be >= 2 when the last speed differs from the first");
  if (count > 1 && !(to > from))
    bad("last sun speed [rpm]", to, "must exceed the first when there are several speeds");
  std::vector<double> v(static_cast<std::size_t>(count));
  for (int k = 0; k < count; ++k)
    v[static_cast<std::size_t>(k)] = count == 1 ? from : from + (to - from) * k / (count - 1);
  return v;
}

int SpeedSweepResult::failed() const {
  return static_cast<int>(
      std::count_if(speeds.begin(), speeds.end(), [](const SpeedResult& r) { return !r.ok(); }));
}

DynamicModel ModelAtSpeed(const DynamicModel& base, double sun_speed_rpm) {
  transmission::DynamicSettings s = base.settings();
  s.sun_speed = io::RpmToRadPerSecond(sun_speed_rpm);
  DynamicModel m(base.stage_model(), s, base.inertias(), base.loads());
  m.SetMeshStiffness(base.sun_mesh_stiffness(), base.ring_mesh_stiffness());
  return m;
}

int PhasingFamily(int harmonic, int sun_teeth, int planets) {
  if (planets < 1)
    throw std::invalid_argument("planet phasing: planets = " + std::to_string(planets) +
                                ": must be >= 1");
  const long n = planets;
  return static_cast<int>(((static_cast<long>(harmonic) * sun_teeth) % n + n) % n);
}

bool EquallySpaced(const geometry::Stage& stage) {
  const int n = stage.planets();
  for (int i = 1; i < n; ++i) {
    const double d = std::remainder(
        stage.planet_angle(i) - stage.planet_angle(0) - 2.0 * std::numbers::pi * i / n,
        2.0 * std::numbers::pi);
    if (std::abs(d) > 1e-9) return false;
  }
  return true;
}

std::vector<Coincidence> FindCoincidences(const DynamicModel& model, const std::vector<Mode>& modes,
                                          double lo_rpm, double hi_rpm, int max_harmonic) {
  if (!(lo_rpm > 0 && lo_rpm <= hi_rpm && std::isfinite(hi_rpm)))
    throw std::invalid_argument("coincidences: sun speed range " + Num(lo_rpm) + " .. " +
                                Num(hi_rpm) + " rpm: needs 0 < low <= high, both finite");
  const geometry::Stage& stage = model.stage_model().stage();
  const double hz_per_rpm = MeshHzPerSunRpm(stage);
  const bool symmetric = EquallySpaced(stage);
  std::vector<Coincidence> found;
  for (std::size_t j = 0; j < modes.size(); ++j) {
    if (modes[j].rigid) continue;
    const std::vector<bool> families = Families(modes[j], model, stage);
    const double f = modes[j].frequency;
    // n_s = f/(h f_m per rpm) falls in [lo, hi] for h in [f/(hi f_m), f/(lo f_m)]; by default
    // only up to the highest harmonic a run resolves (kMaxResolvedHarmonic, run_span.hpp), so
    // that the work is bounded whatever the modes and the range (a mode at 1e17 Hz has 1e14
    // harmonics in any range).
    const double top = max_harmonic > 0 ? max_harmonic : kMaxResolvedHarmonic;
    const double lowest = std::ceil(f / (hi_rpm * hz_per_rpm));
    if (!(lowest <= top)) continue;  // beyond every harmonic counted (NaN too)
    const auto first = std::max(1L, static_cast<long>(lowest));
    const auto last = static_cast<long>(std::min(top, std::floor(f / (lo_rpm * hz_per_rpm))));
    for (long h = first; h <= last; ++h) {
      Coincidence x;
      x.frequency = f;
      x.sun_speed_rpm = f / (static_cast<double>(h) * hz_per_rpm);
      x.mode = static_cast<int>(j);
      x.harmonic = static_cast<int>(h);
      x.phasing_excited = !symmetric || PhasingExcited(families, x.harmonic, stage.sun().teeth());
      if (x.sun_speed_rpm >= lo_rpm && x.sun_speed_rpm <= hi_rpm) found.push_back(x);
    }
  }
  std::sort(found.begin(), found.end(), [](const Coincidence& a, const Coincidence& b) {
    return a.sun_speed_rpm < b.sun_speed_rpm;
  });
  return found;
}

SpeedSweepPlan PlanSpeedSweep(const DynamicModel& base, const SpeedSweepOptions& options) {
  options.Validate();
  const auto t0 = std::chrono::steady_clock::now();
  SpeedSweepPlan plan;
  const transmission::StageModel& stage_model = base.stage_model();
  const geometry::Stage& stage = stage_model.stage();
  const int n = stage.planets();
  const SimulationOptions& sim = options.simulation;

  // Modes and their damping at the window's start. The damping matrix comes from the Jacobian of
  // the right-hand side at the quasi-static start (−M ∂d̈/∂ḋ) of the model without friction: mesh
  // and bearing damping are linear in the velocities and do not depend on the speed; friction's
  // velocity terms do (∂μ/∂v ~ μ/V_e) and are no viscous damping of the modes (not symmetric).
  DynamicModel model = [&] {
    DynamicModel at_speed = ModelAtSpeed(base, options.sun_speeds_rpm.front());
    transmission::DynamicSettings viscous = at_speed.settings();
    viscous.friction.law = transmission::FrictionLaw::kOff;
    DynamicModel m(base.stage_model(), viscous, base.inertias(), base.loads());
    m.SetMeshStiffness(base.sun_mesh_stiffness(), base.ring_mesh_stiffness());
    return m;
  }();
  model.SetStartAngle(options.window_start);
  DynamicModel linear = model;  // the modes' stiffness (the damping stays the base's)
  if (options.modal_mesh_stiffness[0] > 0 && options.modal_mesh_stiffness[1] > 0)
    linear.SetMeshStiffness(options.modal_mesh_stiffness[0], options.modal_mesh_stiffness[1]);
  Eigen::MatrixXd m, k;
  linear.Linearise(options.window_start, &m, &k);
  const std::vector<Mode> modes = SolveModes(m, k, linear.ModeLayout());
  const Eigen::VectorXd d0 = model.QuasiStaticStart(sim.contact, sim.backend);
  const Eigen::VectorXd v0 = Eigen::VectorXd::Zero(model.size());
  auto solver = solvers::MakeContactSolver(sim.backend);
  Evaluation at;
  model.Evaluate(0.0, d0, v0, *solver, sim.contact, nullptr, &at);
  if (!at.ok)
    throw std::runtime_error("speed sweep: the evaluation at the quasi-static start failed: " +
                             at.message);
  Eigen::MatrixXd dd, dv;
  model.Jacobian(0.0, d0, v0, at, &dd, &dv);
  const Eigen::MatrixXd c = -(model.mass().asDiagonal() * dv);
  plan.slowest_decay_rate = std::numeric_limits<double>::infinity();
  for (const Mode& x : modes) {
    if (x.rigid) continue;
    ModeDamping md;
    md.mode = x;
    md.decay_rate = std::numeric_limits<double>::infinity();
    for (Eigen::Index col = 0; col < x.shapes.cols(); ++col) {
      const Eigen::VectorXd phi = x.shapes.col(col);
      md.decay_rate = std::min(md.decay_rate, 0.5 * phi.dot(c * phi));
    }
    md.damping_ratio = md.decay_rate / (2.0 * std::numbers::pi * x.frequency);
    plan.slowest_decay_rate = std::min(plan.slowest_decay_rate, md.decay_rate);
    plan.modes.push_back(md);
  }
  if (plan.modes.empty())
    throw std::invalid_argument("speed sweep: the linearised stage has no vibration mode");
  if (options.skip_time > 0) {
    plan.skip_time = options.skip_time;
  } else {
    if (!(plan.slowest_decay_rate > 0))
      throw std::invalid_argument(
          "speed sweep: slowest modal decay rate = " + Num(plan.slowest_decay_rate) +
          " 1/s: the start transient does not decay (no damping of that mode); give skip_time > 0");
    plan.skip_time = std::log(1.0 / options.transient_fraction) / plan.slowest_decay_rate;
  }

  // Coincidences inside the speed range.
  plan.mesh_hz_per_rpm = MeshHzPerSunRpm(stage);
  std::vector<Mode> shapes;
  for (ModeDamping& md : plan.modes) {
    const std::vector<bool> families = Families(md.mode, model, stage);
    for (int f = 0; f < n; ++f)
      if (families[static_cast<std::size_t>(f)] && f <= n - f) md.families.push_back(f);
    shapes.push_back(md.mode);
  }
  plan.coincidences = FindCoincidences(model, shapes, options.sun_speeds_rpm.front(),
                                       options.sun_speeds_rpm.back(), options.harmonics);

  // The window's carrier angles (the carrier turns the way of base's carrier speed) and the
  // quasi-static reference there.
  const double sign = base.carrier_speed() < 0 ? -1.0 : 1.0;
  const int samples =
      std::max(1, static_cast<int>(std::lround(options.window_cycles * options.outputs_per_cycle)));
  for (int s = 1; s <= samples; ++s)
    plan.window_angles.push_back(options.window_start +
                                 sign * stage.mesh_cycle() * s / options.outputs_per_cycle);
  // The meshes in the order of geometry::Stage::meshes() (geometry::MeshIndex).
  for (const geometry::MeshSummary& mesh : stage.meshes()) plan.meshes.push_back(mesh.name);
  // The quasi-static reference at the window's angles (with base's friction at its speed; a speed
  // with friction takes its own, RunSpeed).
  double te_min = INFINITY, te_max = -INFINITY;
  const RestReference rest = SolveRestReference(
      base, sim, static_cast<int>(plan.window_angles.size()),
      [&](int i) { return plan.window_angles[static_cast<std::size_t>(i)]; },
      [&](const transmission::PositionResult& r) {
        plan.qs_k_gamma = std::max(plan.qs_k_gamma, transmission::MeshLoadFactor(r));
        te_min = std::min(te_min, r.transmission_error);
        te_max = std::max(te_max, r.transmission_error);
      });
  plan.qs_peak_mesh_force = rest.peak_mesh_force;
  plan.qs_te_amplitude = 0.5 * (te_max - te_min);
  plan.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return plan;
}

SpeedResult SummariseSpeed(const SpeedSweepPlan& plan, const std::vector<DynamicSample>& window,
                           const std::vector<double>& qs_peak_mesh_force) {
  const std::vector<double>& rest =
      qs_peak_mesh_force.empty() ? plan.qs_peak_mesh_force : qs_peak_mesh_force;
  SpeedResult r;
  if (window.empty()) return r;
  std::vector<double> peak(rest.size(), 0.0);
  double te_min = INFINITY, te_max = -INFINITY;
  r.lsr_min = INFINITY;
  r.lsr_max = -INFINITY;
  for (const DynamicSample& s : window) {
    r.k_gamma = std::max(r.k_gamma, s.k_gamma);
    for (double l : s.load_sharing) {
      r.lsr_min = std::min(r.lsr_min, l);
      r.lsr_max = std::max(r.lsr_max, l);
    }
    te_min = std::min(te_min, s.transmission_error);
    te_max = std::max(te_max, s.transmission_error);
    r.orbit_radius = std::max(r.orbit_radius, s.sun_centre.norm());
    const Evaluation& e = s.evaluation;
    std::vector<double> mesh(peak.size(), 0.0);
    for (int j = 0; j < e.terms.size(); ++j)
      mesh[MeshIndex(e.terms.contacts[j])] += e.total_force(j);
    for (std::size_t q = 0; q < mesh.size(); ++q) peak[q] = std::max(peak[q], mesh[q]);
    r.helical.Add(s.helical);
  }
  r.helical.Finish();
  r.te_amplitude = 0.5 * (te_max - te_min);
  for (std::size_t q = 0; q < peak.size(); ++q) {
    if (!(rest[q] > 0)) continue;
    const double f = peak[q] / rest[q];
    if (f > r.dynamic_factor) {
      r.dynamic_factor = f;
      r.factor_mesh = static_cast<int>(q);
      r.peak_mesh_force = peak[q];
      r.qs_peak_mesh_force = rest[q];
    }
  }
  return r;
}

namespace {

// The largest |LSR_i − 1/n| of the window and its parts there (DecomposeLoadSharing).
void AddDeviationParts(const DynamicModel& model, const std::vector<DynamicSample>& window,
                       SpeedResult* r) {
  for (const DynamicSample& s : window) {
    const LoadSharingParts parts = DecomposeLoadSharing(model, s);
    for (std::size_t i = 0; i < parts.deviation.size(); ++i) {
      r->largest_residual = std::max(r->largest_residual, std::abs(parts.residual[i]));
      if (!(std::abs(parts.deviation[i]) > r->lsr_deviation)) continue;
      r->lsr_deviation = std::abs(parts.deviation[i]);
      for (int k = 0; k < kLoadSharingPartCount; ++k)
        r->deviation_parts[static_cast<std::size_t>(k)] = Part(parts, k)[i];
    }
  }
}

// The state a carried sweep hands from one speed to the next (speed_sweep.hpp, "Carried state").
struct CarriedState {
  bool valid = false;
  double carrier_angle = 0;  // [rad]
  Eigen::VectorXd d, v;      // [m, rad], [m/s, rad/s]
};

// One speed, start to end; never throws for a failed computation (the result says why). With a
// valid `from` the run starts from its state and carrier angle instead of the quasi-static
// solution; `end` (if given) receives the state at the end of the window (invalid if the run did
// not complete).
SpeedResult RunSpeed(const DynamicModel& base, const SpeedSweepOptions& options,
                     const SpeedSweepPlan& plan, int index, const CarriedState* from = nullptr,
                     CarriedState* end = nullptr) {
  if (end) end->valid = false;
  const double rpm = options.sun_speeds_rpm[static_cast<std::size_t>(index)];
  const auto t0 = std::chrono::steady_clock::now();
  const double c0 = ThreadCpuSeconds();
  SpeedResult r;
  bool start_failed = false;
  try {
    DynamicModel model = ModelAtSpeed(base, rpm);
    const double wc = std::abs(model.carrier_speed());
    const bool carried = from && from->valid;
    model.SetStartAngle(carried ? from->carrier_angle
                                : options.window_start - model.carrier_speed() * plan.skip_time);
    // Outputs: a few through the skipped part (CVODE's NORMAL mode needs no outputs there; one
    // per mesh cycle keeps the progress of a run that fails visible in its message), then the
    // window's samples, at exactly plan.window_angles.
    const double cycle = model.stage_model().stage().mesh_cycle() / wc;
    std::vector<double> times;
    for (double t = cycle; t < plan.skip_time; t += cycle) times.push_back(t);
    const std::size_t skipped = times.size();
    for (std::size_t s = 1; s <= plan.window_angles.size(); ++s)
      times.push_back(plan.skip_time + cycle * static_cast<double>(s) / options.outputs_per_cycle);
    Eigen::VectorXd d0, v0;
    if (carried) {
      d0 = from->d;
      v0 = from->v;
    } else {
      const StartOutcome start =
          model.SolveQuasiStaticStart(options.simulation.contact, options.simulation.backend);
      if (start.status != transmission::RunStatus::kCompleted) {
        r.status = start.status;
        start_failed = true;
        throw std::runtime_error(start.message);
      }
      d0 = start.d;
      v0 = Eigen::VectorXd::Zero(model.size());
    }
    SimulationResult run = Simulate(model, options.simulation, d0, v0, times);
    if (end && run.completed() && !run.samples.empty()) {
      end->valid = true;
      end->carrier_angle = run.samples.back().carrier_angle;
      end->d = run.samples.back().d;
      end->v = run.samples.back().v;
    }
    const std::vector<DynamicSample> window(
        run.samples.begin() + static_cast<std::ptrdiff_t>(std::min(skipped, run.samples.size())),
        run.samples.end());
    // With friction μ depends on the speed: the reference at rest is this speed's.
    std::vector<double> rest;
    if (model.settings().friction.law != transmission::FrictionLaw::kOff) {
      rest =
          SolveRestReference(model, options.simulation, static_cast<int>(plan.window_angles.size()),
                             [&](int k) { return plan.window_angles[static_cast<std::size_t>(k)]; })
              .peak_mesh_force;
    }
    r = SummariseSpeed(plan, window, rest);
    AddDeviationParts(model, window, &r);
    r.warnings = DynamicWarnings(model.stage_model().stage(), window);
    r.stats = run.stats;
    r.status = run.status;
    r.message = run.message;
  } catch (const std::exception& e) {
    // The start's status, or the reference at rest's contact solve (the only other step that
    // throws on legal input).
    if (!start_failed) r.status = transmission::RunStatus::kContactFailure;
    r.message = e.what();
  }
  r.index = index;
  r.sun_speed_rpm = rpm;
  r.mesh_frequency = rpm * plan.mesh_hz_per_rpm;
  r.cpu_seconds = ThreadCpuSeconds() - c0;
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace

SpeedSweepResult SweepSpeeds(const DynamicModel& base, const SpeedSweepOptions& options,
                             const SpeedSweepPlan& plan,
                             const std::function<void(const SpeedResult&)>& on_result) {
  options.Validate();
  SpeedSweepResult out;
  out.plan = plan;
  const auto t1 = std::chrono::steady_clock::now();
  const std::size_t count = options.sun_speeds_rpm.size();
  out.speeds.resize(count);
  if (options.carry != CarryState::kNone) {
    // One after the other, each from the previous speed's end state (speed_sweep.hpp).
    CarriedState state;
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t i = options.carry == CarryState::kUp ? k : count - 1 - k;
      CarriedState next;
      out.speeds[i] = RunSpeed(base, options, out.plan, static_cast<int>(i), &state, &next);
      state = std::move(next);
      if (on_result) on_result(out.speeds[i]);
    }
    out.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
    return out;
  }
  // Work queue in speed order: the lowest speeds simulate the longest time (the window is a
  // number of mesh cycles), so they start first and the pool ends evenly. Each speed writes its
  // own slot; the hand-over is under the queue's lock.
  transmission::RunWorkQueue(
      count, options.threads,
      [&](std::size_t i) {
        out.speeds[i] = RunSpeed(base, options, out.plan, static_cast<int>(i));
      },
      [&](std::size_t i) {
        if (on_result) on_result(out.speeds[i]);
      });
  out.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  return out;
}

int JumpIndex(const std::vector<SpeedResult>& speeds, CarryState carry, double te_threshold) {
  if (carry == CarryState::kNone)
    throw std::invalid_argument("jump: carry = none: a jump needs a sweep that carries its state");
  if (!(te_threshold > 0) || !std::isfinite(te_threshold))
    throw std::invalid_argument("jump: te_threshold = " + Num(te_threshold) +
                                " rad: must be > 0 and finite");
  const int count = static_cast<int>(speeds.size());
  bool above = false;
  for (int k = 0; k < count; ++k) {
    const int i = carry == CarryState::kUp ? k : count - 1 - k;
    const SpeedResult& r = speeds[static_cast<std::size_t>(i)];
    if (!r.ok()) return -1;
    const bool a = r.te_amplitude > te_threshold;
    if (k == 0)
      above = a;
    else if (a != above)
      return i;
  }
  return -1;
}

SpeedSweepResult SweepSpeeds(const DynamicModel& base, const SpeedSweepOptions& options,
                             const std::function<void(const SpeedResult&)>& on_result) {
  return SweepSpeeds(base, options, PlanSpeedSweep(base, options), on_result);
}

}  // namespace epicycle::dynamics
