#include "epicycle/report/ratings.hpp"

#include <cmath>

#include <fmt/format.h>

#include "epicycle/geometry/plane.hpp"
#include "epicycle/report/files.hpp"
#include "epicycle/report/run_files.hpp"

namespace epicycle::report {

nlohmann::json ContactPressureJson(const std::vector<transmission::FlankPressure>& flanks,
                                   const std::string& x_name, double x_scale) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& f : flanks)
    list.push_back({{"gear", transmission::BodyName(f.body)},
                    {"flank", f.drive ? "drive" : "coast"},
                    {"hertz_pressure_MPa", f.pressure / 1e6},
                    {"half_width_um", f.half_width * 1e6},
                    {"roll_deg", JsonValue(geometry::Deg(f.roll))},
                    {"tooth", f.tooth},
                    {"mesh", f.mesh},
                    {"contact", f.tip ? "tip round" : "line of action"},
                    {"local_validity_ratio", JsonValue(f.validity_ratio)},
                    {x_name, f.x * x_scale}});
  return list;
}

std::string ContactPressureText(const std::vector<transmission::FlankPressure>& flanks,
                                const std::string& x_name, double x_scale) {
  if (flanks.empty()) return "";
  std::string out = fmt::format(
      "  contact pressure  flank  contact         p_H [MPa]  half-width [um]  roll [deg]  tooth  "
      "mesh ({})\n",
      x_name);
  for (const auto& f : flanks)
    out += fmt::format("    {:<8} {:<6} {:<14} {:9.1f}  {:9.2f}  {:>9}  {:5}  {} ({:.4g})\n",
                       transmission::BodyName(f.body), f.drive ? "drive" : "coast",
                       f.tip ? "tip round" : "line of action", f.pressure / 1e6, f.half_width * 1e6,
                       Figure(geometry::Deg(f.roll), "{:.3f}", "own tip"), f.tooth, f.mesh,
                       f.x * x_scale);
  return out;
}

nlohmann::json RatingJson(const transmission::StageRating& rating) {
  nlohmann::json factors = nlohmann::json::array();
  for (const auto& f : rating.factors)
    factors.push_back({{"symbol", f.symbol}, {"value", JsonValue(f.value)}, {"source", f.source}});
  nlohmann::json gears = nlohmann::json::array();
  auto mpa = [](double v) { return JsonValue(v / 1e6); };
  for (const auto& g : rating.gears)
    gears.push_back({{"gear", g.gear},
                     {"K_gamma_table", JsonValue(g.k_gamma_table)},
                     {"K_gamma_model", JsonValue(g.k_gamma_model)},
                     {"Y_M", g.reversed_bending},
                     {"bending_mesh", g.bending_mesh},
                     {"sigma_F0_MPa", mpa(g.sigma_f0)},
                     {"sigma_F_table_MPa", mpa(g.sigma_f_table)},
                     {"sigma_F_model_K_gamma_MPa", mpa(g.sigma_f_model)},
                     {"S_F_table", JsonValue(g.s_f_table)},
                     {"S_F_model_K_gamma", JsonValue(g.s_f_model)},
                     {"contact_mesh", g.contact_mesh},
                     {"sigma_H0_MPa", mpa(g.sigma_h0)},
                     {"Z_B_or_Z_D", g.z_bd},
                     {"sigma_H_table_MPa", mpa(g.sigma_h_table)},
                     {"sigma_H_model_K_gamma_MPa", mpa(g.sigma_h_model)},
                     {"S_H_table", JsonValue(g.s_h_table)},
                     {"S_H_model_K_gamma", JsonValue(g.s_h_model)},
                     {"root_stress_model_MPa", mpa(g.root_stress)},
                     {"S_F_model_stress", JsonValue(g.s_f_stress)},
                     {"contact_pressure_model_MPa", mpa(g.contact_pressure)},
                     {"S_H_model_pressure", JsonValue(g.s_h_pressure)},
                     {"note", g.note}});
  nlohmann::json out = {{"tangential_force_per_planet_N", rating.tangential_force},
                         {"K_A", rating.application_factor},
                         {"K_v", rating.dynamic_factor},
                         {"K_v_source", rating.dynamic_source},
                         {"gears", gears},
                         {"factors", factors}};
  if (!rating.face_width.empty()) {
    nlohmann::json meshes = nlohmann::json::array();
    auto um = [](double v) { return JsonValue(v * 1e6); };
    for (const auto& m : rating.face_width)
      meshes.push_back({{"mesh", m.mesh},
                        {"K_gamma_table", JsonValue(m.k_gamma_table)},
                        {"K_gamma_model", JsonValue(m.k_gamma_model)},
                        {"K_Hbeta_model", JsonValue(m.k_h_beta_model)},
                        {"K_Hbeta_ISO_method_C", JsonValue(m.iso.k_h_beta)},
                        {"K_Fbeta_ISO_method_C", JsonValue(m.iso.k_f_beta)},
                        {"N_F", JsonValue(m.iso.n_f)},
                        {"f_ma_um", um(m.iso_inputs.assembly)},
                        {"f_sh_um", um(m.iso_inputs.deflection)},
                        {"f_Hbeta_um", um(m.iso_inputs.lead_slope)},
                        {"B1", JsonValue(m.iso_inputs.b1)},
                        {"B2", JsonValue(m.iso_inputs.b2)},
                        {"F_betax_um", um(m.iso.f_beta_x)},
                        {"F_betax_min_um", um(m.iso.f_beta_x_min)},
                        {"F_betax_at_minimum", m.iso.at_minimum},
                        {"y_beta_um", um(m.iso.y_beta)},
                        {"F_betay_um", um(m.iso.f_beta_y)},
                        {"c_gamma_beta_N_per_mm_um", JsonValue(m.iso.c_gamma_beta / 1e9)},
                        {"F_m_N", JsonValue(m.iso_inputs.mean_force)},
                        {"ISO_face_partly_unloaded", m.iso.lifted},
                        {"K_gamma_K_Hbeta_model", JsonValue(m.k_gamma_k_h_beta_model)},
                        {"K_gamma_K_Hbeta_ISO", JsonValue(m.k_gamma_k_h_beta_iso)},
                        {"root_stress_gear", m.root_stress_gear},
                        {"root_stress_model_MPa", mpa(m.root_stress)},
                        {"S_F_model_stress", JsonValue(m.s_f_stress)},
                        {"hertz_pressure_model_MPa", mpa(m.hertz_pressure)},
                        {"S_H_model_pressure", JsonValue(m.s_h_pressure)}});
    out["face_width"] = meshes;
  }
  return out;
}

std::string RatingText(const transmission::StageRating& rating) {
  std::string out = fmt::format(
      "  ratings (ISO 6336 method B; F_t = {:.1f} N per planet mesh, K_A = {:.3g}, K_v = {:.3g}: "
      "{})\n",
      rating.tangential_force, rating.application_factor, rating.dynamic_factor,
      rating.dynamic_source);
  out +=
      "                K_gamma        sigma_F [MPa] / S_F                 "
      "sigma_H [MPa] / S_H\n"
      "    gear      table  model  ISO table   ISO model   model stress  "
      "ISO table   ISO model   model p_H\n";
  // A stress of 0 (an unloaded gear) has no finite safety factor: "unloaded" (the JSON's null);
  // a factor of thousands (a gear barely touched) in 3 digits, not 40.
  auto pair = [](double sigma, double s) {
    if (!std::isfinite(sigma)) return std::string("    -     -");
    return fmt::format("{:5.0f} {:>5}", sigma / 1e6,
                       !std::isfinite(s)   ? std::string("unloaded")
                       : std::abs(s) < 1e3 ? fmt::format("{:.2f}", s)
                                           : fmt::format("{:.2g}", s));
  };
  for (const auto& g : rating.gears) {
    out +=
        fmt::format("    {:<9} {:>5}  {:>5}  {}  {}  {}    {}  {}  {}\n", g.gear,
                    Figure(g.k_gamma_table, "{:.2f}", "-"), Figure(g.k_gamma_model, "{:.3f}", "-"),
                    pair(g.sigma_f_table, g.s_f_table), pair(g.sigma_f_model, g.s_f_model),
                    pair(g.root_stress, g.s_f_stress), pair(g.sigma_h_table, g.s_h_table),
                    pair(g.sigma_h_model, g.s_h_model), pair(g.contact_pressure, g.s_h_pressure));
  }
  for (const auto& g : rating.gears)
    if (!g.note.empty()) out += fmt::format("    {}: {}\n", g.gear, g.note);
  if (!rating.face_width.empty()) {
    out +=
        "  across the face width (ISO 6336-1 method C fed the model's misalignment and c_gamma; "
        "the model's stresses per slice):\n"
        "    mesh          K_gamma  K_Hbeta model  ISO C  F_betay [um]  K_g K_Hb model  ISO     "
        "sigma_F [MPa] / S_F     p_H [MPa] / S_H\n";
    for (const auto& m : rating.face_width)
      out += fmt::format("    {:<13} {:7.3f}  {:13.3f}  {:5.3f}  {:12.2f}  {:13.3f}  {:5.3f}   {:<7} {}  "
                         "{}\n",
                         m.mesh, m.k_gamma_model, m.k_h_beta_model, m.iso.k_h_beta,
                         m.iso.f_beta_y * 1e6, m.k_gamma_k_h_beta_model, m.k_gamma_k_h_beta_iso,
                         m.root_stress_gear.empty() ? "-" : m.root_stress_gear,
                         pair(m.root_stress, m.s_f_stress), pair(m.hertz_pressure, m.s_h_pressure));
  }
  out += "  factors:\n";
  for (const auto& f : rating.factors)
    out +=
        fmt::format("    {:<34} {:>10}  {}\n", f.symbol, Figure(f.value, "{:.5g}", "-"), f.source);
  return out;
}

}  // namespace epicycle::report
