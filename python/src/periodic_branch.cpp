// The periodic-branch driver of dynamics/.
#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "common.hpp"
#include "epicycle/dynamics/branch_run.hpp"
#include "epicycle/dynamics/periodic.hpp"
#include "epicycle/dynamics/stage_periodic.hpp"
#include "epicycle/report/record_json.hpp"
#include "helical_ranges.hpp"
#include "integration.hpp"
#include "scene.hpp"

namespace epicycle::python {

// A branch of periodic orbits (dynamics/stage_branch.hpp) as arrays, one entry per point.
py::object PeriodicBranch(const ScenePtr& s, const std::string& parameter, double start, double end,
                          int steps, int max_points, const std::string& method,
                          std::optional<int> harmonics, const Integration& integration,
                          std::optional<std::string> cache_dir, py::object progress,
                          bool raise_on_failure) {
  dynamics::BranchRequest request;
  request.method = dynamics::ParsePeriodicMethod(method, "method");
  request.harmonics = harmonics;
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
  // A helical stage: each point's axial loads over its period, the record's points[].helical.
  std::vector<const transmission::HelicalLoadRange*> helical;
  for (const dynamics::StageBranchPoint& p : r.points)
    helical.push_back(p.helical.count > 0 ? &p.helical : nullptr);
  if (std::any_of(helical.begin(), helical.end(), [](const auto* h) { return h != nullptr; }))
    f["helical"] = HelicalRanges(helical);
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
  const dynamics::BranchRequest br;  // the library's defaults, the keywords' too
  m.def(
      "periodic_branch",
      [](const ScenePtr& s, const std::string& parameter, double start, double end, int steps,
         int max_points, const std::string& method, std::optional<int> harmonics, double rtol,
         std::optional<double> rate_scale, std::optional<double> contact_tol,
         const std::string& backend, std::optional<std::string> cache_dir, py::object progress,
         bool raise_on_failure) {
        // The integrator, its order and Jacobian are the request's defaults (not keywords here).
        const dynamics::DynamicRequest& d = DynamicDefaults();
        return PeriodicBranch(s, parameter, start, end, steps, max_points, method, harmonics,
                              MakeIntegration(d.integrator, rtol, rate_scale, contact_tol,
                                              d.max_order, d.analytic_jacobian, backend),
                              cache_dir, std::move(progress), raise_on_failure);
      },
      py::arg("scene"), py::arg("parameter"), py::arg("start"), py::arg("end"), py::kw_only(),
      py::arg("steps") = br.steps,
      py::arg("max_points") = dynamics::StageBranchOptions().max_points,
      py::arg("method") = dynamics::PeriodicMethodName(br.method),
      py::arg("harmonics") = py::none(), py::arg("rtol") = br.run.rtol,
      py::arg("rate_scale") = py::none(), py::arg("contact_tol") = py::none(),
      py::arg("backend") = br.run.backend, py::arg("cache_dir") = py::none(),
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
    A number of the scene by its key path (docs/periodic.md §3, "Continued scene numbers"):
    "sun_speed_rpm" [rpm], "sun_torque_Nm" [N·m], "mesh_damping_ratio" [-], or a pin error
    "errors.pin.planetK.radial_um" / "errors.pin.planetK.tangential_um" [µm]; any other name
    raises ValueError saying why it cannot be continued.
start, end : float
    The range, in the parameter's unit; end != start.
steps : int, default 20
    The largest arclength step is 1/steps of the range [-].
max_points : int, default 400
    The most points of the branch [-].
method : str, default "shooting"
    The periodic back end (`--periodic-method`): "shooting", or "hb", harmonic balance with
    Hill's stability (docs/periodic.md §2) for a stage whose orbit repeats with the mesh.
harmonics : int or None, default None
    method "hb": the harmonics of the mesh period kept [-] (None: 24; `--hb-harmonics`).
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
    their rates [m/s, rad/s] at t = 0) with state_labels; a helical stage's helical: per point
    the axial loads over its period as Result arrays under the keys of the record's
    points[].helical, <name>_mean_<unit> and <name>_max_abs_<unit>, (points,) for
    sun_axial_force_*_N, ring_axial_force_*_N, carrier_axial_force_*_N and (points, n) for the
    planets' sun_mesh_axial_force_*_N, ring_mesh_axial_force_*_N, axial_force_*_N,
    axial_tilting_moment_radial_*_Nm, axial_tilting_moment_tangential_*_Nm,
    tilting_moment_radial_*_Nm, tilting_moment_tangential_*_Nm (column i: planet i + 1);
    bifurcations (kind, the parameter's values, before_point); integrations,
    plain_integrations, steps [-], cpu_s, wall_s [s], warnings; record: the branch's record, the
    keys and values of the program's periodic_branch_summary.json (docs/records.md).

Raises
------
ValueError
    Bad input (the argument's name, value and rule; an unknown parameter, a range of zero width,
    a period of too many mesh cycles).
ComputationError
    The branch stopped before its end and raise_on_failure (its .result the Result above).)doc");
}

}  // namespace epicycle::python
