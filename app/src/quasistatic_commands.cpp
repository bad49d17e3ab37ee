// `epicycle quasistatic SCENE`: the quasi-static load sharing of a stage over a sweep of carrier
// positions. Results are written as they are computed (CSV per position and per tooth pair, a
// JSON summary at the end), with SVG plots of the load-sharing ratios, the loaded static
// transmission error and the sun's path. A position that fails is reported and the sweep goes on.
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

// What the command line gives besides the request's fields.
struct QuasiStaticArgs {
  std::string scene, out = "quasistatic-out", sun, dump;
  std::string range =
      io::NameOf(transmission::kRunRangeNames, transmission::QuasiStaticRequest().range);
  TableArgs tables;
  bool rigid_pins = false, no_local = false, quiet = false, cold = false;
};

// The program's sink: the run's files (report/), its header on the console and the progress bar.
class ConsoleSink final : public report::QuasiStaticRunFiles {
 public:
  ConsoleSink(const QuasiStaticArgs& a, const transmission::QuasiStaticRequest& r, json provenance)
      : QuasiStaticRunFiles(
            {a.out, a.dump, std::filesystem::path(a.scene).stem().string(), r.backend, a.no_local},
            std::move(provenance)),
        r_(r),
        bar_(a.quiet) {}

  void Start(const transmission::QuasiStaticPlan& p) override {
    Print(report::QuasiStaticPlanText(p, r_.backend, !r_.warm_start, r_.threads));
    QuasiStaticRunFiles::Start(p);
    count_ = p.positions;
    bar_.Restart();
  }

  void Position(const transmission::PositionResult& r, int k) override {
    if (!r.converged) {
      ++failed_;
      if (!bar_.tty())
        std::fprintf(stderr, "  position %.4f deg FAILED: %s\n", geometry::Deg(r.carrier_angle),
                     r.message.c_str());
    }
    QuasiStaticRunFiles::Position(r, k);
    bar_.Show(k + 1, count_, failed_, "positions");
  }

 private:
  const transmission::QuasiStaticRequest& r_;
  ProgressBar bar_;
  int count_ = 0, failed_ = 0;
};

void RunQuasiStatic(const QuasiStaticArgs& a, transmission::QuasiStaticRequest& request) {
  request.scene = StageScene(a.scene, a.sun, "quasistatic");
  request.range = transmission::RunRangeFromName(a.range);
  request.angles_option = QuasiStaticArguments::kAnglesDeg.option;
  request.warm_start = !a.cold;
  request.local_terms = !a.no_local;
  request.rating_option = QuasiStaticArguments::kRating.option;
  request.pin_feedback = !a.rigid_pins;
  request.tables = a.tables.Options();

  ConsoleSink sink(a, request, Provenance(request.backend, &request.scene));
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
  using A = QuasiStaticArguments;
  static QuasiStaticArgs a;
  static transmission::QuasiStaticRequest r;
  auto* cmd = app.add_subcommand(
      "quasistatic", "Quasi-static load sharing of a stage over a sweep of carrier positions");
  AddScene(cmd, a.scene);
  Add(cmd, A::kPositions, r.positions);
  Add(cmd, A::kRange, a.range, io::Names(transmission::kRunRangeNames));
  Add(cmd, A::kStartDeg, r.start_deg);
  Add(cmd, A::kAnglesDeg, r.angles_deg);
  AddSun(cmd, a.sun);
  Add(cmd, A::kThreads, r.threads);
  Add(cmd, A::kCold, a.cold);
  Add(cmd, A::kFriction, r.friction, transmission::RestFrictionNames());
  Add(cmd, A::kBackend, r.backend);
  cmd->add_option("--out", a.out, "Output folder (CSV, JSON, SVG)");
  cmd->add_option("--dump-problems", a.dump, "Also write every position's contact problem here");
  AddTables(cmd, a.tables);
  Add(cmd, A::kNoLocal, a.no_local);
  Add(cmd, A::kStresses, r.stresses);
  Add(cmd, A::kRating, r.rating);
  Add(cmd, A::kRigidPins, a.rigid_pins);
  cmd->add_flag("--quiet", a.quiet, "No progress bar");
  cmd->callback([] { RunQuasiStatic(a, r); });
}

}  // namespace epicycle::app
