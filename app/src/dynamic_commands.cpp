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
#include "epicycle/dynamics/modes.hpp"
#include "epicycle/dynamics/run_span.hpp"
#include "epicycle/dynamics/simulation.hpp"
#include "epicycle/dynamics/speed_sweep.hpp"
#include "epicycle/dynamics/dynamic_summary.hpp"
#include "epicycle/dynamics/vibration.hpp"
#include "epicycle/report/ratings.hpp"
#include "epicycle/report/run_files.hpp"
#include "epicycle/report/spectrum_files.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "options.hpp"
#include "periodic_command.hpp"
#include "speed_sweep_command.hpp"
#include "epicycle/io/units.hpp"

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
      spectrum_skip;
  int outputs_per_cycle = 0, max_order = 5, threads = 0, harmonics = 0, periodic_points = 0;
  bool periodic = false, no_cache = false, quiet = false, fd_jacobian = false, stresses = false, spectrum = false,
       rating = false;
};

void RunDynamic(const DynamicArgs& a) {
  transmission::Scene input = StageScene(a.scene, a.sun, "dynamic");
  const std::string range = a.range.empty() ? "planet" : a.range;
  if (!a.speed_sweep.empty() && a.spectrum)
    throw std::invalid_argument("--spectrum belongs to a run at one speed, not --speed-sweep");
  if (!a.speed_sweep.empty() && (a.speed_rpm || a.time))
    throw std::invalid_argument("--speed-sweep = " + a.speed_sweep +
                                ": runs its own speeds and windows; give it without --speed-rpm "
                                "and --time");
  if (a.speed_sweep.empty() && (a.threads != 0 || a.window_cycles != 0))
    throw std::invalid_argument("--threads and --window-cycles belong to --speed-sweep");
  if (!a.speed_sweep.empty()) ParseSpeedSweep(a.speed_sweep);  // bad input before the tables
  // The periodic orbits: over the sun speed (--speed-sweep with --periodic) or another parameter
  // (--continue); their range and the scene's period are checked before the tables.
  std::optional<BranchArgs> branch;
  if (a.periodic && a.speed_sweep.empty())
    throw std::invalid_argument("--periodic: needs --speed-sweep FROM:TO:N (the sun speed's range)");
  if (!a.continue_spec.empty() && !a.speed_sweep.empty())
    throw std::invalid_argument("--continue = " + a.continue_spec +
                                ": one continuation at a time; give it without --speed-sweep");
  if (!a.continue_spec.empty() && a.spectrum)
    throw std::invalid_argument("--spectrum belongs to a run at one speed, not --continue");
  if (a.periodic_points != 0 && !a.periodic && a.continue_spec.empty())
    throw std::invalid_argument("--periodic-points belongs to --periodic and --continue");
  if (a.periodic) branch = ParseBranch("--speed-sweep", a.speed_sweep, input);
  if (!a.continue_spec.empty()) branch = ParseBranch("--continue", a.continue_spec, input);
  if (a.speed_rpm) input.dynamics.sun_speed = io::RpmToRadPerSecond(*a.speed_rpm);
  if (!a.friction.empty())
    input.dynamics.friction.law = transmission::FrictionLawFromName(a.friction);
  input.model.stresses = input.model.stresses || a.stresses || a.rating;
  if (a.rating) transmission::CheckRatingInputs(input, "--rating");
  const auto t0 = std::chrono::steady_clock::now();
  dynamics::StageDynamics rig(std::move(input), TableOptions(a.cache, a.no_cache));
  const transmission::Scene& scene = rig.scene;
  const geometry::Stage& stage = rig.stage;
  const transmission::FeStageCompliance& compliance = rig.compliance;
  const transmission::StageModel& stage_model = rig.stage_model;
  dynamics::DynamicModel& model = rig.model;
  const int n = stage.planets();
  model.SetStartAngle(geometry::Rad(a.start_deg));
  const double setup_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  dynamics::SimulationOptions opt;
  opt.integrator = dynamics::IntegratorFromName(a.integrator);
  opt.backend = solvers::BackendFromName(a.backend);
  opt.rtol = a.rtol;
  if (a.rate_scale) opt.rate_scale = *a.rate_scale;
  if (a.contact_tol) opt.contact.tolerance = *a.contact_tol;
  opt.analytic_jacobian = !a.fd_jacobian;
  opt.max_order = a.max_order;
  if (branch) {
    branch->out = a.out;
    branch->backend = a.backend;
    branch->quiet = a.quiet;
    branch->max_points = a.periodic_points;
    return RunBranch(*branch, rig, opt);
  }
  if (!a.speed_sweep.empty()) {
    const int per_cycle =
        a.outputs_per_cycle > 0 ? a.outputs_per_cycle : SpeedSweepArgs{}.outputs_per_cycle;
    return RunSpeedSweep({a.speed_sweep, a.out, range, a.backend, a.integrator, a.window_cycles,
                          a.start_deg, per_cycle, a.harmonics, a.threads, a.quiet},
                         rig, opt);
  }
  const double f_max = dynamics::HighestModeFrequency(model);
  const int per_cycle =
      a.outputs_per_cycle > 0 ? a.outputs_per_cycle : dynamics::DefaultOutputsPerCycle(model, f_max);
  const dynamics::RunSpan span =
      dynamics::MakeRunSpan(stage, model.carrier_speed(), transmission::RunRangeFromName(range),
                            a.time.value_or(0.0), per_cycle);
  const double duration = span.duration, mesh_hz = span.mesh_frequency;
  const std::string cost = dynamics::RunCostWarning(  // a run of hours: said before it starts
      span, io::RadPerSecondToRpm(model.sun_speed()),
      a.time ? fmt::format("--time = {} s", *a.time) : "--range " + range,
      a.speed_rpm ? fmt::format("--speed-rpm = {}", *a.speed_rpm) : "[dynamics] sun_speed_rpm");
  if (!cost.empty()) std::fprintf(stderr, "warning: %s\n", cost.c_str());
  const int outputs = span.outputs;
  std::optional<dynamics::SpectrumOptions> spectrum;  // bad options before the run
  if (a.spectrum)
    spectrum = dynamics::RunSpectrumOptions(
        span, dynamics::CharacteristicFrequencies(stage, model.sun_speed()),
        a.spectrum_resolution.value_or(0),
        a.spectrum_skip.value_or(dynamics::kDefaultSpectrumSkipCycles),
        {"--spectrum-resolution", a.spectrum_resolution.has_value(), "--spectrum-skip-cycles",
         a.spectrum_skip.has_value(),
         a.time            ? fmt::format("--time = {} s", *a.time)
         : a.range.empty() ? "one planet revolution (the default --range planet)"
                           : "--range " + a.range});
  const char* sun_name = transmission::SunSupportName(stage_model.setup().sun);
  std::printf(
      "%s: %d planets, sun %s, input torque %.1f N m, sun speed %.1f rpm (mesh frequency "
      "%.1f Hz)\n",
      scene.name.c_str(), n, sun_name, scene.loads.sun_torque,
      io::RadPerSecondToRpm(std::abs(model.sun_speed())), mesh_hz);
  for (const std::string& m : compliance.tables().messages()) std::printf("  %s\n", m.c_str());
  for (const std::string& d : scene.damage.Describe()) std::printf("  %s\n", d.c_str());
  std::printf(
      "  mean mesh stiffness: sun-planet %.4g N/m, planet-ring %.4g N/m; mesh damping %.4g and "
      "%.4g N s/m\n",
      model.sun_mesh_stiffness(), model.ring_mesh_stiffness(), model.sun_mesh_damping(),
      model.ring_mesh_damping());
  std::printf("  friction %s, integrator %s (rtol %.1e), back end %s, %d DOFs\n",
              transmission::FrictionLawName(scene.dynamics.friction.law).c_str(),
              a.integrator.c_str(), a.rtol, a.backend.c_str(), model.size());
  const Eigen::VectorXd d0 = model.QuasiStaticStart(opt.contact, opt.backend);
  std::printf(
      "  t = 0: the quasi-static solution at carrier %.4f deg (no start-up transient), "
      "%.4f s simulated in %d outputs, %d per mesh cycle (highest mode %.0f Hz; %.2f s of "
      "set-up)\n",
      geometry::Deg(model.CarrierAngle(0)), duration, outputs, per_cycle, f_max, setup_seconds);

  std::filesystem::create_directories(a.out);
  const std::string base = a.out + "/dynamic";
  const json provenance = Provenance(a.backend, &scene);
  report::DynamicRunRecorder recorder(base, provenance, model, span, spectrum, a.rating);
  const bool tty = !a.quiet && isatty(fileno(stderr));
  const auto t1 = std::chrono::steady_clock::now();
  opt.keep_samples = false;  // each step recorded as it comes, then let go (flat memory)
  const dynamics::SimulationResult result = dynamics::Simulate(
      model, opt, d0, Eigen::VectorXd::Zero(model.size()), span.OutputTimes(),
      [&](const dynamics::DynamicSample& s) {
        recorder.Add(s);
        if (tty)
          Progress(static_cast<int>(recorder.outputs()), outputs, 0,
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count(),
                   "steps");
      });
  std::printf("%s", recorder.Close(scene.name, sun_name).c_str());
  if (tty && !result.completed) std::fprintf(stderr, "\n");

  const dynamics::DynamicSummary sum = recorder.Summary();
  const dynamics::SimulationStats& st = result.stats;
  std::printf("%s", report::DynamicRunText(sum, st, n).c_str());
  std::optional<dynamics::MotionRating> rating;  // ISO 6336 with the run's K_v (docs/stresses.md)
  if (a.rating && sum.samples > 0) rating = recorder.Rate(scene, opt);
  if (rating) std::printf("%s", report::RatingText(rating->rating).c_str());

  // The scene's warnings and those only the results show (docs/scenes.md, "Ranges and validity").
  std::vector<std::string> warnings = scene.warnings;
  if (!cost.empty()) warnings.push_back(cost);
  for (const std::string& w : recorder.Warnings()) warnings.push_back(w);
  PrintWarnings(warnings);
  json j = report::DynamicRunJson(model, opt, span, result, sum);
  j["provenance"] = provenance;
  j["warnings"] = warnings;
  j["setup_seconds"] = setup_seconds;
  if (rating) j["rating"] = report::RatingJson(rating->rating);
  WriteTextFile(base + "_summary.json", j.dump(2) + "\n");

  std::printf(
      "\nwrote %s_steps.csv, _pairs.csv, _bearings.csv, _summary.json, _lsr.svg, _te.svg, "
      "_orbit.svg%s\n",
      base.c_str(),
      a.spectrum ? ", _vibration.csv, _spectrum.csv, _spectrum_lines.csv, _spectrum_*.svg" : "");
  if (!result.completed)
    throw ComputationFailed(fmt::format("the run stopped after {} of {} outputs: {}", sum.samples,
                                        outputs, result.message));
}

struct ModesArgs {
  std::string scene, sun, cache, json;
  std::vector<double> speed_range_rpm;  // empty: the scene's speed / 2 .. x 2
  bool no_cache = false;
};

void RunModes(const ModesArgs& a) {
  if (!a.speed_range_rpm.empty() && !(a.speed_range_rpm[0] <= a.speed_range_rpm[1]))
    throw std::invalid_argument(fmt::format("--speed-range-rpm = {} {}: LO must not exceed HI",
                                            a.speed_range_rpm[0], a.speed_range_rpm[1]));
  dynamics::StageDynamics rig(StageScene(a.scene, a.sun, "modes"),
                              TableOptions(a.cache, a.no_cache));
  const transmission::Scene& scene = rig.scene;
  const geometry::Stage& stage = rig.stage;
  const transmission::StageModel& stage_model = rig.stage_model;
  // The linearisation's mesh stiffness is the tangent dF/dδ about the operating point (the
  // speed sweep's peaks sit at its coincidences; the secant F/δ, which sets the mesh damping, is
  // softer by the local term's curvature and puts them ~3.5 % low on the paper stage).
  const dynamics::OperatingPointModes operating = dynamics::StageModes(rig);
  const std::vector<dynamics::Mode>& modes = operating.modes;
  const dynamics::DynamicModel& model = rig.model;
  const std::array<double, 2>& tangent = operating.mesh_stiffness;
  // Mesh frequency per sun rpm: f_m = z_r ω_c/2π with ω_c = ω_s z_s/(z_s + z_r).
  const double hz_per_rpm = dynamics::MeshHzPerSunRpm(stage);
  std::printf("%s: %d planets, sun %s, %d DOFs (%s)\n", scene.name.c_str(), stage.planets(),
              transmission::SunSupportName(stage_model.setup().sun), model.size(),
              model.settings().ring_elastic ? "ring elastic" : "ring fixed");
  std::printf(
      "  mean mesh stiffness (the mesh-stiffness driver at the scene's load), tangent dF/ddelta "
      "(used here): sun-planet %.4g N/m, planet-ring %.4g N/m\n",
      tangent[0], tangent[1]);
  std::printf(
      "  secant F/delta (sets the mesh damping of a run): sun-planet %.4g N/m, planet-ring %.4g "
      "N/m\n",
      rig.model.sun_mesh_stiffness(), rig.model.ring_mesh_stiffness());
  std::printf("  mesh frequency %.4f Hz per sun rpm\n\n", hz_per_rpm);
  std::printf("  %-5s %-12s %-5s %-14s %s\n", "mode", "f [Hz]", "mult", "type",
              "energy: central tr/rot, planets");
  for (std::size_t j = 0; j < modes.size(); ++j) {
    const auto& x = modes[j];
    const std::string type = x.rigid ? "rigid" : dynamics::ModeTypeName(x.type);
    std::printf("  %-5zu %-12.2f %-5d %-14s %.3f / %.3f, %.3f\n", j + 1, x.frequency,
                x.multiplicity, type.c_str(), x.central_translation, x.central_rotation, x.planets);
  }
  // Every mesh harmonic that meets a mode within the speeds asked (default: the scene's speed
  // / 2 .. x 2), marked by the planet-phasing rule.
  const double rpm = io::RadPerSecondToRpm(model.settings().sun_speed);
  const double lo = a.speed_range_rpm.empty() ? rpm / 2 : a.speed_range_rpm[0];
  const double hi = a.speed_range_rpm.empty() ? rpm * 2 : a.speed_range_rpm[1];
  const auto coincidences = dynamics::FindCoincidences(model, modes, lo, hi);
  std::printf("\n  coincidences h f_m = f_j from %.0f to %.0f rpm (%zu):\n", lo, hi,
              coincidences.size());
  for (const dynamics::Coincidence& c : coincidences)
    std::printf("    %9.1f rpm  harmonic %-3d x mode %d (%.2f Hz, %s)%s\n", c.sun_speed_rpm,
                c.harmonic, c.mode + 1, c.frequency,
                dynamics::ModeTypeName(modes[static_cast<std::size_t>(c.mode)].type).c_str(),
                c.phasing_excited ? "" : "  not excited by a symmetric stage (planet phasing)");
  PrintWarnings(scene.warnings);
  if (!a.json.empty()) {
    nlohmann::json j = report::ModesRunJson(model, operating, lo, hi, coincidences);
    j["provenance"] = Provenance("none", &scene);
    j["warnings"] = scene.warnings;
    WriteTextFile(a.json, j.dump(2) + "\n");
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
                  "NAME:FROM:TO:N: the periodic orbits continued over the stage's sun_speed_rpm, "
                  "sun_torque_Nm or mesh_damping_ratio at the scene's (or --speed-rpm's) speed");
  AddNumber(cmd, "--periodic-points", a.periodic_points,
            "--periodic, --continue: the most points of the branch (default 400)", kSweepSpeeds);
  AddNumber(cmd, "--window-cycles", a.window_cycles,
            "Speed sweep: mesh cycles measured per speed (replaces --range)", kWindowCycles);
  AddNumber(cmd, "--harmonics", a.harmonics,
            "Speed sweep: mark coincidences of mesh harmonics 1..N (default: every one in range)",
            kHarmonics);
  AddNumber(cmd, "--threads", a.threads, "Speed sweep: worker threads (default: every core)",
            kThreads);
  AddNumber(cmd, "--max-order", a.max_order, "Largest BDF order of CVODE (1..5)", kMaxOrder);
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
