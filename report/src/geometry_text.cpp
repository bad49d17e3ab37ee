// The geometry report and the potential contacts as console text (geometry_text.hpp).
#include "epicycle/report/geometry_text.hpp"

#include <string>
#include <vector>

#include <fmt/printf.h>

#include "epicycle/geometry/plane.hpp"

namespace epicycle::report {

using nlohmann::json;

namespace {

constexpr double kToMm = 1e3;

// The "helical" section of the report (report::HelicalStageJson): the gears' normal and
// transverse data, each mesh's working quantities and contact ratios, the axial forces and the
// planets' tilting moments.
std::string HelicalText(const json& h) {
  std::string t;
  t += fmt::sprintf(
      "\nHelical gears (ISO 21771; module, pressure angle and shift given in the normal "
      "section)\n");
  t += fmt::sprintf("  %-8s %9s %6s %9s %9s %9s %9s %9s %9s %10s %10s\n", "gear", "beta[deg]",
                    "hand", "m_n[mm]", "alpha_n", "x_n", "m_t[mm]", "alpha_t", "x_t", "beta_b[deg]",
                    "p_z[mm]");
  for (const auto& [name, g] : h["gears"].items()) {
    t += fmt::sprintf(
        "  %-8s %9.4f %6s %9.4f %9.4f %9.4f %9.5f %9.4f %9.4f %10.4f %10.1f\n", name.c_str(),
        g["helix_angle_deg"].get<double>(), g["hand"].get<std::string>().c_str(),
        g["normal_module_mm"].get<double>(), g["normal_pressure_angle_deg"].get<double>(),
        g["normal_profile_shift"].get<double>(), g["transverse_module_mm"].get<double>(),
        g["transverse_pressure_angle_deg"].get<double>(),
        g["transverse_profile_shift"].get<double>(), g["base_helix_angle_deg"].get<double>(),
        g["lead_mm"].get<double>());
  }
  t += fmt::sprintf("  %-13s %8s %12s %12s %8s %8s %8s\n", "mesh", "b [mm]", "alpha_wt[deg]",
                    "beta_w[deg]", "eps_a", "eps_b", "eps_g");
  for (const json& m : h["meshes"]) {
    t += fmt::sprintf(
        "  %-13s %8.2f %12.4f %12.4f %8.4f %8.4f %8.4f\n", m["name"].get<std::string>().c_str(),
        m["face_width_mm"].get<double>(), m["working_transverse_pressure_angle_deg"].get<double>(),
        m["working_helix_angle_deg"].get<double>(), m["transverse_contact_ratio"].get<double>(),
        m["overlap_ratio"].get<double>(), m["total_contact_ratio"].get<double>());
  }
  if (!h.contains("mesh_forces")) return t;
  t += fmt::sprintf(
      "Axial forces at sun torque %.6g N m shared equally (F_a = F_t tan beta_w; + along the "
      "axis z, out of the drawing)\n",
      h["sun_torque_Nm"].get<double>());
  t += fmt::sprintf("  %-13s %12s %12s %12s %16s %10s\n", "mesh", "F_bt [N]", "F_t [N]", "F_a [N]",
                    "F_a planet [N]", "arm [mm]");
  for (const json& f : h["mesh_forces"]) {
    t += fmt::sprintf("  %-13s %12.1f %12.1f %12.1f %16.1f %10.3f\n",
                      f["name"].get<std::string>().c_str(),
                      f["base_transverse_force_N"].get<double>(),
                      f["transverse_force_N"].get<double>(), f["axial_force_N"].get<double>(),
                      f["axial_force_on_planet_N"].get<double>(), f["planet_arm_mm"].get<double>());
  }
  for (const json& p : h["planets"]) {
    t += fmt::sprintf(
        "  planet %d: tilting moment %.1f N m about its tangential axis, net axial force %.3g N\n",
        p["planet"].get<int>(), p["tilting_moment_Nm"].get<double>(),
        p["net_axial_force_N"].get<double>());
  }
  t += fmt::sprintf("  sun: axial force %.1f N; ring: %.1f N\n",
                    h["sun_axial_force_N"].get<double>(), h["ring_axial_force_N"].get<double>());
  return t;
}

}  // namespace

std::string GeometryReportText(const json& j) {
  std::string t;
  t += fmt::sprintf("epicycle geometry: %s  (%s)\n\n", j["scene"].get<std::string>().c_str(),
                    j["source"].get<std::string>().c_str());
  const json& g = j["gears"];
  std::vector<std::string> names = j["gear_order"].get<std::vector<std::string>>();
  auto row = [&](const char* label, const char* key, const char* f) {
    t += fmt::sprintf("  %-38s", label);
    for (const std::string& n : names) {
      if (g[n].contains(key)) {
        t += fmt::sprintf(f, g[n][key].get<double>());
      } else {
        t += fmt::sprintf("%12s", "-");
      }
    }
    t += fmt::sprintf("\n");
  };
  t += fmt::sprintf("Gears %33s", "");
  for (const std::string& n : names) t += fmt::sprintf("%12s", n.c_str());
  t += fmt::sprintf("\n");
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
    t += fmt::sprintf("  %-7s %s\n", n.c_str(), g[n]["generation"].get<std::string>().c_str());
  }
  for (const std::string& n : names) {
    const json& gn = g[n];
    if (gn.value("undercut", false)) {
      t += fmt::sprintf(
          "  warning: %s is undercut (x = %.4f below %.4f): generated as cut, the involute starts "
          "where the fillet trochoid crosses it, r = %.4f mm\n",
          n.c_str(), gn["profile_shift"].get<double>(),
          gn["min_shift_without_undercut"].get<double>(), gn["undercut_radius_mm"].get<double>());
    }
    if (gn.contains("modification")) {
      for (const auto& [which, m] : gn["modification"].items()) {
        t += fmt::sprintf(
            "  %-7s %s relief %.2f um, %s, from r = %.4f mm (roll %.3f deg) to the %s\n", n.c_str(),
            which.c_str(), m["amount_um"].get<double>(), m["shape"].get<std::string>().c_str(),
            m["start_radius_mm"].get<double>(), m["start_roll_deg"].get<double>(),
            which == "tip" ? "tip circle" : "form circle");
      }
    }
    if (gn.contains("pitch")) {
      t += fmt::sprintf(
          "  %-7s pitch deviations: largest single f_pt %.3f um, total cumulative F_p "
          "%.3f um\n",
          n.c_str(), gn["pitch"]["largest_single_um"].get<double>(),
          gn["pitch"]["total_cumulative_um"].get<double>());
    }
  }
  t += fmt::sprintf(
      "\nMeshes          a [mm]  alpha_w [deg]  j_n [mm]  j_t [mm]  eps_a ISO  eps_a inv  "
      "SAP a/b [mm]      phase\n");
  for (const json& m : j["meshes"]) {
    t += fmt::sprintf(
        "  %-12s %8.3f %10.4f %11.4f %9.4f %10.4f %10.4f  %7.3f/%-8.3f %6.4f\n",
        m["name"].get<std::string>().c_str(), m["centre_distance_mm"].get<double>(),
        m["operating_pressure_angle_deg"].get<double>(), m["normal_backlash_mm"].get<double>(),
        m["transverse_backlash_mm"].get<double>(), m["contact_ratio_iso"].get<double>(),
        m["contact_ratio_involute"].get<double>(), m["sap_a_mm"].get<double>(),
        m["sap_b_mm"].get<double>(), m["phase_cycles"].get<double>());
  }
  for (const json& f : j["fits"]) {
    t += fmt::sprintf("Fit: %s profile shift x = %.6f gives j_n = %.1f um on the %s mesh\n",
                      f["gear"].get<std::string>().c_str(), f["profile_shift"].get<double>(),
                      f["normal_backlash_um"].get<double>(), f["mesh"].get<std::string>().c_str());
  }
  if (!j.contains("assembly")) {
    if (j.contains("helical")) t += HelicalText(j["helical"]);
    return t;
  }
  const json& a = j["assembly"];
  t += fmt::sprintf(
      "\nAssembly: carrier radius %.4f mm, z_sun + z_ring = %d, %s\n",
      a["carrier_radius_mm"].get<double>(), a["z_sun_plus_z_ring"].get<int>(),
      a["equally_spaced"].get<bool>() ? "planets equally spaced" : "planets at given angles");
  for (const json& p : a["planets"]) {
    t += fmt::sprintf(
        "  planet %d at %8.3f deg: (z_s + z_r) psi/360 = %.4f (whole: assemblable); "
        "mesh phase %.4f cycle (%.1f deg) behind planet 1\n",
        p["planet"].get<int>(), p["angle_deg"].get<double>(), p["assembly_teeth"].get<double>(),
        p["mesh_phase_cycles"].get<double>(), 360.0 * p["mesh_phase_cycles"].get<double>());
  }
  t += fmt::sprintf("  one mesh cycle = %.4f deg of carrier rotation\n",
                    a["mesh_cycle_carrier_deg"].get<double>());
  if (j.contains("helical")) t += HelicalText(j["helical"]);
  return t;
}

namespace {

std::string ContactHeader() {
  std::string t;
  t += fmt::sprintf("  %-13s %-12s %-6s %6s %6s %11s %11s %9s %9s %12s %9s %9s %9s %9s\n", "mesh",
                    "kind", "flank", "tooth", "mate", "x [mm]", "y [mm]", "n_x", "n_y",
                    "overlap[um]", "arm_a[mm]", "arm_b[mm]", "rho_a[mm]", "rho_b[mm]");
  t += fmt::sprintf(
      "  (n_x, n_y: unit contact normal out of the mesh's first gear into its second; a "
      "contact force pushes the second gear along +n)\n");
  return t;
}

std::string ContactRow(const std::string& mesh, const geometry::PotentialContact& c, int loaded) {
  return fmt::sprintf(
      "  %-13s %-12s %-6s %6d %6d %11.4f %11.4f %9.6f %9.6f %12.3f %9.3f %9.3f %9.3f %9.3f\n",
      mesh.c_str(), geometry::KindName(c.kind).c_str(), c.side_a == loaded ? "drive" : "coast",
      c.tooth_a, c.tooth_b, c.point.x() * kToMm, c.point.y() * kToMm, c.normal.x(), c.normal.y(),
      c.overlap * 1e6, c.lever_a * kToMm, c.lever_b * kToMm, c.curvature_radius_a * kToMm,
      c.curvature_radius_b * kToMm);
}

}  // namespace

std::string StageContactsText(const geometry::Stage& st, double carrier_deg, double window) {
  std::string t;
  const geometry::StagePoses p = st.Poses(geometry::Rad(carrier_deg));
  geometry::ContactSearchOptions opt;
  opt.gap_window = window;
  t += fmt::sprintf("Potential contacts at carrier angle %.4f deg (gap window %.1f um)\n",
                    carrier_deg, window * 1e6);
  t += ContactHeader();
  for (int i = 0; i < st.planets(); ++i) {
    for (geometry::MeshKind kind :
         {geometry::MeshKind::kSunPlanet, geometry::MeshKind::kPlanetRing}) {
      const int loaded =
          kind == geometry::MeshKind::kSunPlanet ? st.sun_mesh_side() : st.ring_mesh_planet_side();
      const std::string name = st.meshes()[2 * i + (kind == geometry::MeshKind::kPlanetRing)].name;
      for (const geometry::PotentialContact& c : st.Contacts(p, i, kind, opt)) {
        t += ContactRow(name, c, loaded);
      }
    }
  }
  return t;
}

std::string PairContactsText(const geometry::GearPair& pair, double angle_deg, double window) {
  std::string t;
  geometry::ContactSearchOptions opt;
  opt.gap_window = window;
  t += fmt::sprintf("Potential contacts with gear 1 turned %.4f deg (gap window %.1f um)\n",
                    angle_deg, window * 1e6);
  t += ContactHeader();
  for (const geometry::PotentialContact& c :
       pair.Contacts(pair.Poses(geometry::Rad(angle_deg)), opt)) {
    t += ContactRow(pair.summary().name, c, pair.loaded_side());
  }
  return t;
}

}  // namespace epicycle::report
