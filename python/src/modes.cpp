// The modes driver of dynamics/: natural modes about the operating point.
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "common.hpp"
#include "epicycle/dynamics/dynamic_model.hpp"
#include "epicycle/dynamics/modes.hpp"
#include "epicycle/dynamics/modes_run.hpp"
#include "epicycle/dynamics/run_arguments.hpp"
#include "epicycle/dynamics/run_span.hpp"
#include "epicycle/report/record_json.hpp"
#include "epicycle/transmission/dynamic_settings.hpp"
#include "epicycle/transmission/scene.hpp"
#include "integration.hpp"
#include "scene.hpp"

namespace epicycle::python {

namespace {

// The dynamic settings a run used: the one place the bindings read them (from the model the
// library built from the scene).
const transmission::DynamicSettings& SettingsOf(const dynamics::StageDynamics& rig) {
  return rig.model.settings();
}

py::object Modes(const ScenePtr& s, std::optional<std::vector<double>> speed_range_rpm,
                 std::optional<std::string> cache_dir) {
  dynamics::ModesRequest request;
  request.scene = s->scene();
  if (speed_range_rpm) {
    if (speed_range_rpm->size() != 2)
      throw std::invalid_argument("speed_range_rpm: must be two sun speeds LO, HI [rpm]");
    for (const double v : *speed_range_rpm)
      dynamics::CheckArgument(dynamics::ModesArguments::kSpeedRange, v);
    request.speed_range_rpm = {(*speed_range_rpm)[0], (*speed_range_rpm)[1]};
  }
  CancelToken token;
  struct Out {
    std::shared_ptr<const dynamics::StageDynamics> rig;
    dynamics::ModesRecord record;
  };
  const Out out = RunReleased(token, [&] {
    Out o;
    o.rig = s->Dynamics(cache_dir, "modes");  // this scene's, built once
    request.rig = o.rig;
    dynamics::ModesSink none;
    o.record = dynamics::RunModes(request, none);
    return o;
  });
  const dynamics::StageDynamics& rig = *out.rig;
  const double hz_per_rpm = out.record.mesh_hz_per_sun_rpm;
  const auto& modes = out.record.modes;
  const auto count = static_cast<py::ssize_t>(modes.size());
  std::vector<double> freq, ct, cr, pl, rpm;
  std::vector<int> mult;
  std::vector<char> rigid;
  py::list type, shapes, members;
  for (const dynamics::MemberDofs& md : rig.model.ModeLayout()) members.append(md.name);
  std::vector<double> member_energy;
  for (const dynamics::Mode& x : modes) {
    freq.push_back(x.frequency);
    mult.push_back(x.multiplicity);
    rigid.push_back(x.rigid);
    type.append(x.rigid ? std::string("rigid") : dynamics::ModeTypeName(x.type));
    ct.push_back(x.central_translation);
    cr.push_back(x.central_rotation);
    pl.push_back(x.planets);
    for (double e : x.member_energy) member_energy.push_back(e);
    std::vector<double> h = dynamics::HarmonicSunSpeeds(x.frequency, hz_per_rpm, 3);
    h.resize(3, kNaN);
    rpm.insert(rpm.end(), h.begin(), h.end());
    shapes.append(py::array_t<double>(
        {x.shapes.rows(), x.shapes.cols()},
        {sizeof(double), sizeof(double) * static_cast<std::size_t>(x.shapes.rows())},
        x.shapes.data()));
  }
  py::list dofs;
  for (const dynamics::MotionDof& d : rig.model.dofs()) dofs.append(d.Label());
  const auto members_count = static_cast<py::ssize_t>(members.size());
  py::dict f;
  f["scene"] = rig.scene.name;
  f["sun_support"] = transmission::SunSupportName(rig.stage_model.setup().sun);
  f["ring_elastic"] = SettingsOf(rig).ring_elastic;
  f["dofs"] = dofs;
  f["members"] = members;
  f["frequency_Hz"] = Array(std::move(freq));
  f["multiplicity"] = Array(std::move(mult));
  f["type"] = type;
  f["rigid"] = BoolArray(rigid);
  f["central_translation_energy"] = Array(std::move(ct));
  f["central_rotation_energy"] = Array(std::move(cr));
  f["planet_energy"] = Array(std::move(pl));
  f["member_energy"] = Array2(std::move(member_energy), count, members_count);
  f["shapes"] = shapes;
  f["sun_rpm_at_mesh_harmonics_1_2_3"] = Array2(std::move(rpm), count, 3);
  f["mesh_hz_per_sun_rpm"] = hz_per_rpm;
  f["mesh_stiffness_sun_planet_N_per_m"] = out.record.mesh_stiffness[0];
  f["mesh_stiffness_planet_ring_N_per_m"] = out.record.mesh_stiffness[1];
  f["secant_mesh_stiffness_sun_planet_N_per_m"] = out.record.secant_mesh_stiffness[0];
  f["secant_mesh_stiffness_planet_ring_N_per_m"] = out.record.secant_mesh_stiffness[1];
  f["warnings"] = out.record.warnings;
  // The program's JSON (`epicycle modes --json`), its one serialisation, without provenance.
  f["record"] = JsonToPython(report::RecordJson(out.record));
  return Result(f);
}

}  // namespace

// The natural modes.
void BindModes(py::module_& m) {
  m.def("modes", &Modes, py::arg("scene"), py::kw_only(), py::arg("speed_range_rpm") = py::none(),
        py::arg("cache_dir") = py::none(), R"doc(
Natural modes of a stage linearised about its operating point (`epicycle modes`; docs/dynamic.md):
the tangent mesh stiffness dF/dδ at the scene's load, carrier angle 0.

Parameters
----------
scene : Scene
    A stage scene.
speed_range_rpm : [float, float] or None, default None
    Sun speeds LO, HI [rpm] for the mesh-harmonic coincidences (None: the scene's speed / 2 .. x 2).
cache_dir : str or None, default None
    Influence-table cache (as quasistatic's).

Returns
-------
Result
    Per mode group (M groups): frequency_Hz [Hz], multiplicity [-], type ("rigid", "rotational",
    "translational", "planet", "other"), rigid (bool), central_translation_energy,
    central_rotation_energy, planet_energy [-] (kinetic-energy fractions), member_energy
    (M, members) [-], shapes (list of (dofs, multiplicity) arrays, M-orthonormal; units of dofs:
    [m] or [rad]), sun_rpm_at_mesh_harmonics_1_2_3 (M, 3) [rpm] (NaN: none); dofs, members
    (names); mesh_hz_per_sun_rpm [Hz/rpm]; mesh_stiffness_*_N_per_m (tangent, used) and
    secant_mesh_stiffness_*_N_per_m [N/m]; ring_elastic, sun_support, warnings; record: the
    run's record, the keys and values of `epicycle modes --json` (docs/records.md).

Raises
------
ValueError
    A gear-pair scene, or a bad scene value.)doc");
}

}  // namespace epicycle::python
