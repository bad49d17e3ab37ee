// The speed-sweep driver of dynamics/.
#include <algorithm>
#include <array>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "common.hpp"
#include "epicycle/dynamics/load_sharing_parts.hpp"
#include "epicycle/dynamics/modes.hpp"
#include "epicycle/dynamics/run_arguments.hpp"
#include "epicycle/dynamics/speed_sweep.hpp"
#include "epicycle/dynamics/speed_sweep_run.hpp"
#include "epicycle/geometry/plane.hpp"
#include "epicycle/report/record_json.hpp"
#include "epicycle/transmission/run_arguments.hpp"
#include "epicycle/transmission/run_range.hpp"
#include "epicycle/transmission/scene.hpp"
#include "failed_parts.hpp"
#include "helical_ranges.hpp"
#include "integration.hpp"
#include "scene.hpp"

namespace epicycle::python {

// helical_ranges.hpp (here beside its first user, the speed sweep).
py::object HelicalRanges(const std::vector<const transmission::HelicalLoadRange*>& rows) {
  std::size_t n = 0;
  for (const transmission::HelicalLoadRange* x : rows)
    if (x) n = std::max(n, x->mean.planets.size());
  py::dict h;
  const auto count = static_cast<py::ssize_t>(rows.size());
  auto put = [&](const std::string& name, const char* unit, const auto& value) {
    std::vector<double> mean, max_abs;
    for (const transmission::HelicalLoadRange* x : rows) value(x, &mean, &max_abs);
    const auto cols = static_cast<py::ssize_t>(mean.size()) / std::max<py::ssize_t>(count, 1);
    if (cols == 1) {
      h[(name + "_mean_" + unit).c_str()] = Array(std::move(mean));
      h[(name + "_max_abs_" + unit).c_str()] = Array(std::move(max_abs));
    } else {
      h[(name + "_mean_" + unit).c_str()] = Array2(std::move(mean), count, cols);
      h[(name + "_max_abs_" + unit).c_str()] = Array2(std::move(max_abs), count, cols);
    }
  };
  for (const auto& f : transmission::kHelicalMemberFields)
    put(f.name, f.unit,
        [&](const transmission::HelicalLoadRange* x, std::vector<double>* mean,
            std::vector<double>* max_abs) {
          const bool ok = x && x->count > 0;
          mean->push_back(ok ? x->mean.*f.value : kNaN);
          max_abs->push_back(ok ? x->max_abs.*f.value : kNaN);
        });
  for (const auto& f : transmission::kPlanetHelicalFields)
    put(f.name, f.unit,
        [&](const transmission::HelicalLoadRange* x, std::vector<double>* mean,
            std::vector<double>* max_abs) {
          for (std::size_t i = 0; i < n; ++i) {
            const bool ok = x && i < x->mean.planets.size();
            mean->push_back(ok ? x->mean.planets[i].*f.value : kNaN);
            max_abs->push_back(ok ? x->max_abs.planets[i].*f.value : kNaN);
          }
        });
  return Result(h);
}

namespace {

// Python's sink of a speed sweep: the progress of the speeds as they complete.
class SweepProgress final : public dynamics::SpeedSweepSink {
 public:
  explicit SweepProgress(const Progress& report) : report_(report) {}
  void Start(const dynamics::SpeedSweepStart& start) override {
    total_ = static_cast<long>(start.options->sun_speeds_rpm.size());
  }
  void Speed(const dynamics::SpeedResult&, const dynamics::SpeedSweepPlan&) override {
    report_(++done_, total_);
  }

 private:
  const Progress& report_;
  long done_ = 0, total_ = 0;
};

py::object SpeedSweep(const ScenePtr& s, const std::vector<double>& sun_speeds_rpm,
                      const std::string& range, double window_cycles, int outputs_per_cycle,
                      double start_deg, int harmonics, int threads, const Integration& integration,
                      std::optional<std::string> cache_dir, py::object progress,
                      bool raise_on_failure, dynamics::CarryState carry) {
  // Every number by its option's rule (run_arguments.hpp), before any work.
  if (!dynamics::kSweepSpeeds.Holds(static_cast<double>(sun_speeds_rpm.size())))
    throw std::invalid_argument("sun_speeds_rpm: " + std::to_string(sun_speeds_rpm.size()) +
                                " speeds: " + dynamics::kSweepSpeeds.Describe());
  for (std::size_t k = 0; k < sun_speeds_rpm.size(); ++k)
    dynamics::CheckArgument("sun_speeds_rpm[" + std::to_string(k) + "]", sun_speeds_rpm[k],
                            transmission::kSunSpeedRpm);
  if (window_cycles != 0)  // 0: the range's
    dynamics::CheckArgument(dynamics::DynamicArguments::kWindowCycles, window_cycles);
  dynamics::CheckArgument(dynamics::DynamicArguments::kOutputsPerCycle, outputs_per_cycle);
  dynamics::CheckArgument(dynamics::DynamicArguments::kStartDeg, start_deg);
  if (harmonics != 0)  // 0: every harmonic in the range
    dynamics::CheckArgument(dynamics::DynamicArguments::kHarmonics, harmonics);
  dynamics::CheckArgument("threads", threads, transmission::kThreadsOrZero);
  dynamics::SpeedSweepRequest request;
  dynamics::DynamicRequest& run = request.run;
  run.scene = s->scene();
  run.range = transmission::RunRangeFromName(range);
  run.start_deg = start_deg;
  run.outputs_per_cycle = outputs_per_cycle;
  integration.Apply(&run);
  run.tables = TableOptions(cache_dir);
  if (run.scene.kind != transmission::SceneKind::kStage) RequireStage(run.scene, "speed sweep");
  dynamics::ResolvedOptions(run);  // bad input as ValueError before the worker starts
  request.sun_speeds_rpm = sun_speeds_rpm;
  request.window_cycles = window_cycles;
  request.harmonics = harmonics;
  request.threads = threads;
  request.carry = carry;
  CancelToken token;
  const Progress report(std::move(progress), &token);
  SweepProgress sink(report);
  struct Out {
    dynamics::SpeedSweepRecord record;
  };
  const Out out = RunReleased(token, [&] { return Out{dynamics::RunSpeedSweep(request, sink)}; });
  const dynamics::SpeedSweepRecord& r = out.record;
  const dynamics::SpeedSweepPlan& plan = r.plan;
  std::vector<double> rpm, fm, kg, kv, peak, ref, te, orbit, lmin, lmax, dev, residual, wall, cpu;
  std::array<std::vector<double>, dynamics::kLoadSharingPartCount> parts;
  std::vector<char> ok;
  py::list message, factor_mesh, warnings;
  for (const dynamics::SpeedResult& x : r.speeds) {
    const double v = x.ok() ? 1.0 : kNaN;
    rpm.push_back(x.sun_speed_rpm);
    fm.push_back(x.mesh_frequency);
    ok.push_back(x.ok());
    message.append(x.message);
    kg.push_back(v * x.k_gamma);
    kv.push_back(v * x.dynamic_factor);
    factor_mesh.append(x.ok() && x.factor_mesh >= 0
                           ? plan.meshes[static_cast<std::size_t>(x.factor_mesh)]
                           : std::string());
    peak.push_back(v * x.peak_mesh_force);
    ref.push_back(v * x.qs_peak_mesh_force);
    te.push_back(v * x.te_amplitude * 1e6);
    orbit.push_back(v * x.orbit_radius * 1e6);
    lmin.push_back(v * x.lsr_min);
    lmax.push_back(v * x.lsr_max);
    dev.push_back(v * x.lsr_deviation);
    for (std::size_t k = 0; k < parts.size(); ++k) parts[k].push_back(v * x.deviation_parts[k]);
    residual.push_back(v * x.largest_residual);
    wall.push_back(x.wall_seconds);
    cpu.push_back(x.cpu_seconds);
    warnings.append(x.warnings);
  }
  std::vector<double> mode_f, zeta, sigma;
  py::list mode_type, families;
  for (const dynamics::ModeDamping& m : plan.modes) {
    mode_f.push_back(m.mode.frequency);
    zeta.push_back(m.damping_ratio);
    sigma.push_back(m.decay_rate);
    mode_type.append(dynamics::ModeTypeName(m.mode.type));
    families.append(m.families);
  }
  std::vector<double> c_rpm, c_f;
  std::vector<int> c_mode, c_h;
  std::vector<char> c_excited;
  for (const dynamics::Coincidence& c : plan.coincidences) {
    c_rpm.push_back(c.sun_speed_rpm);
    c_f.push_back(c.frequency);
    c_mode.push_back(c.mode);
    c_h.push_back(c.harmonic);
    c_excited.push_back(c.phasing_excited);
  }
  py::dict pm;
  pm["frequency_Hz"] = Array(std::move(mode_f));
  pm["type"] = mode_type;
  pm["damping_ratio"] = Array(std::move(zeta));
  pm["decay_rate_per_s"] = Array(std::move(sigma));
  pm["families"] = families;
  py::dict pc;
  pc["sun_speed_rpm"] = Array(std::move(c_rpm));
  pc["frequency_Hz"] = Array(std::move(c_f));
  pc["mode"] = Array(std::move(c_mode));
  pc["harmonic"] = Array(std::move(c_h));
  pc["phasing_excited"] = BoolArray(c_excited);
  py::dict f;
  f["scene"] = r.scene;
  f["sun_speed_rpm"] = Array(std::move(rpm));
  f["mesh_frequency_Hz"] = Array(std::move(fm));
  f["ok"] = BoolArray(ok);
  f["message"] = message;
  f["k_gamma"] = Array(std::move(kg));
  f["dynamic_factor"] = Array(std::move(kv));
  f["dynamic_factor_mesh"] = factor_mesh;
  f["peak_mesh_force_N"] = Array(std::move(peak));
  f["reference_peak_mesh_force_N"] = Array(std::move(ref));
  f["te_amplitude_urad"] = Array(std::move(te));
  f["sun_orbit_radius_um"] = Array(std::move(orbit));
  f["lsr_min"] = Array(std::move(lmin));
  f["lsr_max"] = Array(std::move(lmax));
  f["lsr_deviation"] = Array(std::move(dev));
  py::dict pp;
  for (std::size_t k = 0; k < parts.size(); ++k)
    pp[dynamics::kLoadSharingPartNames[k]] = Array(std::move(parts[k]));
  f["lsr_deviation_parts"] = Result(pp);
  f["largest_residual"] = Array(std::move(residual));
  f["wall_s"] = Array(std::move(wall));
  f["cpu_s"] = Array(std::move(cpu));
  f["warnings"] = warnings;
  f["modes"] = Result(pm);
  f["coincidences"] = Result(pc);
  f["meshes"] = plan.meshes;
  f["mesh_hz_per_sun_rpm"] = plan.mesh_hz_per_rpm;
  f["skip_time_s"] = plan.skip_time;
  f["qs_k_gamma"] = plan.qs_k_gamma;
  f["qs_te_amplitude_urad"] = plan.qs_te_amplitude * 1e6;
  f["qs_peak_mesh_force_N"] = Array(std::vector<double>(plan.qs_peak_mesh_force));
  f["window_carrier_deg"] = [&] {
    std::vector<double> d;
    for (double a : plan.window_angles) d.push_back(geometry::Deg(a));
    return Array(std::move(d));
  }();
  // A helical stage: each speed's axial loads over its window (NaN where failed).
  if (std::any_of(r.speeds.begin(), r.speeds.end(),
                  [](const dynamics::SpeedResult& x) { return x.helical.count > 0; }))
    f["helical"] = HelicalRanges([&] {
      std::vector<const transmission::HelicalLoadRange*> rows;
      for (const dynamics::SpeedResult& x : r.speeds) rows.push_back(x.ok() ? &x.helical : nullptr);
      return rows;
    }());
  // The record as the program's summary JSON has it (its provenance is the program's).
  f["record"] = JsonToPython(report::RecordJson(r));
  py::object result = Result(f);
  if (raise_on_failure)
    RaiseFailedParts(r.speeds, "speeds", "(result.message lists why)", result);
  return result;
}

}  // namespace

// Speed sweeps and their speed grids.
void BindSpeedSweep(py::module_& m) {
  const dynamics::SpeedSweepRequest sw;  // the library's defaults, the keywords' too
  m.def(
      "speed_sweep",
      [](const ScenePtr& s, const std::vector<double>& sun_speeds_rpm, const std::string& range,
         double window_cycles, int outputs_per_cycle, double start_deg, int harmonics, int threads,
         const std::string& integrator, double rtol, std::optional<double> rate_scale,
         std::optional<double> contact_tol, int max_order, bool analytic_jacobian,
         const std::string& backend, std::optional<std::string> cache_dir, py::object progress,
         bool raise_on_failure, const std::string& carry_state) {
        return SpeedSweep(s, sun_speeds_rpm, range, window_cycles, outputs_per_cycle, start_deg,
                          harmonics, threads,
                          MakeIntegration(integrator, rtol, rate_scale, contact_tol, max_order,
                                          analytic_jacobian, backend),
                          cache_dir, std::move(progress), raise_on_failure,
                          dynamics::ParseCarryState("carry_state", carry_state));
      },
      py::arg("scene"), py::arg("sun_speeds_rpm"), py::kw_only(),
      py::arg("range") = RangeName(dynamics::kDefaultRunRange),
      py::arg("window_cycles") = sw.window_cycles,
      py::arg("outputs_per_cycle") = dynamics::kSweepOutputsPerCycle,
      py::arg("start_deg") = sw.run.start_deg, py::arg("harmonics") = sw.harmonics,
      py::arg("threads") = sw.threads, py::arg("integrator") = sw.run.integrator,
      py::arg("rtol") = sw.run.rtol, py::arg("rate_scale") = py::none(),
      py::arg("contact_tol") = py::none(), py::arg("max_order") = sw.run.max_order,
      py::arg("analytic_jacobian") = sw.run.analytic_jacobian, py::arg("backend") = sw.run.backend,
      py::arg("cache_dir") = py::none(), py::arg("progress") = py::none(),
      py::arg("raise_on_failure") = true,
      py::arg("carry_state") = std::string(dynamics::CarryStateName(sw.carry)),
      (std::string(R"doc(
A speed sweep of the dynamic model (`epicycle dynamic --speed-sweep`; docs/speed_sweeps.md): each
sun speed run from the quasi-static solution, its start transient skipped, then a window measured.

Parameters
----------
scene : Scene
    A stage scene.
sun_speeds_rpm : list of float
    Increasing sun speeds [rpm] (epicycle.speed_grid(from, to, n)).
range : str, default "planet"
    The window: "cycle", "planet", "sun", "revolution".
window_cycles : float, default 0
    A window of this many mesh cycles [-] instead of range (0: range).
outputs_per_cycle : int, default 64
    Samples per mesh cycle [-].
start_deg : float, default 0
    Carrier angle where the window begins [deg].
harmonics : int, default 0
    Mesh harmonics 1..h for the coincidences [-] (0: every one in the speed range, as the
    program's --harmonics).
threads : int, default 0
    Workers [-] (0: every core).
carry_state : str, default "none"
    "up" or "down": the speeds one after the other in that direction, each from the previous
    speed's end state (a slow run-up or run-down, docs/speed_sweeps.md "Carried state"; the
    program's --carry-state); "none": each speed from the quasi-static solution, in parallel.)doc") +
       kIntegrationDoc + R"doc(

Returns
-------
Result
    Per speed: sun_speed_rpm [rpm], mesh_frequency_Hz [Hz], ok, message, k_gamma [-],
    dynamic_factor [-] (K_v) and dynamic_factor_mesh, peak_mesh_force_N [N] and that mesh's
    reference_peak_mesh_force_N [N] (the quasi-static one at the speed, with its friction at
    rest), te_amplitude_urad [µrad], sun_orbit_radius_um [µm], lsr_min, lsr_max [-],
    lsr_deviation (the largest |LSR_i − 1/n|) [-] with lsr_deviation_parts (sun_rotation,
    sun_translation, bearing, friction, off_line, geometry, residual [-] at that sample and
    planet; they sum to the signed deviation) and largest_residual [-] (NaN where failed),
    wall_s, cpu_s [s], warnings; modes (frequency_Hz [Hz], type, damping_ratio [-],
    decay_rate_per_s [1/s], families), coincidences (sun_speed_rpm [rpm], frequency_Hz [Hz], mode,
    harmonic, phasing_excited), meshes, mesh_hz_per_sun_rpm [Hz/rpm], skip_time_s [s], the
    quasi-static reference qs_k_gamma [-], qs_te_amplitude_urad [µrad], qs_peak_mesh_force_N [N]
    per mesh, window_carrier_deg [deg]; a helical stage's helical: per speed its window's axial
    loads, <name>_mean_<unit> and <name>_max_abs_<unit> (the largest magnitude) for
    sun_axial_force_N, ring_axial_force_N, carrier_axial_force_N (S,) [N] and per planet
    sun_mesh_axial_force_N, ring_mesh_axial_force_N, axial_force_N (S, n) [N],
    axial_tilting_moment_radial_Nm, axial_tilting_moment_tangential_Nm, tilting_moment_radial_Nm,
    tilting_moment_tangential_Nm (S, n) [N·m]; record: the sweep's record, the keys and values of
    `speed_sweep_summary.json` but its provenance.

Raises
------
ValueError
    Bad input (the argument's name, value and rule).
ComputationError
    A speed failed and raise_on_failure: the subclass of the failed speeds' status when they share
    one (ContactFailure, IntegratorFailure, TimeLimitReached, GeometryFailure), its .result the
    Result above.)doc")
          .c_str());
  m.def(
      "speed_grid",
      [](double from_rpm, double to_rpm, int count) {
        dynamics::CheckArgument("from_rpm", from_rpm, transmission::kSunSpeedRpm);
        dynamics::CheckArgument("to_rpm", to_rpm, transmission::kSunSpeedRpm);
        dynamics::CheckArgument("count", count, dynamics::kSweepSpeeds);
        return Array(dynamics::SpeedGrid(from_rpm, to_rpm, count));
      },
      py::arg("from_rpm"), py::arg("to_rpm"), py::arg("count"),
      R"doc(
Sun speeds equally spaced from from_rpm to to_rpm, ends included (for speed_sweep).

Parameters
----------
from_rpm : float
    First speed [rpm].
to_rpm : float
    Last speed [rpm].
count : int
    Speeds [-].

Returns
-------
numpy.ndarray
    (count,) sun speeds [rpm].

Raises
------
ValueError
    A speed or count outside its rule.)doc");
}

}  // namespace epicycle::python
