// The modes run's console text (modes_text.hpp).
#include "epicycle/report/modes_text.hpp"

#include <fmt/printf.h>

namespace epicycle::report {

std::string ModesPlanText(const dynamics::ModesPlan& p) {
  const dynamics::StageDynamics& rig = *p.rig;
  return fmt::sprintf("%s: %d planets, sun %s, %d DOFs (%s)\n", rig.scene.name.c_str(),
                      rig.stage.planets(),
                      transmission::SunSupportName(rig.stage_model.setup().sun), rig.model.size(),
                      rig.model.settings().ring_elastic ? "ring elastic" : "ring fixed");
}

std::string ModesRecordText(const dynamics::ModesRecord& r) {
  std::string t;
  t += fmt::sprintf(
      "  mean mesh stiffness (%s at the scene's load), tangent dF/ddelta "
      "(used here): sun-planet %.4g N/m, planet-ring %.4g N/m\n",
      r.sliced_meshes ? "the stage's quasi-static solutions, its meshes in slices"
                      : "the mesh-stiffness driver",
      r.mesh_stiffness[0], r.mesh_stiffness[1]);
  t += fmt::sprintf(
      "  secant F/delta (sets the mesh damping of a run): sun-planet %.4g N/m, planet-ring %.4g "
      "N/m\n",
      r.secant_mesh_stiffness[0], r.secant_mesh_stiffness[1]);
  t += fmt::sprintf("  mesh frequency %.4f Hz per sun rpm\n\n", r.mesh_hz_per_sun_rpm);
  t += fmt::sprintf("  %-5s %-12s %-5s %-14s %s\n", "mode", "f [Hz]", "mult", "type",
                    "energy: central tr/rot, planets");
  for (std::size_t j = 0; j < r.modes.size(); ++j) {
    const auto& x = r.modes[j];
    const std::string type = x.rigid ? "rigid" : dynamics::ModeTypeName(x.type);
    t += fmt::sprintf("  %-5zu %-12.2f %-5d %-14s %.3f / %.3f, %.3f\n", j + 1, x.frequency,
                      x.multiplicity, type.c_str(), x.central_translation, x.central_rotation,
                      x.planets);
  }
  t += fmt::sprintf("\n  coincidences h f_m = f_j from %.0f to %.0f rpm (%zu):\n",
                    r.coincidence_range_rpm[0], r.coincidence_range_rpm[1], r.coincidences.size());
  for (const dynamics::Coincidence& c : r.coincidences)
    t += fmt::sprintf(
        "    %9.1f rpm  harmonic %-3d x mode %d (%.2f Hz, %s)%s\n", c.sun_speed_rpm, c.harmonic,
        c.mode + 1, c.frequency,
        dynamics::ModeTypeName(r.modes[static_cast<std::size_t>(c.mode)].type).c_str(),
        c.phasing_excited ? "" : "  not excited by a symmetric stage (planet phasing)");
  return t;
}

}  // namespace epicycle::report
