// `epicycle geometry SCENE` (report, --json, --svg) and `epicycle contacts SCENE --carrier-deg A`.
#include <cstdio>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "console.hpp"
#include "epicycle/geometry/pair.hpp"
#include "epicycle/geometry/stage.hpp"
#include "epicycle/report/geometry_json.hpp"
#include "epicycle/report/stage_svg.hpp"
#include "epicycle/transmission/scene.hpp"
#include "options.hpp"

namespace epicycle::app {

using geometry::Stage;
using nlohmann::json;

namespace {

constexpr double kToMm = 1e3;

// The "helical" section of the report (report::HelicalStageJson): the gears' normal and
// transverse data, each mesh's working quantities and contact ratios, the axial forces and the
// planets' tilting moments.
void PrintHelical(const json& h) {
  std::printf(
      "\nHelical gears (ISO 21771; module, pressure angle and shift given in the normal "
      "section)\n");
  std::printf("  %-8s %9s %6s %9s %9s %9s %9s %9s %9s %10s %10s\n", "gear", "beta[deg]", "hand",
              "m_n[mm]", "alpha_n", "x_n", "m_t[mm]", "alpha_t", "x_t", "beta_b[deg]", "p_z[mm]");
  for (const auto& [name, g] : h["gears"].items()) {
    std::printf("  %-8s %9.4f %6s %9.4f %9.4f %9.4f %9.5f %9.4f %9.4f %10.4f %10.1f\n",
                name.c_str(), g["helix_angle_deg"].get<double>(),
                g["hand"].get<std::string>().c_str(), g["normal_module_mm"].get<double>(),
                g["normal_pressure_angle_deg"].get<double>(),
                g["normal_profile_shift"].get<double>(), g["transverse_module_mm"].get<double>(),
                g["transverse_pressure_angle_deg"].get<double>(),
                g["transverse_profile_shift"].get<double>(),
                g["base_helix_angle_deg"].get<double>(), g["lead_mm"].get<double>());
  }
  std::printf("  %-13s %8s %12s %12s %8s %8s %8s\n", "mesh", "b [mm]", "alpha_wt[deg]",
              "beta_w[deg]", "eps_a", "eps_b", "eps_g");
  for (const json& m : h["meshes"]) {
    std::printf(
        "  %-13s %8.2f %12.4f %12.4f %8.4f %8.4f %8.4f\n", m["name"].get<std::string>().c_str(),
        m["face_width_mm"].get<double>(), m["working_transverse_pressure_angle_deg"].get<double>(),
        m["working_helix_angle_deg"].get<double>(), m["transverse_contact_ratio"].get<double>(),
        m["overlap_ratio"].get<double>(), m["total_contact_ratio"].get<double>());
  }
  if (!h.contains("mesh_forces")) return;
  std::printf(
      "Axial forces at sun torque %.6g N m shared equally (F_a = F_t tan beta_w; + along the "
      "axis z, out of the drawing)\n",
      h["sun_torque_Nm"].get<double>());
  std::printf("  %-13s %12s %12s %12s %16s %10s\n", "mesh", "F_bt [N]", "F_t [N]", "F_a [N]",
              "F_a planet [N]", "arm [mm]");
  for (const json& f : h["mesh_forces"]) {
    std::printf("  %-13s %12.1f %12.1f %12.1f %16.1f %10.3f\n",
                f["name"].get<std::string>().c_str(), f["base_transverse_force_N"].get<double>(),
                f["transverse_force_N"].get<double>(), f["axial_force_N"].get<double>(),
                f["axial_force_on_planet_N"].get<double>(), f["planet_arm_mm"].get<double>());
  }
  for (const json& p : h["planets"]) {
    std::printf(
        "  planet %d: tilting moment %.1f N m about its tangential axis, net axial force %.3g N\n",
        p["planet"].get<int>(), p["tilting_moment_Nm"].get<double>(),
        p["net_axial_force_N"].get<double>());
  }
  std::printf("  sun: axial force %.1f N; ring: %.1f N\n", h["sun_axial_force_N"].get<double>(),
              h["ring_axial_force_N"].get<double>());
}

void PrintReport(const json& j) {
  std::printf("epicycle geometry: %s  (%s)\n\n", j["scene"].get<std::string>().c_str(),
              j["source"].get<std::string>().c_str());
  const json& g = j["gears"];
  std::vector<std::string> names = j["gear_order"].get<std::vector<std::string>>();
  auto row = [&](const char* label, const char* key, const char* f) {
    std::printf("  %-38s", label);
    for (const std::string& n : names) {
      if (g[n].contains(key)) {
        std::printf(f, g[n][key].get<double>());
      } else {
        std::printf("%12s", "-");
      }
    }
    std::printf("\n");
  };
  std::printf("Gears %33s", "");
  for (const std::string& n : names) std::printf("%12s", n.c_str());
  std::printf("\n");
  row("teeth z", "teeth", "%12.0f");
  row("module m [mm]", "module_mm", "%12.3f");
  row("face width b [mm]", "face_width_mm", "%12.2f");
  row("profile shift x", "profile_shift", "%12.4f");
  row("tool pressure angle [deg]", "pressure_angle_deg", "%12.2f");
  row("reference radius r [mm]", "reference_radius_mm", "%12.4f");
  row("base radius r_b [mm]", "base_radius_mm", "%12.4f");
  row("tip radius r_a [mm]", "tip_radius_mm", "%12.4f");
  row("root radius r_f [mm]", "root_radius_mm", "%12.4f");
  row("form radius r_F (involute start) [mm]", "form_radius_mm", "%12.4f");
  row("tip-form radius (round tangency) [mm]", "tip_form_radius_mm", "%12.4f");
  row("tip round r_t [mm]", "tip_round_radius_mm", "%12.4f");
  row("thickness at r [mm]", "thickness_reference_mm", "%12.4f");
  row("thickness at r_a [mm]", "thickness_tip_mm", "%12.4f");
  row("least shift without undercut", "min_shift_without_undercut", "%12.4f");
  row("hub (axis) radius [mm]", "hub_radius_mm", "%12.2f");
  row("rim radius [mm]", "rim_radius_mm", "%12.2f");
  for (const std::string& n : names) {
    std::printf("  %-7s %s\n", n.c_str(), g[n]["generation"].get<std::string>().c_str());
  }
  for (const std::string& n : names) {
    const json& gn = g[n];
    if (gn.value("undercut", false)) {
      std::printf(
          "  warning: %s is undercut (x = %.4f below %.4f): generated as cut, the involute starts "
          "where the fillet trochoid crosses it, r = %.4f mm\n",
          n.c_str(), gn["profile_shift"].get<double>(),
          gn["min_shift_without_undercut"].get<double>(), gn["undercut_radius_mm"].get<double>());
    }
    if (gn.contains("modification")) {
      for (const auto& [which, m] : gn["modification"].items()) {
        std::printf("  %-7s %s relief %.2f um, %s, from r = %.4f mm (roll %.3f deg) to the %s\n",
                    n.c_str(), which.c_str(), m["amount_um"].get<double>(),
                    m["shape"].get<std::string>().c_str(), m["start_radius_mm"].get<double>(),
                    m["start_roll_deg"].get<double>(),
                    which == "tip" ? "tip circle" : "form circle");
      }
    }
    if (gn.contains("pitch")) {
      std::printf(
          "  %-7s pitch deviations: largest single f_pt %.3f um, total cumulative F_p "
          "%.3f um\n",
          n.c_str(), gn["pitch"]["largest_single_um"].get<double>(),
          gn["pitch"]["total_cumulative_um"].get<double>());
    }
  }
  std::printf(
      "\nMeshes          a [mm]  alpha_w [deg]  j_n [mm]  j_t [mm]  eps_a ISO  eps_a inv  "
      "SAP a/b [mm]      phase\n");
  for (const json& m : j["meshes"]) {
    std::printf("  %-12s %8.3f %10.4f %11.4f %9.4f %10.4f %10.4f  %7.3f/%-8.3f %6.4f\n",
                m["name"].get<std::string>().c_str(), m["centre_distance_mm"].get<double>(),
                m["operating_pressure_angle_deg"].get<double>(),
                m["normal_backlash_mm"].get<double>(), m["transverse_backlash_mm"].get<double>(),
                m["contact_ratio_iso"].get<double>(), m["contact_ratio_involute"].get<double>(),
                m["sap_a_mm"].get<double>(), m["sap_b_mm"].get<double>(),
                m["phase_cycles"].get<double>());
  }
  for (const json& f : j["fits"]) {
    std::printf("Fit: %s profile shift x = %.6f gives j_n = %.1f um on the %s mesh\n",
                f["gear"].get<std::string>().c_str(), f["profile_shift"].get<double>(),
                f["normal_backlash_um"].get<double>(), f["mesh"].get<std::string>().c_str());
  }
  if (!j.contains("assembly")) {
    if (j.contains("helical")) PrintHelical(j["helical"]);
    return;
  }
  const json& a = j["assembly"];
  std::printf(
      "\nAssembly: carrier radius %.4f mm, z_sun + z_ring = %d, %s\n",
      a["carrier_radius_mm"].get<double>(), a["z_sun_plus_z_ring"].get<int>(),
      a["equally_spaced"].get<bool>() ? "planets equally spaced" : "planets at given angles");
  for (const json& p : a["planets"]) {
    std::printf(
        "  planet %d at %8.3f deg: (z_s + z_r) psi/360 = %.4f (whole: assemblable); "
        "mesh phase %.4f cycle (%.1f deg) behind planet 1\n",
        p["planet"].get<int>(), p["angle_deg"].get<double>(), p["assembly_teeth"].get<double>(),
        p["mesh_phase_cycles"].get<double>(), 360.0 * p["mesh_phase_cycles"].get<double>());
  }
  std::printf("  one mesh cycle = %.4f deg of carrier rotation\n",
              a["mesh_cycle_carrier_deg"].get<double>());
  if (j.contains("helical")) PrintHelical(j["helical"]);
}

void PrintContactHeader() {
  std::printf("  %-13s %-12s %-6s %6s %6s %11s %11s %9s %9s %12s %9s %9s %9s %9s\n", "mesh", "kind",
              "flank", "tooth", "mate", "x [mm]", "y [mm]", "n_x", "n_y", "overlap[um]",
              "arm_a[mm]", "arm_b[mm]", "rho_a[mm]", "rho_b[mm]");
  std::printf(
      "  (n_x, n_y: unit contact normal out of the mesh's first gear into its second; a "
      "contact force pushes the second gear along +n)\n");
}

void PrintContactRow(const std::string& mesh, const geometry::PotentialContact& c, int loaded) {
  std::printf(
      "  %-13s %-12s %-6s %6d %6d %11.4f %11.4f %9.6f %9.6f %12.3f %9.3f %9.3f %9.3f %9.3f\n",
      mesh.c_str(), geometry::KindName(c.kind).c_str(), c.side_a == loaded ? "drive" : "coast",
      c.tooth_a, c.tooth_b, c.point.x() * kToMm, c.point.y() * kToMm, c.normal.x(), c.normal.y(),
      c.overlap * 1e6, c.lever_a * kToMm, c.lever_b * kToMm, c.curvature_radius_a * kToMm,
      c.curvature_radius_b * kToMm);
}

void PrintContacts(const Stage& st, double carrier_deg, double window) {
  const geometry::StagePoses p = st.Poses(geometry::Rad(carrier_deg));
  geometry::ContactSearchOptions opt;
  opt.gap_window = window;
  std::printf("Potential contacts at carrier angle %.4f deg (gap window %.1f um)\n", carrier_deg,
              window * 1e6);
  PrintContactHeader();
  for (int i = 0; i < st.planets(); ++i) {
    for (geometry::MeshKind kind :
         {geometry::MeshKind::kSunPlanet, geometry::MeshKind::kPlanetRing}) {
      const int loaded =
          kind == geometry::MeshKind::kSunPlanet ? st.sun_mesh_side() : st.ring_mesh_planet_side();
      const std::string name = st.meshes()[2 * i + (kind == geometry::MeshKind::kPlanetRing)].name;
      for (const geometry::PotentialContact& c : st.Contacts(p, i, kind, opt)) {
        PrintContactRow(name, c, loaded);
      }
    }
  }
}

void PrintPairContacts(const geometry::GearPair& pair, double angle_deg, double window) {
  geometry::ContactSearchOptions opt;
  opt.gap_window = window;
  std::printf("Potential contacts with gear 1 turned %.4f deg (gap window %.1f um)\n", angle_deg,
              window * 1e6);
  PrintContactHeader();
  for (const geometry::PotentialContact& c :
       pair.Contacts(pair.Poses(geometry::Rad(angle_deg)), opt)) {
    PrintContactRow(pair.summary().name, c, pair.loaded_side());
  }
}

}  // namespace

void RegisterGeometryCommands(CLI::App& app) {
  auto* geo = app.add_subcommand("geometry", "Print the stage's gear and mesh geometry report");
  static std::string scene_path, json_path, svg_path, zoom_mesh;
  static double carrier_deg = 0.0, relief_scale = 200.0;
  geo->add_option("scene", scene_path, "Scene file (TOML)")->required()->check(CLI::ExistingFile);
  geo->add_option("--json", json_path, "Also write the report as JSON (keys: docs/geometry.md)");
  geo->add_option("--svg", svg_path, "Draw the stage as SVG");
  AddNumber(geo, "--carrier-deg", carrier_deg,
            "Carrier angle of the drawing [deg] (gear pairs: gear 1's turn)", kCarrierAngleDeg);
  geo->add_option("--zoom", zoom_mesh,
                  "Draw one tooth pair of this mesh instead (sun-planet<i>, planet<i>-ring; a "
                  "pair scene: gear1-gear2, its default): undercut, form circles, relief");
  AddNumber(geo, "--relief-scale", relief_scale,
            "Magnification of the relief in the zoom drawing [-] (default 200)",
            {0, 1e4, true, false, "", ""});
  geo->callback([] {
    const transmission::Scene scene = transmission::ReadScene(scene_path);
    if (scene.kind == transmission::SceneKind::kPair) {
      const geometry::GearPair pair = transmission::MakePair(scene, scene.pair);
      json report = report::PairJson(scene, pair);
      report["provenance"] = Provenance("none", &scene);
      report["warnings"] = scene.warnings;
      PrintReport(report);
      PrintWarnings(scene.warnings);
      if (!json_path.empty()) WriteTextFile(json_path, report.dump(2) + "\n");
      if (!svg_path.empty()) {
        if (!zoom_mesh.empty() && zoom_mesh != "gear1-gear2") {
          throw std::invalid_argument("--zoom = " + zoom_mesh +
                                      ": a gear pair has one mesh, gear1-gear2");
        }
        const geometry::PairPoses p = pair.Poses(geometry::Rad(carrier_deg));
        WriteTextFile(svg_path,
                      report::DrawMeshZoom(pair.A(p), pair.B(p), pair.internal(),
                                           pair.loaded_side(), scene.gap_window, relief_scale));
        std::printf("wrote %s (tooth pair of gear1-gear2)\n", svg_path.c_str());
      }
      return;
    }
    const Stage stage = transmission::MakeStage(scene);
    json report = report::StageJson(scene, stage);
    report["provenance"] = Provenance("none", &scene);
    report["warnings"] = scene.warnings;
    PrintReport(report);
    PrintWarnings(scene.warnings);
    if (!json_path.empty()) {
      WriteTextFile(json_path, report.dump(2) + "\n");
      std::printf("\nwrote %s\n", json_path.c_str());
    }
    if (!svg_path.empty() && !zoom_mesh.empty()) {
      // "sun-planet<i>" or "planet<i>-ring": the mesh names of the report.
      const geometry::StagePoses p = stage.Poses(geometry::Rad(carrier_deg));
      int found = -1;
      for (int m = 0; m < static_cast<int>(stage.meshes().size()); ++m) {
        if (stage.meshes()[m].name == zoom_mesh) found = m;
      }
      if (found < 0) {
        throw std::invalid_argument("--zoom = " + zoom_mesh +
                                    ": not a mesh of the stage (sun-planet<i>, planet<i>-ring)");
      }
      const int i = found / 2;
      const bool ring = found % 2 == 1;
      const std::string svg =
          ring ? report::DrawMeshZoom(stage.Planet(p, i), stage.Ring(p), true,
                                      stage.ring_mesh_planet_side(), scene.gap_window, relief_scale)
               : report::DrawMeshZoom(stage.Sun(p), stage.Planet(p, i), false,
                                      stage.sun_mesh_side(), scene.gap_window, relief_scale);
      WriteTextFile(svg_path, svg);
      std::printf("wrote %s (tooth pair of %s, carrier at %.3f deg)\n", svg_path.c_str(),
                  zoom_mesh.c_str(), carrier_deg);
    } else if (!svg_path.empty()) {
      WriteTextFile(svg_path,
                    report::DrawStage(stage, geometry::Rad(carrier_deg), scene.gap_window));
      std::printf("wrote %s (carrier at %.3f deg)\n", svg_path.c_str(), carrier_deg);
    }
  });

  auto* con = app.add_subcommand("contacts", "List the potential contacts at one carrier position");
  static std::string contacts_scene;
  static double contacts_deg = 0.0;
  con->add_option("scene", contacts_scene, "Scene file (TOML)")
      ->required()
      ->check(CLI::ExistingFile);
  AddNumber(con, "--carrier-deg", contacts_deg, "Carrier angle [deg] (gear pairs: gear 1's turn)",
            kCarrierAngleDeg)
      ->required();
  con->callback([] {
    const transmission::Scene scene = transmission::ReadScene(contacts_scene);
    transmission::RequireSpur(scene, "`epicycle contacts` (the planar contact search)");
    if (scene.kind == transmission::SceneKind::kPair) {
      PrintPairContacts(geometry::GearPair(scene.pair), contacts_deg, scene.gap_window);
    } else {
      PrintContacts(transmission::MakeStage(scene), contacts_deg, scene.gap_window);
    }
    PrintWarnings(scene.warnings);
  });
}

}  // namespace epicycle::app
