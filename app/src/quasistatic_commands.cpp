// `epicycle quasistatic SCENE`: the quasi-static load sharing of a stage over a sweep of carrier
// positions. Results are written as they are computed (CSV per position and per tooth pair, a
// JSON summary at the end), with SVG plots of the load-sharing ratios, the loaded static
// transmission error and the sun's path. A position that fails is reported and the sweep goes on.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "console.hpp"
#include "epicycle/report/quasistatic_run_files.hpp"
#include "epicycle/transmission/quasistatic_run.hpp"
#include "epicycle/transmission/run_range.hpp"
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
  bool rigid_pins = false;
  bool no_cache = false, no_local = false, quiet = false, cold = false, stresses = false,
       rating = false;
};

// The program's sink: the run's files (report/), its header on the console and the progress bar.
class ConsoleSink final : public report::QuasiStaticRunFiles {
 public:
  ConsoleSink(const QuasiStaticArgs& a, json provenance)
      : QuasiStaticRunFiles(
            {a.out, a.dump, std::filesystem::path(a.scene).stem().string(), a.backend, a.no_local},
            std::move(provenance)),
        a_(a),
        tty_(!a.quiet && isatty(fileno(stderr))) {}

  void Start(const transmission::QuasiStaticPlan& p) override {
    Print(report::QuasiStaticPlanText(p, a_.backend, a_.cold, a_.threads));
    QuasiStaticRunFiles::Start(p);
    count_ = p.positions;
    t0_ = std::chrono::steady_clock::now();
  }

  void Position(const transmission::PositionResult& r, int k) override {
    if (!r.converged) {
      ++failed_;
      if (!tty_)
        std::fprintf(stderr, "  position %.4f deg FAILED: %s\n", geometry::Deg(r.carrier_angle),
                     r.message.c_str());
    }
    QuasiStaticRunFiles::Position(r, k);
    if (tty_)
      Progress(k + 1, count_, failed_,
               std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count(),
               "positions");
  }

 private:
  const QuasiStaticArgs& a_;
  bool tty_;
  int count_ = 0, failed_ = 0;
  std::chrono::steady_clock::time_point t0_;
};

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
  request.pin_feedback = !a.rigid_pins;
  request.tables = TableOptions(a.cache, a.no_cache);

  ConsoleSink sink(a, Provenance(a.backend, &request.scene));
  const transmission::QuasiStaticRecord record = transmission::RunQuasiStatic(request, sink);
  sink.Close();
  Print(report::QuasiStaticRecordText(record, sink.base()));
  PrintWarnings(record.warnings);
  sink.Finish(record);
  std::printf(
      "\nwrote %s_positions.csv, _pairs.csv, _summary.json, _lsr.svg, _te.svg, _sun_path.svg%s\n",
      sink.base().c_str(),
      request.scene.face_width.active() ? ", _face_load.csv, _face_load.svg, _k_hbeta.svg" : "");
  if (!a.dump.empty()) std::printf("wrote the contact problems to %s\n", a.dump.c_str());
  const int failed = record.positions - record.converged_positions;
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
  cmd->add_flag("--rigid-pins", a.rigid_pins,
                "Leave out the scene's [[face_width.pin]]: every planet held at its given tilt "
                "(the run without the tilt's feedback)");
  cmd->add_flag("--quiet", a.quiet, "No progress bar");
  cmd->callback([] { RunQuasiStatic(a); });
}

}  // namespace epicycle::app
