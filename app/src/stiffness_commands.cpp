// `epicycle stiffness SCENE --mesh NAME`: mesh stiffness over one mesh cycle at the scene's load,
// each tooth pair's stiffness and load share; CSV (written as computed), SVG and a JSON summary
// beside ISO 6336-1's c′ and c_γα.
#include <cstdio>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "commands.hpp"
#include "console.hpp"
#include "epicycle/report/run_files.hpp"
#include "epicycle/report/stiffness_run_files.hpp"
#include "epicycle/transmission/stiffness_run.hpp"
#include "options.hpp"

namespace epicycle::app {

namespace {

// What the command line gives besides the request's fields.
struct StiffnessArgs {
  std::string scene, out = "stiffness-out";
  TableArgs tables;
  bool no_local = false;
};

// The program's sink: the run's header on the console, the files (report/) and a failed sample
// said on stderr.
class ConsoleSink final : public report::StiffnessRunFiles {
 public:
  using StiffnessRunFiles::StiffnessRunFiles;

  void Pair(const transmission::StiffnessPlan& p) override {
    std::printf("%s: mesh %s, torque on gear 1 %.3f N m, %d positions per cycle, cycles %d..%d\n",
                p.scene->name.c_str(), p.setup->mesh.c_str(), p.setup->torque,
                p.positions_per_cycle, p.first_cycle, p.first_cycle + p.cycles - 1);
  }

  void Start(const transmission::StiffnessPlan& p) override {
    for (const std::string& m : p.compliance->tables().messages()) std::printf("  %s\n", m.c_str());
    for (const std::string& d : p.scene->damage.Describe()) std::printf("  %s\n", d.c_str());
    StiffnessRunFiles::Start(p);
  }

  void Sample(const transmission::MeshSample& s) override {
    StiffnessRunFiles::Sample(s);
    if (!s.converged)
      std::fprintf(stderr, "  position %.4f deg FAILED: %s\n", geometry::Deg(s.angle),
                   s.message.c_str());
  }
};

void RunStiffness(const StiffnessArgs& a, transmission::StiffnessRequest& request) {
  using A = StiffnessArguments;
  request.scene = transmission::ReadScene(a.scene);
  request.local_terms = !a.no_local;
  request.tables = a.tables.Options();
  request.mesh_option = A::kMesh.option;
  request.positions_option = A::kPositions.option;
  request.threads_option = A::kThreads.option;
  ConsoleSink sink(a.out, Provenance(request.backend, &request.scene));
  const transmission::StiffnessRecord record = transmission::RunStiffness(request, sink);
  sink.Close();
  const transmission::MeshStiffnessResult& result = record.result;
  const std::string& base = sink.base();
  Print(report::MeshStiffnessText(record));
  PrintWarnings(record.warnings);
  if (record.healthy) {  // the same cycles with healthy teeth, beside
    const transmission::MeshStiffnessResult& healthy = *record.healthy;
    std::printf("  healthy teeth, same cycles: mean %.4e N/m (damaged %+.2f %%), %.4e .. %.4e\n",
                healthy.mean_stiffness, 100 * (result.mean_stiffness / healthy.mean_stiffness - 1),
                healthy.min_stiffness, healthy.max_stiffness);
  }
  sink.Finish(record);
  std::printf("\nwrote %s.csv, %s.svg, %s.json%s\n", base.c_str(), base.c_str(), base.c_str(),
              sink.k_h_beta() ? (", " + base + "_k_hbeta.svg").c_str() : "");
  if (result.failed > 0)
    throw ComputationFailed(fmt::format("{} position(s) failed (see above)", result.failed));
}

}  // namespace

void RegisterStiffnessCommands(CLI::App& app) {
  using A = StiffnessArguments;
  static StiffnessArgs a;
  static transmission::StiffnessRequest r;
  auto* cmd = app.add_subcommand(
      "stiffness", "Mesh stiffness over one mesh cycle at the scene's load (FE + local contact)");
  AddScene(cmd, a.scene, "Scene file (TOML): a gear pair or a stage");
  Add(cmd, A::kMesh, r.mesh);
  Add(cmd, A::kPositions, r.positions);
  Add(cmd, A::kCycle, r.cycle);
  Add(cmd, A::kThreads, r.threads);
  Add(cmd, A::kBackend, r.backend);
  cmd->add_option("--out", a.out, "Output folder (CSV, SVG, JSON)");
  AddTables(cmd, a.tables);
  Add(cmd, A::kNoLocal, a.no_local);
  Add(cmd, A::kStresses, r.stresses);
  cmd->callback([] { RunStiffness(a, r); });
}

}  // namespace epicycle::app
