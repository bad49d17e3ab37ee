// The stage drivers of transmission/ and geometry/: the geometry report and profiles, the
// potential contacts at a pose, a mesh's stiffness and the quasi-static sweep.
#include <optional>

#include <nlohmann/json.hpp>

#include "common.hpp"
#include "epicycle/geometry/pair.hpp"
#include "epicycle/report/face_width_files.hpp"
#include "epicycle/report/geometry_json.hpp"
#include "epicycle/report/ratings.hpp"
#include "epicycle/report/record_json.hpp"
#include "epicycle/report/run_files.hpp"
#include "epicycle/transmission/mesh_stiffness.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "epicycle/transmission/rating.hpp"
#include "epicycle/transmission/run_arguments.hpp"
#include "epicycle/transmission/run_range.hpp"
#include "epicycle/transmission/stiffness_run.hpp"
#include "epicycle/transmission/sweep_summary.hpp"
#include "epicycle/transmission/validity.hpp"
#include "face_loads.hpp"
#include "scene.hpp"
#include "sweep.hpp"

namespace epicycle::python {

namespace {

using ScenePtr = std::shared_ptr<Scene>;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double Deg(double rad) { return geometry::Deg(rad); }

// A gear's outline and half profile [mm] with each profile point's role.
py::object GearProfiles(const geometry::Gear& gear, int per_segment) {
  const std::vector<geometry::Vec2> outline = gear.Outline(per_segment);
  std::vector<double> xy;
  xy.reserve(2 * outline.size());
  for (const auto& p : outline) {
    xy.push_back(p.x() * 1e3);
    xy.push_back(p.y() * 1e3);
  }
  const geometry::Polyline half = gear.half_profile().Sample(per_segment);
  std::vector<double> hxy;
  py::list roles;
  for (std::size_t i = 0; i < half.points.size(); ++i) {
    hxy.push_back(half.points[i].x() * 1e3);
    hxy.push_back(half.points[i].y() * 1e3);
    roles.append(geometry::RoleName(half.roles[i]));
  }
  const auto n = static_cast<py::ssize_t>(outline.size());
  const auto h = static_cast<py::ssize_t>(half.points.size());
  py::dict f;
  f["teeth"] = gear.teeth();
  f["outline_mm"] = Array2(std::move(xy), n, 2);
  f["half_profile_mm"] = Array2(std::move(hxy), h, 2);
  f["half_profile_roles"] = roles;
  return Result(f);
}

py::object Geometry(const ScenePtr& s, int per_segment) {
  geometry::CheckArgument("points_per_segment", per_segment, geometry::kPointsPerSegment);
  const transmission::Scene& scene = s->scene();
  py::dict f;
  py::dict gears;
  if (scene.kind == transmission::SceneKind::kPair) {
    const geometry::GearPair pair = transmission::MakePair(scene, scene.pair);
    f["report"] = JsonToPython(report::PairJson(scene, pair));
    gears["gear1"] = GearProfiles(pair.gear1(), per_segment);
    gears["gear2"] = GearProfiles(pair.gear2(), per_segment);
  } else {
    const geometry::Stage stage = transmission::MakeStage(scene);
    f["report"] = JsonToPython(report::StageJson(scene, stage));
    gears["sun"] = GearProfiles(stage.sun(), per_segment);
    for (int i = 0; i < stage.planets(); ++i)
      gears[py::str("planet" + std::to_string(i + 1))] = GearProfiles(stage.planet(i), per_segment);
    gears["ring"] = GearProfiles(stage.ring(), per_segment);
  }
  f["gears"] = gears;
  f["warnings"] = scene.warnings;
  return Result(f);
}

py::object Contacts(const ScenePtr& s, double carrier_deg, std::optional<double> gap_window_um) {
  transmission::CheckArgument(transmission::GeometryArguments::kContactsCarrierDeg, carrier_deg);
  // The window given: the scene's key contact.gap_window_um set, with the scene reader's rule.
  const ScenePtr run_scene = gap_window_um ? s->Edited([w = *gap_window_um](toml::table& t) {
    if (!t["contact"].is_table()) t.insert_or_assign("contact", toml::table{});
    t["contact"].as_table()->insert_or_assign("gap_window_um", w);
  })
                                           : s;
  const transmission::Scene& scene = run_scene->scene();
  RequireStage(scene, "contacts");
  const geometry::Stage st = transmission::MakeStage(scene);
  const geometry::StagePoses p = st.Poses(geometry::Rad(carrier_deg));
  geometry::ContactSearchOptions opt;
  opt.gap_window = scene.gap_window;
  py::list mesh, kind, flank;
  std::vector<int> tooth, mate;
  std::vector<double> x, y, nx, ny, overlap, arm_a, arm_b, rho_a, rho_b;
  for (int i = 0; i < st.planets(); ++i) {
    for (geometry::MeshKind k : {geometry::MeshKind::kSunPlanet, geometry::MeshKind::kPlanetRing}) {
      const int loaded =
          k == geometry::MeshKind::kSunPlanet ? st.sun_mesh_side() : st.ring_mesh_planet_side();
      for (const geometry::PotentialContact& c : st.Contacts(p, i, k, opt)) {
        mesh.append(geometry::MeshName(i, k));
        kind.append(geometry::KindName(c.kind));
        flank.append(c.side_a == loaded ? "drive" : "coast");
        tooth.push_back(c.tooth_a);
        mate.push_back(c.tooth_b);
        x.push_back(c.point.x() * 1e3);
        y.push_back(c.point.y() * 1e3);
        nx.push_back(c.normal.x());
        ny.push_back(c.normal.y());
        overlap.push_back(c.overlap * 1e6);
        arm_a.push_back(c.lever_a * 1e3);
        arm_b.push_back(c.lever_b * 1e3);
        rho_a.push_back(c.curvature_radius_a * 1e3);
        rho_b.push_back(c.curvature_radius_b * 1e3);
      }
    }
  }
  py::dict f;
  f["carrier_deg"] = carrier_deg;
  f["mesh"] = mesh;
  f["kind"] = kind;
  f["flank"] = flank;
  f["tooth"] = Array(std::move(tooth));
  f["mate"] = Array(std::move(mate));
  f["x_mm"] = Array(std::move(x));
  f["y_mm"] = Array(std::move(y));
  f["normal_x"] = Array(std::move(nx));
  f["normal_y"] = Array(std::move(ny));
  f["overlap_um"] = Array(std::move(overlap));
  f["arm_a_mm"] = Array(std::move(arm_a));
  f["arm_b_mm"] = Array(std::move(arm_b));
  f["curvature_radius_a_mm"] = Array(std::move(rho_a));
  f["curvature_radius_b_mm"] = Array(std::move(rho_b));
  return Result(f);
}

// A record as Python: the keys and values of the program's summary JSON (report::RecordJson), its
// one serialisation, without the program's provenance.
template <class Record>
py::object RecordObject(const Record& record) {
  return JsonToPython(report::RecordJson(record));
}

// A run's progress as its sink sees the samples.
class StiffnessProgress final : public transmission::StiffnessSink {
 public:
  explicit StiffnessProgress(const Progress& report) : report_(report) {}
  void Start(const transmission::StiffnessPlan& p) override {
    total_ = static_cast<long>(p.positions_per_cycle) * p.cycles;
  }
  void Sample(const transmission::MeshSample&) override { report_(++done_, total_); }

 private:
  const Progress& report_;
  long done_ = 0, total_ = 0;
};

py::object MeshStiffness(const ScenePtr& s, const std::string& mesh, int positions, int cycle,
                         const std::string& backend, bool local_terms, bool tooth_coupling,
                         bool stresses, int threads, std::optional<std::string> cache_dir,
                         py::object progress) {
  transmission::StiffnessRequest request;
  request.scene = s->scene();
  request.mesh = mesh;
  request.positions = positions;
  request.cycle = cycle;
  request.threads = threads;
  request.backend = backend;
  request.local_terms = local_terms;
  request.tooth_coupling = tooth_coupling;
  request.stresses = stresses;
  request.tables = TableOptions(cache_dir);
  CancelToken token;
  const Progress report(std::move(progress), &token);
  struct Out {
    transmission::StiffnessRecord record;
  };
  const Out out = RunReleased(token, [&] {
    StiffnessProgress sink(report);
    return Out{transmission::RunStiffness(request, sink)};
  });
  const transmission::MeshStiffnessResult& r = out.record.result;
  std::vector<double> angle, rotation, approach, force, k, validity;
  std::vector<char> ok;
  py::list messages;
  std::vector<double> p_angle, p_force, p_k, p_share, p_roll;
  std::vector<int> p_t1, p_t2;
  py::list p_kind;
  for (const auto& x : r.samples) {
    angle.push_back(Deg(x.angle));
    ok.push_back(x.converged);
    messages.append(x.message);
    rotation.push_back(x.rotation * 1e6);
    approach.push_back(x.approach * 1e6);
    force.push_back(x.total_force);
    k.push_back(x.mesh_stiffness);
    validity.push_back(x.local_validity_ratio);
    for (const auto& p : x.pairs) {
      p_angle.push_back(Deg(x.angle));
      p_t1.push_back(p.tooth1);
      p_t2.push_back(p.tooth2);
      p_kind.append(geometry::KindName(p.kind));
      p_force.push_back(p.force);
      p_k.push_back(p.stiffness);
      p_share.push_back(p.share);
      p_roll.push_back(Deg(p.roll1));
    }
  }
  py::dict pairs;
  pairs["angle_deg"] = Array(std::move(p_angle));
  pairs["tooth1"] = Array(std::move(p_t1));
  pairs["tooth2"] = Array(std::move(p_t2));
  pairs["kind"] = p_kind;
  pairs["force_N"] = Array(std::move(p_force));
  pairs["stiffness_N_per_m"] = Array(std::move(p_k));
  pairs["share"] = Array(std::move(p_share));
  pairs["roll1_deg"] = Array(std::move(p_roll));
  py::dict f;
  f["mesh"] = r.mesh;
  f["torque_Nm"] = r.torque;
  f["face_width_mm"] = r.face_width * 1e3;
  f["angle_deg"] = Array(std::move(angle));
  f["converged"] = BoolArray(ok);
  f["message"] = messages;
  f["rotation_urad"] = Array(std::move(rotation));
  f["approach_um"] = Array(std::move(approach));
  f["total_force_N"] = Array(std::move(force));
  f["stiffness_N_per_m"] = Array(std::move(k));
  f["local_validity_ratio"] = Array(std::move(validity));
  f["pairs"] = Result(pairs);
  f["failed"] = r.failed;
  f["mean_stiffness_N_per_m"] = r.mean_stiffness;
  f["min_stiffness_N_per_m"] = r.min_stiffness;
  f["max_stiffness_N_per_m"] = r.max_stiffness;
  f["peak_pair_stiffness_N_per_m"] = r.peak_pair_stiffness;
  f["mean_stiffness_N_per_mm_um"] = r.mean_per_width();
  f["peak_pair_stiffness_N_per_mm_um"] = r.peak_pair_per_width();
  f["iso6336_c_prime_N_per_mm_um"] = out.record.iso6336_c_prime;
  f["iso6336_c_gamma_alpha_N_per_mm_um"] = out.record.iso6336_c_gamma_alpha;
  f["contact_ratio"] = out.record.contact_ratio;
  f["warnings"] = out.record.warnings;
  f["record"] = RecordObject(out.record);
  py::object result = Result(f);
  if (r.failed > 0)
    RaiseComputationError(std::to_string(r.failed) + " of " + std::to_string(r.samples.size()) +
                              " mesh-stiffness samples failed",
                          result);
  return result;
}

// The statistics of a sweep (SummariseSweep), NaN where no position converged.
py::object SummaryObject(const transmission::SweepSummary& s) {
  py::dict f;
  f["positions"] = s.positions;
  f["converged"] = s.converged;
  f["lsr_mean"] = Array(std::vector<double>(s.lsr_mean));
  f["lsr_min"] = Array(std::vector<double>(s.lsr_min));
  f["lsr_max"] = Array(std::vector<double>(s.lsr_max));
  f["k_gamma"] = s.k_gamma;
  f["k_gamma_mean"] = s.k_gamma_mean;
  f["te_min_urad"] = s.transmission_error_min * 1e6;
  f["te_max_urad"] = s.transmission_error_max * 1e6;
  f["te_peak_to_peak_urad"] = s.TransmissionErrorPeakToPeak() * 1e6;
  f["sun_displacement_max_um"] = s.sun_displacement_max * 1e6;
  if (s.friction) {
    f["efficiency_mean"] = s.efficiency_mean;
    f["efficiency_min"] = s.efficiency_min;
    f["friction_power_mean_W"] = s.friction_power_mean;
    f["friction_iterations_mean"] = s.friction_iterations_mean;
  }
  // Stresses on: the same read-outs as the program's summary JSON (report/), as Python objects.
  if (!s.root_stress.empty())
    f["root_stress"] =
        JsonToPython(report::RootStressJson(s.root_stress, "carrier_deg", geometry::Deg(1.0)));
  if (!s.contact_pressure.empty())
    f["contact_pressure"] = JsonToPython(
        report::ContactPressureJson(s.contact_pressure, "carrier_deg", geometry::Deg(1.0)));
  return Result(f);
}

}  // namespace

SweepRequest MakeSweepRequest(const ScenePtr& s, const std::string& range, int positions,
                              double start_deg, std::optional<std::vector<double>> angles_deg,
                              int threads, bool warm_start, const std::string& backend,
                              bool local_terms, const std::string& friction, bool stresses,
                              bool rating) {
  SweepRequest q;
  if (positions != 0)  // 0: the default, 60 per mesh cycle
    transmission::CheckArgument(transmission::QuasiStaticArguments::kPositions, positions);
  transmission::CheckArgument(transmission::QuasiStaticArguments::kStartDeg, start_deg);
  if (angles_deg) q.angles = transmission::CheckedCarrierAngles("angles_deg", *angles_deg);
  transmission::CheckArgument(transmission::QuasiStaticArguments::kThreads, threads);
  // Stresses (or a rating, which needs them): the scene with [model] stresses = true.
  q.scene = stresses || rating ? WithStresses(s) : s;
  if (rating)
    transmission::CheckRatingInputs(transmission::RatingInputsOf(q.scene->scene()), "rating=True");
  q.options.backend = BackendOf(backend);
  q.options.threads = threads;
  q.options.warm_start = warm_start;
  transmission::SetRestFriction(s->scene().dynamics, friction, &q.options);
  q.options.Validate();
  q.range = transmission::RunRangeFromName(range);
  q.positions = positions;
  q.start_deg = start_deg;
  q.local_terms = local_terms;
  return q;
}

std::vector<double> SweepRequest::Angles(const geometry::Stage& stage) const {
  if (angles) return *angles;
  const int count = positions > 0 ? positions : transmission::DefaultPositions(stage, range);
  return transmission::SweepAngles(geometry::Rad(start_deg),
                                   transmission::CarrierSpan(stage, range), count);
}

PositionRow RowOf(const transmission::PositionResult& r, int planets, bool with_friction) {
  PositionRow w;
  const bool good = r.converged;
  w.carrier_deg = Deg(r.carrier_angle);
  w.converged = good;
  if (good) {
    w.lsr = r.load_sharing;
    w.factor = transmission::LoadSharingFactors(r);
    w.k_gamma = transmission::MeshLoadFactor(r);
    w.te_rad = r.transmission_error;
    w.sun_x_m = r.sun_displacement.x();
    w.sun_y_m = r.sun_displacement.y();
  } else {
    w.lsr.assign(static_cast<std::size_t>(planets), kNaN);
    w.factor = w.lsr;
    w.k_gamma = w.te_rad = w.sun_x_m = w.sun_y_m = kNaN;
  }
  w.geometric_iterations = r.geometric_iterations;
  w.contact_iterations = r.contact_iterations;
  w.warm_started = r.warm_started;
  w.residual = r.report.residual.total;
  w.status = solvers::StatusName(r.report.status);
  w.active_contacts = r.report.active_contacts;
  w.contacts = static_cast<int>(r.problem.contacts.size());
  w.solve_ms = r.report.total_seconds * 1e3;
  w.message = r.message;
  if (with_friction) {
    w.friction_power_W = good ? r.friction_power : kNaN;
    w.input_power_W = good ? r.input_power : kNaN;
    w.output_power_W = good ? r.output_power : kNaN;
    w.efficiency = good ? r.Efficiency() : kNaN;
    w.force_change = r.force_change;
  }
  return w;
}

py::object QuasiStatic(const ScenePtr& s, const std::string& range, int positions, double start_deg,
                       std::optional<std::vector<double>> angles_deg, int threads, bool warm_start,
                       const std::string& backend, bool local_terms,
                       std::optional<std::string> cache_dir, py::object progress,
                       bool raise_on_failure, const std::string& friction, bool stresses,
                       bool rating, bool pin_feedback) {
  const std::optional<std::vector<double>> angles_copy = angles_deg;
  const SweepRequest q =
      MakeSweepRequest(s, range, positions, start_deg, std::move(angles_deg), threads, warm_start,
                       backend, local_terms, friction, stresses, rating);
  const transmission::QuasiStaticOptions& opt = q.options;
  // The library's run on this scene's cached rig: the record the program writes, and every
  // position kept for the per-position columns.
  transmission::QuasiStaticRequest request;
  request.scene = q.scene->scene();
  request.backend = backend;
  request.range = q.range;
  request.positions = q.positions;
  if (q.angles) request.angles_deg = *angles_copy;
  request.start_deg = start_deg;
  request.threads = threads;
  request.warm_start = warm_start;
  request.local_terms = local_terms;
  request.friction = friction;
  request.stresses = stresses;
  request.rating = rating;
  request.pin_feedback = pin_feedback;
  request.rating_option = "rating=True";
  CancelToken token;
  const Progress report(std::move(progress), &token);
  class Keep final : public transmission::QuasiStaticSink {
   public:
    explicit Keep(const Progress& report) : report_(report) {}
    void Start(const transmission::QuasiStaticPlan& p) override { total_ = p.positions; }
    void Position(const transmission::PositionResult& r, int k) override {
      results.push_back(r);
      report_(k + 1, total_);
    }
    std::vector<transmission::PositionResult> results;

   private:
    const Progress& report_;
    long total_ = 0;
  };
  struct Out {
    std::shared_ptr<const StageRig> rig;
    std::vector<transmission::PositionResult> results;
    transmission::QuasiStaticRecord record;
  };
  Out out = RunReleased(token, [&] {
    Out o;
    o.rig = q.scene->Rig(cache_dir, "quasistatic");
    request.rig = o.rig;
    Keep keep(report);
    o.record = transmission::RunQuasiStatic(request, keep);
    o.results = std::move(keep.results);
    return o;
  });

  const int n = out.rig->stage.planets();
  std::vector<double> deg, residual, solve_ms;
  RunColumns run;
  Interned names;
  std::vector<int> geo_it, contact_it, active, contacts;
  std::vector<char> ok, warm;
  py::list status, message;
  PairColumns p;
  std::vector<double> p_force, p_friction, p_sliding;
  // Friction at rest (docs/quasistatic.md): per position P_f, P_in, P_out, η, the fixed point's
  // last change; NaN where not converged.
  const bool with_friction = opt.friction.law != transmission::FrictionLaw::kOff;
  std::vector<double> loss, p_in, p_out, efficiency, change;
  int failed = 0;
  for (const transmission::PositionResult& r : out.results) {
    const PositionRow w = RowOf(r, n, with_friction);
    failed += !w.converged;
    deg.push_back(w.carrier_deg);
    ok.push_back(w.converged);
    run.Add(w.lsr, w.factor, w.k_gamma, w.te_rad, w.sun_x_m, w.sun_y_m);
    geo_it.push_back(w.geometric_iterations);
    contact_it.push_back(w.contact_iterations);
    warm.push_back(w.warm_started);
    residual.push_back(w.residual);
    status.append(names(w.status));
    active.push_back(w.active_contacts);
    contacts.push_back(w.contacts);
    solve_ms.push_back(w.solve_ms);
    message.append(names(w.message));
    if (with_friction) {
      loss.push_back(w.friction_power_W);
      p_in.push_back(w.input_power_W);
      p_out.push_back(w.output_power_W);
      efficiency.push_back(w.efficiency);
      change.push_back(w.force_change);
    }
    for (std::size_t j = 0; j < r.problem.contacts.size() && w.converged; ++j) {
      const auto k = static_cast<Eigen::Index>(j);
      const double force = r.solution.force(k);
      if (!(force > 0)) continue;
      const transmission::StageContact& c = r.problem.contacts[j];
      p.Add(Deg(r.carrier_angle), c);
      p_force.push_back(force);
      if (with_friction) {
        p_friction.push_back(r.friction_force(k));
        p_sliding.push_back(r.sliding_velocity(k));
      }
    }
  }
  py::dict pairs;
  p.Fill(pairs, "carrier_deg");
  pairs["force_N"] = Array(std::move(p_force));
  if (with_friction) {
    pairs["friction_N"] = Array(std::move(p_friction));
    pairs["sliding_m_per_s"] = Array(std::move(p_sliding));
  }

  const transmission::Scene& scene = out.rig->scene;
  py::dict f;
  f["scene"] = scene.name;
  f["sun_support"] = transmission::SunSupportName(transmission::SetupFromScene(scene).sun);
  f["sun_torque_Nm"] = scene.loads.sun_torque;
  f["backend"] = backend;
  f["planets"] = n;
  f["carrier_deg"] = Array(std::move(deg));
  f["converged"] = BoolArray(ok);
  run.Fill(f, n);
  f["geometric_iterations"] = Array(std::move(geo_it));
  f["contact_iterations"] = Array(std::move(contact_it));
  f["warm_started"] = BoolArray(warm);
  f["residual"] = Array(std::move(residual));
  f["status"] = status;
  f["active_contacts"] = Array(std::move(active));
  f["contacts"] = Array(std::move(contacts));
  f["solve_ms"] = Array(std::move(solve_ms));
  f["message"] = message;
  f["friction"] = transmission::FrictionLawName(opt.friction.law);
  if (with_friction) {
    f["friction_power_W"] = Array(std::move(loss));
    f["input_power_W"] = Array(std::move(p_in));
    f["output_power_W"] = Array(std::move(p_out));
    f["efficiency"] = Array(std::move(efficiency));
    f["force_change"] = Array(std::move(change));
  }
  f["pairs"] = Result(pairs);
  if (out.rig->scene.face_width.active()) {
    // Per position and mesh, the face-load CSV's columns (the run's rig: its meshes, slices and
    // stresses): NaN where the position did not converge.
    std::vector<const std::vector<transmission::MeshFaceLoad>*> rows;
    for (const transmission::PositionResult& r : out.results)
      rows.push_back(r.converged ? &r.face_loads : nullptr);
    AddFaceLoads(report::StageFaceMeshes(out.rig->stage).names, out.rig->scene.face_width.slices,
                 out.rig->compliance.has_root_stress(), rows, &f);
  }
  f["summary"] = SummaryObject(out.record.summary);
  if (out.record.rating) f["rating"] = JsonToPython(report::RatingJson(*out.record.rating));
  f["warnings"] = out.record.warnings;
  f["record"] = RecordObject(out.record);
  py::object result = Result(f);
  if (failed > 0 && raise_on_failure)
    RaiseComputationError(std::to_string(failed) + " of " + std::to_string(out.results.size()) +
                              " positions failed (result.message lists why)",
                          result);
  return result;
}

void BindStage(py::module_& m) {
  m.def("geometry", &Geometry, py::arg("scene"), py::kw_only(), py::arg("points_per_segment") = 20, R"doc(
The generated geometry of a scene's gears (`epicycle geometry --json`; docs/geometry.md).

Parameters
----------
scene : Scene
    A stage or gear-pair scene.
points_per_segment : int, default 20
    Points per profile segment [-], in [1, 1000].

Returns
-------
Result
    report : dict, the geometry report (keys with units, docs/geometry.md); gears : {name:
    Result(teeth, outline_mm (K, 2) [mm] the whole gear in its body frame, half_profile_mm (H, 2)
    [mm] one flank root to tip, half_profile_roles: list of str)}; warnings : list of str.

Raises
------
ValueError
    A bad argument (its name, value and rule).)doc");
  m.def("contacts", &Contacts, py::arg("scene"), py::arg("carrier_deg") = 0.0, py::kw_only(),
        py::arg("gap_window_um") = py::none(), R"doc(
The potential contacts of every mesh of a stage at a carrier angle (rigid poses with the scene's
errors), as `epicycle contacts` prints them.

Parameters
----------
scene : Scene
    A stage scene.
carrier_deg : float, default 0
    Carrier angle [deg].
gap_window_um : float or None, default None
    Contacts with overlap >= -window [µm] (None: the scene's [contact] gap_window_um).

Returns
-------
Result
    Per contact: mesh, kind, flank ("drive"/"coast"), tooth, mate, x_mm, y_mm [mm], normal_x,
    normal_y [-] (out of the mesh's first gear), overlap_um [µm] (> 0 interpenetration),
    arm_a_mm, arm_b_mm [mm] (moment arms), curvature_radius_a_mm, curvature_radius_b_mm [mm].

Raises
------
ValueError
    A gear-pair scene, or a bad argument (its name, value and rule).)doc");
  const transmission::StiffnessRequest st;  // the library's defaults, the keywords' too
  m.def("mesh_stiffness", &MeshStiffness, py::arg("scene"), py::arg("mesh") = st.mesh,
        py::kw_only(), py::arg("positions") = st.positions, py::arg("cycle") = st.cycle,
        py::arg("backend") = st.backend, py::arg("local_terms") = st.local_terms,
        py::arg("tooth_coupling") = st.tooth_coupling, py::arg("stresses") = st.stresses,
        py::arg("threads") = st.threads, py::arg("cache_dir") = py::none(),
        py::arg("progress") = py::none(), R"doc(
Mesh stiffness of a gear pair over one mesh cycle (`epicycle stiffness`): a pair scene, or one mesh
of a stage ("sun-planet1", "planet2-ring") at the scene's load share.

Parameters
----------
scene : Scene
    A gear-pair or stage scene.
mesh : str, default ""
    The stage's mesh ("sun-planet1", "planet2-ring"); "" for a pair scene.
positions : int, default 60
    Samples per mesh cycle [-].
cycle : int, default -1
    This one mesh cycle of gear 1 (-1: the cycles a damaged tooth meshes in, else the first).
backend : str, default "newton"
    Contact back end ("newton", "ipopt", "nlopt-slsqp", ...).
local_terms : bool, default True
    False: the structural compliance only.
tooth_coupling : bool, default True
    True: the bodies couple the teeth (the model); False: every contact's compliance alone
    (the off-diagonal terms dropped: the potential-energy method's independent springs).
stresses : bool, default False
    Each gear's root stress too (the scene's model.stresses).
threads : int, default 0
    Workers [-] (0: one per core).
cache_dir : str or None, default None
    Influence-table cache folder (None: $EPICYCLE_CACHE_DIR or ~/.cache/epicycle; "": in memory).
progress : callable or None, default None
    progress(done, total), called as samples complete.

Returns
-------
Result
    Per sample angle_deg [deg] (gear 1 from the cycle start), converged, message, rotation_urad
    [µrad] (loaded static TE), approach_um [µm] (deflection along the line of action),
    total_force_N [N], stiffness_N_per_m [N/m], local_validity_ratio [-]; pairs (per loaded tooth
    pair: angle_deg, tooth1, tooth2, kind, force_N, stiffness_N_per_m, share, roll1_deg); mean,
    min, max and peak single-pair stiffness [N/m] and per face width [N/(mm·µm)]; ISO 6336-1's
    iso6336_c_prime_N_per_mm_um and iso6336_c_gamma_alpha_N_per_mm_um [N/(mm·µm)] for comparison;
    contact_ratio [-] (tip circles); torque_Nm [N·m], face_width_mm [mm], warnings; record: the
    run's record, the keys and values of `epicycle stiffness`'s JSON (docs/records.md).

Raises
------
ValueError
    A bad argument (its name, value and rule) or mesh name.
ComputationError
    A sample failed (its .result the Result above).)doc");
  const transmission::QuasiStaticRequest& qs = QuasiStaticDefaults();
  m.def("quasistatic", &QuasiStatic, py::arg("scene"), py::kw_only(),
        py::arg("range") = RangeName(qs.range), py::arg("positions") = qs.positions,
        py::arg("start_deg") = qs.start_deg, py::arg("angles_deg") = py::none(),
        py::arg("threads") = qs.threads, py::arg("warm_start") = qs.warm_start,
        py::arg("backend") = qs.backend, py::arg("local_terms") = qs.local_terms,
        py::arg("cache_dir") = py::none(), py::arg("progress") = py::none(),
        py::arg("raise_on_failure") = true, py::arg("friction") = qs.friction,
        py::arg("stresses") = qs.stresses, py::arg("rating") = qs.rating,
        py::arg("pin_feedback") = qs.pin_feedback,
        R"doc(
Quasi-static load sharing of a stage over carrier positions (`epicycle quasistatic`;
docs/quasistatic.md). The sun support is the scene's (key supports.sun: "fixed", "floating").

Parameters
----------
scene : Scene
    A stage scene.
range : str, default "cycle"
    "cycle" (one mesh cycle), "planet" (one planet revolution relative to the carrier), "sun"
    (one sun revolution relative to the carrier), "revolution" (one carrier revolution).
positions : int, default 0
    Positions over the range [-] (0: 60 per mesh cycle, docs/quasistatic.md "Positions").
start_deg : float, default 0
    Carrier angle of the first position [deg].
angles_deg : list of float or None, default None
    Given carrier angles [deg] instead of range and positions.
threads : int, default 0
    Workers [-] (0: one per core; with warm_start the results depend on the thread count within
    the solver tolerances).
warm_start : bool, default True
    Each position from its neighbour.
backend : str, default "newton"
    Contact back end ("newton", "ipopt", "nlopt-slsqp", ...).
local_terms : bool, default True
    False: the structural compliance only.
cache_dir : str or None, default None
    Influence-table cache (None: $EPICYCLE_CACHE_DIR or ~/.cache/epicycle; "": in memory).
progress : callable or None, default None
    progress(done, total), called in order as positions complete.
raise_on_failure : bool, default True
    Raise ComputationError if positions failed (else return the Result).
friction : str, default "off"
    Friction at rest (docs/quasistatic.md, "Friction at rest"): "off", "scene" (the scene's
    [dynamics] friction), or a law ("constant", "xu-kahraman", "benedict-kelley") with the
    scene's coefficient, lubricant and sun_speed_rpm.
stresses : bool, default False
    Root stresses and contact pressures (docs/stresses.md; the scene's model.stresses).
rating : bool, default False
    ISO 6336 ratings (implies stresses; needs the scene's material.bending_limit_MPa and
    material.contact_limit_MPa).
pin_feedback : bool, default True
    False: leave out the scene's [[face_width.pin]], every planet held at its given tilt (the run
    without the tilt's feedback; `--rigid-pins`).

Returns
-------
Result
    Per position (P positions, n planets): carrier_deg (P,) [deg], converged (P,) bool, lsr (P, n)
    [-] (LSR_i, paper eq. 4; NaN where not converged), load_sharing_factor (P, n) [-]
    (L_i = n LSR_i), k_gamma (P,) [-] (max_i L_i), te_urad (P,) [µrad] (loaded static
    transmission error at the sun), sun_x_um, sun_y_um (P,) [µm] (sun centre displacement),
    geometric_iterations, contact_iterations, warm_started, residual [-], status,
    active_contacts, contacts, solve_ms [ms], message; pairs: per loaded tooth pair carrier_deg,
    mesh, kind, flank, tooth_a, tooth_b, force_N [N]; summary: positions, converged,
    lsr_mean/lsr_min/lsr_max (n,) [-], k_gamma [-], k_gamma_mean [-], te_min_urad, te_max_urad,
    te_peak_to_peak_urad [µrad], sun_displacement_max_um [µm]; scene, sun_support, sun_torque_Nm
    [N·m], backend, planets, warnings; friction (the law's name).
    With friction: per position friction_power_W, input_power_W, output_power_W [W], efficiency
    [-] (P_out/P_in), force_change [-] (the fixed point's last relative change), per pair
    friction_N [N] and sliding_m_per_s [m/s], and in the summary efficiency_mean, efficiency_min
    [-], friction_power_mean_W [W], friction_iterations_mean [-]; lsr is then the whole sun-mesh
    torque's share, friction included.
    With S >= 2 slices of the face width (M meshes, the face-load CSV's columns; NaN where not
    converged): face_meshes (M names: sun-planet1.., then planet1-ring..), k_hbeta (P, M) [-],
    largest_load_z_mm (P, M) [mm] (the most loaded slice's centre), line_load_N_per_mm (P, M, S)
    [N/mm] (w_s, slice s at z = -b/2 + (s + 1/2) b/S); with stresses also root_stress_MPa
    (P, M, S) [MPa] (the slice's largest fillet tension of the mesh's two gears) and
    hertz_pressure_MPa (P, M, S) [MPa] (the slice's largest Hertz pressure; 0 where it carries
    nothing).
    With stresses: the summary's root_stress (per gear tension_MPa, compression_MPa [MPa] with
    carrier_deg, tooth, fillet and arc_from_space_centre_mm [mm], largest_range_MPa) and
    contact_pressure (per gear and flank hertz_pressure_MPa [MPa], half_width_um [µm], roll_deg
    [deg], contact, mesh, carrier_deg).
    With rating: rating, as `epicycle quasistatic --rating`'s JSON (per gear sigma_F_*_MPa,
    S_F_*, sigma_H_*_MPa, S_H_* with the table's and the run's K_gamma and the model's own;
    every factor with its value and source).

Raises
------
ValueError
    Bad input (the argument's name, value and rule).
ComputationError
    Positions failed and raise_on_failure (its .result the Result above).)doc");
}

}  // namespace epicycle::python
