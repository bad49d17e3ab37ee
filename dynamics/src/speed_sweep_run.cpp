// One speed sweep: the request resolved, the rig built once, the plan, the speeds streamed, the
// record (speed_sweep_run.hpp; docs/speed_sweeps.md).
#include "epicycle/dynamics/speed_sweep_run.hpp"

#include <algorithm>
#include <thread>

#include "epicycle/io/number_format.hpp"
#include "epicycle/transmission/run_range.hpp"

namespace epicycle::dynamics {

int SpeedSweepRecord::failed() const {
  return static_cast<int>(
      std::count_if(speeds.begin(), speeds.end(), [](const SpeedResult& r) { return !r.ok(); }));
}

SpeedSweepRecord RunSpeedSweep(const SpeedSweepRequest& request, SpeedSweepSink& sink) {
  const DynamicRequest& run = request.run;
  SimulationOptions simulation = ResolvedOptions(run);
  simulation.keep_samples = true;  // each speed keeps its window
  const transmission::Scene scene = ResolvedScene(run);
  // The sweep's modes and windows take the pair driver's mesh stiffness: planar stages only.
  transmission::RequireSpur(scene, "`epicycle dynamic --speed-sweep` (the speed sweep)");
  const StageDynamics rig(scene, run.tables);
  const DynamicModel& base = rig.model;
  SpeedSweepOptions o;
  o.sun_speeds_rpm = request.sun_speeds_rpm;
  o.threads = request.threads > 0
                  ? request.threads
                  : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  o.window_cycles =
      request.window_cycles > 0
          ? request.window_cycles
          : transmission::MeshCycles(rig.stage,
                                     run.range.value_or(transmission::RunRange::kPlanetRevolution));
  o.outputs_per_cycle = run.outputs_per_cycle > 0 ? run.outputs_per_cycle : kSweepOutputsPerCycle;
  o.carry = request.carry;
  if (o.carry != CarryState::kNone) o.threads = 1;  // one speed after the other
  o.harmonics = request.harmonics;
  o.window_start = geometry::Rad(run.start_deg);
  o.simulation = simulation;
  // The modes from the tangent mesh stiffness (speed_sweep.hpp: the resonances sit at its
  // coincidences, not at the secant's).
  o.modal_mesh_stiffness = MeanTangentMeshStiffness(rig.scene, rig.stage, rig.fe);

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

}  // namespace epicycle::dynamics
