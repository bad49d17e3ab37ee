// One mesh-stiffness run: the request resolved, the pair and its tables built once, the samples
// streamed, the record (stiffness_run.hpp; docs/model.md §4).
#include "epicycle/transmission/stiffness_run.hpp"

#include <stdexcept>

#include "epicycle/geometry/helical.hpp"
#include "epicycle/geometry/plane.hpp"

#include "epicycle/transmission/helical_scene.hpp"
#include "epicycle/transmission/run_arguments.hpp"
#include "epicycle/transmission/validity.hpp"

namespace epicycle::transmission {

namespace {

// The mesh-stiffness statistics of a run (the record's and its healthy twin's fields).
void VisitResult(const MeshStiffnessResult& r, RecordVisitor& visit) {
  visit.Text("mesh", r.mesh);
  visit.Number("torque_gear1_Nm", r.torque);
  visit.Number("face_width_mm", r.face_width * 1e3);
  visit.Integer("positions", static_cast<long>(r.samples.size()));
  visit.Integer("failed_positions", r.failed);
  visit.Number("mean_mesh_stiffness_N_per_m", r.mean_stiffness);
  visit.Number("mean_mesh_stiffness_N_per_mm_um", r.mean_per_width());
  visit.Number("peak_single_pair_stiffness_N_per_m", r.peak_pair_stiffness);
  visit.Number("peak_single_pair_stiffness_N_per_mm_um", r.peak_pair_per_width());
  visit.Number("min_mesh_stiffness_N_per_m", r.min_stiffness);
  visit.Number("max_mesh_stiffness_N_per_m", r.max_stiffness);
  if (!r.root_stress.empty())
    visit.RootStress("root_stress", r.root_stress, "angle_deg", geometry::Deg(1.0));
  if (r.slices > 1) {
    visit.Integer("slices", r.slices);
    visit.Number("K_Hbeta_max", r.k_h_beta_max);
    visit.Number("K_Hbeta_mean", r.k_h_beta_mean);
    visit.Number("angle_at_K_Hbeta_max_deg", geometry::Deg(r.k_h_beta_angle));
    visit.Number("largest_load_z_mm", r.largest_z * 1e3);
  }
  if (r.helical)
    visit.Number("peak_slice_pair_stiffness_N_per_mm_um", r.peak_slice_pair_per_width());
}

// The pair's own comparison values, in the record and in its healthy twin.
void VisitReferences(const StiffnessRecord& r, RecordVisitor& visit) {
  visit.Number("contact_ratio", r.contact_ratio);
  visit.Number("iso6336_c_prime_N_per_mm_um", r.iso6336_c_prime);
  visit.Number("iso6336_c_gamma_alpha_N_per_mm_um", r.iso6336_c_gamma_alpha);
  if (r.helix_angle > 0) {
    visit.Number("helix_angle_deg", geometry::Deg(r.helix_angle));
    visit.Number("overlap_ratio", r.overlap_ratio);
  }
}

// A spur stage's mesh in the stage's slices (docs/face_width.md, "One mesh of a sliced stage"):
// its coupling and the leads of its two gears (`gears`: the stage's names of gear 1 and gear 2),
// renamed "gear1" and "gear2". The pair is held on fixed axes: what tilts the planet in the stage
// (its pin's tilt, the pins' bending, the carrier's wind-up) has no place in it and is refused.
void SpurStageMeshSlices(const FaceWidthSpec& stage, const std::string& mesh, int planet,
                         geometry::MeshKind kind, const std::vector<std::string>& gears,
                         FaceWidthSpec* out) {
  const std::string rule =
      ": the mesh-stiffness driver holds the mesh's two gears on fixed axes and takes the "
      "stage's slices and the two gears' leads only; `epicycle quasistatic` computes the "
      "stage's load across the face with it";
  for (const PinTilt& t : stage.pin_tilts)
    if (t.planet == planet)
      throw std::invalid_argument("--mesh = '" + mesh + "': " + t.where + " tilts planet " +
                                  std::to_string(planet + 1) + "'s pin" + rule);
  if (!stage.pins.empty())
    throw std::invalid_argument("--mesh = '" + mesh + "': " + stage.pins[0].where +
                                " makes the planets tilt on their pins under load" + rule);
  if (stage.carrier_torsional_stiffness > 0)
    throw std::invalid_argument("--mesh = '" + mesh + "': " + stage.carrier_where + " = " +
                                std::to_string(stage.carrier_torsional_stiffness) +
                                " N m/rad winds the carrier up under torque" + rule);
  out->slices = stage.slices;
  out->coupling = stage.coupling;
  out->coupling_length = stage.coupling_length;
  // The mesh kind's structural kernel (coupling = "table").
  out->coupling_table = kind == geometry::MeshKind::kPlanetRing ? stage.coupling_table_planet_ring
                                                                : stage.coupling_table;
  for (const LeadSpec& l : stage.leads)
    for (std::size_t g = 0; g < gears.size(); ++g)
      if (l.gear == gears[g]) {
        out->leads.push_back(l);
        out->leads.back().gear = g == 0 ? "gear1" : "gear2";
      }
}

// MakeMeshPair with a spur stage's slices: the mesh-stiffness driver's pair (the quasi-static
// rating's c_γα keeps MakeMeshPair's plane pair).
MeshPairSetup MakeSlicedMeshPair(const Scene& scene, const geometry::Stage* stage,
                                 const std::string& mesh) {
  MeshPairSetup s = MakeMeshPair(scene, stage, mesh);
  if (scene.kind != SceneKind::kStage || !scene.face_width.active() ||
      s.spec.gear1.helix.helical())
    return s;
  for (const geometry::MeshSummary& m : stage->meshes())
    if (m.name == s.mesh)
      SpurStageMeshSlices(scene.face_width, s.mesh, m.planet, m.kind, s.gears, &s.face_width);
  return s;
}

}  // namespace

StiffnessRecord RunStiffness(const StiffnessRequest& request, StiffnessSink& sink) {
  CheckArgument(request.positions_option, request.positions, kStiffnessPositions);
  CheckArgument(request.threads_option, request.threads, kThreadsOrZero);
  Scene scene = request.scene;
  scene.model.stresses = scene.model.stresses || request.stresses;
  // A helical pair is resolved in slices of the face width (helical_slices.hpp).
  RequireHelicalSlices(scene, "`epicycle stiffness`");
  FeComplianceOptions tables = request.tables;
  tables.helical_slices = IsHelical(scene);
  std::optional<geometry::Stage> stage;
  if (scene.kind == SceneKind::kStage) {
    stage.emplace(MakeStage(scene));
    if (request.mesh.empty()) {
      std::string names;
      for (const auto& m : stage->meshes()) names += (names.empty() ? "" : ", ") + m.name;
      throw std::invalid_argument(request.mesh_option +
                                  " is required for a stage scene; its meshes are " + names);
    }
  }
  const MeshPairSetup setup = MakeSlicedMeshPair(scene, stage ? &*stage : nullptr, request.mesh);
  const geometry::GearPair pair = MakePair(scene, setup.spec);
  const auto [first, cycles] =
      request.cycle >= 0 ? std::array<int, 2>{request.cycle, 1} : DamagedToothCycles(setup, pair);
  MeshStiffnessOptions opt;
  opt.positions = request.positions * cycles;
  opt.first_cycle = first;
  opt.cycles = cycles;
  opt.threads = request.threads;
  opt.backend = solvers::BackendFromName(request.backend);
  opt.local_terms = request.local_terms;
  opt.tooth_coupling = request.tooth_coupling;
  opt.Validate();

  StiffnessPlan plan;
  plan.scene = &scene;
  plan.setup = &setup;
  plan.pair = &pair;
  plan.positions_per_cycle = request.positions;
  plan.first_cycle = first;
  plan.cycles = cycles;
  plan.face_width = geometry::ContactFaceWidth(pair.gear1(), pair.gear2());
  sink.Pair(plan);
  const FePairCompliance compliance(scene, pair, tables, setup.gears);
  plan.compliance = &compliance;
  sink.Start(plan);

  StiffnessRecord record;
  record.result = ComputeMeshStiffness(setup, pair, compliance, opt,
                                       [&](const MeshSample& s) { sink.Sample(s); });
  record.scene = scene.name;
  record.plane = scene.model.plane == solvers::PlaneAssumption::kPlaneStrain ? "strain" : "stress";
  record.local_terms = request.local_terms;
  const compliance::iso6336::PairData iso = IsoPairData(pair);
  record.iso6336_c_prime = compliance::iso6336::SinglePairStiffness(iso);
  record.iso6336_c_gamma_alpha = compliance::iso6336::MeshStiffness(iso);
  record.contact_ratio = pair.summary().contact_ratio_iso;
  if (pair.gear1().spec().helix.helical()) {
    record.helix_angle = pair.gear1().spec().helix.angle;
    record.overlap_ratio = geometry::OverlapRatio(plan.face_width, record.helix_angle,
                                                  geometry::NormalModule(pair.gear1()));
  }
  record.join_depth = {compliance.JoiningDepth(0), compliance.JoiningDepth(1)};
  // The scene's warnings and those only the results show (docs/scenes.md, "Ranges and validity").
  record.warnings = scene.warnings;
  for (const std::string& w : MeshStiffnessWarnings(pair, record.result))
    record.warnings.push_back(w);
  if (request.healthy && (first != 0 || cycles != 1))
    record.healthy = ComputeHealthyMeshStiffness(scene, setup, pair, tables, opt);
  return record;
}

void VisitRecord(const StiffnessRecord& r, RecordVisitor& visit) {
  VisitResult(r.result, visit);
  VisitReferences(r, visit);
  visit.Texts("warnings", r.warnings);
  visit.Text("scene", r.scene);
  visit.Flag("local_terms", r.local_terms);
  visit.Text("plane", r.plane);
  visit.Numbers("join_depth_mm", {r.join_depth[0] * 1e3, r.join_depth[1] * 1e3});
  if (r.healthy) {
    visit.BeginObject("healthy");
    VisitResult(*r.healthy, visit);
    VisitReferences(r, visit);
    visit.EndObject();
  }
}

}  // namespace epicycle::transmission
