// A speed sweep's console text and summary JSON (speed_sweep_run_files.hpp).
#include "epicycle/report/speed_sweep_run_files.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "epicycle/report/record_json.hpp"
#include "epicycle/report/run_files.hpp"

namespace epicycle::report {

namespace {

std::string ModeName(const dynamics::SpeedSweepPlan& plan, int mode) {
  const dynamics::Mode& m = plan.modes[static_cast<std::size_t>(mode)].mode;
  return fmt::format("mode {} ({}, {:.0f} Hz)", mode + 1, dynamics::ModeTypeName(m.type),
                     m.frequency);
}

}  // namespace

std::string SpeedSweepPlanText(const dynamics::SpeedSweepStart& start) {
  const dynamics::StageDynamics& rig = *start.rig;
  const transmission::Scene& scene = rig.scene;
  const dynamics::DynamicModel& base = rig.model;
  const dynamics::SpeedSweepOptions& o = *start.options;
  const dynamics::SpeedSweepPlan& plan = *start.plan;
  std::string t = fmt::format(
      "{}: speed sweep, {} sun speeds {:.1f} .. {:.1f} rpm, sun {}, {} threads{}\n", scene.name,
      o.sun_speeds_rpm.size(), o.sun_speeds_rpm.front(), o.sun_speeds_rpm.back(),
      transmission::SunSupportName(rig.stage_model.setup().sun), o.threads,
      o.carry == dynamics::CarryState::kNone
          ? ""
          : fmt::format(", carrying the state {}", dynamics::CarryStateName(o.carry)));
  for (const std::string& m : rig.compliance.tables().messages()) t += "  " + m + "\n";
  t += fmt::format(
      "  mean mesh stiffness: sun-planet {:.4g} N/m, planet-ring {:.4g} N/m (secant F/delta: the "
      "mesh damping {:.4g} and {:.4g} N s/m); tangent dF/ddelta {:.4g} and {:.4g} N/m (the modes); "
      "friction {}, rtol {:.1e}\n",
      base.sun_mesh_stiffness(), base.ring_mesh_stiffness(), base.sun_mesh_damping(),
      base.ring_mesh_damping(), o.modal_mesh_stiffness[0], o.modal_mesh_stiffness[1],
      transmission::FrictionLawName(scene.dynamics.friction.law), o.simulation.rtol);
  t += "  modes of the linearised stage (f, type, modal damping ratio, decay rate):\n";
  for (std::size_t j = 0; j < plan.modes.size(); ++j) {
    const dynamics::ModeDamping& m = plan.modes[j];
    std::string k;
    for (int f : m.families) {
      if (!k.empty()) k += ',';
      k += std::to_string(f);
    }
    t += fmt::format(
        "    mode {:<3} {:10.2f} Hz  {:<13} x{}  family k = {:<5} zeta {:.4f}  sigma "
        "{:.1f} 1/s\n",
        j + 1, m.mode.frequency, dynamics::ModeTypeName(m.mode.type), m.mode.multiplicity, k,
        m.damping_ratio, m.decay_rate);
  }
  t += fmt::format(
      "  coincidences h f_m = f_j in the range (mesh frequency {:.4f} Hz per sun rpm):\n",
      plan.mesh_hz_per_rpm);
  for (const dynamics::Coincidence& c : plan.coincidences)
    t += fmt::format(
        "    {:9.1f} rpm  harmonic {} x {}{}\n", c.sun_speed_rpm, c.harmonic,
        ModeName(plan, c.mode),
        c.phasing_excited ? "" : "  (not excited by a symmetric stage: planet phasing)");
  t += fmt::format(
      "  per speed: the quasi-static start, {:.3f} ms skipped (ln(1/{:.0e})/sigma_min, sigma_min = "
      "{:.1f} 1/s), then {:.4g} mesh cycles measured from carrier {:.3f} deg ({} samples); "
      "quasi-static reference over the same positions: K_gamma {:.6f} (planned in {:.2f} s)\n",
      plan.skip_time * 1e3, o.transient_fraction, plan.slowest_decay_rate, o.window_cycles,
      geometry::Deg(o.window_start), plan.window_angles.size(), plan.qs_k_gamma, plan.seconds);
  return t;
}

std::string SpeedSweepRecordText(const dynamics::SpeedSweepRecord& record) {
  std::string t =
      fmt::format("\n  {:<10} {:<9} {:<9} {:<9} {:<13} {:<11} {:<10} {}\n", "sun rpm", "K_gamma",
                  "K_v", "mesh", "TE amp urad", "orbit um", "CPU s", "status");
  for (const dynamics::SpeedResult& r : record.speeds) {
    const std::string mesh = r.factor_mesh >= 0 ? record.plan.meshes[r.factor_mesh] : "";
    t += fmt::format("  {:<10.1f} {:<9.5f} {:<9.5f} {:<9} {:<13.3f} {:<11.4f} {:<10.2f} {}\n",
                     r.sun_speed_rpm, r.k_gamma, r.dynamic_factor, mesh, r.te_amplitude * 1e6,
                     r.orbit_radius * 1e6, r.cpu_seconds, r.ok() ? "ok" : r.message);
  }
  const double speeds = static_cast<double>(record.speeds.size());
  t += fmt::format(
      "  {:.1f} s wall for {} speeds on {} threads, {:.1f} s CPU in the speeds ({:.2f} s per "
      "speed; CPU/wall {:.2f}: the parallel speed-up on an otherwise idle machine)\n",
      record.wall_seconds, record.speeds.size(), record.threads, record.cpu_seconds,
      record.cpu_seconds / speeds, record.cpu_seconds / std::max(record.wall_seconds, 1e-9));
  return t;
}

nlohmann::json SpeedSweepRecordJson(const dynamics::SpeedSweepRecord& record,
                                    const nlohmann::json& provenance) {
  return SummaryJson(record, provenance);
}

}  // namespace epicycle::report
