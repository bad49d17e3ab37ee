// One speed sweep of a stage, as every front end asks for it: a request (a dynamic run's request
// and the speeds, window and threads), a run that builds the rig once, plans the modes and the
// window, and streams each speed's result to a sink as it completes, and one record of the sweep
// (docs/speed_sweeps.md). The program (`epicycle dynamic --speed-sweep`) parses its options into
// a request and formats the record; report/ writes its one serialisation (report::RecordJson),
// whose keys the fields VisitRecord names.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "epicycle/dynamics/dynamic_run.hpp"
#include "epicycle/dynamics/run_tolerances.hpp"
#include "epicycle/dynamics/speed_sweep.hpp"
#include "epicycle/transmission/record.hpp"

namespace epicycle::dynamics {

/// What a speed sweep is asked for. `run` gives the scene and its overrides, the integrator's
/// settings, the window's range (none: one planet revolution) and start (start_deg), and the
/// window's samples per mesh cycle (outputs_per_cycle; 0: kSweepOutputsPerCycle); its speed,
/// time, spectrum, stresses and rating belong to a run at one speed and are not used.
struct SpeedSweepRequest {
  DynamicRequest run;
  std::vector<double> sun_speeds_rpm;  ///< [rpm], increasing (SpeedGrid)
  double window_cycles = 0;            ///< > 0: mesh cycles measured per speed, replacing range
  int harmonics = 0;                   ///< coincidences of mesh harmonics 1..N; 0: every one
  int threads = 0;                     ///< worker threads; 0: every core
  /// kUp / kDown: a run-up or run-down, each speed from the previous one's end state, on one
  /// thread (speed_sweep.hpp, "Carried state").
  CarryState carry = CarryState::kNone;
  /// Non-empty: the sweep runs in place of a periodic branch over the same range, and why (the
  /// front end's words around BranchPeriodTooLong); kept in the record, not among its warnings.
  std::string periodic_fallback;
};

/// The samples per mesh cycle of a speed sweep's window by default.
inline constexpr int kSweepOutputsPerCycle = 64;

/// What the sweep has built and planned before its first speed.
struct SpeedSweepStart {
  const StageDynamics* rig = nullptr;
  const SpeedSweepOptions* options = nullptr;  ///< as resolved (threads, window, modal stiffness)
  const SpeedSweepPlan* plan = nullptr;
};

/// Where a sweep streams its results, in completion order.
class SpeedSweepSink {
 public:
  virtual ~SpeedSweepSink() = default;
  /// Once, after the plan and before the first speed.
  virtual void Start(const SpeedSweepStart& /*start*/) {}
  /// Each speed as soon as it completes (under one lock).
  virtual void Speed(const SpeedResult& /*result*/, const SpeedSweepPlan& /*plan*/) {}
};

/// What a speed sweep found: its settings as run, its plan, every speed's result and status.
struct SpeedSweepRecord {
  std::string scene;
  double sun_torque = 0;  ///< [N·m]
  transmission::FrictionLaw friction = transmission::FrictionLaw::kOff;
  std::string integrator;  ///< as the request names it
  /// The back end as the request names it; rate_scale 0: each speed's highest natural frequency.
  RunTolerances tolerances;
  double transient_fraction = 0, window_cycles = 0, window_start_deg = 0;  ///< [-, -, deg]
  std::array<double, 2> mesh_stiffness{}, modal_mesh_stiffness{};  ///< secant, tangent [N/m]
  int threads = 0;
  CarryState carry = CarryState::kNone;  ///< as requested
  SpeedSweepPlan plan;
  std::vector<SpeedResult> speeds;    ///< in the order of the speeds
  double wall_seconds = 0;            ///< of the speeds' runs [s]
  double cpu_seconds = 0;             ///< CPU in the speeds [s]
  std::vector<std::string> warnings;  ///< the scene's and each speed's ("at N rpm: ...")
  /// Why the sweep ran instead of the periodic branch asked for ("": it was not asked for).
  std::string periodic_fallback;
  int failed() const;                 ///< speeds that did not complete
};

/// Builds the rig once, plans the sweep and runs every speed (each to `sink` as it completes);
/// a speed that fails is a status in its result, not an exception.
/// @throws std::invalid_argument for a request that breaks a rule; std::runtime_error when the
///         plan's quasi-static reference fails; whatever `sink` throws.
SpeedSweepRecord RunSpeedSweep(const SpeedSweepRequest& request, SpeedSweepSink& sink);

/// The record's fields, each once with its name and unit (its serialisation's keys): the
/// definitions of the figures, the plan (modes with their damping, coincidences, the quasi-static
/// reference), per speed its status, counts, times and (when it completed) its figures, the
/// settings and the times.
void VisitRecord(const SpeedSweepRecord& record, transmission::RecordVisitor& visit);

}  // namespace epicycle::dynamics
