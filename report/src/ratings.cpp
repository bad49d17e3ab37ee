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
                       f.tip ? "tip round" : "line of action", f.pressure / 1e6,
                       f.half_width * 1e6, Num(geometry::Deg(f.roll), "{:.3f}", "own tip"),
                       f.tooth, f.mesh, f.x * x_scale);
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
  return {{"tangential_force_per_planet_N", rating.tangential_force},
          {"K_A", rating.application_factor},
          {"K_v", rating.dynamic_factor},
          {"K_v_source", rating.dynamic_source},
          {"gears", gears},
          {"factors", factors}};
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
                    Num(g.k_gamma_table, "{:.2f}", "-"), Num(g.k_gamma_model, "{:.3f}", "-"),
                    pair(g.sigma_f_table, g.s_f_table), pair(g.sigma_f_model, g.s_f_model),
                    pair(g.root_stress, g.s_f_stress), pair(g.sigma_h_table, g.s_h_table),
                    pair(g.sigma_h_model, g.s_h_model), pair(g.contact_pressure, g.s_h_pressure));
  }
  for (const auto& g : rating.gears)
    if (!g.note.empty()) out += fmt::format("    {}: {}\n", g.gear, g.note);
  out += "  factors:\n";
  for (const auto& f : rating.factors)
    out += fmt::format("    {:<34} {:>10}  {}\n", f.symbol, Num(f.value, "{:.5g}", "-"), f.source);
  return out;
}

}  // namespace epicycle::report
