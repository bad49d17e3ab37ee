#include "epicycle/dynamics/stage_branch.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <utility>

#include "epicycle/dynamics/harmonic_balance.hpp"
#include "epicycle/io/number_format.hpp"
#include "epicycle/solvers/contact_solver.hpp"
#include "epicycle/transmission/load_sharing.hpp"

namespace epicycle::dynamics {

using io::Num;

namespace {

[[noreturn]] void Fail(const std::string& field, double value, const std::string& rule) {
  throw std::invalid_argument("stage branch: " + field + " = " + Num(value) + ": " + rule);
}

double CpuSeconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

// The integrator's absolute tolerance per state component: atol_angle or atol_length per DOF, the
// rates' times rate_scale (SimulationOptions).
Eigen::VectorXd Tolerances(const DynamicModel& m, const SimulationOptions& s) {
  const int n = m.size();
  Eigen::VectorXd atol(2 * n);
  for (int k = 0; k < n; ++k) {
    atol(k) = m.dofs()[static_cast<std::size_t>(k)].axis == MotionDof::kRotation ? s.atol_angle
                                                                                 : s.atol_length;
    atol(n + k) = atol(k) * s.rate_scale;
  }
  return atol;
}

// One period of the orbit by Simulate: K_γ, TE amplitude and sun orbit as the speed sweep reads
// them off its window (dynamics/speed_sweep.hpp).
bool PeriodFigures(const DynamicModel& m, const SimulationOptions& sim, const Eigen::VectorXd& y,
                   double period, int samples, StageBranchPoint* p, std::string* message) {
  const int n = m.size();
  std::vector<double> times;
  for (int k = 1; k <= samples; ++k) times.push_back(period * k / samples);
  SimulationOptions s = sim;
  s.keep_samples = false;
  double te_lo = 0, te_hi = 0;
  bool first = true;
  p->k_gamma = 0;
  p->orbit_radius = 0;
  p->helical = {};
  const SimulationResult r =
      Simulate(m, s, y.head(n), y.tail(n), times, [&](const DynamicSample& d) {
        p->k_gamma = std::max(p->k_gamma, d.k_gamma);
        p->orbit_radius = std::max(p->orbit_radius, d.sun_centre.norm());
        p->helical.Add(d.helical);
        te_lo = first ? d.transmission_error : std::min(te_lo, d.transmission_error);
        te_hi = first ? d.transmission_error : std::max(te_hi, d.transmission_error);
        first = false;
      });
  p->te_amplitude = (te_hi - te_lo) / 2;
  p->helical.Finish();
  if (!r.completed()) *message = "the period's figures: " + r.message;
  return r.completed();
}

// The same figures off a harmonic-balance orbit: the model evaluated at `samples` instants
// t_k = k T/samples of the series (k = 1..samples), the contact solve warm-started from the last.
bool SeriesFigures(const DynamicModel& m, const SimulationOptions& sim,
                   const Eigen::MatrixXd& coefficients, double period, int samples,
                   StageBranchPoint* p, std::string* message) {
  const int n = m.size();
  const FourierBasis basis(static_cast<int>(coefficients.rows() - 1) / 2,
                           2 * static_cast<int>(coefficients.rows()));
  const Eigen::MatrixXd y =
      basis.Evaluate(coefficients, Eigen::VectorXd::LinSpaced(samples, 1.0 / samples, 1.0));
  const std::unique_ptr<solvers::ContactSolver> solver = solvers::MakeContactSolver(sim.backend);
  const int sun = m.Find(MotionDof::kSun, MotionDof::kRotation);
  const int carrier = m.Find(MotionDof::kCarrier, MotionDof::kRotation);
  const int sx = m.Find(MotionDof::kSun, MotionDof::kX);
  Evaluation at, warm;
  p->k_gamma = 0;
  p->orbit_radius = 0;
  p->helical = {};
  double te_lo = INFINITY, te_hi = -INFINITY;
  for (int k = 0; k < samples; ++k) {
    const Eigen::VectorXd d = y.row(k).head(n).transpose(), v = y.row(k).tail(n).transpose();
    const double t = period * (k + 1) / samples;
    m.Evaluate(t, d, v, *solver, sim.contact, k ? &warm : nullptr, &at, /*energies=*/false);
    if (!at.ok) {
      *message = "the series' figures at t = " + Num(t) + " s: " + at.message;
      return false;
    }
    // As Simulate's samples (dynamics/simulation.hpp, DynamicSample): K_γ, TE at the sun, orbit.
    const std::vector<double> lsr =
        transmission::LoadSharingRatios(at.sun_mesh_torque, at.input_torque);
    for (double r : lsr) p->k_gamma = std::max(p->k_gamma, static_cast<double>(lsr.size()) * r);
    const double te = sun >= 0       ? d(sun)
                      : carrier >= 0 ? -m.stage_model().stage().sun_ratio() * d(carrier)
                                     : 0.0;
    te_lo = std::min(te_lo, te);
    te_hi = std::max(te_hi, te);
    if (sx >= 0) p->orbit_radius = std::max(p->orbit_radius, std::hypot(d(sx), d(sx + 1)));
    if (m.stage_model().helical())
      p->helical.Add(transmission::HelicalLoadsOf(m.stage_model().stage(), at.poses,
                                                  at.terms.contacts, at.total_force));
    std::swap(at, warm);
  }
  p->te_amplitude = (te_hi - te_lo) / 2;
  p->helical.Finish();
  return true;
}

}  // namespace

std::string PeriodicMethodName(PeriodicMethod method) {
  return method == PeriodicMethod::kHarmonicBalance ? "hb" : "shooting";
}

PeriodicMethod ParsePeriodicMethod(const std::string& word, const std::string& what) {
  if (word == "shooting") return PeriodicMethod::kShooting;
  if (word == "hb") return PeriodicMethod::kHarmonicBalance;
  throw std::invalid_argument(what + " = '" + word +
                              "': not a periodic method (shooting, hb: harmonic balance)");
}

std::string BranchPeriodRefusal(const StagePeriod& period, long max_period_mesh_cycles) {
  if (period.mesh_cycles <= max_period_mesh_cycles) return {};
  std::string why;
  for (const std::string& r : period.reasons) why += (why.empty() ? "" : "; ") + r;
  return "stage branch: the stage's period = " + std::to_string(period.mesh_cycles) +
         " mesh cycles (" + why +
         "): must be <= max_period_mesh_cycles = " + std::to_string(max_period_mesh_cycles) +
         " (shooting integrates the period with its variational equations at every Newton "
         "iteration, where a time integration settles in a number of cycles that does not grow "
         "with "
         "the period: run the time-integration sweep)";
}

void CheckBranchPeriod(const StagePeriod& period, long max_period_mesh_cycles) {
  const std::string refusal = BranchPeriodRefusal(period, max_period_mesh_cycles);
  if (!refusal.empty()) throw std::invalid_argument(refusal);
}

void StageBranchOptions::Validate() const {
  const std::vector<std::string> names = StagePeriodicSystem::ParameterNames();
  if (std::find(names.begin(), names.end(), parameter) == names.end() &&
      !ParseStageErrorKey(parameter, std::numeric_limits<int>::max())) {
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
    throw std::invalid_argument("stage branch: parameter = '" + parameter +
                                "': not a parameter of the stage (its parameters: " + list +
                                ", errors.pin.planetK.radial_um, errors.pin.planetK.tangential_um, "
                                "errors.runout.GEAR.amplitude_um)");
  }
  if (!std::isfinite(start)) Fail("start", start, "must be finite");
  if (!std::isfinite(end)) Fail("end", end, "must be finite");
  if (end == start)
    Fail("end", end, "equals start = " + Num(start) + ": the range must have non-zero width");
  if (max_period_mesh_cycles < 1)
    Fail("max_period_mesh_cycles", static_cast<double>(max_period_mesh_cycles), "must be >= 1");
  if (period.mesh_cycles < 1)
    Fail("period mesh cycles", static_cast<double>(period.mesh_cycles), "must be >= 1");
  if (samples_per_period < 4) Fail("samples_per_period", samples_per_period, "must be >= 4");
  if (harmonics < 1) Fail("harmonics", harmonics, "must be >= 1");
  if (hb_samples != 0 && hb_samples < 2 * harmonics + 1)
    Fail("hb_samples", hb_samples,
         "must be 0 (4 harmonics) or >= 2 harmonics + 1 = " + std::to_string(2 * harmonics + 1));
  if (hill_harmonics < 0) Fail("hill_harmonics", hill_harmonics, "must be >= 0 (0: harmonics)");
  if (!(simulation.rate_scale > 0))
    Fail("rate_scale", simulation.rate_scale,
         "must be > 0 (the rates' absolute tolerance of the shooting)");
  simulation.Validate();
}

StageBranchRecord ContinueStageBranch(
    const DynamicModel& base, const StageBranchOptions& o,
    const std::function<void(const StageBranchRecord&)>& on_point) {
  o.Validate();
  const double cpu0 = CpuSeconds();
  const auto wall0 = std::chrono::steady_clock::now();
  CheckBranchPeriod(o.period, o.max_period_mesh_cycles);
  // An error amplitude: the system's fourth parameter, the stage rebuilt per value.
  const std::vector<std::string> names = StagePeriodicSystem::ParameterNames();
  std::optional<StageErrorKey> error;
  if (std::find(names.begin(), names.end(), o.parameter) == names.end()) {
    error = ParseStageErrorKey(o.parameter, base.stage_model().planets());
    if (!error)
      throw std::invalid_argument("stage branch: parameter = '" + o.parameter +
                                  "': names no gear of this stage (planet1..planet" +
                                  std::to_string(base.stage_model().planets()) + ")");
  }
  const StagePeriodicSystem system(base, o.simulation.backend, o.simulation.contact,
                                   o.period.mesh_cycles, error);
  const int column = system.ParameterIndex(o.parameter);
  StageBranchRecord rec;
  rec.parameter = o.parameter;
  rec.unit = system.parameters()[static_cast<std::size_t>(column)].unit;
  rec.period_mesh_cycles = o.period.mesh_cycles;
  rec.period_reasons = o.period.reasons;
  rec.method = o.method;
  const bool hb = o.method == PeriodicMethod::kHarmonicBalance;
  rec.harmonics = hb ? o.harmonics : 0;
  const int n = base.size();
  for (const char* suffix : {"", " rate"})
    for (const MotionDof& f : base.dofs())
      rec.dof_labels.push_back(f.Label() + std::string(suffix));

  Eigen::VectorXd p = system.DefaultParameters();
  // Both ends must be values the model takes (a damping ratio in [0, 1], a torque of the loaded
  // flanks' sign, a pin error with which the planets assemble): bad input, before any point.
  for (const auto& [field, value] : {std::pair{"start", o.start}, std::pair{"end", o.end}}) {
    p(column) = value;
    try {
      system.ModelAt(p);
    } catch (const std::invalid_argument& e) {
      Fail(field, value, "a value of " + o.parameter + " the model refuses: " + e.what());
    }
  }
  p(column) = o.start;
  if (hb && system.PeriodMap(p).size() != 0)
    throw std::invalid_argument(
        "stage branch: method = hb: the stage's translations (a floating sun, elastic pins) repeat "
        "turned by the carrier's advance, not periodic in the model's coordinates: harmonic "
        "balance needs an orbit that is; use shooting");
  const DynamicModel& start_model = system.ModelAt(p);
  Eigen::VectorXd y0 = Eigen::VectorXd::Zero(2 * n);
  y0.head(n) = start_model.QuasiStaticStart(o.simulation.contact, o.simulation.backend);

  ContinuationOptions c;
  c.parameter = o.parameter;
  c.start = o.start;
  c.end = o.end;
  c.initial_step = o.initial_step;
  c.max_step = o.max_step;
  c.min_step = o.min_step;
  c.max_points = o.max_points;
  c.shooting.rtol = o.simulation.rtol;
  c.shooting.atol = Tolerances(base, o.simulation);
  c.shooting.max_steps = o.simulation.max_steps;
  // The state's scale: the quasi-static deviations (at least 100 absolute tolerances), and for the
  // rates that amplitude vibrating at the highest mesh frequency of the range (a response that
  // follows the mesh has rates in proportion to the speed).
  Eigen::VectorXd p_end = p;
  p_end(column) = o.end;
  const double cycles = static_cast<double>(o.period.mesh_cycles);
  const double mesh_rate =
      2 * std::numbers::pi * cycles / std::min(system.Period(p), system.Period(p_end));
  c.state_scale.resize(2 * n);
  for (int k = 0; k < n; ++k) {
    c.state_scale(k) = std::max(std::abs(y0(k)), 100 * c.shooting.atol(k));
    c.state_scale(n + k) = std::max(mesh_rate * c.state_scale(k), 100 * c.shooting.atol(n + k));
  }
  c.amplitude_samples = 0;  // BranchPoint::amplitude is not used: the figures come from Simulate

  std::size_t written = 0;
  // The new points of the branch so far into the record, with their figures.
  auto collect = [&](const ContinuationResult& so_far) {
    for (; written < so_far.points.size(); ++written) {
      const BranchPoint& b = so_far.points[written];
      StageBranchPoint q;
      q.index = static_cast<int>(written);
      q.parameter = b.parameter;
      Eigen::VectorXd pb = p;
      pb(column) = b.parameter;
      q.sun_speed_rpm = pb(0);
      q.period = b.period;
      q.spectral_radius = b.floquet.spectral_radius;
      q.stability = b.floquet.stability;
      q.real_above_one = b.floquet.real_above_one;
      q.real_below_minus_one = b.floquet.real_below_minus_one;
      q.complex_outside = b.floquet.complex_outside;
      q.arclength = b.arclength;
      q.corrector_iterations = b.corrector_iterations;
      q.state = b.state;
      std::string message;
      const bool figures = hb ? SeriesFigures(system.ModelAt(pb), o.simulation, b.coefficients,
                                              b.period, o.samples_per_period, &q, &message)
                              : PeriodFigures(system.ModelAt(pb), o.simulation, b.state, b.period,
                                              o.samples_per_period, &q, &message);
      if (!figures && rec.figures_message.empty())
        rec.figures_message =
            "at " + o.parameter + " = " + Num(b.parameter) + " " + rec.unit + ": " + message;
      rec.points.push_back(std::move(q));
    }
    rec.bifurcations.clear();
    for (const Bifurcation& b : so_far.bifurcations)
      rec.bifurcations.push_back({b.kind, b.parameter, b.after_point, b.multiplier});
    rec.cpu_seconds = CpuSeconds() - cpu0;
    rec.wall_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  };
  const auto stream = [&](const ContinuationResult& so_far) {
    collect(so_far);
    if (on_point) on_point(rec);
  };
  HarmonicBalanceOptions h;
  if (hb) {
    h.harmonics = o.harmonics;
    h.samples = o.hb_samples;
    h.hill_harmonics = std::min(o.hill_harmonics, o.harmonics);
    h.rtol = c.shooting.rtol;
    h.atol = c.shooting.atol;
  }
  const ContinuationResult r = hb ? ContinueHarmonicBalance(system, c, h, y0, p, stream)
                                  : ContinuePeriodicOrbit(system, c, y0, p, stream);
  collect(r);
  rec.status = r.status;
  rec.message = r.message;
  rec.integrations = r.integrations;
  rec.plain_integrations = r.plain_integrations;
  rec.steps = r.steps;
  rec.rebuilds = system.rebuilds();
  rec.cpu_seconds = CpuSeconds() - cpu0;
  rec.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return rec;
}

double SeparatingTeAmplitude(const StageBranchRecord& from_below,
                             const StageBranchRecord& from_above) {
  if (from_below.bifurcations.empty() || from_above.bifurcations.empty())
    throw std::invalid_argument(
        "separating TE amplitude: both branches need a fold (from below: " +
        std::to_string(from_below.bifurcations.size()) +
        " bifurcations, from above: " + std::to_string(from_above.bifurcations.size()) + ")");
  const StageBranchBifurcation& upper = from_below.bifurcations.front();
  const StageBranchBifurcation& lower = from_above.bifurcations.front();
  double small_max = 0, large_min = INFINITY;
  for (const StageBranchPoint& p : from_below.points)
    if (p.index < upper.after_point) small_max = std::max(small_max, p.te_amplitude);
  for (const StageBranchPoint& p : from_above.points)
    if (p.index < lower.after_point && p.parameter <= upper.parameter)
      large_min = std::min(large_min, p.te_amplitude);
  if (!std::isfinite(large_min))
    throw std::invalid_argument(
        "separating TE amplitude: the branch from above has no point at or "
        "below the upper fold's " +
        io::Num(upper.parameter) + " " + from_below.unit);
  return 0.5 * (small_max + large_min);
}

}  // namespace epicycle::dynamics
