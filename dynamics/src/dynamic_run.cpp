// One dynamic run: the request resolved, the rig built once, the quasi-static start, the steps
// streamed and accumulated, the record (dynamic_run.hpp; docs/dynamic.md).
#include "epicycle/dynamics/dynamic_run.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "epicycle/dynamics/run_arguments.hpp"
#include "epicycle/dynamics/spectrum.hpp"
#include "epicycle/io/units.hpp"
#include "epicycle/transmission/helical_scene.hpp"
#include "epicycle/transmission/run_arguments.hpp"

namespace epicycle::dynamics {

transmission::Scene ResolvedScene(const DynamicRequest& request) {
  transmission::Scene scene = request.scene;
  if (scene.kind != transmission::SceneKind::kStage)
    throw std::invalid_argument(scene.name + ": a gear-pair scene; a dynamic run needs a stage");
  if (request.sun) scene.supports.sun = *request.sun;
  if (request.sun_speed_rpm) {
    CheckArgument(request.names.speed, *request.sun_speed_rpm, transmission::kSunSpeedRpm);
    scene.dynamics.sun_speed = io::RpmToRadPerSecond(*request.sun_speed_rpm);
  }
  if (!request.friction.empty())
    scene.dynamics.friction.law = transmission::FrictionLawFromName(request.friction);
  scene.model.stresses = scene.model.stresses || request.stresses || request.rating;
  if (request.rating)
    transmission::CheckRatingInputs(transmission::RatingInputsOf(scene), request.names.rating);
  return scene;
}

SimulationOptions ResolvedOptions(const DynamicRequest& r) {
  const DynamicOptionNames& n = r.names;
  if (r.time_s) CheckArgument(n.time, *r.time_s, kRunTimeS);
  if (r.outputs_per_cycle != 0)
    CheckArgument(n.outputs_per_cycle, r.outputs_per_cycle, kOutputsPerCycle);
  CheckArgument(n.start, r.start_deg, transmission::kCarrierAngleDeg);
  CheckArgument(n.rtol, r.rtol, kRelativeTolerance);
  if (r.rate_scale) CheckArgument(n.rate_scale, *r.rate_scale, kRateScale);
  if (r.contact_tolerance)
    CheckArgument(n.contact_tolerance, *r.contact_tolerance, kRunContactTolerance);
  CheckArgument(n.max_order, r.max_order, kMaxOrder);
  if (r.max_steps) CheckArgument(n.max_steps, static_cast<double>(*r.max_steps), kMaxSteps);
  if (r.time_limit_s) CheckArgument(n.time_limit, *r.time_limit_s, kRunTimeLimitS);
  if (r.spectrum_resolution_hz)
    CheckArgument(n.spectrum_resolution, *r.spectrum_resolution_hz, kSpectrumResolution);
  if (r.spectrum_skip_cycles)
    CheckArgument(n.spectrum_skip, *r.spectrum_skip_cycles, kSpectrumSkipCycles);
  SimulationOptions o;
  o.integrator = IntegratorFromName(r.integrator);
  o.backend = solvers::BackendFromName(r.backend);
  o.rtol = r.rtol;
  if (r.rate_scale) o.rate_scale = *r.rate_scale;
  if (r.contact_tolerance) o.contact.tolerance = *r.contact_tolerance;
  o.analytic_jacobian = r.analytic_jacobian;
  o.max_order = r.max_order;
  if (r.max_steps) o.max_steps = *r.max_steps;
  if (r.time_limit_s) o.time_limit = *r.time_limit_s;
  o.keep_samples = false;  // each step to the sink and the accumulators, then let go
  o.Validate();
  return o;
}

namespace {

// The settings of the record, known before the first step.
DynamicRecord Settings(const DynamicModel& model, const SimulationOptions& o, const RunSpan& span) {
  DynamicRecord r;
  r.scene = model.stage_model().name();
  r.sun = model.stage_model().setup().sun;
  r.sun_torque = model.sun_torque();
  r.sun_speed_rpm = io::RadPerSecondToRpm(std::abs(model.sun_speed()));
  r.mesh_frequency = span.mesh_frequency;
  r.friction = model.settings().friction.law;
  r.integrator = o.integrator;
  r.tolerances = TolerancesOf(o, solvers::BackendName(o.backend));
  r.tolerances.rate_scale = 0;  // the run's, once it has started (SimulationStats::rate_scale)
  r.duration = span.duration;
  r.outputs = span.outputs;
  r.mesh_stiffness = {model.sun_mesh_stiffness(), model.ring_mesh_stiffness()};
  return r;
}

// What set the run's length and speed, as the user gave them (for the messages).
std::string DurationSource(const DynamicRequest& r) {
  return r.time_s
             ? fmt::format("{} = {} s", r.names.time, *r.time_s)
             : r.names.range + " " +
                   io::NameOf(transmission::kRunRangeNames, r.range.value_or(kDefaultRunRange));
}

}  // namespace

DynamicRecord RunDynamic(const DynamicRequest& request, DynamicSink& sink) {
  transmission::Scene scene = ResolvedScene(request);
  const SimulationOptions opt = ResolvedOptions(request);
  // A helical stage in slices, each at its own section's poses (docs/model.md §10).
  transmission::RequireHelicalSlices(scene, "`epicycle dynamic`");
  transmission::FeComplianceOptions tables = request.tables;
  tables.helical_slices = true;
  const auto t0 = std::chrono::steady_clock::now();
  StageDynamics rig(std::move(scene), tables);
  DynamicModel& model = rig.model;
  model.SetStartAngle(geometry::Rad(request.start_deg));
  DynamicPlan plan;
  plan.rig = &rig;
  plan.options = &opt;
  plan.setup_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // The start first: a stage whose start fails (a planet separated from a member) has no
  // operating point to linearise about; its plan keeps the default's floor of outputs.
  const StartOutcome start = model.SolveQuasiStaticStart(opt.contact, opt.backend);
  plan.started = start.status == transmission::RunStatus::kCompleted;
  plan.highest_mode_hz = plan.started ? HighestModeFrequency(model) : 0.0;
  plan.outputs_per_cycle = request.outputs_per_cycle > 0
                               ? request.outputs_per_cycle
                               : DefaultOutputsPerCycle(model, plan.highest_mode_hz);
  const RunSpan span =
      MakeRunSpan(rig.stage, model.carrier_speed(), request.range.value_or(kDefaultRunRange),
                  request.time_s.value_or(0.0), plan.outputs_per_cycle);
  plan.span = &span;
  plan.cost_warning = RunCostWarning(  // a run of hours: said before it starts
      span, io::RadPerSecondToRpm(model.sun_speed()), DurationSource(request),
      request.sun_speed_rpm ? fmt::format("{} = {}", request.names.speed, *request.sun_speed_rpm)
                            : std::string("[dynamics] sun_speed_rpm"));
  std::optional<SpectrumOptions> spectrum;  // bad options before the run
  if (request.spectrum)
    spectrum = RunSpectrumOptions(
        span, CharacteristicFrequencies(rig.stage, model.sun_speed()),
        request.spectrum_resolution_hz.value_or(0),
        request.spectrum_skip_cycles.value_or(kDefaultSpectrumSkipCycles),
        {request.names.spectrum_resolution, request.spectrum_resolution_hz.has_value(),
         request.names.spectrum_skip, request.spectrum_skip_cycles.has_value(),
         request.time_s || request.range
             ? DurationSource(request)
             : "one planet revolution (the default " + request.names.range + " planet)"});
  plan.spectrum = &spectrum;

  DynamicRecord record = Settings(model, opt, span);
  record.setup_seconds = plan.setup_seconds;
  sink.Start(plan);
  record.warnings = rig.scene.warnings;
  if (!plan.cost_warning.empty()) record.warnings.push_back(plan.cost_warning);
  if (!plan.started) {
    record.status = start.status;
    record.failure = start.message;
    return record;
  }

  DynamicAccumulator accumulator;
  DynamicWarningTally tally(rig.stage);
  std::optional<MotionLoads> loads;
  if (request.rating) loads.emplace(rig.stage);
  const SimulationResult result = Simulate(model, opt, start.d, Eigen::VectorXd::Zero(model.size()),
                                           span.OutputTimes(), [&](const DynamicSample& s) {
                                             accumulator.Add(s);
                                             tally.Add(s);
                                             if (loads) loads->Add(s);
                                             sink.Step(s);
                                           });
  sink.Stop();
  record.status = result.status;
  record.failure = result.message;
  record.stats = result.stats;
  record.tolerances.rate_scale = result.stats.rate_scale;
  record.summary = accumulator.Result();
  for (const std::string& w : tally.Messages()) record.warnings.push_back(w);
  // ISO 6336 with the run's K_v (docs/stresses.md)
  if (loads && record.summary.samples > 0)
    record.rating =
        RateRun(rig.rating, model, opt, span, *loads, record.summary.root_stress).rating;
  return record;
}

void VisitRecord(const DynamicRecord& r, transmission::RecordVisitor& visit) {
  visit.Text("scene", r.scene);
  visit.Text("sun_support", transmission::SunSupportName(r.sun));
  visit.Number("sun_torque_Nm", r.sun_torque);
  visit.Number("sun_speed_rpm", r.sun_speed_rpm);
  visit.Number("mesh_frequency_Hz", r.mesh_frequency);
  visit.Text("friction", transmission::FrictionLawName(r.friction));
  visit.Text("integrator", IntegratorName(r.integrator));
  VisitTolerances(r.tolerances, visit);
  visit.Text("start", "quasi-static solution at t = 0 (no start-up transient)");
  visit.Number("duration_s", r.duration);
  visit.Integer("outputs", r.outputs);
  visit.Text("status", transmission::RunStatusName(r.status));
  visit.Flag("completed", r.completed());
  visit.Text("failure", r.failure);
  visit.Number("mesh_stiffness_sun_planet_N_per_m", r.mesh_stiffness[0]);
  visit.Number("mesh_stiffness_planet_ring_N_per_m", r.mesh_stiffness[1]);
  const DynamicSummary& s = r.summary;
  if (!s.root_stress.empty()) visit.RootStress("root_stress", s.root_stress, "time_s", 1.0);
  transmission::VisitPlanets(visit, s.lsr_mean, s.lsr_min, s.lsr_max);
  visit.Integer("outputs_written", s.samples);
  visit.Number("K_gamma_max", s.k_gamma);
  visit.Number("transmission_error_min_urad", s.te_min * 1e6);
  visit.Number("transmission_error_max_urad", s.te_max * 1e6);
  visit.Number("transmission_error_peak_to_peak_urad", s.te_peak_to_peak() * 1e6);
  visit.Number("sun_orbit_radius_max_um", s.orbit_radius * 1e6);
  visit.Number("sun_orbit_radius_mean_um", s.orbit_mean_radius * 1e6);
  transmission::VisitFaceWidth(visit, s.face_width);
  transmission::VisitHelicalLoads(visit, s.helical_mean);  // means over the steps written
  const SimulationStats& st = r.stats;
  visit.Integer("steps", st.steps);
  visit.Integer("evaluations", st.rhs_evaluations);
  visit.Integer("fd_jacobian_evaluations", st.fd_rhs_evaluations);
  visit.Integer("jacobians", st.jacobian_evaluations);
  visit.Integer("failed_contact_solves", st.failed_solves);
  visit.Integer("error_test_failures", st.error_test_failures);
  visit.Integer("nonlinear_failures", st.nonlinear_failures);
  visit.Integer("failed_geometry", st.failed_geometry);
  visit.Number("wall_seconds", st.wall_seconds);
  visit.Number("evaluation_seconds", st.rhs_seconds);
  if (r.rating) visit.Rating("rating", *r.rating);
  visit.Texts("warnings", r.warnings);
  visit.Number("setup_seconds", r.setup_seconds);
}

}  // namespace epicycle::dynamics
