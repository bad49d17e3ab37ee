// The dynamic factor K_v of a run (docs/model.md §9 "Ratings"): per mesh, the largest total
// tooth force of the run (elastic plus damping, Σ over the mesh's contacts) over the largest
// quasi-static one at the same carrier angles; K_v is the largest ratio over the meshes. The
// quasi-static reference is solved at the run's output angles with the run's back end, contact
// options and friction (at rest, at the run's speed), so both peaks are taken over the same poses
// under the same loads and K_v is the dynamics' part alone; with the run it gives the rating's K_γ
// at rest (transmission::RateStage) and the run gives the model's own stresses in motion.
#pragma once

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "epicycle/dynamics/dynamic_model.hpp"
#include "epicycle/dynamics/run_span.hpp"
#include "epicycle/dynamics/simulation.hpp"
#include "epicycle/transmission/contact_pressure.hpp"
#include "epicycle/transmission/rating.hpp"
#include "epicycle/transmission/root_stress.hpp"
#include "epicycle/transmission/scene.hpp"
#include "epicycle/transmission/sweep_summary.hpp"

namespace epicycle::dynamics {

/// The loads of a run's output steps that a rating needs, gathered one step at a time (nothing
/// grows with the steps): the largest total force per mesh and, when the steps carry root
/// stresses, the largest Hertz pressure per flank (transmission::ContactPressureTracker, x the
/// time [s]).
class MotionLoads {
 public:
  /// Meshes in the order of geometry::Stage::meshes() (2 per planet).
  explicit MotionLoads(const geometry::Stage& stage);
  /// One output step; a step whose evaluation failed only counts.
  void Add(const DynamicSample& s);
  int steps() const { return steps_; }      ///< steps added whose evaluation was ok [-]
  long outputs() const { return outputs_; }  ///< steps added, failed ones included [-]
  const std::vector<double>& peak_mesh_force() const { return peak_; }  ///< per mesh [N]
  std::vector<transmission::FlankPressure> contact_pressure() const { return pressure_.Result(); }

 private:
  std::vector<double> peak_;
  transmission::ContactPressureTracker pressure_;
  int steps_ = 0;
  long outputs_ = 0;
};

/// The quasi-static reference of a run: at given carrier angles, the model's stage solved with
/// the run's back end and contact options and the model's friction law at its sun speed (friction
/// at rest, docs/quasistatic.md "Friction at rest"), so that a ratio of the run to it is the
/// dynamics' part alone.
struct RestReference {
  /// The largest total tooth force per mesh over the settled positions, in the order of
  /// geometry::Stage::meshes() [N].
  std::vector<double> peak_mesh_force;
  int left_out = 0;  ///< positions whose friction fixed point did not settle, left out [-]
};

/// The reference of `model` at `count` carrier angles angle(k) [rad], k = 0..count−1, streamed:
/// each settled position is handed to `each` as it is solved (nothing is kept per position).
/// @throws std::runtime_error naming the carrier angle of a position that fails other than by its
///         friction not settling, or when no position settled.
RestReference SolveRestReference(
    const DynamicModel& model, const SimulationOptions& options, int count,
    const std::function<double(int)>& angle,
    const std::function<void(const transmission::PositionResult&)>& each = {});

/// K_v with the mesh that gives it and the quasi-static reference.
struct DynamicFactor {
  double value = std::numeric_limits<double>::quiet_NaN();  ///< K_v [-]
  int mesh = -1;                 ///< index into geometry::Stage::meshes(), −1: none
  std::string mesh_name;         ///< "sun-planet1", ...
  double peak_dynamic = 0;       ///< that mesh's largest total force in motion [N]
  double peak_quasi_static = 0;  ///< and at rest at the same angles [N]
  /// Reference positions left out because their friction fixed point did not settle [-].
  int reference_left_out = 0;
  /// The quasi-static sweep at the run's angles (its K_γ, load sharing; with the scene's
  /// stresses its root stresses and pressures).
  transmission::SweepSummary quasi_static;
  std::string source;  ///< one line: how K_v was obtained, for a rating's factor list
};

/// K_v of a run of `model` whose output steps were at times `output_times` [s] (their carrier
/// angles model.CarrierAngle(t)) with peaks `loads`: SolveRestReference at those angles.
/// @throws std::invalid_argument if `loads` has no step or its meshes are not the model's;
///         what SolveRestReference throws.
DynamicFactor DynamicLoadFactor(const DynamicModel& model, const SimulationOptions& options,
                                const std::vector<double>& output_times, const MotionLoads& loads);

/// A run's rating (docs/stresses.md "Ratings in motion"): ISO 6336 with K_γ of the quasi-static
/// reference at the run's angles and the run's K_v (the standard's K_v is ≥ 1: a run whose peaks
/// stay below the quasi-static ones is rated with 1, and the factor's source says so), beside the
/// model's own root stresses `root_stress` (the run's, DynamicSummary::root_stress) and the
/// loads' contact pressures, which carry the dynamics and take no K_v.
struct MotionRating {
  DynamicFactor factor;
  transmission::StageRating rating;
};
/// `inputs`: the rig's rating inputs (StageDynamics::rating).
/// @throws as DynamicLoadFactor and transmission::RateStage (inputs without the limits).
MotionRating RateInMotion(const transmission::RatingInputs& inputs, const DynamicModel& model,
                          const SimulationOptions& options, const std::vector<double>& output_times,
                          const MotionLoads& loads,
                          const std::vector<transmission::RootStressSummary>& root_stress);
/// RateInMotion of a run over `span` whose output steps, in order from the first, were added to
/// `loads` (a run that stopped early: the output times of the steps it made). The one rating of
/// a run that `epicycle dynamic --rating` and Python's dynamic(rating=True) give.
MotionRating RateRun(const transmission::RatingInputs& inputs, const DynamicModel& model,
                     const SimulationOptions& options, const RunSpan& span,
                     const MotionLoads& loads,
                     const std::vector<transmission::RootStressSummary>& root_stress);

}  // namespace epicycle::dynamics
