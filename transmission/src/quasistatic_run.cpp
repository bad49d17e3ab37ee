// One quasi-static run: the request resolved, the rig built once, the positions streamed, the
// record (quasistatic_run.hpp; docs/quasistatic.md).
#include "epicycle/transmission/quasistatic_run.hpp"
#include "epicycle/transmission/helical_scene.hpp"

#include <chrono>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "epicycle/transmission/mesh_stiffness.hpp"
#include "epicycle/transmission/run_arguments.hpp"
#include "epicycle/transmission/validity.hpp"

namespace epicycle::transmission {

namespace {

double Since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

QuasiStaticRecord RunQuasiStatic(const QuasiStaticRequest& request, QuasiStaticSink& sink) {
  Scene scene = request.scene;
  if (scene.kind != SceneKind::kStage)
    throw std::invalid_argument(scene.name +
                                ": a gear-pair scene; a quasi-static run needs a stage");
  if (request.sun) scene.supports.sun = *request.sun;
  if (!request.pin_feedback) scene.face_width.pins.clear();
  scene.model.stresses = scene.model.stresses || request.stresses || request.rating;
  if (request.rating) CheckRatingInputs(RatingInputsOf(scene), request.rating_option);
  if (request.rig && request.rig->compliance.has_root_stress() != scene.model.stresses)
    throw std::invalid_argument(scene.name + ": the prebuilt rig's tables " +
                                (scene.model.stresses ? "have no" : "have") +
                                " root stresses; the run asks for the opposite");
  std::optional<geometry::Stage> own_stage;  // checked before the tables are built
  if (!request.rig) own_stage.emplace(MakeStage(scene));
  // The stage's own rules (hands, assembly) first, as a prebuilt rig has met them (Python's),
  // then this driver's: every front end reports the same first error of a scene.
  RequireHelicalSlices(scene, "`epicycle quasistatic`");
  // The stage until the rig exists (then the rig's: own_stage moves into it).
  const geometry::Stage& early = request.rig ? request.rig->stage : *own_stage;
  const int n = early.planets();

  // The carrier angles: the list given, or `count` over the range (computed as they are needed).
  const std::vector<double> angles =
      request.angles_deg.empty() ? std::vector<double>{}
                                 : CheckedCarrierAngles(request.angles_option, request.angles_deg);
  const int count = !angles.empty()         ? static_cast<int>(angles.size())
                    : request.positions > 0 ? request.positions
                                            : DefaultPositions(early, request.range);
  const double start = geometry::Rad(request.start_deg);
  const double span = angles.empty() ? CarrierSpan(early, request.range) : 0.0;
  const auto angle = [&](int k) {
    return angles.empty() ? SweepAngle(start, span, k, count) : angles[static_cast<std::size_t>(k)];
  };

  QuasiStaticOptions opt;
  opt.backend = solvers::BackendFromName(request.backend);
  opt.threads = request.threads;
  opt.warm_start = request.warm_start;
  SetRestFriction(scene.dynamics, request.friction, &opt);
  opt.Validate();

  const auto t0 = std::chrono::steady_clock::now();
  const std::shared_ptr<const StageRig> rig =
      request.rig ? request.rig
                  : std::make_shared<const StageRig>(scene, std::move(*own_stage), request.tables);
  const double table_seconds = Since(t0);
  const geometry::Stage& stage = rig->stage;
  const FeStageCompliance& compliance = rig->compliance;
  StageSetup setup = SetupFromScene(scene);
  setup.local_terms = request.local_terms;
  const StageModel model = rig->Model(setup);

  QuasiStaticPlan plan;
  plan.scene = &scene;
  plan.stage = &stage;
  plan.compliance = &compliance;
  plan.options = &opt;
  plan.positions = count;
  plan.first_angle = count > 0 ? angle(0) : 0.0;
  plan.span = span;
  plan.table_seconds = table_seconds;
  plan.friction = opt.friction.law != FrictionLaw::kOff;
  sink.Start(plan);

  QuasiStaticRecord record;
  record.scene = scene.name;
  record.sun = setup.sun;
  record.sun_torque = scene.loads.sun_torque;
  record.backend = request.backend;
  record.local_terms = request.local_terms;
  record.warm_start = request.warm_start;
  if (plan.friction) record.friction = opt.friction.law;
  record.threads = request.threads;
  record.positions = count;
  record.table_seconds = table_seconds;

  SweepAccumulator accumulator(n);
  ValidityTally tally(stage, "position(s)");
  int failed = 0;
  const auto t1 = std::chrono::steady_clock::now();
  SweepEach(model, scene.loads, count, angle, opt, [&](const PositionResult& r, int k) {
    if (!r.converged && ++failed <= kListedFailures)
      record.failures.push_back(
          fmt::format("{:.4f} deg: {}", geometry::Deg(r.carrier_angle), r.message));
    accumulator.Add(r);
    tally.Add(r);
    sink.Position(r, k);
  });
  record.sweep_seconds = Since(t1);
  record.failures_not_listed = std::max(0, failed - kListedFailures);

  record.warnings = scene.warnings;
  for (const std::string& w : tally.Messages()) record.warnings.push_back(w);
  record.summary = accumulator.Result();
  record.converged_positions = record.summary.converged;
  if (request.rating && record.converged_positions > 0) {
    if (record.summary.face_width.empty()) {
      record.rating = RateStage(rig->rating, stage, record.summary);
    } else {
      // Method C's c_γ: the model's own mean mesh stiffness per unit width, of planet 1's meshes
      // on the rig's tables (the run's load).
      const std::array<double, 2> c =
          MeanMeshStiffnessPerWidth(StageMeshPairs(scene, stage, compliance));
      record.rating =
          RateStage(rig->rating, stage, record.summary, 1.0, "quasi-static run", nullptr, &c);
    }
  }
  return record;
}

void VisitPlanets(RecordVisitor& visit, const std::vector<double>& mean,
                  const std::vector<double>& min, const std::vector<double>& max) {
  visit.BeginList("planets");
  for (std::size_t i = 0; i < mean.size(); ++i) {
    visit.Item();
    visit.Integer("planet", static_cast<long>(i + 1));
    visit.Number("lsr_mean", mean[i]);
    visit.Number("lsr_min", min[i]);
    visit.Number("lsr_max", max[i]);
  }
  visit.EndList();
}

void VisitRecord(const SweepSummary& s, RecordVisitor& visit) {
  VisitPlanets(visit, s.lsr_mean, s.lsr_min, s.lsr_max);
  visit.Number("K_gamma_max", s.k_gamma);
  visit.Number("transmission_error_min_urad", s.transmission_error_min * 1e6);
  visit.Number("transmission_error_max_urad", s.transmission_error_max * 1e6);
  visit.Number("sun_displacement_max_um", s.sun_displacement_max * 1e6);
  visit.Stresses(s);
  VisitFaceWidth(visit, s.face_width);
  VisitHelicalLoads(visit, s.helical_mean);  // means over the converged positions
  if (!s.pin_tilts.empty()) {
    // Each planet's tilt on its pin under load (pin.hpp), over the converged positions.
    visit.BeginObject("pins");
    visit.Number("iterations_mean", s.pin_iterations_mean);
    visit.Number("iterations_max", s.pin_iterations_max);
    visit.BeginList("planets");
    for (std::size_t i = 0; i < s.pin_tilts.size(); ++i) {
      const SweepSummary::PinTiltSummary& t = s.pin_tilts[i];
      visit.Item();
      visit.Integer("planet", static_cast<long>(i + 1));
      visit.Number("tilt_radial_mean_urad", t.radial_mean * 1e6);
      visit.Number("tilt_radial_min_urad", t.radial_min * 1e6);
      visit.Number("tilt_radial_max_urad", t.radial_max * 1e6);
      visit.Number("tilt_tangential_mean_urad", t.tangential_mean * 1e6);
      visit.Number("tilt_tangential_min_urad", t.tangential_min * 1e6);
      visit.Number("tilt_tangential_max_urad", t.tangential_max * 1e6);
    }
    visit.EndList();
    visit.EndObject();
  }
  if (s.friction) {
    visit.Number("efficiency_mean", s.efficiency_mean);
    visit.Number("efficiency_min", s.efficiency_min);
    visit.Number("friction_power_mean_W", s.friction_power_mean);
    visit.Number("friction_iterations_mean", s.friction_iterations_mean);
  }
}

void VisitRecord(const QuasiStaticRecord& r, RecordVisitor& visit) {
  VisitRecord(r.summary, visit);  // the statistics, none where no position converged
  visit.Texts("warnings", r.warnings);
  visit.Text("scene", r.scene);
  visit.Text("sun_support", SunSupportName(r.sun));
  visit.Number("sun_torque_Nm", r.sun_torque);
  visit.Text("backend", r.backend);
  visit.Flag("local_terms", r.local_terms);
  visit.Flag("warm_start", r.warm_start);
  if (r.friction) visit.Text("friction", FrictionLawName(*r.friction));
  if (r.rating) visit.Rating("rating", *r.rating);
  visit.Integer("threads", r.threads);  // 0: one per core
  visit.Integer("positions", r.positions);
  visit.Integer("converged_positions", r.converged_positions);
  visit.Texts("failures", r.failures);  // the first kListedFailures
  if (r.failures_not_listed > 0) visit.Integer("failures_not_listed", r.failures_not_listed);
  visit.Number("sweep_seconds", r.sweep_seconds);
  visit.Number("table_seconds", r.table_seconds);
}

}  // namespace epicycle::transmission
