// The stage's dynamic model (docs/model.md §7) as a PeriodicSystem (docs/periodic.md §1): the
// state y = (d, ḋ), the deviations from the rigid kinematics and their rates; f from
// DynamicModel::Evaluate (the contact solve warm-started from the last evaluation), ∂f/∂y from
// DynamicModel::Jacobian (frozen contact geometry: an approximation, which slows the shooting's
// Newton but does not change the orbit it converges to); the period the mesh cycle in the carrier
// frame, T = 2π/(z_r |ω_c|), for a stage whose errors repeat with the mesh and whose coordinates
// do (checked by the caller: translations in the inertial frame of members that move with the
// carrier do not). No parameters.
#pragma once

#include <memory>

#include "epicycle/dynamics/dynamic_model.hpp"
#include "epicycle/dynamics/periodic.hpp"

namespace epicycle::dynamics {

class StagePeriodicSystem : public PeriodicSystem {
 public:
  /// `model` must outlive this object.
  StagePeriodicSystem(const DynamicModel& model, solvers::Backend backend,
                      solvers::ContactOptions contact);
  int size() const override { return 2 * model_.size(); }
  std::vector<PeriodicParameter> parameters() const override { return {}; }
  double Period(const Eigen::VectorXd& p) const override;
  bool Rhs(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& p,
           Eigen::VectorXd* f) const override;
  bool has_jacobian() const override { return true; }
  bool Jacobian(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& p,
                Eigen::MatrixXd* jac) const override;
  long evaluations() const { return evaluations_; }  ///< Evaluate calls so far [-]

 private:
  // One evaluation at (t, y) into *at, warm-started from the last; false if it failed.
  bool EvaluateAt(double t, const Eigen::VectorXd& y, Evaluation* at) const;

  const DynamicModel& model_;
  solvers::ContactOptions contact_;
  // The integrator calls Rhs and Jacobian in turn on one thread: the contact solver and the warm
  // start are state of the calls, not of the system.
  std::unique_ptr<solvers::ContactSolver> solver_;
  mutable Evaluation warm_, scratch_;
  mutable bool warm_valid_ = false;
  // Where warm_ was evaluated: a Jacobian at that very state (the periodic solver asks for f and
  // then ∂f/∂y at each state of the variational equations) reads it instead of solving again.
  mutable double warm_t_ = 0;
  mutable Eigen::VectorXd warm_y_;
  mutable long evaluations_ = 0;
};

}  // namespace epicycle::dynamics
