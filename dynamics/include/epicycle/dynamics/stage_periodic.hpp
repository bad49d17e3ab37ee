// The stage's dynamic model (docs/model.md §7) as a PeriodicSystem (docs/periodic.md §1): the
// state y = (d, ḋ), the deviations from the rigid kinematics and their rates; f from
// DynamicModel::Evaluate (the contact solve warm-started from the last evaluation), ∂f/∂y from
// DynamicModel::Jacobian (frozen contact geometry: an approximation, which slows the shooting's
// Newton but does not change the orbit it converges to).
//
// The period (docs/periodic.md §3, "The stage's period"): k mesh cycles in the carrier frame,
// T = k 2π/(z_r |ω_c|), k from StagePeriodMeshCycles (1 for a stage whose errors repeat with the
// mesh). Over T the carrier advances Δφ_c = sign(ω_c) k 2π/z_r; the stage's translations, in the
// inertial frame, repeat turned by Δφ_c (isotropic bearings, no gravity: the equations commute
// with a rotation of the plane), so the period map S (PeriodicSystem::PeriodMap) turns every
// (x, y) pair of deviations and of their rates back by Δφ_c; rotations are left alone.
//
// Parameters (the scene's keys, so that a continuation names them as a scene file does):
//   sun_speed_rpm       [rpm]   the sun's speed (DynamicSettings::sun_speed; T depends on it)
//   sun_torque_Nm       [N·m]   the input torque T_s (StageLoads::sun_torque)
//   mesh_damping_ratio  [-]     ζ of the mesh damping (DynamicSettings::mesh_damping_ratio)
// and, when the system is made for one (StageErrorKey), a fourth: an error's amplitude named by its
// scene key path, errors.pin.planetK.radial_um / tangential_um or errors.runout.GEAR.amplitude_um
// [µm]. A parameter value other than the base model's builds a DynamicModel with it over the same
// stage model (an error's value: over a stage model of a geometry::Stage rebuilt with it, the same
// compliance and setup), the base's mean mesh stiffnesses (so c_m = 2ζ√(k_m m_eq) with the base's
// k_m) and start angle; the last few are kept, since the continuation's parameter derivative
// evaluates f at λ ± h in turn.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "epicycle/dynamics/dynamic_model.hpp"
#include "epicycle/dynamics/periodic.hpp"
#include "epicycle/transmission/damage.hpp"

namespace epicycle::dynamics {

/// The stage's period in mesh cycles and why.
struct StagePeriod {
  /// k: the least number of mesh cycles after which every error and damaged tooth is back where
  /// it was relative to the carrier, up to the turn of the whole plane by the carrier's advance
  /// [-]; ≥ 1.
  long mesh_cycles = 1;
  std::vector<std::string> reasons;  ///< "planet1 run-out: 24 mesh cycles", ... (empty: k = 1)
};

/// The common period of the mesh and the rotations that the stage's errors and damage need
/// (docs/periodic.md §3, "The stage's period"). Over k mesh cycles the sun turns relative to the
/// carrier by 2πk/z_s and a planet by −2πk/z_p; a run-out or a damaged tooth on one of them is
/// back when that turn is whole (z_s | k, z_p | k). The ring is held: its run-out or damaged
/// tooth stays put in the inertial frame, which the period map does not turn, so it needs
/// whole carrier turns (z_r | k). k is the lcm of what the stage has. Pin and thickness errors
/// are fixed in the carrier frame (k = 1).
StagePeriod StagePeriodMeshCycles(const geometry::Stage& stage, const transmission::Damage& damage);
/// The same from the stage's spec (the tooth counts and errors are all it reads).
StagePeriod StagePeriodMeshCycles(const geometry::StageSpec& spec,
                                  const transmission::Damage& damage);

/// An error amplitude of the scene that a branch continues by rebuilding the stage's geometry per
/// value (docs/periodic.md §3, "Continued scene numbers"): its key path and what it sets.
struct StageErrorKey {
  enum class Kind { kPinRadial, kPinTangential, kRunout };
  std::string key;  ///< "errors.pin.planet1.tangential_um", "errors.runout.sun.amplitude_um"
  Kind kind = Kind::kPinTangential;
  int gear = 0;  ///< 0-based planet index; −1 the sun, −2 the ring (run-outs)
  /// The key's value in `spec` [µm] (0 when the scene has no such error).
  double Value(const geometry::StageSpec& spec) const;
  /// `spec` with the value [µm] written in (the error lists sized to the planets if empty).
  void Set(geometry::StageSpec* spec, double value_um) const;
};

/// The error key `name` names: errors.pin.planetK.radial_um, errors.pin.planetK.tangential_um or
/// errors.runout.GEAR.amplitude_um (GEAR sun, ring, planetK), K = 1..planets; none for any other
/// name (a planet out of range included).
std::optional<StageErrorKey> ParseStageErrorKey(const std::string& name, int planets);

class StagePeriodicSystem : public PeriodicSystem {
 public:
  static constexpr const char* kSunSpeed = "sun_speed_rpm";
  static constexpr const char* kSunTorque = "sun_torque_Nm";
  static constexpr const char* kMeshDampingRatio = "mesh_damping_ratio";
  /// The parameters' names in order, as parameters() gives them.
  static std::vector<std::string> ParameterNames() {
    return {kSunSpeed, kSunTorque, kMeshDampingRatio};
  }

  /// `model` must outlive this object. `mesh_cycles` k ≥ 1 (StagePeriodMeshCycles). `error`: the
  /// fourth parameter, an error amplitude (none: the three above only).
  /// @throws std::invalid_argument for mesh_cycles < 1.
  StagePeriodicSystem(const DynamicModel& model, solvers::Backend backend,
                      solvers::ContactOptions contact, long mesh_cycles = 1,
                      std::optional<StageErrorKey> error = std::nullopt);
  int size() const override { return 2 * base_.size(); }
  std::vector<PeriodicParameter> parameters() const override;
  double Period(const Eigen::VectorXd& p) const override;
  Eigen::MatrixXd PeriodMap(const Eigen::VectorXd& p) const override;
  bool Rhs(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& p,
           Eigen::VectorXd* f) const override;
  bool has_jacobian() const override { return true; }
  bool Jacobian(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& p,
                Eigen::MatrixXd* jac) const override;
  long evaluations() const { return evaluations_; }  ///< Evaluate calls so far [-]
  long mesh_cycles() const { return mesh_cycles_; }  ///< k [-]
  /// Geometries rebuilt for an error's value so far (each a geometry::Stage, its stage model and
  /// dynamic model) [-].
  long rebuilds() const { return rebuilds_; }
  /// The dynamic model at parameters p (the base model's when p is empty or its defaults).
  /// @throws std::invalid_argument as DynamicModel's constructor for a value it refuses.
  const DynamicModel& ModelAt(const Eigen::VectorXd& p) const;

 private:
  // One evaluation at (t, y; p) into *at, warm-started from the last; false if it failed.
  bool EvaluateAt(const DynamicModel& model, double t, const Eigen::VectorXd& y,
                  Evaluation* at) const;
  bool IsWarm(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& p) const;

  const DynamicModel& base_;
  Eigen::VectorXd defaults_;
  solvers::ContactOptions contact_;
  long mesh_cycles_ = 1;
  std::optional<StageErrorKey> error_;
  // The integrator calls Rhs and Jacobian in turn on one thread: the contact solver, the warm
  // start and the models at other parameter values are state of the calls, not of the system.
  std::unique_ptr<solvers::ContactSolver> solver_;
  struct Cached {
    Eigen::VectorXd p;
    // An error's value: the stage rebuilt with it and its stage model, which `model` refers to.
    std::unique_ptr<geometry::Stage> stage;
    std::unique_ptr<transmission::StageModel> stage_model;
    std::unique_ptr<DynamicModel> model;
  };
  mutable std::vector<Cached> models_;  // most recently used first
  mutable Evaluation warm_, scratch_;
  mutable bool warm_valid_ = false;
  // Where warm_ was evaluated: a Jacobian at that very state (the periodic solver asks for f and
  // then ∂f/∂y at each state of the variational equations) reads it instead of solving again.
  mutable double warm_t_ = 0;
  mutable Eigen::VectorXd warm_y_, warm_p_;
  mutable long evaluations_ = 0;
  mutable long rebuilds_ = 0;
};

}  // namespace epicycle::dynamics
