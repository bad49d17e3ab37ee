// One dynamic run of a stage, as every front end asks for it: a request (the scene and typed
// overrides, every default resolved here), a run that builds the rig once, starts from the
// quasi-static solution and streams each output step to a sink, and one record of what the run
// found (docs/dynamic.md). The program (`epicycle dynamic`) and Python's `dynamic` parse their
// options into a request and format the record; report/ writes the record's one serialisation
// (report::DynamicRecordJson), whose keys are the record's fields as VisitRecord names them.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "epicycle/dynamics/dynamic_factor.hpp"
#include "epicycle/dynamics/dynamic_model.hpp"
#include "epicycle/dynamics/dynamic_summary.hpp"
#include "epicycle/dynamics/run_arguments.hpp"
#include "epicycle/dynamics/run_span.hpp"
#include "epicycle/dynamics/run_tolerances.hpp"
#include "epicycle/dynamics/simulation.hpp"
#include "epicycle/dynamics/vibration.hpp"
#include "epicycle/transmission/record.hpp"
#include "epicycle/transmission/run_range.hpp"
#include "epicycle/transmission/run_status.hpp"
#include "epicycle/transmission/scene.hpp"

namespace epicycle::dynamics {

/// The names under which a front end's user gives the request's fields, for the messages that
/// name them (the program: "--time", "--speed-rpm"; Python: "time_s", "sun_speed_rpm"), both from
/// DynamicArguments (run_arguments.hpp).
struct DynamicOptionNames {
  using A = DynamicArguments;
  std::string time = A::kTime.keyword, speed = A::kSpeedRpm.keyword, range = A::kRange.keyword,
              rating = A::kRating.keyword, spectrum_resolution = A::kSpectrumResolution.keyword,
              spectrum_skip = A::kSpectrumSkip.keyword,
              outputs_per_cycle = A::kOutputsPerCycle.keyword, start = A::kStartDeg.keyword,
              rtol = A::kRtol.keyword, rate_scale = A::kRateScale.keyword,
              contact_tolerance = A::kContactTol.keyword, max_order = A::kMaxOrder.keyword,
              max_steps = A::kMaxSteps.keyword, time_limit = A::kTimeLimit.keyword;
  /// The program's names (its options).
  static DynamicOptionNames Program() {
    return {A::kTime.option,
            A::kSpeedRpm.option,
            A::kRange.option,
            A::kRating.option,
            A::kSpectrumResolution.option,
            A::kSpectrumSkip.option,
            A::kOutputsPerCycle.option,
            A::kStartDeg.option,
            A::kRtol.option,
            A::kRateScale.option,
            A::kContactTol.option,
            A::kMaxOrder.option,
            A::kMaxSteps.option,
            A::kTimeLimit.option};
  }
};

/// The span a dynamic run (and a speed sweep's window) covers when the request gives neither a
/// range nor a time: one planet revolution relative to the carrier.
inline constexpr transmission::RunRange kDefaultRunRange =
    transmission::RunRange::kPlanetRevolution;

/// What a dynamic run is asked for; an unset optional is the scene's or the library's default.
struct DynamicRequest {
  transmission::Scene scene;                    ///< read and validated (ReadScene)
  std::optional<transmission::SunSupport> sun;  ///< overrides [supports] sun
  std::optional<double> sun_speed_rpm;          ///< overrides [dynamics] sun_speed_rpm [rpm]
  std::string friction;                         ///< "": the scene's law; else a law's name
  std::optional<transmission::RunRange> range;  ///< none: one planet revolution
  std::optional<double> time_s;                 ///< simulated time instead of the range [s]
  double start_deg = 0;                         ///< carrier angle at t = 0 [deg]
  int outputs_per_cycle = 0;  ///< output steps per mesh cycle; 0: DefaultOutputsPerCycle
  std::string backend = "newton", integrator = "cvode-bdf";
  double rtol = 1e-6;                       ///< the integrator's relative tolerance [-]
  std::optional<double> rate_scale;         ///< [rad/s]; none: SimulationOptions' default
  std::optional<double> contact_tolerance;  ///< none: SimulationOptions' default
  int max_order = 5;                        ///< CVODE's largest BDF order
  bool analytic_jacobian = true;
  std::optional<long> max_steps;       ///< per output interval; none: SimulationOptions'
  std::optional<double> time_limit_s;  ///< wall-time budget of the run [s]; none: no limit
  bool stresses = false;  ///< root stresses per step (also when the scene asks for them)
  bool rating = false;    ///< ISO 6336 ratings with the run's K_v (implies stresses)
  bool spectrum = false;  ///< the vibration signals and their spectra (docs/spectra.md)
  std::optional<double> spectrum_resolution_hz, spectrum_skip_cycles;
  transmission::FeComplianceOptions tables;  ///< the influence tables' cache
  DynamicOptionNames names;
};

/// The request's settings resolved against the scene, before the rig is built: the scene as run
/// (sun, speed, friction and stresses overridden) and the integrator's options.
/// @throws std::invalid_argument for a request that breaks a rule (named as `names` says).
transmission::Scene ResolvedScene(const DynamicRequest& request);
SimulationOptions ResolvedOptions(const DynamicRequest& request);

/// What the run has built before its first step (for a front end's header and files).
struct DynamicPlan {
  const StageDynamics* rig = nullptr;  ///< the scene as run, its stage, tables and model
  const SimulationOptions* options = nullptr;
  const RunSpan* span = nullptr;
  const std::optional<SpectrumOptions>* spectrum = nullptr;  ///< with the request's spectrum
  int outputs_per_cycle = 0;                                 ///< as resolved [-]
  double highest_mode_hz = 0;  ///< highest natural frequency of the linearised model [Hz]
  double setup_seconds = 0;    ///< wall time to build the rig [s]
  std::string cost_warning;    ///< RunCostWarning ("" for a run of minutes)
  bool started = true;         ///< the quasi-static start solved (else no step follows)
};

/// Where a run streams what it computes, in order.
class DynamicSink {
 public:
  virtual ~DynamicSink() = default;
  /// Once, after the rig and the quasi-static start, before the first step.
  virtual void Start(const DynamicPlan& /*plan*/) {}
  /// Each output step as soon as it is computed; it is let go after this call (flat memory).
  virtual void Step(const DynamicSample& /*sample*/) {}
  /// Once after the last step of a run that started, while the rig still exists (the plan's
  /// pointers are let go after this call).
  virtual void Stop() {}
};

/// What a dynamic run found. Every field is in the record's one serialisation (VisitRecord),
/// named with its unit there.
struct DynamicRecord {
  std::string scene;
  transmission::SunSupport sun = transmission::SunSupport::kFixed;
  double sun_torque = 0;      ///< [N·m], with its sign
  double sun_speed_rpm = 0;   ///< |ω_s| [rpm]
  double mesh_frequency = 0;  ///< [Hz]
  transmission::FrictionLaw friction = transmission::FrictionLaw::kOff;
  Integrator integrator = Integrator::kCvodeBdf;
  /// As run; rate_scale the run's (SimulationStats::rate_scale; 0 when the start failed).
  RunTolerances tolerances;
  double duration = 0;  ///< [s]
  int outputs = 0;      ///< output steps asked for [-]
  transmission::RunStatus status = transmission::RunStatus::kCompleted;
  std::string failure;                     ///< where and why the run stopped ("" when completed)
  std::array<double, 2> mesh_stiffness{};  ///< secant, {sun–planet, planet–ring} [N/m]
  DynamicSummary summary;                  ///< over the steps written
  SimulationStats stats;
  std::optional<transmission::StageRating> rating;  ///< when asked and a step was written
  std::vector<std::string> warnings;  ///< the scene's, the run's cost and the results'
  double setup_seconds = 0;           ///< [s]
  bool completed() const { return status == transmission::RunStatus::kCompleted; }
};

/// Builds the rig once, starts from the quasi-static solution, integrates (each step to `sink`
/// as it is computed) and returns the record. A run that fails midway, or whose start fails, is
/// a status in the record, not an exception.
/// @throws std::invalid_argument for a request that breaks a rule; whatever `sink` throws.
DynamicRecord RunDynamic(const DynamicRequest& request, DynamicSink& sink);

/// The record's fields, each once with its name and unit (its serialisation's keys).
void VisitRecord(const DynamicRecord& record, transmission::RecordVisitor& visit);

}  // namespace epicycle::dynamics
