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
#include "epicycle/report/record_json.hpp"
#include "epicycle/report/run_files.hpp"
#include "epicycle/transmission/quasistatic_run.hpp"
#include "epicycle/transmission/run_range.hpp"
#include "epicycle/transmission/sweep_summary.hpp"
#include "epicycle/transmission/validity.hpp"
#include "epicycle/io/units.hpp"
#include "options.hpp"

namespace epicycle::app {

namespace {

using json = nlohmann::json;

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

// The program's sink: the run's header, its files and plots written position by position, the
// problems dumped when asked, the progress bar.
class ConsoleSink final : public transmission::QuasiStaticSink {
 public:
  ConsoleSink(const QuasiStaticArgs& a, json provenance)
      : a_(a), provenance_(std::move(provenance)), tty_(!a.quiet && isatty(fileno(stderr))) {}

  void Start(const transmission::QuasiStaticPlan& p) override {
    const transmission::Scene& scene = *p.scene;
    const int n = p.stage->planets();
    sun_name_ = transmission::SunSupportName(scene.supports.sun);
    scene_name_ = scene.name;
    count_ = p.positions;
    std::printf("%s: %d planets, sun %s, input torque %.1f N m, back end %s\n", scene.name.c_str(),
                n, sun_name_.c_str(), scene.loads.sun_torque, a_.backend.c_str());
    for (const std::string& m : p.compliance->tables().messages()) std::printf("  %s\n", m.c_str());
    for (const std::string& d : scene.damage.Describe()) std::printf("  %s\n", d.c_str());
    const std::string threads = a_.threads == 0 ? std::string("one thread per core")
                                                : fmt::format("{} thread(s)", a_.threads);
    std::printf("  %d positions from %.4f deg (%.2f s for the tables), %s, %s\n", p.positions,
                geometry::Deg(p.first_angle), p.table_seconds,
                a_.cold ? "every position cold" : "each warm-started from its neighbour",
                threads.c_str());
    std::filesystem::create_directories(a_.out);
    if (!a_.dump.empty()) std::filesystem::create_directories(a_.dump);
    base_ = a_.out + "/quasistatic";
    files_ = std::make_unique<report::QuasiStaticFiles>(base_, provenance_, n, p.friction,
                                                        p.compliance->has_root_stress());
    if (p.friction)
      std::printf("  friction %s at rest, sun at %.1f rpm\n",
                  transmission::FrictionLawName(p.options->friction.law).c_str(),
                  io::RadPerSecondToRpm(p.options->sun_speed));
    plots_ = std::make_unique<report::QuasiStaticPlots>(base_, n, p.positions,
                                                        360.0 / p.stage->ring().teeth(),
                                                        geometry::Deg(p.span));
    t0_ = std::chrono::steady_clock::now();
  }

  void Position(const transmission::PositionResult& r, int k) override {
    const double deg = geometry::Deg(r.carrier_angle);
    if (!r.converged) {
      ++failed_;
      if (!tty_) std::fprintf(stderr, "  position %.4f deg FAILED: %s\n", deg, r.message.c_str());
    }
    files_->Write(r);
    plots_->Add(r);
    if (!a_.dump.empty() && r.problem.data.compliance.size() > 0)
      report::WriteStageProblemFile(
          a_.dump,
          fmt::format("{}_{}_{}_{:03d}", std::filesystem::path(a_.scene).stem().string(),
                      sun_name_, a_.no_local ? "linear" : "local", k),
          r.problem.data, provenance_,
          fmt::format("{} at carrier {:.4f} deg, sun {}, back end {}: {}", scene_name_, deg,
                      sun_name_, a_.backend, r.converged ? "converged" : r.message));
    if (tty_)
      Progress(k + 1, count_, failed_,
               std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count(),
               "positions");
  }

  void Close() { files_->Close(); }
  void WritePlots() { plots_->Write(scene_name_, sun_name_); }
  const std::string& base() const { return base_; }

 private:
  const QuasiStaticArgs& a_;
  json provenance_;
  bool tty_;
  std::string sun_name_, scene_name_, base_;
  int count_ = 0, failed_ = 0;
  std::unique_ptr<report::QuasiStaticFiles> files_;
  std::unique_ptr<report::QuasiStaticPlots> plots_;
  std::chrono::steady_clock::time_point t0_;
};

// The record as the console report.
void PrintRecord(const transmission::QuasiStaticRecord& r, int planets) {
  const transmission::SweepSummary& summary = r.summary;
  std::printf("\n  planet   LSR mean     LSR min      LSR max      (ideal 1/n = %.6f)\n",
              1.0 / planets);
  for (int i = 0; i < planets; ++i) {
    const char* f = "{:<12.6f}";
    std::printf("  %-8d %s %s %s\n", i + 1, Num(summary.lsr_mean[i], f, "-           ").c_str(),
                Num(summary.lsr_min[i], f, "-           ").c_str(),
                Num(summary.lsr_max[i], f, "-").c_str());
  }
  if (r.converged_positions > 0) {
    std::printf("  K_gamma (max L_i)            %.6f\n", summary.k_gamma);
    std::printf("  transmission error           %.3f .. %.3f urad (peak to peak %.3f urad)\n",
                summary.transmission_error_min * 1e6, summary.transmission_error_max * 1e6,
                summary.TransmissionErrorPeakToPeak() * 1e6);
    std::printf("  sun displacement, largest    %.3f um\n", summary.sun_displacement_max * 1e6);
    if (r.friction)
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
  if (r.rating) std::printf("%s", report::RatingText(*r.rating).c_str());
  std::printf("  positions converged          %d of %d, %.3f s (%.3f ms per position)\n",
              r.converged_positions, r.positions, r.sweep_seconds,
              1e3 * r.sweep_seconds / r.positions);
  for (const std::string& f : r.failures) std::printf("  FAILED %s\n", f.c_str());
}

void RunQuasiStatic(const QuasiStaticArgs& a) {
  transmission::QuasiStaticRequest request;
  request.scene = StageScene(a.scene, a.sun, "quasistatic");
  request.backend = a.backend;
  request.range = transmission::RunRangeFromName(a.range);
  request.positions = a.positions;
  request.angles_deg = a.angles_deg;
  request.angles_option = "--angles-deg";
  request.start_deg = a.start_deg;
  request.threads = a.threads;
  request.warm_start = !a.cold;
  request.local_terms = !a.no_local;
  request.friction = a.friction;
  request.stresses = a.stresses;
  request.rating = a.rating;
  request.rating_option = "--rating";
  request.tables = TableOptions(a.cache, a.no_cache);

  const json provenance = Provenance(a.backend, &request.scene);
  ConsoleSink sink(a, provenance);
  const transmission::QuasiStaticRecord record = transmission::RunQuasiStatic(request, sink);
  sink.Close();
  const int planets = static_cast<int>(record.summary.lsr_mean.size());
  PrintRecord(record, planets);
  const int failed = record.positions - record.converged_positions;
  if (record.failures_not_listed > 0)
    std::printf("  and %d more failed (status and message in %s_positions.csv)\n",
                record.failures_not_listed, sink.base().c_str());
  PrintWarnings(record.warnings);
  WriteTextFile(sink.base() + "_summary.json",
                report::QuasiStaticRecordJson(record, provenance).dump(2) + "\n");
  sink.WritePlots();
  std::printf(
      "\nwrote %s_positions.csv, _pairs.csv, _summary.json, _lsr.svg, _te.svg, _sun_path.svg\n",
      sink.base().c_str());
  if (!a.dump.empty()) std::printf("wrote the contact problems to %s\n", a.dump.c_str());
  if (failed > 0)
    throw ComputationFailed(
        fmt::format("{} of {} positions failed (listed above)", failed, record.positions));
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
