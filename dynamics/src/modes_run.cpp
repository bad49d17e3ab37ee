// The natural modes of a stage about its operating point as a run and a record (modes_run.hpp;
// docs/dynamic.md "Natural modes").
#include "epicycle/dynamics/modes_run.hpp"

#include <stdexcept>

#include <fmt/format.h>

#include "epicycle/dynamics/run_span.hpp"
#include "epicycle/io/units.hpp"
#include "epicycle/transmission/helical_scene.hpp"

namespace epicycle::dynamics {

ModesRecord RunModes(const ModesRequest& request, ModesSink& sink) {
  if (request.speed_range_rpm && !((*request.speed_range_rpm)[0] <= (*request.speed_range_rpm)[1]))
    throw std::invalid_argument(
        fmt::format("{} = {} {}: LO must not exceed HI", request.speed_range_option,
                    (*request.speed_range_rpm)[0], (*request.speed_range_rpm)[1]));
  std::shared_ptr<const StageDynamics> rig = request.rig;
  if (!rig) {
    transmission::Scene scene = request.scene;
    if (scene.kind != transmission::SceneKind::kStage)
      throw std::invalid_argument(scene.name + ": a gear-pair scene; modes need a stage");
    if (request.sun) scene.supports.sun = *request.sun;
    // A helical stage in slices: the tangent stiffness of its sliced meshes (docs/model.md §10).
    transmission::RequireHelicalSlices(scene, "`epicycle modes`");
    transmission::FeComplianceOptions tables = request.tables;
    tables.helical_slices = true;
    rig = std::make_shared<const StageDynamics>(std::move(scene), tables);
  }
  sink.Start({rig.get()});
  // The linearisation's mesh stiffness is the tangent dF/dδ about the operating point (the
  // speed sweep's peaks sit at its coincidences; the secant F/δ, which sets the mesh damping, is
  // softer by the local term's curvature and puts them ~3.5 % low on the paper stage).
  const OperatingPointModes operating = StageModes(*rig);
  const DynamicModel& model = rig->model;
  ModesRecord record;
  record.scene = rig->scene.name;
  record.mesh_stiffness = operating.mesh_stiffness;
  record.secant_mesh_stiffness = {model.sun_mesh_stiffness(), model.ring_mesh_stiffness()};
  record.sliced_meshes = rig->stage_model.helical();
  // Mesh frequency per sun rpm: f_m = z_r ω_c/2π with ω_c = ω_s z_s/(z_s + z_r).
  record.mesh_hz_per_sun_rpm = MeshHzPerSunRpm(rig->stage);
  record.modes = operating.modes;
  // Every mesh harmonic that meets a mode within the speeds asked (default: the scene's speed
  // / 2 .. x 2), marked by the planet-phasing rule.
  const double rpm = io::RadPerSecondToRpm(model.settings().sun_speed);
  record.coincidence_range_rpm =
      request.speed_range_rpm ? *request.speed_range_rpm : std::array<double, 2>{rpm / 2, rpm * 2};
  record.coincidences = FindCoincidences(model, record.modes, record.coincidence_range_rpm[0],
                                         record.coincidence_range_rpm[1]);
  record.warnings = rig->scene.warnings;
  return record;
}

void VisitRecord(const ModesRecord& r, transmission::RecordVisitor& visit) {
  visit.Text("scene", r.scene);
  visit.Number("mesh_stiffness_sun_planet_N_per_m", r.mesh_stiffness[0]);
  visit.Number("mesh_stiffness_planet_ring_N_per_m", r.mesh_stiffness[1]);
  visit.Text("mesh_stiffness_kind", "tangent dF/ddelta, mean over a mesh cycle");
  visit.Number("secant_mesh_stiffness_sun_planet_N_per_m", r.secant_mesh_stiffness[0]);
  visit.Number("secant_mesh_stiffness_planet_ring_N_per_m", r.secant_mesh_stiffness[1]);
  if (r.sliced_meshes)  // a helical stage (docs/model.md §10)
    visit.Text("mesh_stiffness_source",
               "the stage's quasi-static solutions over a mesh cycle, its meshes in slices");
  visit.Number("mesh_frequency_Hz_per_sun_rpm", r.mesh_hz_per_sun_rpm);
  visit.BeginList("modes");
  for (const Mode& x : r.modes) {
    visit.Item();
    visit.Number("frequency_Hz", x.frequency);
    visit.Integer("multiplicity", x.multiplicity);
    visit.Text("type", x.rigid ? std::string("rigid") : ModeTypeName(x.type));
    visit.Number("central_translation_energy", x.central_translation);
    visit.Number("central_rotation_energy", x.central_rotation);
    visit.Number("planet_energy", x.planets);
    visit.Numbers("sun_rpm_at_mesh_harmonics_1_2_3",
                  HarmonicSunSpeeds(x.frequency, r.mesh_hz_per_sun_rpm, 3));
  }
  visit.EndList();
  visit.Numbers("coincidence_range_rpm", {r.coincidence_range_rpm[0], r.coincidence_range_rpm[1]});
  VisitCoincidences(r.coincidences, visit);
  visit.Texts("warnings", r.warnings);
}

void VisitCoincidences(const std::vector<Coincidence>& coincidences,
                       transmission::RecordVisitor& visit) {
  visit.BeginList("coincidences");
  for (const Coincidence& c : coincidences) {
    visit.Item();
    visit.Number("sun_speed_rpm", c.sun_speed_rpm);
    visit.Number("frequency_Hz", c.frequency);
    visit.Integer("mode", c.mode + 1);
    visit.Integer("harmonic", c.harmonic);
    visit.Flag("phasing_excited", c.phasing_excited);
  }
  visit.EndList();
}

}  // namespace epicycle::dynamics
