// One branch of periodic orbits: the request resolved, the rig built once, the points streamed,
// the record (branch_run.hpp; docs/periodic.md §3).
#include "epicycle/dynamics/branch_run.hpp"

#include <algorithm>
#include <stdexcept>

#include "epicycle/geometry/plane.hpp"
#include "epicycle/transmission/helical_scene.hpp"

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
  o.parameter = r.parameter;
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
  o.period = StagePeriodMeshCycles(geometry::Stage(scene.stage), scene.damage);
  try {
    CheckBranchPeriod(o.period, o.max_period_mesh_cycles);
  } catch (const std::invalid_argument& e) {
    if (r.names.period.empty()) throw;
    throw std::invalid_argument(r.names.period + ": " + e.what());
  }
  return o;
}

}  // namespace

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
  visit.Number("cpu_seconds", b.cpu_seconds);
  visit.Number("wall_seconds", b.wall_seconds);
  visit.Texts("warnings", r.warnings);
}

}  // namespace epicycle::dynamics
