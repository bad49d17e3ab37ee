// `epicycle quasistatic SCENE`: the quasi-static load sharing of a stage over a sweep of carrier
// positions. Results are written as they are computed (CSV per position and per tooth pair, a
// JSON summary at the end), with SVG plots of the load-sharing ratios, the loaded static
// transmission error and the sun's path. A position that fails is reported and the sweep goes on.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "console.hpp"
#include "epicycle/report/ratings.hpp"
#include "epicycle/report/run_files.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "epicycle/transmission/run_range.hpp"
#include "epicycle/transmission/sweep_summary.hpp"
#include "epicycle/transmission/validity.hpp"
#include "options.hpp"

namespace epicycle::app {

namespace {

using json = nlohmann::json;

constexpr int kListedFailures = 100;  // failed positions listed in the report and the JSON

struct QuasiStaticArgs {
  std::string scene, backend = "newton", out = "quasistatic-out", range = "cycle", sun, cache, dump,
                     friction = "off";
  int positions = 0;  // 0: transmission::DefaultPositions, 60 per mesh cycle
  int threads = 0;    // 0: one per core
  std::vector<double> angles_deg;
  double start_deg = 0.0;
  bool no_cache = false, no_local = false, quiet = false, cold = false, stresses = false,
       rating = false;
};

void RunQuasiStatic(const QuasiStaticArgs& a) {
  transmission::Scene scene = StageScene(a.scene, a.sun, "quasistatic");
  scene.model.stresses = scene.model.stresses || a.stresses || a.rating;
  if (a.rating) transmission::CheckRatingInputs(scene, "--rating");
  const geometry::Stage stage = transmission::MakeStage(scene);
  const int n = stage.planets();

  // The carrier angles: the list given, or `count` over the range (computed as they are needed).
  const std::vector<double> angles =
      a.angles_deg.empty() ? std::vector<double>{}
                           : transmission::CheckedCarrierAngles("--angles-deg", a.angles_deg);
  const transmission::RunRange range = transmission::RunRangeFromName(a.range);
  const int count = !angles.empty() ? static_cast<int>(angles.size())
                    : a.positions > 0 ? a.positions
                                      : transmission::DefaultPositions(stage, range);
  const double start = geometry::Rad(a.start_deg), span = transmission::CarrierSpan(stage, range);
  const auto angle = [&](int k) {
    return angles.empty() ? transmission::SweepAngle(start, span, k, count)
                          : angles[static_cast<std::size_t>(k)];
  };

  const transmission::FeComplianceOptions fe = TableOptions(a.cache, a.no_cache);
  const auto t0 = std::chrono::steady_clock::now();
  const transmission::FeStageCompliance compliance(scene, stage, fe);
  const double table_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  transmission::StageSetup setup = transmission::SetupFromScene(scene);
  setup.local_terms = !a.no_local;
  const transmission::StageModel model(stage, compliance, setup);
  transmission::QuasiStaticOptions opt;
  opt.backend = solvers::BackendFromName(a.backend);
  opt.threads = a.threads;
  opt.warm_start = !a.cold;
  transmission::SetRestFriction(scene.dynamics, a.friction, &opt);
  const bool friction = opt.friction.law != transmission::FrictionLaw::kOff;
  const char* sun_name = transmission::SunSupportName(setup.sun);
  std::printf("%s: %d planets, sun %s, input torque %.1f N m, back end %s\n", scene.name.c_str(), n,
              sun_name, scene.loads.sun_torque, a.backend.c_str());
  for (const std::string& m : compliance.tables().messages()) std::printf("  %s\n", m.c_str());
  for (const std::string& d : scene.damage.Describe()) std::printf("  %s\n", d.c_str());
  const std::string threads =
      a.threads == 0 ? std::string("one thread per core") : fmt::format("{} thread(s)", a.threads);
  std::printf("  %d positions from %.4f deg (%.2f s for the tables), %s, %s\n", count,
              geometry::Deg(angle(0)), table_seconds,
              a.cold ? "every position cold" : "each warm-started from its neighbour",
              threads.c_str());

  std::filesystem::create_directories(a.out);
  if (!a.dump.empty()) std::filesystem::create_directories(a.dump);
  const std::string base = a.out + "/quasistatic";
  const json provenance = Provenance(a.backend, &scene);
  report::QuasiStaticFiles files(base, provenance, n, friction, compliance.has_root_stress());
  if (friction)
    std::printf("  friction %s at rest, sun at %.1f rpm\n",
                transmission::FrictionLawName(opt.friction.law).c_str(),
                opt.sun_speed * 30 / std::numbers::pi);

  const bool tty = !a.quiet && isatty(fileno(stderr));
  // Every position is written, summarised and drawn as it comes, then let go (flat memory).
  int failed = 0;
  std::vector<std::string> failures;  // the first kListedFailures
  transmission::SweepAccumulator accumulator(n);
  transmission::ValidityTally tally(stage, "position(s)");
  report::QuasiStaticPlots plots(base, n, count, 360.0 / stage.ring().teeth(),  // mesh cycle
                                 angles.empty() ? geometry::Deg(span) : 0.0);
  const auto t1 = std::chrono::steady_clock::now();
  transmission::SweepEach(
      model, scene.loads, count, angle, opt, [&](const transmission::PositionResult& r, int k) {
        const double deg = geometry::Deg(r.carrier_angle);
        if (!r.converged) {
          if (++failed <= kListedFailures)
            failures.push_back(fmt::format("{:.4f} deg: {}", deg, r.message));
          if (!tty)
            std::fprintf(stderr, "  position %.4f deg FAILED: %s\n", deg, r.message.c_str());
        }
        files.Write(r);
        accumulator.Add(r);
        tally.Add(r);
        plots.Add(r);
        if (!a.dump.empty() && r.problem.data.compliance.size() > 0)
          report::WriteStageProblemFile(
              a.dump,
              fmt::format("{}_{}_{}_{:03d}", std::filesystem::path(a.scene).stem().string(),
                          sun_name, a.no_local ? "linear" : "local", k),
              r.problem.data, provenance,
              fmt::format("{} at carrier {:.4f} deg, sun {}, back end {}: {}", scene.name, deg,
                          sun_name, a.backend, r.converged ? "converged" : r.message));
        if (tty)
          Progress(k + 1, count, failed,
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count(),
                   "positions");
      });
  files.Close();
  const double sweep_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();

  std::vector<std::string> warnings = scene.warnings;
  for (const std::string& w : tally.Messages()) warnings.push_back(w);

  // Summary over the converged positions (none converged: no statistics, "-" in the report).
  const transmission::SweepSummary summary = accumulator.Result();
  const int good = summary.converged;
  std::printf("\n  planet   LSR mean     LSR min      LSR max      (ideal 1/n = %.6f)\n", 1.0 / n);
  for (int i = 0; i < n; ++i) {
    const char* f = "{:<12.6f}";
    std::printf("  %-8d %s %s %s\n", i + 1, Num(summary.lsr_mean[i], f, "-           ").c_str(),
                Num(summary.lsr_min[i], f, "-           ").c_str(),
                Num(summary.lsr_max[i], f, "-").c_str());
  }
  if (good > 0) {
    std::printf("  K_gamma (max L_i)            %.6f\n", summary.k_gamma);
    std::printf("  transmission error           %.3f .. %.3f urad (peak to peak %.3f urad)\n",
                summary.transmission_error_min * 1e6, summary.transmission_error_max * 1e6,
                summary.TransmissionErrorPeakToPeak() * 1e6);
    std::printf("  sun displacement, largest    %.3f um\n", summary.sun_displacement_max * 1e6);
    if (friction)
      std::printf("  efficiency mean %.6f (min %.6f), friction loss mean %.3f W, %.2f iterations\n",
                  summary.efficiency_mean, summary.efficiency_min, summary.friction_power_mean,
                  summary.friction_iterations_mean);
  } else {
    std::printf("  K_gamma, transmission error, sun displacement: - (no position converged)\n");
  }
  std::printf(
      "%s",
      report::RootStressText(summary.root_stress, "carrier deg", 180.0 / std::numbers::pi).c_str());
  std::printf("%s", report::ContactPressureText(summary.contact_pressure, "carrier deg",
                                                180.0 / std::numbers::pi)
                        .c_str());
  std::optional<transmission::StageRating> rating;
  if (a.rating && good > 0) rating = transmission::RateStage(scene, stage, summary);
  if (rating) std::printf("%s", report::RatingText(*rating).c_str());
  std::printf("  positions converged          %d of %d, %.3f s (%.3f ms per position)\n", good,
              count, sweep_seconds, 1e3 * sweep_seconds / count);
  for (const std::string& f : failures) std::printf("  FAILED %s\n", f.c_str());
  if (failed > kListedFailures)
    std::printf("  and %d more failed (status and message in %s_positions.csv)\n",
                failed - kListedFailures, base.c_str());
  PrintWarnings(warnings);

  json j = report::SweepSummaryJson(summary);  // the statistics, null where none converged
  j["provenance"] = provenance;
  j["warnings"] = warnings;
  j["scene"] = scene.name;
  j["sun_support"] = sun_name;
  j["sun_torque_Nm"] = scene.loads.sun_torque;
  j["backend"] = a.backend;
  j["local_terms"] = !a.no_local;
  j["warm_start"] = !a.cold;
  if (friction) j["friction"] = transmission::FrictionLawName(opt.friction.law);
  if (rating) j["rating"] = report::RatingJson(*rating);
  j["threads"] = a.threads;  // 0: one per core
  j["positions"] = count;
  j["converged_positions"] = good;
  j["failures"] = failures;  // the first kListedFailures
  if (failed > kListedFailures) j["failures_not_listed"] = failed - kListedFailures;
  j["sweep_seconds"] = sweep_seconds;
  j["table_seconds"] = table_seconds;
  WriteTextFile(base + "_summary.json", j.dump(2) + "\n");

  plots.Write(scene.name, sun_name);
  std::printf(
      "\nwrote %s_positions.csv, _pairs.csv, _summary.json, _lsr.svg, _te.svg, _sun_path.svg\n",
      base.c_str());
  if (!a.dump.empty()) std::printf("wrote the contact problems to %s\n", a.dump.c_str());
  if (failed > 0)
    throw ComputationFailed(
        fmt::format("{} of {} positions failed (listed above)", failed, count));
}

}  // namespace

void RegisterQuasiStaticCommands(CLI::App& app) {
  static QuasiStaticArgs a;
  auto* cmd = app.add_subcommand(
      "quasistatic", "Quasi-static load sharing of a stage over a sweep of carrier positions");
  cmd->add_option("scene", a.scene, "Scene file (TOML) of a stage")
      ->required()
      ->check(CLI::ExistingFile);
  AddNumber(cmd, "--positions", a.positions,
            "Positions of the sweep (default 60 per mesh cycle: docs/quasistatic.md, Positions)",
            kSweepPositions);
  cmd->add_option("--range", a.range,
                  "Sweep one mesh cycle, one planet or sun revolution relative to the carrier "
                  "(the period of a planet's run-out, of a sun tooth's damage), or one carrier "
                  "revolution")
      ->check(CLI::IsMember(io::Names(transmission::kRunRangeNames)));
  AddNumber(cmd, "--start-deg", a.start_deg, "Carrier angle of the first position [deg]",
            kCarrierAngleDeg);
  AddNumber(cmd, "--angles-deg", a.angles_deg, "A given list of carrier angles [deg]",
            kCarrierAngleDeg);
  cmd->add_option("--sun", a.sun, "Override the scene's sun support")
      ->check(CLI::IsMember(SunOverrideNames()));
  AddNumber(cmd, "--threads", a.threads,
            "Worker threads: the positions in contiguous chunks, one per thread (0: one per core)",
            kThreadsOrZero);
  cmd->add_flag("--cold", a.cold,
                "Start every position from its kinematic poses and zero forces (no warm start "
                "from the neighbour)");
  cmd->add_option("--friction", a.friction,
                  "Friction at rest: off (default), scene (the scene's [dynamics] friction), or a "
                  "law; lubricant and sliding from the scene's [lubricant] and sun_speed_rpm")
      ->check(CLI::IsMember(transmission::RestFrictionNames()));
  cmd->add_option("--backend", a.backend, "Contact back end (newton, ipopt, nlopt-slsqp, ...)");
  cmd->add_option("--out", a.out, "Output folder (CSV, JSON, SVG)");
  cmd->add_option("--dump-problems", a.dump, "Also write every position's contact problem here");
  cmd->add_option("--cache", a.cache, "Influence-table cache folder (default: ~/.cache/epicycle)");
  cmd->add_flag("--no-cache", a.no_cache, "Build the influence tables in memory only");
  cmd->add_flag("--no-local", a.no_local, "Structural compliance only (no local contact term)");
  cmd->add_flag("--stresses", a.stresses,
                "Also root stresses and contact pressures per position (the scene's [model] "
                "stresses)");
  cmd->add_flag("--rating", a.rating,
                "ISO 6336 ratings with the run's K_gamma and stresses (needs the scene's "
                "[material] bending_limit_MPa and contact_limit_MPa; implies --stresses)");
  cmd->add_flag("--quiet", a.quiet, "No progress bar");
  cmd->callback([] { RunQuasiStatic(a); });
}

}  // namespace epicycle::app
