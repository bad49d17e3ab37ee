// The dynamic driver of dynamics/: a run in time.
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <thread>

#include "common.hpp"
#include "epicycle/dynamics/branch_run.hpp"
#include "epicycle/dynamics/dynamic_factor.hpp"
#include "epicycle/dynamics/dynamic_run.hpp"
#include "epicycle/dynamics/dynamic_summary.hpp"
#include "epicycle/dynamics/load_sharing_parts.hpp"
#include "epicycle/dynamics/modes.hpp"
#include "epicycle/dynamics/modes_run.hpp"
#include "epicycle/dynamics/run_arguments.hpp"
#include "epicycle/dynamics/run_span.hpp"
#include "epicycle/dynamics/simulation.hpp"
#include "epicycle/dynamics/speed_sweep.hpp"
#include "epicycle/dynamics/speed_sweep_run.hpp"
#include "epicycle/dynamics/vibration.hpp"
#include "epicycle/io/units.hpp"
#include "epicycle/report/face_width_files.hpp"
#include "epicycle/report/ratings.hpp"
#include "epicycle/report/record_json.hpp"
#include "epicycle/report/run_files.hpp"
#include "epicycle/report/speed_sweep_run_files.hpp"
#include "epicycle/transmission/rating.hpp"
#include "epicycle/transmission/run_range.hpp"
#include "epicycle/transmission/stage_problem.hpp"
#include "face_loads.hpp"
#include "integration.hpp"
#include "scene.hpp"

namespace epicycle::python {

namespace {

py::object StatsObject(const dynamics::SimulationStats& st) {
  py::dict f;
  f["steps"] = st.steps;
  f["rhs_evaluations"] = st.rhs_evaluations;
  f["jacobian_evaluations"] = st.jacobian_evaluations;
  f["fd_rhs_evaluations"] = st.fd_rhs_evaluations;
  f["failed_solves"] = st.failed_solves;
  f["failed_geometry"] = st.failed_geometry;
  f["error_test_failures"] = st.error_test_failures;
  f["nonlinear_failures"] = st.nonlinear_failures;
  f["restarts"] = st.restarts;
  f["rhs_s"] = st.rhs_seconds;
  f["jacobian_s"] = st.jacobian_seconds;
  f["wall_s"] = st.wall_seconds;
  f["rate_scale_per_s"] = st.rate_scale;
  return Result(f);
}

// A run's summary (dynamics::DynamicSummary) as Python values in the names' units.
py::dict SummaryObject(const dynamics::DynamicSummary& sum) {
  py::dict summary;
  summary["samples"] = sum.samples;
  summary["lsr_mean"] = Array(std::vector<double>(sum.lsr_mean));
  summary["lsr_min"] = Array(std::vector<double>(sum.lsr_min));
  summary["lsr_max"] = Array(std::vector<double>(sum.lsr_max));
  summary["k_gamma"] = sum.k_gamma;
  summary["te_min_urad"] = sum.te_min * 1e6;
  summary["te_max_urad"] = sum.te_max * 1e6;
  summary["te_peak_to_peak_urad"] = sum.te_peak_to_peak() * 1e6;
  summary["orbit_radius_max_um"] = sum.orbit_radius * 1e6;
  summary["orbit_radius_mean_um"] = sum.orbit_mean_radius * 1e6;
  summary["max_pair_force_N"] = sum.max_pair_force;
  // Stresses on: the summary JSON's root_stress (report/), as Python objects.
  if (!sum.root_stress.empty())
    summary["root_stress"] = JsonToPython(report::RootStressJson(sum.root_stress, "time_s", 1.0));
  return summary;
}

// A helical stage's per-step axial loads (the steps file's axial-load columns, docs/model.md §10)
// into `f`: NaN where a step has no value for a planet.
void AddHelicalSteps(const std::vector<dynamics::DynamicSample>& samples, int n, py::dict* f) {
  const auto count = static_cast<py::ssize_t>(samples.size());
  std::vector<double> sun_axial, ring_axial, carrier_axial, mesh_axial, radial, tangential;
  for (const dynamics::DynamicSample& x : samples) {
    sun_axial.push_back(x.helical.sun_axial_force);
    ring_axial.push_back(x.helical.ring_axial_force);
    carrier_axial.push_back(x.helical.carrier_axial_force);
    for (int i = 0; i < n; ++i) {
      const bool has = static_cast<int>(x.helical.planets.size()) > i;
      const auto k = static_cast<std::size_t>(i);
      mesh_axial.push_back(has ? x.helical.planets[k].sun_mesh_axial : kNaN);
      radial.push_back(has ? x.helical.planets[k].moment_radial : kNaN);
      tangential.push_back(has ? x.helical.planets[k].moment_tangential : kNaN);
    }
  }
  const auto width = static_cast<py::ssize_t>(n);
  (*f)["sun_axial_force_N"] = Array(std::move(sun_axial));
  (*f)["ring_axial_force_N"] = Array(std::move(ring_axial));
  (*f)["carrier_axial_force_N"] = Array(std::move(carrier_axial));
  (*f)["sun_mesh_axial_force_N"] = Array2(std::move(mesh_axial), count, width);
  (*f)["tilting_moment_radial_Nm"] = Array2(std::move(radial), count, width);
  (*f)["tilting_moment_tangential_Nm"] = Array2(std::move(tangential), count, width);
}

// Python's sink of a dynamic run: every output step kept (Python returns them as arrays), its
// vibration values computed while the run's model exists, and what the arrays need of the rig.
class KeepSteps final : public dynamics::DynamicSink {
 public:
  explicit KeepSteps(const Progress& report) : report_(report) {}
  void Start(const dynamics::DynamicPlan& p) override {
    model_ = &p.rig->model;
    planets = p.rig->stage.planets();
    bodies = p.rig->compliance.has_root_stress() ? transmission::PlanetBody(planets) : 0;
    channels = dynamics::VibrationChannels(p.rig->model);
    damping = {p.rig->model.sun_mesh_damping(), p.rig->model.ring_mesh_damping()};
    if (p.rig->scene.face_width.active()) face_meshes = report::StageFaceMeshes(p.rig->stage).names;
    helical = p.rig->stage_model.helical();
    total_ = p.span->outputs;
  }
  void Step(const dynamics::DynamicSample& x) override {
    samples.push_back(x);
    vibration.emplace_back();
    dynamics::VibrationValues(*model_, x, &vibration.back());
    report_(static_cast<long>(samples.size()), total_);
  }
  void Stop() override { model_ = nullptr; }

  std::vector<dynamics::DynamicSample> samples;
  std::vector<std::vector<double>> vibration;  // per step, per channel
  std::vector<dynamics::VibrationChannel> channels;
  std::array<double, 2> damping{};  // the mesh damping [N s/m]
  int planets = 0, bodies = 0;
  std::vector<std::string> face_meshes;  // with slices of the face width: the steps CSV's meshes
  bool helical = false;                  // a helical stage: the steps CSV's axial-load columns

 private:
  const Progress& report_;
  const dynamics::DynamicModel* model_ = nullptr;
  long total_ = 0;
};

py::object Dynamic(const ScenePtr& scene, std::optional<double> sun_speed_rpm,
                   const std::string& range, double time_s, std::optional<int> outputs_per_cycle,
                   double start_deg, const Integration& integration,
                   std::optional<std::string> cache_dir, py::object progress, bool raise_on_failure,
                   bool stresses, bool rating, std::optional<long> max_steps,
                   std::optional<double> time_limit_s) {
  dynamics::DynamicRequest request;
  request.scene = scene->scene();
  request.names.speed = "dynamics.sun_speed_rpm";  // the scene key it sets
  request.names.rating = "rating=True";
  request.sun_speed_rpm = sun_speed_rpm;
  request.range = transmission::RunRangeFromName(range);
  if (time_s != 0) request.time_s = time_s;  // 0: the range
  // None: the library's default; a number given is checked as given (0 is not the default).
  if (outputs_per_cycle)
    dynamics::CheckArgument(dynamics::DynamicArguments::kOutputsPerCycle, *outputs_per_cycle);
  request.outputs_per_cycle = outputs_per_cycle.value_or(0);
  request.start_deg = start_deg;
  integration.Apply(&request);
  request.max_steps = max_steps;
  request.time_limit_s = time_limit_s;
  request.stresses = stresses;
  request.rating = rating;
  request.tables = TableOptions(cache_dir);
  if (request.scene.kind != transmission::SceneKind::kStage) RequireStage(request.scene, "dynamic");
  dynamics::ResolvedOptions(request);  // bad input as ValueError before the worker starts
  CancelToken token;
  const Progress report(std::move(progress), &token);
  KeepSteps sink(report);
  struct Out {
    dynamics::DynamicRecord record;
  };
  const Out out = RunReleased(token, [&] { return Out{dynamics::RunDynamic(request, sink)}; });
  const dynamics::DynamicRecord& record = out.record;

  const int n = sink.planets;
  const auto& samples = sink.samples;
  const auto count = static_cast<py::ssize_t>(samples.size());
  // Stresses: per step each gear's largest tension and compression [MPa] (NaN for a failed
  // step), the columns sigma_t_<gear>_MPa, sigma_c_<gear>_MPa of the program's steps file.
  const int bodies = sink.bodies;
  std::vector<std::vector<double>> sigma(2 * static_cast<std::size_t>(bodies));
  std::vector<double> time, deg, balance, w_ext, w_diss, kin, elastic, compliance_work,
      friction_power, sun_bearing, planet_bearing;
  std::vector<int> contacts, active;
  RunColumns run;
  PairColumns p;
  std::vector<double> p_total, p_elastic, p_friction, p_rate;
  // The vibration output (dynamics/vibration.hpp), one array per channel.
  const std::vector<dynamics::VibrationChannel>& channels = sink.channels;
  std::vector<std::vector<double>> vibration(channels.size());
  for (std::size_t step = 0; step < samples.size(); ++step) {
    const dynamics::DynamicSample& x = samples[step];
    for (std::size_t c = 0; c < channels.size(); ++c)
      vibration[c].push_back(sink.vibration[step][c]);
    const dynamics::Evaluation& e = x.evaluation;
    for (int b = 0; b < bodies; ++b) {
      const bool has = std::ssize(x.root_stress) > b;
      const auto k = static_cast<std::size_t>(b);
      sigma[2 * k].push_back(has ? x.root_stress[k].tension / 1e6 : kNaN);
      sigma[2 * k + 1].push_back(has ? x.root_stress[k].compression / 1e6 : kNaN);
    }
    time.push_back(x.time);
    deg.push_back(geometry::Deg(x.carrier_angle));
    std::vector<double> factors;
    for (double v : x.load_sharing) factors.push_back(static_cast<double>(n) * v);
    run.Add(x.load_sharing, factors, x.k_gamma, x.transmission_error, x.sun_centre.x(),
            x.sun_centre.y());
    balance.push_back(x.sun_torque_balance);
    w_ext.push_back(x.external_work);
    w_diss.push_back(x.dissipated_work);
    kin.push_back(e.kinetic_energy);
    elastic.push_back(e.elastic_energy);
    compliance_work.push_back(x.compliance_work);
    friction_power.push_back(e.friction_power);
    int a = 0;
    for (int j = 0; j < e.total_force.size(); ++j) a += e.total_force(j) > 0;
    contacts.push_back(e.terms.size());
    active.push_back(a);
    sun_bearing.push_back(e.sun_bearing_force.x());
    sun_bearing.push_back(e.sun_bearing_force.y());
    for (int i = 0; i < n; ++i) {
      const bool has = static_cast<int>(e.planet_bearing_force.size()) > i;
      planet_bearing.push_back(has ? e.planet_bearing_force[static_cast<std::size_t>(i)].x()
                                   : kNaN);
      planet_bearing.push_back(has ? e.planet_bearing_force[static_cast<std::size_t>(i)].y()
                                   : kNaN);
    }
    for (int j = 0; j < e.terms.size(); ++j) {
      if (!(e.total_force(j) > 0)) continue;
      const transmission::StageContact& c = e.terms.contacts[static_cast<std::size_t>(j)];
      p.Add(x.time, c);
      p_total.push_back(e.total_force(j));
      p_elastic.push_back(e.force(j));
      p_friction.push_back(e.friction(j));
      p_rate.push_back(e.overlap_rate(j) * 1e3);
    }
  }
  py::dict pairs;
  p.Fill(pairs, "time_s");
  pairs["normal_force_N"] = Array(std::move(p_total));
  pairs["elastic_force_N"] = Array(std::move(p_elastic));
  pairs["friction_force_N"] = Array(std::move(p_friction));
  pairs["overlap_rate_mm_per_s"] = Array(std::move(p_rate));
  py::dict vib;
  py::list kinds;
  for (std::size_t c = 0; c < channels.size(); ++c) {
    // The unit as a name's suffix: rad, N, Nm, m_per_s2, m.
    std::string unit = channels[c].unit;
    if (unit == "N m") unit = "Nm";
    if (unit == "m/s2") unit = "m_per_s2";
    const std::string key = channels[c].name + "_" + unit;
    vib[key.c_str()] = Array(std::move(vibration[c]));
    kinds.append(py::make_tuple(key, dynamics::SignalKindName(channels[c].kind)));
  }
  vib["channels"] = kinds;

  py::dict f;
  f["scene"] = record.scene;
  f["sun_support"] = transmission::SunSupportName(record.sun);
  f["sun_torque_Nm"] = record.sun_torque;
  f["sun_speed_rpm"] = record.sun_speed_rpm;
  f["mesh_frequency_Hz"] = record.mesh_frequency;
  f["duration_s"] = record.duration;
  f["outputs"] = record.outputs;
  f["friction"] = transmission::FrictionLawName(record.friction);
  f["mesh_stiffness_sun_planet_N_per_m"] = record.mesh_stiffness[0];
  f["mesh_stiffness_planet_ring_N_per_m"] = record.mesh_stiffness[1];
  f["mesh_damping_sun_planet_Ns_per_m"] = sink.damping[0];
  f["mesh_damping_planet_ring_Ns_per_m"] = sink.damping[1];
  f["planets"] = n;
  f["time_s"] = Array(std::move(time));
  f["carrier_deg"] = Array(std::move(deg));
  run.Fill(f, n);
  f["sun_torque_balance_Nm"] = Array(std::move(balance));
  f["external_work_J"] = Array(std::move(w_ext));
  f["dissipated_work_J"] = Array(std::move(w_diss));
  f["kinetic_energy_J"] = Array(std::move(kin));
  f["elastic_energy_J"] = Array(std::move(elastic));
  f["compliance_work_J"] = Array(std::move(compliance_work));
  f["contacts"] = Array(std::move(contacts));
  f["active_contacts"] = Array(std::move(active));
  f["friction_power_W"] = Array(std::move(friction_power));
  f["sun_bearing_force_N"] = Array2(std::move(sun_bearing), count, 2);
  f["planet_bearing_force_N"] = py::array_t<double>(
      {count, static_cast<py::ssize_t>(n), py::ssize_t{2}}, planet_bearing.data());
  f["pairs"] = Result(pairs);
  if (!sink.face_meshes.empty()) {
    // Per step and mesh (the steps file's K_Hbeta_<mesh>, largest_z_mm_<mesh>): NaN where the
    // step carries no face loads.
    std::vector<const std::vector<transmission::MeshFaceLoad>*> rows;
    for (const dynamics::DynamicSample& x : samples) rows.push_back(&x.face_loads);
    AddFaceLoads(sink.face_meshes, 0, false, rows, &f);
  }
  if (sink.helical) AddHelicalSteps(samples, n, &f);
  f["vibration"] = Result(vib);
  f["summary"] = Result(SummaryObject(record.summary));
  f["stats"] = StatsObject(record.stats);
  f["status"] = transmission::RunStatusName(record.status);
  f["completed"] = record.completed();
  f["message"] = record.failure;
  if (bodies > 0) {
    py::dict root;
    const std::vector<std::string> gears = transmission::BodyNames(bodies);
    for (std::size_t b = 0; b < gears.size(); ++b) {
      root[("sigma_t_" + gears[b] + "_MPa").c_str()] = Array(std::move(sigma[2 * b]));
      root[("sigma_c_" + gears[b] + "_MPa").c_str()] = Array(std::move(sigma[2 * b + 1]));
    }
    f["root_stress"] = Result(root);
  }
  if (record.rating) f["rating"] = JsonToPython(report::RatingJson(*record.rating));
  f["warnings"] = record.warnings;
  // The record as the program's summary JSON has it: the same keys and values (its provenance
  // is the program's).
  nlohmann::json j = report::DynamicRecordJson(record, nlohmann::json());
  j.erase("provenance");
  f["record"] = JsonToPython(j);
  py::object result = Result(f);
  if (!record.completed() && raise_on_failure)
    RaiseRunFailure(record.status,
                    samples.empty() && record.stats.steps == 0
                        ? record.failure
                        : "the run stopped after " + std::to_string(samples.size()) + " of " +
                              std::to_string(record.outputs) + " outputs: " + record.failure,
                    result);
  return result;
}

}  // namespace

// A run in time and the natural modes.
void BindDynamicRun(py::module_& m) {
  const dynamics::DynamicRequest& d = DynamicDefaults();  // the keywords' defaults
  m.def(
      "dynamic",
      [](const ScenePtr& s, std::optional<double> sun_speed_rpm, const std::string& range,
         double time_s, std::optional<int> outputs_per_cycle, double start_deg,
         const std::string& integrator, double rtol, std::optional<double> rate_scale,
         std::optional<double> contact_tol, int max_order, bool analytic_jacobian,
         const std::string& backend, std::optional<std::string> cache_dir, py::object progress,
         bool raise_on_failure, bool stresses, bool rating, std::optional<long> max_steps,
         std::optional<double> time_limit_s) {
        return Dynamic(s, sun_speed_rpm, range, time_s, outputs_per_cycle, start_deg,
                       MakeIntegration(integrator, rtol, rate_scale, contact_tol, max_order,
                                       analytic_jacobian, backend),
                       cache_dir, std::move(progress), raise_on_failure, stresses, rating,
                       max_steps, time_limit_s);
      },
      py::arg("scene"), py::arg("sun_speed_rpm") = py::none(), py::kw_only(),
      py::arg("range") = RangeName(dynamics::kDefaultRunRange), py::arg("time_s") = 0.0,
      py::arg("outputs_per_cycle") = py::none(), py::arg("start_deg") = d.start_deg,
      py::arg("integrator") = d.integrator, py::arg("rtol") = d.rtol,
      py::arg("rate_scale") = py::none(), py::arg("contact_tol") = py::none(),
      py::arg("max_order") = d.max_order, py::arg("analytic_jacobian") = d.analytic_jacobian,
      py::arg("backend") = d.backend, py::arg("cache_dir") = py::none(),
      py::arg("progress") = py::none(), py::arg("raise_on_failure") = true,
      py::arg("stresses") = d.stresses, py::arg("rating") = d.rating,
      py::arg("max_steps") = py::none(), py::arg("time_limit_s") = py::none(),
      (std::string(R"doc(
The dynamic model of a stage integrated in time (`epicycle dynamic`; docs/dynamic.md), from the
quasi-static solution at t = 0. The dynamic settings are the scene's ([dynamics], [lubricant],
[supports] keys).

Parameters
----------
scene : Scene
    A stage scene.
sun_speed_rpm : float or None, default None
    Sun speed [rpm] (None: the scene's dynamics.sun_speed_rpm; given: that key is set, with the
    scene reader's checks).
range : str, default "planet"
    Carrier rotation simulated: "cycle", "planet", "sun", "revolution" (as quasistatic's).
time_s : float, default 0
    Simulate this long instead [s] (0: the range).
outputs_per_cycle : int or None, default None
    Output steps per mesh cycle [-] (None: the library's default, as the program's: 10 per period
    of the highest natural frequency, 20 to 500; docs/dynamic.md, Outputs).
start_deg : float, default 0
    Carrier angle at t = 0 [deg].)doc") +
       kIntegrationDoc + R"doc(
stresses : bool, default False
    Root stresses per output step (docs/stresses.md; the scene's model.stresses), as
    `epicycle dynamic --stresses`.
rating : bool, default False
    ISO 6336 ratings with the run's K_v (implies stresses; needs the scene's
    material.bending_limit_MPa and material.contact_limit_MPa), as `epicycle dynamic --rating`.
max_steps : int or None, default None
    Integrator steps per output interval before the run stops (None: 2000000), as --max-steps.
time_limit_s : float or None, default None
    Wall-time budget of the run [s] (None: none), as --time-limit.

Returns
-------
Result
    Per output step (T steps, n planets): time_s [s], carrier_deg [deg], lsr (T, n) [-],
    load_sharing_factor (T, n) [-], k_gamma [-], te_urad [µrad] (dynamic TE at the sun), sun_x_um,
    sun_y_um [µm] (sun centre from nominal), sun_torque_balance_Nm [N·m], external_work_J,
    dissipated_work_J, kinetic_energy_J, elastic_energy_J, compliance_work_J [J], contacts,
    active_contacts, friction_power_W [W], sun_bearing_force_N (T, 2) [N],
    planet_bearing_force_N (T, n, 2) [N]; with slices of the face width face_meshes (M names),
    k_hbeta (T, M) [-] and largest_load_z_mm (T, M) [mm] (the steps file's K_Hbeta_<mesh> and
    largest_z_mm_<mesh>); with a helical stage (its axial and tilting motions held)
    sun_axial_force_N, ring_axial_force_N, carrier_axial_force_N (T,) [N] along +z,
    sun_mesh_axial_force_N (T, n) [N] (the sun mesh's on each planet), tilting_moment_radial_Nm
    and tilting_moment_tangential_Nm (T, n) [N·m] (the steps file's columns of those names,
    suffixed _<planet>); pairs (per loaded tooth pair and step: time_s, mesh,
    kind, flank, tooth_a, tooth_b, normal_force_N, elastic_force_N, friction_force_N [N],
    overlap_rate_mm_per_s [mm/s]); vibration (per step, the signals of docs/spectra.md: te_rad,
    ring_force_x_N, ring_force_y_N, ring_torque_Nm, sun_force_x_N/sun_force_y_N (held sun) or
    sun_x_m/sun_y_m (floating), and channels: (name, "torsional" or "housing")
    pairs); summary (lsr_mean/min/max (n,) [-], k_gamma [-], te_min/max/peak_to_peak_urad [µrad],
    orbit_radius_max/mean_um [µm], max_pair_force_N [N]); stats (integrator counts, times [s]);
    sun_speed_rpm [rpm], mesh_frequency_Hz [Hz], duration_s [s], outputs, mesh stiffness [N/m]
    and damping [N·s/m] of the meshes, status ("completed", "contact-failure",
    "integrator-failure", "time-limit", "geometry"), completed, message, warnings; record (the
    run's record as a dict: the keys and values of the program's dynamic_summary.json but its
    provenance).
    With stresses: root_stress (per step sigma_t_<gear>_MPa, sigma_c_<gear>_MPa [MPa], each
    gear's largest tension and compression, NaN for a failed step: the steps file's columns) and
    the summary's root_stress (per gear tension_MPa, compression_MPa [MPa] with time_s [s], tooth,
    fillet and arc_from_space_centre_mm [mm], largest_range_MPa: the summary JSON's).
    With rating: rating, as the summary JSON's (per gear sigma_F_*_MPa, S_F_*, sigma_H_*_MPa,
    S_H_*; every factor with its value and source, K_v the run's).

Raises
------
ValueError
    Bad input (the argument's name, value and rule), a rating without the material's limits.
ComputationError
    The run stopped early (or its quasi-static start failed) and raise_on_failure, as the
    subclass of its status: ContactFailure, IntegratorFailure, TimeLimitReached or
    GeometryFailure (its .result the steps computed and the record).)doc")
          .c_str());
}

}  // namespace epicycle::python
