// The drivers of dynamics/: a dynamic run in time, the natural modes, a speed sweep.
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
#include "scene.hpp"

namespace epicycle::python {

namespace {

using ScenePtr = std::shared_ptr<Scene>;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The integrator and contact settings of a run (SimulationOptions), each number by its option's
// rule (dynamics/run_arguments.hpp), then by Validate.
struct Integration {
  std::string integrator = "cvode-bdf";
  double rtol = 1e-6;
  std::optional<double> rate_scale, contact_tol;
  int max_order = 5;
  bool analytic_jacobian = true;
  std::string backend = "newton";
  dynamics::SimulationOptions Options() const {
    dynamics::CheckArgument("rtol", rtol, dynamics::kRelativeTolerance);
    if (rate_scale) dynamics::CheckArgument("rate_scale", *rate_scale, dynamics::kRateScale);
    if (contact_tol)
      dynamics::CheckArgument("contact_tol", *contact_tol, dynamics::kRunContactTolerance);
    dynamics::CheckArgument("max_order", max_order, dynamics::kMaxOrder);
    dynamics::SimulationOptions o;
    o.integrator = dynamics::IntegratorFromName(integrator);
    o.backend = BackendOf(backend);
    o.rtol = rtol;
    if (rate_scale) o.rate_scale = *rate_scale;
    if (contact_tol) o.contact.tolerance = *contact_tol;
    o.analytic_jacobian = analytic_jacobian;
    o.max_order = max_order;
    o.Validate();
    return o;
  }
  // The same settings as a run's request (the library resolves and checks them).
  void Apply(dynamics::DynamicRequest* request) const {
    request->integrator = integrator;
    request->rtol = rtol;
    request->rate_scale = rate_scale;
    request->contact_tolerance = contact_tol;
    request->max_order = max_order;
    request->analytic_jacobian = analytic_jacobian;
    request->backend = backend;
  }
};

// The dynamic settings a run used: the one place the bindings read them (from the model the
// library built from the scene).
const transmission::DynamicSettings& SettingsOf(const dynamics::StageDynamics& rig) {
  return rig.model.settings();
}

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
    dynamics::CheckArgument("outputs_per_cycle", *outputs_per_cycle, dynamics::kOutputsPerCycle);
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
    const std::size_t meshes = sink.face_meshes.size();
    std::vector<double> k_h_beta, largest_z;
    for (const dynamics::DynamicSample& x : samples)
      for (std::size_t m = 0; m < meshes; ++m) {
        const bool has = x.face_loads.size() == meshes;
        k_h_beta.push_back(has ? x.face_loads[m].k_h_beta : kNaN);
        largest_z.push_back(has ? x.face_loads[m].largest_z * 1e3 : kNaN);
      }
    const auto width = static_cast<py::ssize_t>(meshes);
    f["face_meshes"] = sink.face_meshes;
    f["k_hbeta"] = Array2(std::move(k_h_beta), count, width);
    f["largest_load_z_mm"] = Array2(std::move(largest_z), count, width);
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

py::object Modes(const ScenePtr& s, std::optional<std::vector<double>> speed_range_rpm,
                 std::optional<std::string> cache_dir) {
  dynamics::ModesRequest request;
  request.scene = s->scene();
  if (speed_range_rpm) {
    if (speed_range_rpm->size() != 2)
      throw std::invalid_argument("speed_range_rpm: must be two sun speeds LO, HI [rpm]");
    for (const double v : *speed_range_rpm)
      transmission::CheckArgument("speed_range_rpm", v, transmission::kSunSpeedRpm);
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

// Python's sink of a speed sweep: the progress of the speeds as they complete.
class SweepProgress final : public dynamics::SpeedSweepSink {
 public:
  explicit SweepProgress(const Progress& report) : report_(report) {}
  void Start(const dynamics::SpeedSweepStart& start) override {
    total_ = static_cast<long>(start.options->sun_speeds_rpm.size());
  }
  void Speed(const dynamics::SpeedResult&, const dynamics::SpeedSweepPlan&) override {
    report_(++done_, total_);
  }

 private:
  const Progress& report_;
  long done_ = 0, total_ = 0;
};

py::object SpeedSweep(const ScenePtr& s, const std::vector<double>& sun_speeds_rpm,
                      const std::string& range, double window_cycles, int outputs_per_cycle,
                      double start_deg, int harmonics, int threads, const Integration& integration,
                      std::optional<std::string> cache_dir, py::object progress,
                      bool raise_on_failure, dynamics::CarryState carry) {
  // Every number by its option's rule (run_arguments.hpp), before any work.
  if (!dynamics::kSweepSpeeds.Holds(static_cast<double>(sun_speeds_rpm.size())))
    throw std::invalid_argument("sun_speeds_rpm: " + std::to_string(sun_speeds_rpm.size()) +
                                " speeds: " + dynamics::kSweepSpeeds.Describe());
  for (std::size_t k = 0; k < sun_speeds_rpm.size(); ++k)
    dynamics::CheckArgument("sun_speeds_rpm[" + std::to_string(k) + "]", sun_speeds_rpm[k],
                            transmission::kSunSpeedRpm);
  if (window_cycles != 0)  // 0: the range's
    dynamics::CheckArgument("window_cycles", window_cycles, dynamics::kWindowCycles);
  dynamics::CheckArgument("outputs_per_cycle", outputs_per_cycle, dynamics::kOutputsPerCycle);
  dynamics::CheckArgument("start_deg", start_deg, transmission::kCarrierAngleDeg);
  if (harmonics != 0)  // 0: every harmonic in the range
    dynamics::CheckArgument("harmonics", harmonics, dynamics::kHarmonics);
  dynamics::CheckArgument("threads", threads, transmission::kThreadsOrZero);
  dynamics::SpeedSweepRequest request;
  dynamics::DynamicRequest& run = request.run;
  run.scene = s->scene();
  run.range = transmission::RunRangeFromName(range);
  run.start_deg = start_deg;
  run.outputs_per_cycle = outputs_per_cycle;
  integration.Apply(&run);
  run.tables = TableOptions(cache_dir);
  if (run.scene.kind != transmission::SceneKind::kStage) RequireStage(run.scene, "speed sweep");
  dynamics::ResolvedOptions(run);  // bad input as ValueError before the worker starts
  request.sun_speeds_rpm = sun_speeds_rpm;
  request.window_cycles = window_cycles;
  request.harmonics = harmonics;
  request.threads = threads;
  request.carry = carry;
  CancelToken token;
  const Progress report(std::move(progress), &token);
  SweepProgress sink(report);
  struct Out {
    dynamics::SpeedSweepRecord record;
  };
  const Out out = RunReleased(token, [&] { return Out{dynamics::RunSpeedSweep(request, sink)}; });
  const dynamics::SpeedSweepRecord& r = out.record;
  const dynamics::SpeedSweepPlan& plan = r.plan;
  std::vector<double> rpm, fm, kg, kv, peak, ref, te, orbit, lmin, lmax, dev, residual, wall, cpu;
  std::array<std::vector<double>, dynamics::kLoadSharingPartCount> parts;
  std::vector<char> ok;
  py::list message, factor_mesh, warnings;
  for (const dynamics::SpeedResult& x : r.speeds) {
    const double v = x.ok() ? 1.0 : kNaN;
    rpm.push_back(x.sun_speed_rpm);
    fm.push_back(x.mesh_frequency);
    ok.push_back(x.ok());
    message.append(x.message);
    kg.push_back(v * x.k_gamma);
    kv.push_back(v * x.dynamic_factor);
    factor_mesh.append(x.ok() && x.factor_mesh >= 0
                           ? plan.meshes[static_cast<std::size_t>(x.factor_mesh)]
                           : std::string());
    peak.push_back(v * x.peak_mesh_force);
    ref.push_back(v * x.qs_peak_mesh_force);
    te.push_back(v * x.te_amplitude * 1e6);
    orbit.push_back(v * x.orbit_radius * 1e6);
    lmin.push_back(v * x.lsr_min);
    lmax.push_back(v * x.lsr_max);
    dev.push_back(v * x.lsr_deviation);
    for (std::size_t k = 0; k < parts.size(); ++k) parts[k].push_back(v * x.deviation_parts[k]);
    residual.push_back(v * x.largest_residual);
    wall.push_back(x.wall_seconds);
    cpu.push_back(x.cpu_seconds);
    warnings.append(x.warnings);
  }
  std::vector<double> mode_f, zeta, sigma;
  py::list mode_type, families;
  for (const dynamics::ModeDamping& m : plan.modes) {
    mode_f.push_back(m.mode.frequency);
    zeta.push_back(m.damping_ratio);
    sigma.push_back(m.decay_rate);
    mode_type.append(dynamics::ModeTypeName(m.mode.type));
    families.append(m.families);
  }
  std::vector<double> c_rpm, c_f;
  std::vector<int> c_mode, c_h;
  std::vector<char> c_excited;
  for (const dynamics::Coincidence& c : plan.coincidences) {
    c_rpm.push_back(c.sun_speed_rpm);
    c_f.push_back(c.frequency);
    c_mode.push_back(c.mode);
    c_h.push_back(c.harmonic);
    c_excited.push_back(c.phasing_excited);
  }
  py::dict pm;
  pm["frequency_Hz"] = Array(std::move(mode_f));
  pm["type"] = mode_type;
  pm["damping_ratio"] = Array(std::move(zeta));
  pm["decay_rate_per_s"] = Array(std::move(sigma));
  pm["families"] = families;
  py::dict pc;
  pc["sun_speed_rpm"] = Array(std::move(c_rpm));
  pc["frequency_Hz"] = Array(std::move(c_f));
  pc["mode"] = Array(std::move(c_mode));
  pc["harmonic"] = Array(std::move(c_h));
  pc["phasing_excited"] = BoolArray(c_excited);
  py::dict f;
  f["scene"] = r.scene;
  f["sun_speed_rpm"] = Array(std::move(rpm));
  f["mesh_frequency_Hz"] = Array(std::move(fm));
  f["ok"] = BoolArray(ok);
  f["message"] = message;
  f["k_gamma"] = Array(std::move(kg));
  f["dynamic_factor"] = Array(std::move(kv));
  f["dynamic_factor_mesh"] = factor_mesh;
  f["peak_mesh_force_N"] = Array(std::move(peak));
  f["reference_peak_mesh_force_N"] = Array(std::move(ref));
  f["te_amplitude_urad"] = Array(std::move(te));
  f["sun_orbit_radius_um"] = Array(std::move(orbit));
  f["lsr_min"] = Array(std::move(lmin));
  f["lsr_max"] = Array(std::move(lmax));
  f["lsr_deviation"] = Array(std::move(dev));
  py::dict pp;
  for (std::size_t k = 0; k < parts.size(); ++k)
    pp[dynamics::kLoadSharingPartNames[k]] = Array(std::move(parts[k]));
  f["lsr_deviation_parts"] = Result(pp);
  f["largest_residual"] = Array(std::move(residual));
  f["wall_s"] = Array(std::move(wall));
  f["cpu_s"] = Array(std::move(cpu));
  f["warnings"] = warnings;
  f["modes"] = Result(pm);
  f["coincidences"] = Result(pc);
  f["meshes"] = plan.meshes;
  f["mesh_hz_per_sun_rpm"] = plan.mesh_hz_per_rpm;
  f["skip_time_s"] = plan.skip_time;
  f["qs_k_gamma"] = plan.qs_k_gamma;
  f["qs_te_amplitude_urad"] = plan.qs_te_amplitude * 1e6;
  f["qs_peak_mesh_force_N"] = Array(std::vector<double>(plan.qs_peak_mesh_force));
  f["window_carrier_deg"] = [&] {
    std::vector<double> d;
    for (double a : plan.window_angles) d.push_back(geometry::Deg(a));
    return Array(std::move(d));
  }();
  // The record as the program's summary JSON has it (its provenance is the program's).
  nlohmann::json j = report::SpeedSweepRecordJson(r, nlohmann::json());
  j.erase("provenance");
  f["record"] = JsonToPython(j);
  py::object result = Result(f);
  if (r.failed() > 0 && raise_on_failure)
    RaiseComputationError(std::to_string(r.failed()) + " of " + std::to_string(r.speeds.size()) +
                              " speeds failed (result.message lists why)",
                          result);
  return result;
}

// The integration parameters dynamic and speed_sweep share (numpydoc entries).
const char* kIntegrationDoc = R"doc(
integrator : str, default "cvode-bdf"
    "cvode-bdf" or "arkode-erk".
rtol : float, default 1e-6
    Relative tolerance [-].
rate_scale : float or None, default None
    Rate tolerance scale [1/s] (None: the library's default 1e4; 0: the stage's highest
    linearised natural frequency).
contact_tol : float or None, default None
    Contact solve tolerance [-] on the nondimensional residual (None: 1e-10).
max_order : int, default 5
    CVODE's largest BDF order [-].
analytic_jacobian : bool, default True
    The contact sensitivity (False: CVODE's difference quotients).
backend : str, default "newton"
    The contact back end.
cache_dir : str or None, default None
    Influence-table cache (as quasistatic's).
progress : callable or None, default None
    progress(done, total), called as results complete.
raise_on_failure : bool, default True
    Raise ComputationError on a failure (else return the Result).)doc";

// The integration settings of a driver call, as its keyword options give them.
Integration MakeIntegration(const std::string& integrator, double rtol,
                            std::optional<double> rate_scale, std::optional<double> contact_tol,
                            int max_order, bool analytic_jacobian, const std::string& backend) {
  Integration i;
  i.integrator = integrator;
  i.rtol = rtol;
  i.rate_scale = rate_scale;
  i.contact_tol = contact_tol;
  i.max_order = max_order;
  i.analytic_jacobian = analytic_jacobian;
  i.backend = backend;
  return i;
}

// A run in time and the natural modes.
void BindDynamicRun(py::module_& m) {
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
      py::arg("range") = "planet", py::arg("time_s") = 0.0,
      py::arg("outputs_per_cycle") = py::none(), py::arg("start_deg") = 0.0,
      py::arg("integrator") = "cvode-bdf", py::arg("rtol") = 1e-6,
      py::arg("rate_scale") = py::none(), py::arg("contact_tol") = py::none(),
      py::arg("max_order") = 5, py::arg("analytic_jacobian") = true, py::arg("backend") = "newton",
      py::arg("cache_dir") = py::none(), py::arg("progress") = py::none(),
      py::arg("raise_on_failure") = true, py::arg("stresses") = false, py::arg("rating") = false,
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

// Speed sweeps and their speed grids.
void BindSpeedSweep(py::module_& m) {
  m.def(
      "speed_sweep",
      [](const ScenePtr& s, const std::vector<double>& sun_speeds_rpm, const std::string& range,
         double window_cycles, int outputs_per_cycle, double start_deg, int harmonics, int threads,
         const std::string& integrator, double rtol, std::optional<double> rate_scale,
         std::optional<double> contact_tol, int max_order, bool analytic_jacobian,
         const std::string& backend, std::optional<std::string> cache_dir, py::object progress,
         bool raise_on_failure, const std::string& carry_state) {
        return SpeedSweep(s, sun_speeds_rpm, range, window_cycles, outputs_per_cycle, start_deg,
                          harmonics, threads,
                          MakeIntegration(integrator, rtol, rate_scale, contact_tol, max_order,
                                          analytic_jacobian, backend),
                          cache_dir, std::move(progress), raise_on_failure,
                          dynamics::ParseCarryState("carry_state", carry_state));
      },
      py::arg("scene"), py::arg("sun_speeds_rpm"), py::kw_only(), py::arg("range") = "planet",
      py::arg("window_cycles") = 0.0, py::arg("outputs_per_cycle") = 64, py::arg("start_deg") = 0.0,
      py::arg("harmonics") = 0, py::arg("threads") = 0, py::arg("integrator") = "cvode-bdf",
      py::arg("rtol") = 1e-6, py::arg("rate_scale") = py::none(),
      py::arg("contact_tol") = py::none(), py::arg("max_order") = 5,
      py::arg("analytic_jacobian") = true, py::arg("backend") = "newton",
      py::arg("cache_dir") = py::none(), py::arg("progress") = py::none(),
      py::arg("raise_on_failure") = true, py::arg("carry_state") = "none",
      (std::string(R"doc(
A speed sweep of the dynamic model (`epicycle dynamic --speed-sweep`; docs/speed_sweeps.md): each
sun speed run from the quasi-static solution, its start transient skipped, then a window measured.

Parameters
----------
scene : Scene
    A stage scene.
sun_speeds_rpm : list of float
    Increasing sun speeds [rpm] (epicycle.speed_grid(from, to, n)).
range : str, default "planet"
    The window: "cycle", "planet", "sun", "revolution".
window_cycles : float, default 0
    A window of this many mesh cycles [-] instead of range (0: range).
outputs_per_cycle : int, default 64
    Samples per mesh cycle [-].
start_deg : float, default 0
    Carrier angle where the window begins [deg].
harmonics : int, default 0
    Mesh harmonics 1..h for the coincidences [-] (0: every one in the speed range, as the
    program's --harmonics).
threads : int, default 0
    Workers [-] (0: every core).
carry_state : str, default "none"
    "up" or "down": the speeds one after the other in that direction, each from the previous
    speed's end state (a slow run-up or run-down, docs/speed_sweeps.md "Carried state"; the
    program's --carry-state); "none": each speed from the quasi-static solution, in parallel.)doc") +
       kIntegrationDoc + R"doc(

Returns
-------
Result
    Per speed: sun_speed_rpm [rpm], mesh_frequency_Hz [Hz], ok, message, k_gamma [-],
    dynamic_factor [-] (K_v) and dynamic_factor_mesh, peak_mesh_force_N [N] and that mesh's
    reference_peak_mesh_force_N [N] (the quasi-static one at the speed, with its friction at
    rest), te_amplitude_urad [µrad], sun_orbit_radius_um [µm], lsr_min, lsr_max [-],
    lsr_deviation (the largest |LSR_i − 1/n|) [-] with lsr_deviation_parts (sun_rotation,
    sun_translation, bearing, friction, off_line, geometry, residual [-] at that sample and
    planet; they sum to the signed deviation) and largest_residual [-] (NaN where failed),
    wall_s, cpu_s [s], warnings; modes (frequency_Hz [Hz], type, damping_ratio [-],
    decay_rate_per_s [1/s], families), coincidences (sun_speed_rpm [rpm], frequency_Hz [Hz], mode,
    harmonic, phasing_excited), meshes, mesh_hz_per_sun_rpm [Hz/rpm], skip_time_s [s], the
    quasi-static reference qs_k_gamma [-], qs_te_amplitude_urad [µrad], qs_peak_mesh_force_N [N]
    per mesh, window_carrier_deg [deg]; record: the sweep's record, the keys and values of
    `speed_sweep_summary.json` but its provenance.

Raises
------
ValueError
    Bad input (the argument's name, value and rule).
ComputationError
    A speed failed and raise_on_failure (its .result the Result above).)doc")
          .c_str());
  m.def(
      "speed_grid",
      [](double from_rpm, double to_rpm, int count) {
        dynamics::CheckArgument("from_rpm", from_rpm, transmission::kSunSpeedRpm);
        dynamics::CheckArgument("to_rpm", to_rpm, transmission::kSunSpeedRpm);
        dynamics::CheckArgument("count", count, dynamics::kSweepSpeeds);
        return Array(dynamics::SpeedGrid(from_rpm, to_rpm, count));
      },
      py::arg("from_rpm"), py::arg("to_rpm"), py::arg("count"),
      R"doc(
Sun speeds equally spaced from from_rpm to to_rpm, ends included (for speed_sweep).

Parameters
----------
from_rpm : float
    First speed [rpm].
to_rpm : float
    Last speed [rpm].
count : int
    Speeds [-].

Returns
-------
numpy.ndarray
    (count,) sun speeds [rpm].

Raises
------
ValueError
    A speed or count outside its rule.)doc");
}

}  // namespace

// A branch of periodic orbits (dynamics/stage_branch.hpp) as arrays, one entry per point.
py::object PeriodicBranch(const ScenePtr& s, const std::string& parameter, double start, double end,
                          int steps, int max_points, const Integration& integration,
                          std::optional<std::string> cache_dir, py::object progress,
                          bool raise_on_failure) {
  dynamics::BranchRequest request;
  request.run.scene = s->scene();
  integration.Apply(&request.run);
  request.run.tables = TableOptions(cache_dir);
  request.parameter = parameter;
  request.start = start;
  request.end = end;
  request.steps = steps;
  request.max_points = max_points;
  integration.Options();  // bad input as ValueError, by Python's names, before the worker starts
  RequireStage(s->scene(), "periodic_branch");
  CancelToken token;
  const Progress report(std::move(progress), &token);
  // Reports each point against the most points.
  class ProgressSink final : public dynamics::BranchSink {
   public:
    explicit ProgressSink(const Progress& report) : report_(report) {}
    void Start(const dynamics::BranchPlan& plan) override { most_ = plan.options->max_points; }
    void Point(const dynamics::StageBranchRecord& so_far) override {
      report_(static_cast<long>(so_far.points.size()), most_);
    }

   private:
    const Progress& report_;
    long most_ = 0;
  } sink(report);
  struct Out {
    dynamics::BranchRecord record;
  };
  const Out out = RunReleased(token, [&] { return Out{dynamics::RunBranch(request, sink)}; });
  const dynamics::StageBranchRecord& r = out.record.branch;
  const auto n = static_cast<py::ssize_t>(r.points.size());
  const py::ssize_t width = n > 0 ? r.points.front().state.size() : 0;
  std::vector<double> value, rpm, period, rho, kg, te, orbit, arc, states;
  std::vector<int> above, below, outside;
  std::vector<char> stable;
  py::list stability;
  for (const dynamics::StageBranchPoint& p : r.points) {
    value.push_back(p.parameter);
    rpm.push_back(p.sun_speed_rpm);
    period.push_back(p.period);
    stability.append(dynamics::StabilityName(p.stability));
    stable.push_back(p.stability != dynamics::Stability::kUnstable);
    rho.push_back(p.spectral_radius);
    above.push_back(p.real_above_one);
    below.push_back(p.real_below_minus_one);
    outside.push_back(p.complex_outside);
    kg.push_back(p.k_gamma);
    te.push_back(p.te_amplitude * 1e6);
    orbit.push_back(p.orbit_radius * 1e6);
    arc.push_back(p.arclength);
    states.insert(states.end(), p.state.data(), p.state.data() + p.state.size());
  }
  py::list kind;
  std::vector<double> where;
  std::vector<int> before;
  for (const dynamics::StageBranchBifurcation& b : r.bifurcations) {
    kind.append(dynamics::BifurcationKindName(b.kind));
    where.push_back(b.parameter);
    before.push_back(b.after_point);
  }
  py::dict bif;
  bif["kind"] = kind;
  bif[r.parameter.c_str()] = Array(std::move(where));
  bif["before_point"] = Array(std::move(before));
  py::dict f;
  f["scene"] = out.record.scene;
  f["parameter"] = r.parameter;
  f["unit"] = r.unit;
  f["ok"] = r.ok();
  f["status"] = dynamics::ContinuationStatusName(r.status);
  f["message"] = r.message.empty() ? r.figures_message : r.message;
  f["period_mesh_cycles"] = r.period_mesh_cycles;
  f[r.parameter.c_str()] = Array(std::move(value));
  if (r.parameter != dynamics::StagePeriodicSystem::kSunSpeed)
    f["sun_speed_rpm"] = Array(std::move(rpm));
  f["period_s"] = Array(std::move(period));
  f["stability"] = stability;
  f["stable"] = BoolArray(stable);
  f["spectral_radius"] = Array(std::move(rho));
  f["real_multipliers_above_1"] = Array(std::move(above));
  f["real_multipliers_below_minus_1"] = Array(std::move(below));
  f["complex_multipliers_outside"] = Array(std::move(outside));
  f["k_gamma"] = Array(std::move(kg));
  f["te_amplitude_urad"] = Array(std::move(te));
  f["sun_orbit_radius_um"] = Array(std::move(orbit));
  f["arclength"] = Array(std::move(arc));
  f["state"] = Array2(std::move(states), n, width);
  f["state_labels"] = r.dof_labels;
  f["bifurcations"] = Result(bif);
  f["integrations"] = r.integrations;
  f["plain_integrations"] = r.plain_integrations;
  f["steps"] = r.steps;
  f["cpu_s"] = r.cpu_seconds;
  f["wall_s"] = r.wall_seconds;
  f["warnings"] = out.record.warnings;
  // The record as the program's summary JSON has it: the same keys and values (its provenance
  // aside, docs/records.md).
  f["record"] = JsonToPython(report::RecordJson(out.record));
  py::object result = Result(f);
  if (!r.ok() && raise_on_failure)
    RaiseComputationError("periodic branch: " + f["message"].cast<std::string>(), result);
  return result;
}

void BindPeriodicBranch(py::module_& m) {
  m.def(
      "periodic_branch",
      [](const ScenePtr& s, const std::string& parameter, double start, double end, int steps,
         int max_points, double rtol, std::optional<double> rate_scale,
         std::optional<double> contact_tol, const std::string& backend,
         std::optional<std::string> cache_dir, py::object progress, bool raise_on_failure) {
        return PeriodicBranch(
            s, parameter, start, end, steps, max_points,
            MakeIntegration("cvode-bdf", rtol, rate_scale, contact_tol, 5, true, backend),
            cache_dir, std::move(progress), raise_on_failure);
      },
      py::arg("scene"), py::arg("parameter"), py::arg("start"), py::arg("end"), py::kw_only(),
      py::arg("steps") = 20, py::arg("max_points") = 400, py::arg("rtol") = 1e-6,
      py::arg("rate_scale") = py::none(), py::arg("contact_tol") = py::none(),
      py::arg("backend") = "newton", py::arg("cache_dir") = py::none(),
      py::arg("progress") = py::none(), py::arg("raise_on_failure") = true,
      R"doc(
The stage's periodic orbits continued over a parameter (`epicycle dynamic --speed-sweep ...
--periodic` and `--continue`; docs/periodic.md §3): shooting from the quasi-static start at
`start`, then pseudo-arclength continuation to `end` through the folds, both branches with their
Floquet stability.

Parameters
----------
scene : Scene
    A stage scene whose period is at most 4 mesh cycles (no run-out or damage that repeats only
    over longer).
parameter : str
    "sun_speed_rpm" [rpm], "sun_torque_Nm" [N·m] or "mesh_damping_ratio" [-].
start, end : float
    The range, in the parameter's unit; end != start.
steps : int, default 20
    The largest arclength step is 1/steps of the range [-].
max_points : int, default 400
    The most points of the branch [-].
rtol : float, default 1e-6
    Relative tolerance of the integrations [-].
rate_scale : float or None, default None
    Rate tolerance scale [1/s] (None: 1e4; must be > 0 here).
contact_tol : float or None, default None
    Contact solve tolerance [-] on the nondimensional residual (None: 1e-10).
backend : str, default "newton"
    The contact back end.
cache_dir : str or None, default None
    Influence-table cache (as quasistatic's).
progress : callable or None, default None
    progress(points, max_points), called as points are computed.
raise_on_failure : bool, default True
    Raise ComputationError when the branch stops before `end` (else return the Result).

Returns
-------
Result
    parameter, unit, ok, status, message, period_mesh_cycles; per point (arrays in arclength
    order): the parameter's values under its own name (e.g. sun_speed_rpm [rpm]), sun_speed_rpm
    [rpm] when another is continued, period_s [s], stability (str), stable (bool),
    spectral_radius [-], real_multipliers_above_1, real_multipliers_below_minus_1,
    complex_multipliers_outside [-], k_gamma [-], te_amplitude_urad [µrad],
    sun_orbit_radius_um [µm], arclength [-], state (points × 2n: the deviations [m, rad] and
    their rates [m/s, rad/s] at t = 0) with state_labels; bifurcations (kind, the parameter's
    values, before_point); integrations, plain_integrations, steps [-], cpu_s, wall_s [s], warnings; record: the
    branch's record, the keys and values of the program's periodic_branch_summary.json
    (docs/records.md).

Raises
------
ValueError
    Bad input (the argument's name, value and rule; an unknown parameter, a range of zero width,
    a period of too many mesh cycles).
ComputationError
    The branch stopped before its end and raise_on_failure (its .result the Result above).)doc");
}

void BindDynamic(py::module_& m) {
  BindDynamicRun(m);
  BindSpeedSweep(m);
  BindPeriodicBranch(m);
}

}  // namespace epicycle::python
