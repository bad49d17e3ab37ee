// One branch of periodic orbits: the request resolved, the rig built once, the points streamed,
// the record (branch_run.hpp; docs/periodic.md §3).
#include "epicycle/dynamics/branch_run.hpp"

#include <algorithm>
#include <optional>
#include <stdexcept>
#include <vector>

#include "epicycle/geometry/plane.hpp"
#include "epicycle/transmission/helical_scene.hpp"
#include "epicycle/transmission/scene_keys.hpp"

namespace epicycle::dynamics {

namespace {

// The branch's options from the request and the scene as run, checked before the rig is built.
StageBranchOptions Options(const BranchRequest& r, const transmission::Scene& scene,
                           const SimulationOptions& simulation) {
  if (r.steps < 1)
    throw std::invalid_argument(r.names.steps + " = " + std::to_string(r.steps) +
                                ": must be >= 1 (the largest step is 1/" + r.names.steps +
                                " of the range)");
  if (r.max_points && *r.max_points < 2)
    throw std::invalid_argument(r.names.max_points + " = " + std::to_string(*r.max_points) +
                                ": must be >= 2");
  StageBranchOptions o;
  o.parameter = ResolveBranchParameter(scene, r.parameter, r.names.parameter,
                                       o.max_period_mesh_cycles, &o.period);
  o.start = r.start;
  o.end = r.end;
  o.max_step = std::max(1.0 / r.steps, o.min_step);
  o.initial_step = std::min(o.initial_step, o.max_step);
  if (r.max_points) o.max_points = *r.max_points;
  o.method = r.method;
  if (r.harmonics) {
    if (*r.harmonics < 1 || r.method != PeriodicMethod::kHarmonicBalance)
      throw std::invalid_argument(r.names.harmonics + " = " + std::to_string(*r.harmonics) +
                                  ": must be >= 1, with the harmonic-balance method (hb)");
    o.harmonics = *r.harmonics;
  }
  o.simulation = simulation;
  o.Validate();
  try {
    CheckBranchPeriod(o.period, o.max_period_mesh_cycles);
  } catch (const std::invalid_argument& e) {
    if (r.names.period.empty()) throw;
    throw std::invalid_argument(r.names.period + ": " + e.what());
  }
  return o;
}

}  // namespace

std::string ResolveBranchParameter(const transmission::Scene& scene, const std::string& name,
                                   const std::string& what, long max_period_mesh_cycles,
                                   StagePeriod* period) {
  *period = StagePeriodMeshCycles(scene.stage, scene.damage);
  const std::vector<std::string> names = StagePeriodicSystem::ParameterNames();
  if (std::find(names.begin(), names.end(), name) != names.end()) return name;
  // The three model parameters by their scene key paths.
  const std::vector<std::string> paths = {"dynamics.sun_speed_rpm", "load.sun_torque_Nm",
                                          "dynamics.mesh_damping_ratio"};
  for (std::size_t k = 0; k < paths.size(); ++k)
    if (name == paths[k]) return names[k];
  std::string list;
  for (const std::string& n : names) list += n + ", ";
  list +=
      "errors.pin.planetK.radial_um, errors.pin.planetK.tangential_um (K = 1.." +
      std::to_string(scene.stage.planets) + ")";
  const std::string head = what + " = '" + name + "': ";
  if (const std::optional<StageErrorKey> error = ParseStageErrorKey(name, scene.stage.planets)) {
    if (error->kind != StageErrorKey::Kind::kRunout) return name;
    // A run-out's amplitude: the period is the stage's with that run-out present at any value.
    geometry::StageSpec spec = scene.stage;
    error->Set(&spec, std::max(error->Value(spec), 1.0));
    const StagePeriod with = StagePeriodMeshCycles(spec, scene.damage);
    if (with.mesh_cycles > max_period_mesh_cycles) {
      std::string why;
      for (const std::string& r : with.reasons) why += (why.empty() ? "" : "; ") + r;
      throw std::invalid_argument(
          head + "a run-out turns with its gear: the stage's period with it = " +
          std::to_string(with.mesh_cycles) + " mesh cycles (" + why +
          "): must be <= max_period_mesh_cycles = " + std::to_string(max_period_mesh_cycles) +
          " for a branch (shooting integrates the whole period at every Newton iteration, "
          "docs/periodic.md §4); a branch continues " + list);
    }
    *period = with;
    return name;
  }
  switch (transmission::FindSceneKey(scene, name)) {
    case transmission::SceneKeyKind::kNumber:
      throw std::invalid_argument(
          head + "a number of the scene that a branch cannot continue: the gears, their "
                 "compliance tables, the supports and the model's settings are built from it "
                 "once per run; a branch continues " + list);
    case transmission::SceneKeyKind::kOther:
      throw std::invalid_argument(head + "not a number in the scene " + scene.source +
                                  " (a branch continues a number: " + list + ")");
    case transmission::SceneKeyKind::kAbsent:
      break;
  }
  throw std::invalid_argument(head + "not a key of the scene " + scene.source +
                              " that a branch can continue (" + list +
                              "; a key path as the scene file writes it, an array's entry by "
                              "its gear)");
}

std::string BranchPeriodTooLong(const BranchRequest& request) {
  const transmission::Scene& scene = request.run.scene;
  return BranchPeriodRefusal(StagePeriodMeshCycles(geometry::Stage(scene.stage), scene.damage),
                             StageBranchOptions{}.max_period_mesh_cycles);
}

BranchRecord RunBranch(const BranchRequest& request, BranchSink& sink) {
  transmission::Scene scene = ResolvedScene(request.run);
  // A helical stage in slices (docs/model.md §10): the planar state, the axial and tilting
  // motions held, so the orbit is the spur stage's problem with its sliced meshes.
  transmission::RequireHelicalSlices(scene, "`epicycle dynamic --periodic` (the periodic branch)");
  const StageBranchOptions o = Options(request, scene, ResolvedOptions(request.run));
  transmission::FeComplianceOptions tables = request.run.tables;
  tables.helical_slices = true;
  StageDynamics rig(std::move(scene), tables);
  rig.model.SetStartAngle(geometry::Rad(request.run.start_deg));
  sink.Start({&rig, &o});
  BranchRecord record;
  record.scene = rig.scene.name;
  record.tolerances = TolerancesOf(o.simulation, request.run.backend);
  record.range = {o.start, o.end};
  record.max_step = o.max_step;
  record.warnings = rig.scene.warnings;
  record.branch = ContinueStageBranch(rig.model, o,
                                      [&](const StageBranchRecord& so_far) { sink.Point(so_far); });
  return record;
}

void VisitRecord(const BranchRecord& r, transmission::RecordVisitor& visit) {
  const StageBranchRecord& b = r.branch;
  const char* parameter = b.parameter.c_str();
  const bool speed_column = b.parameter != StagePeriodicSystem::kSunSpeed;
  visit.Text("scene", r.scene);
  visit.Text("parameter", b.parameter);
  visit.Text("unit", b.unit);
  visit.Text("method", PeriodicMethodName(b.method));
  visit.Integer("harmonics", b.harmonics);
  visit.Numbers("range", {r.range[0], r.range[1]});
  visit.Number("max_step", r.max_step);
  VisitTolerances(r.tolerances, visit);
  visit.Integer("period_mesh_cycles", b.period_mesh_cycles);
  visit.Texts("period_reasons", b.period_reasons);
  visit.Text("status", ContinuationStatusName(b.status));
  visit.Text("message", b.message);
  visit.Text("figures_message", b.figures_message);
  visit.BeginList("bifurcations");
  for (const StageBranchBifurcation& f : b.bifurcations) {
    visit.Item();
    visit.Text("kind", BifurcationKindName(f.kind));
    visit.Number(parameter, f.parameter);
    visit.Integer("before_point", f.after_point);
    visit.Number("multiplier_re", f.multiplier.real());
    visit.Number("multiplier_im", f.multiplier.imag());
  }
  visit.EndList();
  visit.BeginList("points");
  for (const StageBranchPoint& p : b.points) {
    visit.Item();
    visit.Integer("index", p.index);
    visit.Number(parameter, p.parameter);
    if (speed_column) visit.Number("sun_speed_rpm", p.sun_speed_rpm);
    visit.Number("period_s", p.period);
    visit.Text("stability", StabilityName(p.stability));
    visit.Number("spectral_radius", p.spectral_radius);
    visit.Number("K_gamma", p.k_gamma);
    visit.Number("te_amplitude_urad", p.te_amplitude * 1e6);
    visit.Number("sun_orbit_radius_um", p.orbit_radius * 1e6);
    transmission::VisitHelicalLoads(visit, p.helical);  // over the period (a helical stage)
  }
  visit.EndList();
  visit.Integer("integrations", b.integrations);
  visit.Integer("plain_integrations", b.plain_integrations);
  visit.Integer("steps", b.steps);
  visit.Integer("stage_rebuilds", b.rebuilds);
  visit.Number("cpu_seconds", b.cpu_seconds);
  visit.Number("wall_seconds", b.wall_seconds);
  visit.Texts("warnings", r.warnings);
}

}  // namespace epicycle::dynamics
