// One branch of the stage's periodic orbits, as every front end asks for it (docs/periodic.md §3,
// "The stage's branch"): a request (a dynamic run's request for the scene, its overrides and the
// integrator's settings, and the parameter's range; every default resolved here), a run that
// builds the rig once, continues the branch and streams it to a sink point by point, and one
// record of the branch. The program (`epicycle dynamic --speed-sweep ... --periodic`, `--continue`)
// and Python's `periodic_branch` parse their options into a request and format the record;
// report/ writes its one serialisation (report::RecordJson), whose keys the fields VisitRecord
// names.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "epicycle/dynamics/dynamic_run.hpp"
#include "epicycle/dynamics/run_tolerances.hpp"
#include "epicycle/dynamics/stage_branch.hpp"
#include "epicycle/transmission/record.hpp"

namespace epicycle::dynamics {

/// The names under which a front end's user gives the branch's own fields, for the messages.
struct BranchOptionNames {
  std::string parameter = "parameter", steps = "steps", max_points = "max_points";
  /// Put before the message refusing a period of too many mesh cycles ("": none).
  std::string period;
  std::string harmonics = "harmonics";
};

/// What a branch is asked for. `run` gives the scene and its overrides (sun support, friction,
/// the speed at which another parameter is continued), the carrier angle at t = 0 (start_deg),
/// the integrator's tolerances, the contact back end and the tables; its range, time, outputs,
/// spectrum, stresses and rating belong to a run in time and are not used.
struct BranchRequest {
  DynamicRequest run;
  /// The scene number continued, by its name: StagePeriodicSystem::kSunSpeed, kSunTorque,
  /// kMeshDampingRatio (or their key paths dynamics.sun_speed_rpm, load.sun_torque_Nm,
  /// dynamics.mesh_damping_ratio), or an error amplitude's key path (ParseStageErrorKey);
  /// ResolveBranchParameter says which names a scene can be continued over, and why not.
  std::string parameter = StagePeriodicSystem::kSunSpeed;
  double start = 0;               ///< λ at the first point [the parameter's unit]
  double end = 0;                 ///< λ where the branch stops [its unit]; ≠ start
  int steps = 20;                 ///< the largest arclength step is 1/steps of the range [-], ≥ 1
  std::optional<int> max_points;  ///< the most points [-], ≥ 2; none: StageBranchOptions'
  PeriodicMethod method = PeriodicMethod::kShooting;  ///< the periodic back end
  std::optional<int> harmonics;  ///< harmonic balance's H [-], ≥ 1; none: StageBranchOptions'
  BranchOptionNames names;
};

/// What the run has built before the first point (for a front end's header).
struct BranchPlan {
  const StageDynamics* rig = nullptr;
  const StageBranchOptions* options = nullptr;  ///< as resolved
};

/// Where a branch streams its points as the continuation computes them.
class BranchSink {
 public:
  virtual ~BranchSink() = default;
  /// Once, after the rig is built and before the shooting from the start.
  virtual void Start(const BranchPlan& /*plan*/) {}
  /// After each new point: the branch so far (its last point new; bifurcations up to it).
  virtual void Point(const StageBranchRecord& /*so_far*/) {}
};

/// What a branch found, with the settings it ran with. Every field is in the record's one
/// serialisation (VisitRecord).
struct BranchRecord {
  std::string scene;
  RunTolerances tolerances;       ///< the back end as the request names it
  std::array<double, 2> range{};  ///< {start, end} [the parameter's unit]
  double max_step = 0;            ///< the largest arclength step (scaled, docs/periodic.md §1) [-]
  StageBranchRecord branch;       ///< the points, bifurcations, status and counts
  std::vector<std::string> warnings;  ///< the scene's
  bool ok() const { return branch.ok(); }
};

/// Resolves the request, refuses a period of too many mesh cycles before any table is built,
/// builds the rig once and continues the branch (each point to `sink` as it is computed). A
/// continuation that stops early is a status in the record, not an exception.
/// @throws std::invalid_argument for a request that breaks a rule (named as `names` say);
///         std::runtime_error if the quasi-static start fails; whatever `sink` throws.
BranchRecord RunBranch(const BranchRequest& request, BranchSink& sink);

/// The parameter a branch of `scene` continues when asked for `name` (the record's name: an alias
/// resolved to its short name), and the stage's period over the branch (a continued run-out's
/// included) (docs/periodic.md §3, "Continued scene numbers").
/// @throws std::invalid_argument "<what> = '<name>': <rule>" for a name that is not a key of the
///         scene, a key that is not a number, a number that a branch cannot continue (the gears,
///         the compliance tables and the settings are built once from it), a run-out whose period
///         exceeds max_period_mesh_cycles.
std::string ResolveBranchParameter(const transmission::Scene& scene, const std::string& name,
                                   const std::string& what, long max_period_mesh_cycles,
                                   StagePeriod* period);

/// Why a branch of this request's stage would not pay (BranchPeriodRefusal: a period of more mesh
/// cycles than StageBranchOptions::max_period_mesh_cycles, docs/periodic.md §4), empty when it
/// would. A front end asked for periodic orbits over a speed range falls back on the
/// time-integration sweep of that range with this as its warning.
std::string BranchPeriodTooLong(const BranchRequest& request);

/// The record's fields, each once with its name and unit (its serialisation's keys); a point's
/// and a bifurcation's parameter value under the parameter's own key.
void VisitRecord(const BranchRecord& record, transmission::RecordVisitor& visit);

}  // namespace epicycle::dynamics
