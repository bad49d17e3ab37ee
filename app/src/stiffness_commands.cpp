// `epicycle stiffness SCENE --mesh NAME`: mesh stiffness over one mesh cycle at the scene's load,
// each tooth pair's stiffness and load share; CSV (written as computed), SVG and a JSON summary
// beside ISO 6336-1's c′ and c_γα.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "console.hpp"
#include "epicycle/report/face_width_files.hpp"
#include "epicycle/report/record_json.hpp"
#include "epicycle/report/run_files.hpp"
#include "epicycle/transmission/stiffness_run.hpp"
#include "options.hpp"

namespace epicycle::app {

namespace {

using json = nlohmann::json;

struct StiffnessArgs {
  std::string scene, mesh, backend = "newton", out = "stiffness-out", cache;
  int positions = transmission::kDefaultStiffnessPositions, cycle = -1;
  int threads = 0;  // 0: one per core
  bool no_cache = false, no_local = false, stresses = false;
};

// The program's sink: the run's header on the console and the CSV written as each sample is
// computed (a failed sample said on stderr).
class ConsoleSink final : public transmission::StiffnessSink {
 public:
  ConsoleSink(const StiffnessArgs& a, json provenance)
      : a_(a), provenance_(std::move(provenance)) {}

  void Pair(const transmission::StiffnessPlan& p) override {
    std::printf("%s: mesh %s, torque on gear 1 %.3f N m, %d positions per cycle, cycles %d..%d\n",
                p.scene->name.c_str(), p.setup->mesh.c_str(), p.setup->torque,
                p.positions_per_cycle, p.first_cycle, p.first_cycle + p.cycles - 1);
  }

  void Start(const transmission::StiffnessPlan& p) override {
    const transmission::MeshPairSetup& setup = *p.setup;
    for (const std::string& m : p.compliance->tables().messages()) std::printf("  %s\n", m.c_str());
    for (const std::string& d : p.scene->damage.Describe()) std::printf("  %s\n", d.c_str());
    std::filesystem::create_directories(a_.out);
    base = a_.out + "/stiffness_" + setup.mesh;
    face_width = p.face_width;
    csv_.emplace(base + ".csv", provenance_, face_width,
                 p.compliance->has_root_stress() ? setup.gears : std::vector<std::string>{},
                 setup.face_width.slices);
    if (setup.face_width.active()) k_h_beta.emplace(std::vector<std::string>{setup.mesh});
  }

  void Sample(const transmission::MeshSample& s) override {
    csv_->Write(s);  // written as computed
    if (k_h_beta && s.converged) k_h_beta->Add(geometry::Deg(s.angle), {s.face_load});
    if (!s.converged)
      std::fprintf(stderr, "  position %.4f deg FAILED: %s\n", geometry::Deg(s.angle),
                   s.message.c_str());
  }

  void Close() { csv_->Close(); }

  std::string base;
  double face_width = 0;
  std::optional<report::KHBetaPlot> k_h_beta;  // with slices of the face width

 private:
  const StiffnessArgs& a_;
  json provenance_;
  std::optional<report::MeshStiffnessFile> csv_;
};

void RunStiffness(const StiffnessArgs& a) {
  transmission::StiffnessRequest request;
  request.scene = transmission::ReadScene(a.scene);
  request.mesh = a.mesh;
  request.positions = a.positions;
  request.cycle = a.cycle;
  request.threads = a.threads;
  request.backend = a.backend;
  request.local_terms = !a.no_local;
  request.stresses = a.stresses;
  request.tables = TableOptions(a.cache, a.no_cache);
  request.mesh_option = "--mesh";
  request.positions_option = "--positions";
  request.threads_option = "--threads";
  const json provenance = Provenance(a.backend, &request.scene);
  ConsoleSink sink(a, provenance);
  const transmission::StiffnessRecord record = transmission::RunStiffness(request, sink);
  sink.Close();
  const transmission::MeshStiffnessResult& result = record.result;
  const std::string& base = sink.base;
  Print(report::MeshStiffnessText(record));
  report::WriteMeshStiffnessPlot(
      base + ".svg", record.scene + ": " + result.mesh + " mesh stiffness", result, sink.face_width,
      {record.iso6336_c_gamma_alpha, record.iso6336_c_prime});
  PrintWarnings(record.warnings);
  if (record.healthy) {  // the same cycles with healthy teeth, beside
    const transmission::MeshStiffnessResult& healthy = *record.healthy;
    std::printf("  healthy teeth, same cycles: mean %.4e N/m (damaged %+.2f %%), %.4e .. %.4e\n",
                healthy.mean_stiffness, 100 * (result.mean_stiffness / healthy.mean_stiffness - 1),
                healthy.min_stiffness, healthy.max_stiffness);
  }
  WriteTextFile(base + ".json", report::SummaryJson(record, provenance).dump(2) + "\n");
  if (sink.k_h_beta)  // K_Hβ over the mesh cycle
    WriteTextFile(base + "_k_hbeta.svg",
                  sink.k_h_beta->Svg(record.scene + ": " + result.mesh, "gear 1 rotation [deg]"));
  std::printf("\nwrote %s.csv, %s.svg, %s.json%s\n", base.c_str(), base.c_str(), base.c_str(),
              sink.k_h_beta ? (", " + base + "_k_hbeta.svg").c_str() : "");
  if (result.failed > 0)
    throw ComputationFailed(fmt::format("{} position(s) failed (see above)", result.failed));
}

}  // namespace

void RegisterStiffnessCommands(CLI::App& app) {
  static StiffnessArgs a;
  auto* cmd = app.add_subcommand(
      "stiffness", "Mesh stiffness over one mesh cycle at the scene's load (FE + local contact)");
  cmd->add_option("scene", a.scene, "Scene file (TOML): a gear pair or a stage")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--mesh", a.mesh, "Mesh of a stage: sun-planet1, planet1-ring, ...");
  AddNumber(cmd, "--positions", a.positions, "Positions per mesh cycle", kStiffnessPositions);
  AddNumber(cmd, "--cycle", a.cycle, "Sweep this one mesh cycle", kStiffnessCycle);
  AddNumber(cmd, "--threads", a.threads,
            "Worker threads: the positions in contiguous chunks, one per thread (0: one per core)",
            kThreadsOrZero);
  cmd->add_option("--backend", a.backend, "Contact back end (newton, ipopt, nlopt-slsqp, ...)");
  cmd->add_option("--out", a.out, "Output folder (CSV, SVG, JSON)");
  cmd->add_option("--cache", a.cache, "Influence-table cache folder (default: ~/.cache/epicycle)");
  cmd->add_flag("--no-cache", a.no_cache, "Build the influence tables in memory only");
  cmd->add_flag("--no-local", a.no_local, "Structural compliance only (no local contact term)");
  cmd->add_flag("--stresses", a.stresses,
                "Also each gear's root stress per position (the scene's [model] stresses)");
  cmd->callback([] { RunStiffness(a); });
}

}  // namespace epicycle::app
