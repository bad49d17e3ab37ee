// `epicycle dynamic SCENE`: the dynamic model of the stage (docs/dynamic.md) integrated in time at
// a sun speed, from the quasi-static solution at t = 0. Results are written as they are computed
// (CSV per output step, per tooth pair and per bearing; a JSON summary at the end; SVG plots of
// LSR(t), TE(t) and the sun's orbit). A run that fails midway keeps every step already written
// and says where and why (non-zero exit).
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

// What the command line gives besides the request's fields.
struct DynamicArgs {
  std::string scene, out = "dynamic-out", range, sun, speed_sweep,
                     continue_spec;  // range "": planet
  TableArgs tables;
  double window_cycles = 0;
  int threads = 0, harmonics = 0, periodic_points = 0, hb_harmonics = 0;
  std::string periodic_method;
  std::string carry_state;  // --carry-state: empty (none), up, down
  bool periodic = false, quiet = false, fd_jacobian = false;
};

// The program's sink: the run's files (report/), its header on the console and the progress bar.
class ConsoleSink final : public report::DynamicRunOutput {
 public:
  ConsoleSink(const DynamicArgs& a, const dynamics::DynamicRequest& r, json provenance)
      : DynamicRunOutput(a.out, std::move(provenance)), r_(r), bar_(a.quiet) {}

  void Start(const dynamics::DynamicPlan& p) override {
    if (!p.cost_warning.empty()) std::fprintf(stderr, "warning: %s\n", p.cost_warning.c_str());
    Print(report::DynamicPlanText(p, r_.integrator, r_.backend));
    DynamicRunOutput::Start(p);
    planets_ = p.rig->stage.planets();
    outputs_ = p.span->outputs;
    bar_.Restart();
  }

  void Step(const dynamics::DynamicSample& s) override {
    DynamicRunOutput::Step(s);
    bar_.Show(static_cast<int>(steps()), outputs_, 0, "steps");
  }

  bool tty() const { return bar_.tty(); }
  int planets() const { return planets_; }

 private:
  const dynamics::DynamicRequest& r_;
  ProgressBar bar_;
  int planets_ = 0, outputs_ = 0;
};

// The request's fields the command line does not bind directly.
void Complete(const DynamicArgs& a, dynamics::DynamicRequest& r) {
  r.scene = StageScene(a.scene, a.sun, "dynamic");
  if (!a.range.empty()) r.range = transmission::RunRangeFromName(a.range);
  r.analytic_jacobian = !a.fd_jacobian;
  r.tables = a.tables.Options();
  r.names = dynamics::DynamicOptionNames::Program();
}

void RunDynamic(const DynamicArgs& a, dynamics::DynamicRequest& r) {
  if (!a.speed_sweep.empty() && r.spectrum)
    throw std::invalid_argument("--spectrum belongs to a run at one speed, not --speed-sweep");
  if (!a.speed_sweep.empty() && (r.sun_speed_rpm || r.time_s))
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
  Complete(a, r);
  const dynamics::DynamicRequest& request = r;
  // The periodic orbits: over the sun speed (--speed-sweep with --periodic) or another parameter
  // (--continue); their range and the scene's period are checked before the tables.
  if (a.periodic && a.speed_sweep.empty())
    throw std::invalid_argument(
        "--periodic: needs --speed-sweep FROM:TO:N (the sun speed's range)");
  if (!a.continue_spec.empty() && !a.speed_sweep.empty())
    throw std::invalid_argument("--continue = " + a.continue_spec +
                                ": one continuation at a time; give it without --speed-sweep");
  if (!a.continue_spec.empty() && r.spectrum)
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
    dynamics::ParseSpeedSweep("--speed-sweep", a.speed_sweep);  // bad input before the tables
    dynamics::SpeedSweepRequest sweep;
    sweep.run = request;
    sweep.window_cycles = a.window_cycles;
    sweep.harmonics = a.harmonics;
    sweep.threads = a.threads;
    sweep.carry = carry;
    sweep.periodic_fallback = fallback;
    return RunSpeedSweep({a.speed_sweep, a.out, r.backend, a.quiet}, std::move(sweep));
  }
  ConsoleSink sink(a, r, Provenance(r.backend, &request.scene));
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
        r.spectrum ? ", _vibration.csv, _spectrum.csv, _spectrum_lines.csv, _spectrum_*.svg" : "");
  else
    std::printf("\nwrote %s_summary.json\n", sink.base().c_str());
  if (!record.completed())  // the start's failure, or where the run stopped
    throw ComputationFailed(
        sink.started() ? fmt::format("the run stopped after {} of {} outputs: {}",
                                     record.summary.samples, record.outputs, record.failure)
                       : record.failure);
}

struct ModesArgs {
  std::string scene, sun, json;
  std::vector<double> speed_range_rpm;  // empty: the scene's speed / 2 .. x 2
  TableArgs tables;
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
  request.speed_range_option = dynamics::ModesArguments::kSpeedRange.option;
  request.tables = a.tables.Options();
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
  AddScene(modes, m.scene);
  AddSun(modes, m.sun);
  modes->add_option("--json", m.json, "Also write the modes as JSON");
  Add(modes, dynamics::ModesArguments::kSpeedRange, m.speed_range_rpm)->expected(2);
  AddTables(modes, m.tables);
  modes->callback([] { RunModes(m); });

  using A = DynamicArguments;
  static DynamicArgs a;
  static dynamics::DynamicRequest r;
  auto* cmd = app.add_subcommand(
      "dynamic", "Dynamic load sharing of a stage in time at a sun speed (docs/dynamic.md)");
  AddScene(cmd, a.scene);
  Add(cmd, A::kSpeedRpm, r.sun_speed_rpm);
  Add(cmd, A::kRange, a.range, io::Names(transmission::kRunRangeNames));
  Add(cmd, A::kTime, r.time_s);
  Add(cmd, A::kStartDeg, r.start_deg);
  AddSun(cmd, a.sun);
  Add(cmd, A::kFriction, r.friction, io::Names(transmission::kFrictionLawNames));
  Add(cmd, A::kBackend, r.backend);
  Add(cmd, A::kIntegrator, r.integrator, {"cvode-bdf", "arkode-erk"});
  Add(cmd, A::kRtol, r.rtol);
  Add(cmd, A::kRateScale, r.rate_scale);
  Add(cmd, A::kContactTol, r.contact_tolerance);
  Add(cmd, A::kOutputsPerCycle, r.outputs_per_cycle);
  Add(cmd, A::kSpeedSweep, a.speed_sweep);
  Add(cmd, A::kPeriodic, a.periodic);
  Add(cmd, A::kContinue, a.continue_spec);
  Add(cmd, A::kPeriodicPoints, a.periodic_points);
  Add(cmd, A::kPeriodicMethod, a.periodic_method);
  Add(cmd, A::kHbHarmonics, a.hb_harmonics);
  Add(cmd, A::kWindowCycles, a.window_cycles);
  Add(cmd, A::kHarmonics, a.harmonics);
  Add(cmd, A::kThreads, a.threads);
  Add(cmd, A::kCarryState, a.carry_state);
  Add(cmd, A::kMaxOrder, r.max_order);
  Add(cmd, A::kMaxSteps, r.max_steps);
  Add(cmd, A::kTimeLimit, r.time_limit_s);
  Add(cmd, A::kSpectrum, r.spectrum);
  Add(cmd, A::kSpectrumResolution, r.spectrum_resolution_hz);
  Add(cmd, A::kSpectrumSkip, r.spectrum_skip_cycles);
  Add(cmd, A::kRating, r.rating);
  Add(cmd, A::kStresses, r.stresses);
  Add(cmd, A::kFdJacobian, a.fd_jacobian);
  cmd->add_option("--out", a.out, "Output folder (CSV, JSON, SVG)");
  AddTables(cmd, a.tables);
  cmd->add_flag("--quiet", a.quiet, "No progress bar");
  cmd->callback([] { RunDynamic(a, r); });
}

}  // namespace epicycle::app
