#include "epicycle/report/geometry_json.hpp"

#include <cmath>
#include <tuple>

#include <fmt/format.h>

#include "epicycle/geometry/helical.hpp"
#include "epicycle/geometry/iso.hpp"

namespace epicycle::report {

using geometry::Deg;
using geometry::Gear;
using geometry::Stage;
using nlohmann::json;

namespace {

constexpr double kToMm = 1e3;

json FitsJson(const transmission::Scene& scene) {
  json fits = json::array();
  for (const transmission::ShiftFit& f : scene.fits) {
    fits.push_back({{"gear", f.gear},
                    {"mesh", f.mesh},
                    {"normal_backlash_um", f.normal_backlash * 1e6},
                    {"profile_shift", f.profile_shift}});
  }
  return fits;
}

// A helical gear's normal-section data and the transverse quantities derived from it.
json HelicalGearJson(const Gear& g) {
  const geometry::GearSpec& s = g.spec();
  const double c = std::cos(s.helix.angle);
  const double alpha_n = std::atan(std::tan(s.pressure_angle) * c);
  const geometry::TransverseQuantities t = geometry::Transverse(
      g.teeth(), geometry::NormalModule(g), alpha_n, s.profile_shift / c, s.helix.angle);
  return {{"helix_angle_deg", Deg(s.helix.angle)},
          {"hand", geometry::HandName(s.helix.hand)},
          {"normal_module_mm", geometry::NormalModule(g) * kToMm},
          {"normal_pressure_angle_deg", Deg(alpha_n)},
          {"normal_profile_shift", s.profile_shift / c},
          {"transverse_module_mm", t.module * kToMm},
          {"transverse_pressure_angle_deg", Deg(t.pressure_angle)},
          {"transverse_profile_shift", t.profile_shift},
          {"reference_diameter_mm", t.reference_diameter * kToMm},
          {"base_diameter_mm", t.base_diameter * kToMm},
          {"base_helix_angle_deg", Deg(t.base_helix_angle)},
          {"axial_pitch_mm", t.axial_pitch * kToMm},
          {"lead_mm", t.lead * kToMm}};
}

json HelicalMeshJson(const geometry::HelicalMesh& h) {
  return {{"name", h.name},
          {"face_width_mm", h.face_width * kToMm},
          {"transverse_module_mm", h.transverse_module * kToMm},
          {"normal_module_mm", h.normal_module * kToMm},
          {"helix_angle_deg", Deg(h.helix_angle)},
          {"base_helix_angle_deg", Deg(h.base_helix_angle)},
          {"working_transverse_pressure_angle_deg", Deg(h.working_pressure_angle)},
          {"working_helix_angle_deg", Deg(h.working_helix_angle)},
          {"transverse_contact_ratio", h.transverse_contact_ratio},
          {"overlap_ratio", h.overlap_ratio},
          {"total_contact_ratio", h.total_contact_ratio}};
}

}  // namespace

json HelicalStageJson(const transmission::Scene& scene, const Stage& st) {
  json gears;
  gears["sun"] = HelicalGearJson(st.sun());
  gears["planet"] = HelicalGearJson(st.planet(0));
  gears["ring"] = HelicalGearJson(st.ring());
  json meshes = json::array();
  for (const geometry::MeshSummary& m : st.meshes()) {
    const bool ring = m.kind == geometry::MeshKind::kPlanetRing;
    meshes.push_back(
        HelicalMeshJson(ring ? geometry::SummariseHelicalMesh(m, st.planet(m.planet), st.ring())
                             : geometry::SummariseHelicalMesh(m, st.sun(), st.planet(m.planet))));
  }
  const geometry::StageAxialLoads loads = geometry::AxialLoads(st, scene.loads.sun_torque);
  json forces = json::array();
  for (const geometry::MeshAxialLoad& a : loads.meshes)
    forces.push_back({{"name", a.name},
                      {"base_transverse_force_N", a.base_transverse_force},
                      {"transverse_force_N", a.transverse_force},
                      {"axial_force_N", a.axial_force},
                      {"axial_force_on_planet_N", a.axial_on_planet},
                      {"planet_arm_mm", a.planet_arm * kToMm}});
  json planets = json::array();
  for (const geometry::PlanetTilt& p : loads.planets)
    planets.push_back({{"planet", p.planet + 1},
                       {"tilting_moment_Nm", p.tilting_moment},
                       {"net_axial_force_N", p.net_axial_force}});
  return {{"gears", gears},
          {"meshes", meshes},
          {"sun_torque_Nm", scene.loads.sun_torque},
          {"mesh_forces", forces},
          {"planets", planets},
          {"sun_axial_force_N", loads.sun_axial_force},
          {"ring_axial_force_N", loads.ring_axial_force}};
}

json GearJson(const Gear& g) {
  const geometry::GearSpec& s = g.spec();
  json j;
  j["teeth"] = g.teeth();
  j["module_mm"] = g.module() * kToMm;
  j["face_width_mm"] = s.face_width * kToMm;
  j["profile_shift"] = s.profile_shift;
  j["pressure_angle_deg"] = Deg(s.pressure_angle);
  j["reference_radius_mm"] = g.reference_radius() * kToMm;
  j["base_radius_mm"] = g.base_radius() * kToMm;
  j["tip_radius_mm"] = g.tip_radius() * kToMm;
  j["root_radius_mm"] = g.root_radius() * kToMm;
  j["form_radius_mm"] = g.form_radius() * kToMm;
  j["tip_form_radius_mm"] = g.tip_form_radius() * kToMm;
  j["thickness_reference_mm"] = g.ThicknessAt(g.reference_radius()) * kToMm;
  j["thickness_tip_mm"] = g.tip_thickness() * kToMm;
  j["tip_round_radius_mm"] = s.tip_round_radius * kToMm;
  j["thickness_error_um"] = s.thickness_error * 1e6;
  j["undercut"] = g.undercut();
  if (g.undercut()) j["undercut_radius_mm"] = g.undercut_radius() * kToMm;
  json mods = json::object();
  for (const auto& [which, relief, start_roll] :
       {std::tuple{"tip", s.modification.tip, g.tip_relief_start_roll()},
        std::tuple{"root", s.modification.root, g.root_relief_start_roll()}}) {
    if (relief.amount == 0) continue;
    mods[which] = {
        {"amount_um", relief.amount * 1e6},
        {"start_radius_mm", relief.start_radius * kToMm},
        {"start_roll_deg", Deg(start_roll)},
        {"shape", relief.shape == geometry::ReliefShape::kLinear ? "linear" : "parabolic"}};
  }
  if (!mods.empty()) j["modification"] = mods;
  if (!s.pitch_deviations.empty()) {
    const geometry::iso::PitchStatistics p =
        geometry::iso::PitchDeviationStatistics(s.pitch_deviations);
    json list = json::array();
    for (double v : s.pitch_deviations) list.push_back(v * 1e6);
    j["pitch"] = {{"cumulative_um", list},
                  {"largest_single_um", p.largest_single * 1e6},
                  {"total_cumulative_um", p.total_cumulative * 1e6}};
  }
  if (g.internal()) {
    j["rim_radius_mm"] = s.hub_radius * kToMm;
    j["generation"] = s.shaper ? fmt::format("shaper z_c = {}, x_c = {}", s.shaper->teeth,
                                             s.shaper->profile_shift)
                               : std::string("direct (involute, base rounding, tip rounding)");
  } else {
    j["hub_radius_mm"] = s.hub_radius * kToMm;
    j["min_shift_without_undercut"] = g.MinimumShiftWithoutUndercut();
    j["generation"] = fmt::format("rack: addendum {} m, dedendum {} m, tip round {} m",
                                  s.rack->addendum / g.module(), s.rack->dedendum / g.module(),
                                  s.rack->tip_radius / g.module());
  }
  return j;
}

json MeshJson(const geometry::MeshSummary& m) {
  return {{"name", m.name},
          {"centre_distance_mm", m.centre_distance * kToMm},
          {"operating_pressure_angle_deg", Deg(m.pressure_angle)},
          {"zero_backlash_pressure_angle_deg", Deg(m.zero_backlash_pressure_angle)},
          {"normal_backlash_mm", m.normal_backlash * kToMm},
          {"transverse_backlash_mm", m.transverse_backlash * kToMm},
          {"contact_ratio_iso", m.contact_ratio_iso},
          {"contact_ratio_involute", m.contact_ratio},
          {"sap_a_mm", m.sap_a * kToMm},
          {"sap_b_mm", m.sap_b * kToMm},
          {"phase_cycles", m.phase}};
}

json PairJson(const transmission::Scene& scene, const geometry::GearPair& pair) {
  json j;
  j["scene"] = scene.name;
  j["source"] = scene.source;
  j["gears"]["gear1"] = GearJson(pair.gear1());
  j["gears"]["gear2"] = GearJson(pair.gear2());
  j["gear_order"] = {"gear1", "gear2"};
  j["meshes"] = json::array({MeshJson(pair.summary())});
  j["fits"] = FitsJson(scene);
  if (transmission::IsHelical(scene))
    j["helical"] = {
        {"gears",
         {{"gear1", HelicalGearJson(pair.gear1())}, {"gear2", HelicalGearJson(pair.gear2())}}},
        {"meshes", json::array({HelicalMeshJson(geometry::SummariseHelicalMesh(
                       pair.summary(), pair.gear1(), pair.gear2()))})}};
  return j;
}

json StageJson(const transmission::Scene& scene, const Stage& st) {
  json j;
  j["scene"] = scene.name;
  j["source"] = scene.source;
  j["gears"]["sun"] = GearJson(st.sun());
  j["gears"]["planet"] = GearJson(st.planet(0));
  j["gears"]["ring"] = GearJson(st.ring());
  j["gear_order"] = {"sun", "planet", "ring"};
  json meshes = json::array();
  for (const geometry::MeshSummary& m : st.meshes()) meshes.push_back(MeshJson(m));
  j["meshes"] = meshes;
  const int zsum = st.sun().teeth() + st.ring().teeth();
  json planets = json::array();
  for (int i = 0; i < st.planets(); ++i) {
    planets.push_back({{"planet", i + 1},
                       {"angle_deg", Deg(st.planet_angle(i))},
                       {"assembly_teeth", zsum * st.planet_angle(i) / (2 * geometry::kPi)},
                       {"mesh_phase_cycles", st.meshes()[2 * i].phase}});
  }
  j["assembly"] = {{"carrier_radius_mm", st.carrier_radius() * kToMm},
                   {"planets", planets},
                   {"z_sun_plus_z_ring", zsum},
                   {"equally_spaced", st.spec().planet_angles.empty()},
                   {"mesh_cycle_carrier_deg", Deg(st.mesh_cycle())}};
  j["fits"] = FitsJson(scene);
  if (transmission::IsHelical(scene)) j["helical"] = HelicalStageJson(scene, st);
  return j;
}

}  // namespace epicycle::report
