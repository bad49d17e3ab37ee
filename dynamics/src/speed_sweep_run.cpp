// One speed sweep: the request resolved, the rig built once, the plan, the speeds streamed, the
// record (speed_sweep_run.hpp; docs/speed_sweeps.md).
#include "epicycle/dynamics/speed_sweep_run.hpp"

#include <algorithm>
#include <thread>

#include "epicycle/dynamics/load_sharing_parts.hpp"
#include "epicycle/dynamics/modes.hpp"
#include "epicycle/dynamics/modes_run.hpp"
#include "epicycle/io/number_format.hpp"
#include "epicycle/transmission/helical_scene.hpp"
#include "epicycle/transmission/run_range.hpp"

namespace epicycle::dynamics {

namespace {

// One speed's fields: its status, counts, times and warnings, and where it completed its figures.
void VisitSpeed(const SpeedResult& r, const SpeedSweepPlan& plan,
                transmission::RecordVisitor& visit) {
  visit.Number("sun_speed_rpm", r.sun_speed_rpm);
  visit.Number("mesh_frequency_Hz", r.mesh_frequency);
  visit.Flag("ok", r.ok());
  visit.Text("status", transmission::RunStatusName(r.status));
  visit.Text("message", r.message);
  visit.Integer("steps", r.stats.steps);
  visit.Integer("evaluations", r.stats.rhs_evaluations);
  visit.Integer("failed_contact_solves", r.stats.failed_solves);
  visit.Number("cpu_s", r.cpu_seconds);
  visit.Number("wall_s", r.wall_seconds);
  visit.Texts("warnings", r.warnings);
  if (!r.ok()) return;
  visit.Number("K_gamma", r.k_gamma);
  visit.Number("dynamic_factor", r.dynamic_factor);
  visit.Text("dynamic_factor_mesh", r.factor_mesh >= 0 ? plan.meshes[r.factor_mesh] : "");
  visit.Number("peak_mesh_force_N", r.peak_mesh_force);
  visit.Number("quasi_static_peak_mesh_force_N", r.qs_peak_mesh_force);
  visit.Number("te_amplitude_urad", r.te_amplitude * 1e6);
  visit.Number("sun_orbit_radius_um", r.orbit_radius * 1e6);
  visit.Number("lsr_min", r.lsr_min);
  visit.Number("lsr_max", r.lsr_max);
  visit.Number("lsr_deviation", r.lsr_deviation);
  visit.BeginObject("lsr_deviation_parts");
  for (int k = 0; k < kLoadSharingPartCount; ++k)
    visit.Number(kLoadSharingPartNames[k], r.deviation_parts[static_cast<std::size_t>(k)]);
  visit.EndObject();
  visit.Number("largest_residual", r.largest_residual);
  transmission::VisitHelicalLoads(visit, r.helical);  // over the window (a helical stage)
}

}  // namespace

int SpeedSweepRecord::failed() const {
  return static_cast<int>(
      std::count_if(speeds.begin(), speeds.end(), [](const SpeedResult& r) { return !r.ok(); }));
}

SpeedSweepRecord RunSpeedSweep(const SpeedSweepRequest& request, SpeedSweepSink& sink) {
  const DynamicRequest& run = request.run;
  SimulationOptions simulation = ResolvedOptions(run);
  simulation.keep_samples = true;  // each speed keeps its window
  const transmission::Scene scene = ResolvedScene(run);
  // A helical stage in slices, each at its own section's poses, its mesh stiffnesses the stage's
  // own sliced ones (docs/model.md §10).
  transmission::RequireHelicalSlices(scene, "`epicycle dynamic --speed-sweep`");
  transmission::FeComplianceOptions tables = run.tables;
  tables.helical_slices = true;
  const StageDynamics rig(scene, tables);
  const DynamicModel& base = rig.model;
  SpeedSweepOptions o;
  o.sun_speeds_rpm = request.sun_speeds_rpm;
  o.threads = request.threads > 0
                  ? request.threads
                  : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  o.window_cycles = request.window_cycles > 0
                        ? request.window_cycles
                        : transmission::MeshCycles(rig.stage, run.range.value_or(kDefaultRunRange));
  o.outputs_per_cycle = run.outputs_per_cycle > 0 ? run.outputs_per_cycle : kSweepOutputsPerCycle;
  o.carry = request.carry;
  if (o.carry != CarryState::kNone) o.threads = 1;  // one speed after the other
  o.harmonics = request.harmonics;
  o.window_start = geometry::Rad(run.start_deg);
  o.simulation = simulation;
  // The modes from the tangent mesh stiffness (speed_sweep.hpp: the resonances sit at its
  // coincidences, not at the secant's).
  o.modal_mesh_stiffness = rig.TangentMeshStiffness();

  SpeedSweepRecord record;
  record.scene = rig.scene.name;
  record.sun_torque = rig.scene.loads.sun_torque;
  record.friction = rig.scene.dynamics.friction.law;
  record.integrator = run.integrator;
  record.tolerances = TolerancesOf(simulation, run.backend);
  record.transient_fraction = o.transient_fraction;
  record.window_cycles = o.window_cycles;
  record.window_start_deg = run.start_deg;
  record.mesh_stiffness = {base.sun_mesh_stiffness(), base.ring_mesh_stiffness()};
  record.modal_mesh_stiffness = o.modal_mesh_stiffness;
  record.threads = o.threads;
  record.carry = o.carry;
  record.periodic_fallback = request.periodic_fallback;
  record.plan = PlanSpeedSweep(base, o);
  sink.Start({&rig, &o, &record.plan});

  const SpeedSweepResult res =
      SweepSpeeds(base, o, record.plan, [&](const SpeedResult& r) { sink.Speed(r, record.plan); });
  record.speeds = res.speeds;
  record.wall_seconds = res.wall_seconds;
  record.warnings = rig.scene.warnings;
  for (const SpeedResult& r : res.speeds) {
    record.cpu_seconds += r.cpu_seconds;
    for (const std::string& w : r.warnings)
      record.warnings.push_back("at " + io::Num(r.sun_speed_rpm, 9) + " rpm: " + w);
  }
  return record;
}

void VisitRecord(const SpeedSweepRecord& r, transmission::RecordVisitor& visit) {
  const SpeedSweepPlan& plan = r.plan;
  visit.BeginObject("definitions");
  visit.Text("K_gamma", "max over window samples and planets of n LSR_i");
  visit.Text("dynamic_factor",
             "max over meshes of (peak total normal force of the mesh in motion, damping "
             "included) / (peak quasi-static total normal force of that mesh at the same carrier "
             "angles, with the same friction at rest at that speed: "
             "quasi_static_peak_mesh_force_N of the speed; the top-level one is at the scene's "
             "speed)");
  visit.Text("te_amplitude", "half the peak-to-peak dynamic transmission error at the sun");
  visit.Text("sun_orbit_radius", "largest sun-centre displacement over the window");
  visit.Text("window",
             "each speed starts at the quasi-static solution, skips skip_time_s (start transient "
             "below transient_fraction in every mode) and measures window_mesh_cycles from "
             "window_start_carrier_deg");
  visit.EndObject();
  visit.BeginObject("quasi_static_peak_mesh_force_N");
  for (std::size_t q = 0; q < plan.meshes.size(); ++q)
    visit.Number(plan.meshes[q].c_str(), plan.qs_peak_mesh_force[q]);
  visit.EndObject();
  visit.BeginList("modes");
  for (const ModeDamping& m : plan.modes) {
    visit.Item();
    visit.Number("frequency_Hz", m.mode.frequency);
    visit.Text("type", ModeTypeName(m.mode.type));
    visit.Integer("multiplicity", m.mode.multiplicity);
    visit.Integers("cyclic_families_k", std::vector<long>(m.families.begin(), m.families.end()));
    visit.Number("damping_ratio", m.damping_ratio);
    visit.Number("decay_rate_per_s", m.decay_rate);
  }
  visit.EndList();
  VisitCoincidences(plan.coincidences, visit);
  visit.BeginList("speeds");
  for (const SpeedResult& s : r.speeds) {
    visit.Item();
    VisitSpeed(s, plan, visit);
  }
  visit.EndList();
  visit.Texts("warnings", r.warnings);
  visit.Text("scene", r.scene);
  visit.Number("sun_torque_Nm", r.sun_torque);
  visit.Text("friction", transmission::FrictionLawName(r.friction));
  visit.Text("integrator", r.integrator);
  // rate_tolerance_scale_rad_per_s 0: each speed's highest linearised natural frequency (its
  // speed's run reports it).
  VisitTolerances(r.tolerances, visit);
  visit.Number("skip_time_s", plan.skip_time);
  visit.Number("transient_fraction", r.transient_fraction);
  visit.Number("slowest_modal_decay_rate_per_s", plan.slowest_decay_rate);
  visit.Number("window_mesh_cycles", r.window_cycles);
  visit.Integer("window_samples", static_cast<long>(plan.window_angles.size()));
  visit.Number("window_start_carrier_deg", r.window_start_deg);
  visit.Number("mesh_frequency_Hz_per_sun_rpm", plan.mesh_hz_per_rpm);
  visit.Number("mesh_stiffness_sun_planet_N_per_m", r.mesh_stiffness[0]);
  visit.Number("mesh_stiffness_planet_ring_N_per_m", r.mesh_stiffness[1]);
  visit.Number("tangent_mesh_stiffness_sun_planet_N_per_m", r.modal_mesh_stiffness[0]);
  visit.Number("tangent_mesh_stiffness_planet_ring_N_per_m", r.modal_mesh_stiffness[1]);
  visit.Number("quasi_static_K_gamma", plan.qs_k_gamma);
  visit.Number("quasi_static_te_amplitude_urad", plan.qs_te_amplitude * 1e6);
  visit.Integer("failed_speeds", r.failed());
  visit.Integer("threads", r.threads);
  visit.Text("carry_state", CarryStateName(r.carry));
  visit.Text("periodic_fallback", r.periodic_fallback);
  visit.Number("plan_seconds", plan.seconds);
  visit.Number("wall_seconds", r.wall_seconds);
  visit.Number("cpu_seconds_in_speeds", r.cpu_seconds);
  visit.Number("cpu_over_wall", r.cpu_seconds / std::max(r.wall_seconds, 1e-9));
}

}  // namespace epicycle::dynamics
