// `epicycle geometry SCENE` (report, --json, --svg) and `epicycle contacts SCENE --carrier-deg A`.
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "console.hpp"
#include "epicycle/geometry/pair.hpp"
#include "epicycle/geometry/stage.hpp"
#include "epicycle/report/geometry_json.hpp"
#include "epicycle/report/geometry_text.hpp"
#include "epicycle/report/stage_svg.hpp"
#include "epicycle/transmission/scene.hpp"
#include "options.hpp"

namespace epicycle::app {

using geometry::Stage;
using nlohmann::json;

void RegisterGeometryCommands(CLI::App& app) {
  using A = transmission::GeometryArguments;
  auto* geo = app.add_subcommand("geometry", "Print the stage's gear and mesh geometry report");
  static std::string scene_path, json_path, svg_path, zoom_mesh;
  static double carrier_deg = 0.0, relief_scale = 200.0;
  AddScene(geo, scene_path, "Scene file (TOML)");
  geo->add_option("--json", json_path, "Also write the report as JSON (keys: docs/geometry.md)");
  geo->add_option("--svg", svg_path, "Draw the stage as SVG");
  Add(geo, A::kCarrierDeg, carrier_deg);
  geo->add_option("--zoom", zoom_mesh,
                  "Draw one tooth pair of this mesh instead (sun-planet<i>, planet<i>-ring; a "
                  "pair scene: gear1-gear2, its default): undercut, form circles, relief");
  Add(geo, A::kReliefScale, relief_scale);
  geo->callback([] {
    const transmission::Scene scene = transmission::ReadScene(scene_path);
    std::optional<geometry::GearPair> pair;
    std::optional<Stage> stage;
    json report;
    if (scene.kind == transmission::SceneKind::kPair) {
      pair.emplace(transmission::MakePair(scene, scene.pair));
      report = report::PairJson(scene, *pair);
    } else {
      stage.emplace(transmission::MakeStage(scene));
      report = report::StageJson(scene, *stage);
    }
    report["provenance"] = Provenance("none", &scene);
    report["warnings"] = scene.warnings;
    Print(report::GeometryReportText(report));
    PrintWarnings(scene.warnings);
    if (!json_path.empty()) {
      WriteTextFile(json_path, report.dump(2) + "\n");
      if (stage) std::printf("\nwrote %s\n", json_path.c_str());
    }
    if (pair && !svg_path.empty()) {
      WriteTextFile(svg_path,
                    report::DrawPairMeshZoom(*pair, geometry::Rad(carrier_deg),
                                             zoom_mesh.empty() ? "gear1-gear2" : zoom_mesh,
                                             scene.gap_window, relief_scale));
      std::printf("wrote %s (tooth pair of gear1-gear2)\n", svg_path.c_str());
    }
    if (pair) return;
    if (!svg_path.empty() && !zoom_mesh.empty()) {
      const std::string svg = report::DrawStageMeshZoom(*stage, geometry::Rad(carrier_deg),
                                                        zoom_mesh, scene.gap_window, relief_scale);
      WriteTextFile(svg_path, svg);
      std::printf("wrote %s (tooth pair of %s, carrier at %.3f deg)\n", svg_path.c_str(),
                  zoom_mesh.c_str(), carrier_deg);
    } else if (!svg_path.empty()) {
      WriteTextFile(svg_path,
                    report::DrawStage(*stage, geometry::Rad(carrier_deg), scene.gap_window));
      std::printf("wrote %s (carrier at %.3f deg)\n", svg_path.c_str(), carrier_deg);
    }
  });

  auto* con = app.add_subcommand("contacts", "List the potential contacts at one carrier position");
  static std::string contacts_scene;
  static double contacts_deg = 0.0;
  AddScene(con, contacts_scene, "Scene file (TOML)");
  Add(con, A::kContactsCarrierDeg, contacts_deg)->required();
  con->callback([] {
    const transmission::Scene scene = transmission::ReadScene(contacts_scene);
    transmission::RequireSpur(scene, "`epicycle contacts` (the planar contact search)");
    if (scene.kind == transmission::SceneKind::kPair) {
      Print(
          report::PairContactsText(geometry::GearPair(scene.pair), contacts_deg, scene.gap_window));
    } else {
      Print(report::StageContactsText(transmission::MakeStage(scene), contacts_deg,
                                      scene.gap_window));
    }
    PrintWarnings(scene.warnings);
  });
}

}  // namespace epicycle::app
