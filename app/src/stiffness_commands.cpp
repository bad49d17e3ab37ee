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
#include "epicycle/report/run_files.hpp"
#include "epicycle/transmission/mesh_stiffness.hpp"
#include "epicycle/transmission/validity.hpp"
#include "options.hpp"

namespace epicycle::app {

namespace {

using json = nlohmann::json;

struct StiffnessArgs {
  std::string scene, mesh, backend = "newton", out = "stiffness-out", cache;
  int positions = 60, cycle = -1;
  int threads = 0;  // 0: one per core
  bool no_cache = false, no_local = false, stresses = false;
};

void RunStiffness(const StiffnessArgs& a) {
  transmission::Scene scene = transmission::ReadScene(a.scene);
  scene.model.stresses = scene.model.stresses || a.stresses;
  std::optional<geometry::Stage> stage;
  if (scene.kind == transmission::SceneKind::kStage) {
    stage.emplace(transmission::MakeStage(scene));
    if (a.mesh.empty()) {
      std::string names;
      for (const auto& m : stage->meshes()) names += (names.empty() ? "" : ", ") + m.name;
      throw std::invalid_argument("--mesh is required for a stage scene; its meshes are " + names);
    }
  }
  const transmission::MeshPairSetup setup =
      transmission::MakeMeshPair(scene, stage ? &*stage : nullptr, a.mesh);
  const geometry::GearPair pair = transmission::MakePair(scene, setup.spec);
  const transmission::FeComplianceOptions fe = TableOptions(a.cache, a.no_cache);
  const auto [first, cycles] =
      a.cycle >= 0 ? std::array<int, 2>{a.cycle, 1} : transmission::DamagedToothCycles(setup, pair);
  std::printf("%s: mesh %s, torque on gear 1 %.3f N m, %d positions per cycle, cycles %d..%d\n",
              scene.name.c_str(), setup.mesh.c_str(), setup.torque, a.positions, first,
              first + cycles - 1);
  const transmission::FePairCompliance compliance(scene, pair, fe, setup.gears);
  for (const std::string& m : compliance.tables().messages()) std::printf("  %s\n", m.c_str());
  for (const std::string& d : scene.damage.Describe()) std::printf("  %s\n", d.c_str());

  transmission::MeshStiffnessOptions opt;
  opt.positions = a.positions * cycles;
  opt.first_cycle = first;
  opt.cycles = cycles;
  opt.threads = a.threads;
  opt.backend = solvers::BackendFromName(a.backend);
  opt.local_terms = !a.no_local;
  std::filesystem::create_directories(a.out);
  const std::string base = a.out + "/stiffness_" + setup.mesh;
  const json provenance = Provenance(a.backend, &scene);
  const double b = geometry::ContactFaceWidth(pair.gear1(), pair.gear2());
  report::MeshStiffnessFile csv(
      base + ".csv", provenance, b,
      compliance.has_root_stress() ? setup.gears : std::vector<std::string>{});
  const auto result = transmission::ComputeMeshStiffness(
      setup, pair, compliance, opt, [&](const transmission::MeshSample& s) {
        csv.Write(s);  // written as computed
        if (!s.converged)
          std::fprintf(stderr, "  position %.4f deg FAILED: %s\n", geometry::Deg(s.angle),
                       s.message.c_str());
      });
  csv.Close();
  const compliance::iso6336::PairData iso = transmission::IsoPairData(pair);
  const double c_prime = compliance::iso6336::SinglePairStiffness(iso);
  const double c_gamma = compliance::iso6336::MeshStiffness(iso);
  std::printf("%s", report::MeshStiffnessText(pair, result, c_prime, c_gamma).c_str());

  report::WriteMeshStiffnessPlot(base + ".svg", scene.name + ": " + setup.mesh + " mesh stiffness",
                                 result, b, {c_gamma, c_prime});

  // The scene's warnings and those only the results show (docs/scenes.md, "Ranges and validity").
  std::vector<std::string> warnings = scene.warnings;
  for (const std::string& w : transmission::MeshStiffnessWarnings(pair, result))
    warnings.push_back(w);
  PrintWarnings(warnings);
  json j = report::MeshStiffnessJson(pair, result, c_prime, c_gamma);
  j["provenance"] = provenance;
  j["warnings"] = warnings;
  j["scene"] = scene.name;
  j["local_terms"] = !a.no_local;
  j["plane"] = scene.model.plane == solvers::PlaneAssumption::kPlaneStrain ? "strain" : "stress";
  j["join_depth_mm"] = {compliance.JoiningDepth(0) * 1e3, compliance.JoiningDepth(1) * 1e3};
  if (first != 0 || cycles != 1) {  // the same cycles with healthy teeth, beside
    const auto healthy = transmission::ComputeHealthyMeshStiffness(scene, setup, pair, fe, opt);
    std::printf("  healthy teeth, same cycles: mean %.4e N/m (damaged %+.2f %%), %.4e .. %.4e\n",
                healthy.mean_stiffness, 100 * (result.mean_stiffness / healthy.mean_stiffness - 1),
                healthy.min_stiffness, healthy.max_stiffness);
    j["healthy"] = report::MeshStiffnessJson(pair, healthy, c_prime, c_gamma);
  }
  WriteTextFile(base + ".json", j.dump(2) + "\n");
  std::printf("\nwrote %s.csv, %s.svg, %s.json\n", base.c_str(), base.c_str(), base.c_str());
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
