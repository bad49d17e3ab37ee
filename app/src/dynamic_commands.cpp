// `epicycle dynamic SCENE`: the dynamic model of the stage (docs/dynamic.md) integrated in time at
// a sun speed, from the quasi-static solution at t = 0. Results are written as they are computed
// (CSV per output step, per tooth pair and per bearing; a JSON summary at the end; SVG plots of
// LSR(t), TE(t) and the sun's orbit). A run that fails midway keeps every step already written
// and says where and why (non-zero exit).
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "console.hpp"
#include "epicycle/dynamics/dynamic_run.hpp"
#include "epicycle/dynamics/dynamic_summary.hpp"
#include "epicycle/dynamics/modes.hpp"
#include "epicycle/dynamics/modes_run.hpp"
#include "epicycle/dynamics/run_span.hpp"
#include "epicycle/dynamics/simulation.hpp"
#include "epicycle/dynamics/speed_sweep.hpp"
#include "epicycle/dynamics/vibration.hpp"
#include "epicycle/io/units.hpp"
#include "epicycle/report/dynamic_run_files.hpp"
#include "epicycle/report/modes_text.hpp"
#include "epicycle/report/ratings.hpp"
#include "epicycle/report/record_json.hpp"
#include "epicycle/report/run_files.hpp"
#include "epicycle/report/spectrum_files.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "options.hpp"
#include "periodic_command.hpp"
#include "speed_sweep_command.hpp"

namespace epicycle::app {

namespace {

using json = nlohmann::json;

struct DynamicArgs {
  std::string scene, backend = "newton", integrator = "cvode-bdf", out = "dynamic-out", range, sun,
                     friction, cache, speed_sweep, continue_spec;  // range "": planet
  double rtol = 1e-6, start_deg = 0, window_cycles = 0;
  // Not given: the scene's speed, the range's duration, the library's defaults (the spectrum's:
  // one carrier revolution, 4 mesh cycles skipped).
  std::optional<double> speed_rpm, time, rate_scale, contact_tol, spectrum_resolution,
      spectrum_skip, time_limit;
  std::optional<long> max_steps;
  int outputs_per_cycle = 0, max_order = 5, threads = 0, harmonics = 0, periodic_points = 0,
      hb_harmonics = 0;
  std::string periodic_method;
  std::string carry_state;  // --carry-state: empty (none), up, down
  bool periodic = false, no_cache = false, quiet = false, fd_jacobian = false, stresses = false,
       spectrum = false, rating = false;
};

// The program's sink: the run's files (report/), its header on the console and the progress bar.
class ConsoleSink final : public report::DynamicRunOutput {
 public:
  ConsoleSink(const DynamicArgs& a, json provenance)
      : DynamicRunOutput(a.out, std::move(provenance)),
        a_(a),
        tty_(!a.quiet && isatty(fileno(stderr))) {}

  void Start(const dynamics::DynamicPlan& p) override {
    if (!p.cost_warning.empty()) std::fprintf(stderr, "warning: %s\n", p.cost_warning.c_str());
    Print(report::DynamicPlanText(p, a_.integrator, a_.backend));
    DynamicRunOutput::Start(p);
    planets_ = p.rig->stage.planets();
    outputs_ = p.span->outputs;
    t0_ = std::chrono::steady_clock::now();
  }

  void Step(const dynamics::DynamicSample& s) override {
    DynamicRunOutput::Step(s);
    if (tty_)
      Progress(static_cast<int>(steps()), outputs_, 0,
               std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count(),
               "steps");
  }

  bool tty() const { return tty_; }
  int planets() const { return planets_; }

 private:
  const DynamicArgs& a_;
  bool tty_;
  int planets_ = 0, outputs_ = 0;
  std::chrono::steady_clock::time_point t0_;
};

dynamics::DynamicRequest Request(const DynamicArgs& a) {
  dynamics::DynamicRequest r;
  r.scene = StageScene(a.scene, a.sun, "dynamic");
  r.sun_speed_rpm = a.speed_rpm;
  r.friction = a.friction;
  if (!a.range.empty()) r.range = transmission::RunRangeFromName(a.range);
  r.time_s = a.time;
  r.start_deg = a.start_deg;
  r.outputs_per_cycle = a.outputs_per_cycle;
  r.backend = a.backend;
  r.integrator = a.integrator;
  r.rtol = a.rtol;
  r.rate_scale = a.rate_scale;
  r.contact_tolerance = a.contact_tol;
  r.max_order = a.max_order;
  r.analytic_jacobian = !a.fd_jacobian;
  r.max_steps = a.max_steps;
  r.time_limit_s = a.time_limit;
  r.stresses = a.stresses;
  r.rating = a.rating;
  r.spectrum = a.spectrum;
  r.spectrum_resolution_hz = a.spectrum_resolution;
  r.spectrum_skip_cycles = a.spectrum_skip;
  r.tables = TableOptions(a.cache, a.no_cache);
  r.names = {"--time",
             "--speed-rpm",
             "--range",
             "--rating",
             "--spectrum-resolution",
             "--spectrum-skip-cycles",
             "--outputs-per-cycle",
             "--start-deg",
             "--rtol",
             "--rate-scale",
             "--contact-tol",
             "--max-order",
             "--max-steps",
             "--time-limit"};
  return r;
}

void RunDynamic(const DynamicArgs& a) {
  if (!a.speed_sweep.empty() && a.spectrum)
    throw std::invalid_argument("--spectrum belongs to a run at one speed, not --speed-sweep");
  if (!a.speed_sweep.empty() && (a.speed_rpm || a.time))
    throw std::invalid_argument("--speed-sweep = " + a.speed_sweep +
                                ": runs its own speeds and windows; give it without --speed-rpm "
                                "and --time");
  if (a.speed_sweep.empty() && (a.threads != 0 || a.window_cycles != 0))
    throw std::invalid_argument("--threads and --window-cycles belong to --speed-sweep");
  if (!a.carry_state.empty() && (a.speed_sweep.empty() || a.periodic))
    throw std::invalid_argument("--carry-state = " + a.carry_state +
                                ": belongs to --speed-sweep's time integration (not --periodic, "
                                "which follows the branch itself)");
  const dynamics::CarryState carry =
      a.carry_state.empty() ? dynamics::CarryState::kNone
                            : dynamics::ParseCarryState("--carry-state", a.carry_state);
  const dynamics::DynamicRequest request = Request(a);
  // The periodic orbits: over the sun speed (--speed-sweep with --periodic) or another parameter
  // (--continue); their range and the scene's period are checked before the tables.
  if (a.periodic && a.speed_sweep.empty())
    throw std::invalid_argument(
        "--periodic: needs --speed-sweep FROM:TO:N (the sun speed's range)");
  if (!a.continue_spec.empty() && !a.speed_sweep.empty())
    throw std::invalid_argument("--continue = " + a.continue_spec +
                                ": one continuation at a time; give it without --speed-sweep");
  if (!a.continue_spec.empty() && a.spectrum)
    throw std::invalid_argument("--spectrum belongs to a run at one speed, not --continue");
  if (a.periodic_points != 0 && !a.periodic && a.continue_spec.empty())
    throw std::invalid_argument("--periodic-points belongs to --periodic and --continue");
  if ((!a.periodic_method.empty() || a.hb_harmonics != 0) && !a.periodic && a.continue_spec.empty())
    throw std::invalid_argument(
        "--periodic-method and --hb-harmonics belong to --periodic and "
        "--continue");
  std::string fallback;  // why a periodic sweep runs by time integration ("": it does not)
  if (a.periodic || !a.continue_spec.empty()) {
    dynamics::BranchRequest branch;
    branch.run = request;
    if (a.periodic)
      ParseBranch("--speed-sweep", a.speed_sweep, &branch);
    else
      ParseBranch("--continue", a.continue_spec, &branch);
    if (a.periodic_points != 0) branch.max_points = a.periodic_points;
    if (!a.periodic_method.empty())
      branch.method = dynamics::ParsePeriodicMethod(a.periodic_method, "--periodic-method");
    if (a.hb_harmonics != 0) branch.harmonics = a.hb_harmonics;
    branch.names.harmonics = "--hb-harmonics";
    // A period too long for shooting to pay: the same speed range by time integration, said so.
    const std::string too_long = a.periodic ? dynamics::BranchPeriodTooLong(branch) : "";
    if (too_long.empty())
      return RunBranch({a.periodic ? "--speed-sweep" : "--continue",
                        a.periodic ? a.speed_sweep : a.continue_spec, a.out, a.quiet},
                       branch);
    fallback = too_long +
               "; the speed sweep runs by time integration instead (--periodic-method, "
               "--hb-harmonics and --periodic-points are unused)";
    std::fprintf(stderr, "warning: --periodic: %s\n", fallback.c_str());
  }
  if (!a.speed_sweep.empty()) {
    ParseSpeedSweep(a.speed_sweep);  // bad input before the tables
    dynamics::SpeedSweepRequest sweep;
    sweep.run = request;
    sweep.window_cycles = a.window_cycles;
    sweep.harmonics = a.harmonics;
    sweep.threads = a.threads;
    sweep.carry = carry;
    sweep.periodic_fallback = fallback;
    return RunSpeedSweep({a.speed_sweep, a.out, a.backend, a.quiet}, std::move(sweep));
  }
  ConsoleSink sink(a, Provenance(a.backend, &request.scene));
  const dynamics::DynamicRecord record = dynamics::RunDynamic(request, sink);
  if (sink.started()) {
    Print(sink.spectrum_text());
    if (sink.tty() && !record.completed()) std::fprintf(stderr, "\n");
    Print(report::DynamicRecordText(record, sink.planets()));
  }
  PrintWarnings(record.warnings);
  sink.Finish(record);
  if (sink.started())
    std::printf(
        "\nwrote %s_steps.csv, _pairs.csv, _bearings.csv, _summary.json, _lsr.svg, _te.svg, "
        "_orbit.svg%s%s\n",
        sink.base().c_str(), record.summary.face_width.empty() ? "" : ", _k_hbeta.svg",
        a.spectrum ? ", _vibration.csv, _spectrum.csv, _spectrum_lines.csv, _spectrum_*.svg" : "");
  else
    std::printf("\nwrote %s_summary.json\n", sink.base().c_str());
  if (!record.completed())  // the start's failure, or where the run stopped
    throw ComputationFailed(
        sink.started() ? fmt::format("the run stopped after {} of {} outputs: {}",
                                     record.summary.samples, record.outputs, record.failure)
                       : record.failure);
}

struct ModesArgs {
  std::string scene, sun, cache, json;
  std::vector<double> speed_range_rpm;  // empty: the scene's speed / 2 .. x 2
  bool no_cache = false;
};

// The program's modes sink: the rig's header on the console before the modes are solved.
class ModesConsole final : public dynamics::ModesSink {
 public:
  void Start(const dynamics::ModesPlan& p) override { Print(report::ModesPlanText(p)); }
};

void RunModes(const ModesArgs& a) {
  dynamics::ModesRequest request;
  request.scene = StageScene(a.scene, a.sun, "modes");
  if (!a.speed_range_rpm.empty())
    request.speed_range_rpm = {a.speed_range_rpm[0], a.speed_range_rpm[1]};
  request.speed_range_option = "--speed-range-rpm";
  request.tables = TableOptions(a.cache, a.no_cache);
  ModesConsole console;
  const dynamics::ModesRecord r = dynamics::RunModes(request, console);
  Print(report::ModesRecordText(r));
  PrintWarnings(r.warnings);
  if (!a.json.empty()) {
    WriteTextFile(a.json,
                  report::SummaryJson(r, Provenance("none", &request.scene)).dump(2) + "\n");
    std::printf("\nwrote %s\n", a.json.c_str());
  }
}

}  // namespace

void RegisterDynamicCommands(CLI::App& app) {
  static ModesArgs m;
  auto* modes = app.add_subcommand(
      "modes", "Natural modes of the stage linearised about its operating point (docs/dynamic.md)");
  modes->add_option("scene", m.scene, "Scene file (TOML) of a stage")
      ->required()
      ->check(CLI::ExistingFile);
  modes->add_option("--sun", m.sun, "Override the scene's sun support")
      ->check(CLI::IsMember(SunOverrideNames()));
  modes->add_option("--json", m.json, "Also write the modes as JSON");
  AddNumber(modes, "--speed-range-rpm", m.speed_range_rpm,
            "Sun speeds LO HI [rpm] for the mesh-harmonic coincidences (default: the scene's "
            "speed / 2 .. x 2)",
            kSunSpeedRpm)
      ->expected(2);
  modes->add_option("--cache", m.cache, "Influence-table cache folder");
  modes->add_flag("--no-cache", m.no_cache, "Build the influence tables in memory only");
  modes->callback([] { RunModes(m); });

  static DynamicArgs a;
  auto* cmd = app.add_subcommand(
      "dynamic", "Dynamic load sharing of a stage in time at a sun speed (docs/dynamic.md)");
  cmd->add_option("scene", a.scene, "Scene file (TOML) of a stage")
      ->required()
      ->check(CLI::ExistingFile);
  AddNumber(cmd, "--speed-rpm", a.speed_rpm,
            "Sun speed [rpm] (default: the scene's [dynamics] sun_speed_rpm, else 1500)",
            kSunSpeedRpm);
  cmd->add_option("--range", a.range,
                  "Simulate one mesh cycle, one planet or sun revolution relative to the "
                  "carrier, or one carrier revolution")
      ->check(CLI::IsMember(io::Names(transmission::kRunRangeNames)));
  AddNumber(cmd, "--time", a.time, "Simulate this long instead [s]", kRunTimeS);
  AddNumber(cmd, "--start-deg", a.start_deg, "Carrier angle at t = 0 [deg]", kCarrierAngleDeg);
  cmd->add_option("--sun", a.sun, "Override the scene's sun support")
      ->check(CLI::IsMember(SunOverrideNames()));
  cmd->add_option("--friction", a.friction, "Override the scene's friction law")
      ->check(CLI::IsMember(io::Names(transmission::kFrictionLawNames)));
  cmd->add_option("--backend", a.backend, "Contact back end (newton, ipopt, nlopt-lbfgs, ...)");
  cmd->add_option("--integrator", a.integrator, "cvode-bdf (default) or arkode-erk")
      ->check(CLI::IsMember({"cvode-bdf", "arkode-erk"}));
  AddNumber(cmd, "--rtol", a.rtol, "Relative tolerance of the integrator", kRelativeTolerance);
  AddNumber(cmd, "--rate-scale", a.rate_scale,
            "Absolute tolerance of the rates = that of the positions times this [1/s] "
            "(default 1e4; 0: the stage's highest linearised natural frequency; "
            "docs/dynamic_cost.md, Error against run time)",
            kRateScale);
  AddNumber(cmd, "--contact-tol", a.contact_tol,
            "Tolerance of every contact solve on its nondimensional residual (default 1e-10)",
            kRunContactTolerance);
  AddNumber(cmd, "--outputs-per-cycle", a.outputs_per_cycle,
            "Output steps per mesh cycle (default: 10 per period of the highest natural "
            "frequency, 20 to 500; 64 in a speed sweep's window; docs/dynamic.md, Outputs)",
            kOutputsPerCycle);
  cmd->add_option("--speed-sweep", a.speed_sweep,
                  "FROM:TO:N: run N sun speeds [rpm] from FROM to TO (ends included) in parallel; "
                  "per speed K_gamma, dynamic factor, TE amplitude, sun orbit, against speed with "
                  "the mesh-harmonic coincidences of the natural frequencies (--range or "
                  "--window-cycles: the measured window; --start-deg: where it begins)");
  cmd->add_flag("--periodic", a.periodic,
                "Speed sweep: the periodic orbits instead of time integrations: shooting and "
                "pseudo-arclength continuation from FROM to TO through the folds, both branches "
                "with their Floquet stability, steps of at most 1/N of the range "
                "(docs/periodic.md)");
  cmd->add_option("--continue", a.continue_spec,
                  "NAME:FROM:TO:N: the periodic orbits continued over a number of the scene at the "
                  "scene's (or --speed-rpm's) speed: sun_speed_rpm, sun_torque_Nm, "
                  "mesh_damping_ratio, errors.pin.planetK.radial_um or tangential_um");
  AddNumber(cmd, "--periodic-points", a.periodic_points,
            "--periodic, --continue: the most points of the branch (default 400)", kSweepSpeeds);
  cmd->add_option("--periodic-method", a.periodic_method,
                  "--periodic, --continue: shooting (the default) or hb: harmonic balance with "
                  "Hill's stability, for a stage whose orbit repeats with the mesh "
                  "(docs/periodic.md)");
  AddNumber(cmd, "--hb-harmonics", a.hb_harmonics,
            "--periodic-method hb: harmonics of the mesh period kept (default 24)", kHarmonics);
  AddNumber(cmd, "--window-cycles", a.window_cycles,
            "Speed sweep: mesh cycles measured per speed (replaces --range)", kWindowCycles);
  AddNumber(cmd, "--harmonics", a.harmonics,
            "Speed sweep: mark coincidences of mesh harmonics 1..N (default: every one in range)",
            kHarmonics);
  AddNumber(cmd, "--threads", a.threads, "Speed sweep: worker threads (default: every core)",
            kThreads);
  cmd->add_option("--carry-state", a.carry_state,
                  "Speed sweep: up or down: a run-up or run-down, one speed after the other in "
                  "that order, each from the previous speed's end state (the jumps of "
                  "docs/periodic.md); none: each speed from rest (the default)");
  AddNumber(cmd, "--max-order", a.max_order, "Largest BDF order of CVODE (1..5)", kMaxOrder);
  AddNumber(cmd, "--max-steps", a.max_steps,
            "Integrator steps per output interval before the run stops (default 2000000)",
            dynamics::kMaxSteps);
  AddNumber(cmd, "--time-limit", a.time_limit,
            "Wall-time budget of the run [s]: when spent it stops with what it has (exit 1)",
            dynamics::kRunTimeLimitS);
  cmd->add_flag("--spectrum", a.spectrum,
                "Also the vibration signals per step and their spectra (docs/spectra.md)");
  AddNumber(cmd, "--spectrum-resolution", a.spectrum_resolution,
            "Spectrum: segment length 1/this [Hz] (default 0: one carrier revolution)",
            kSpectrumResolution);
  AddNumber(cmd, "--spectrum-skip-cycles", a.spectrum_skip,
            "Spectrum: mesh cycles left out at the start (default 4)", kSpectrumSkipCycles);
  cmd->add_flag("--rating", a.rating,
                "ISO 6336 ratings with the run's K_v and the stresses in motion (needs the scene's "
                "[material] bending_limit_MPa and contact_limit_MPa; implies --stresses)");
  cmd->add_flag("--stresses", a.stresses,
                "Also each gear's root stress per output step (the scene's [model] stresses)");
  cmd->add_flag("--fd-jacobian", a.fd_jacobian,
                "CVODE's finite-difference Jacobian instead of the contact sensitivity");
  cmd->add_option("--out", a.out, "Output folder (CSV, JSON, SVG)");
  cmd->add_option("--cache", a.cache, "Influence-table cache folder (default: ~/.cache/epicycle)");
  cmd->add_flag("--no-cache", a.no_cache, "Build the influence tables in memory only");
  cmd->add_flag("--quiet", a.quiet, "No progress bar");
  cmd->callback([] { RunDynamic(a); });
}

}  // namespace epicycle::app
