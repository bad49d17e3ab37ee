#include "epicycle/dynamics/stage_periodic.hpp"

#include <cmath>
#include <utility>

namespace epicycle::dynamics {

StagePeriodicSystem::StagePeriodicSystem(const DynamicModel& model, solvers::Backend backend,
                                         solvers::ContactOptions contact)
    : model_(model), contact_(std::move(contact)), solver_(solvers::MakeContactSolver(backend)) {}

double StagePeriodicSystem::Period(const Eigen::VectorXd&) const {
  return model_.stage_model().stage().mesh_cycle() / std::abs(model_.carrier_speed());
}

bool StagePeriodicSystem::EvaluateAt(double t, const Eigen::VectorXd& y, Evaluation* at) const {
  const int n = model_.size();
  model_.Evaluate(t, y.head(n), y.tail(n), *solver_, contact_, warm_valid_ ? &warm_ : nullptr, at,
                  /*energies=*/false);
  ++evaluations_;
  return at->ok;
}

bool StagePeriodicSystem::Rhs(double t, const Eigen::VectorXd& y, const Eigen::VectorXd&,
                              Eigen::VectorXd* f) const {
  if (!EvaluateAt(t, y, &scratch_)) return false;
  const int n = model_.size();
  f->head(n) = y.tail(n);
  f->tail(n) = scratch_.acceleration;
  std::swap(warm_, scratch_);
  warm_valid_ = true;
  warm_t_ = t;
  warm_y_ = y;
  return true;
}

bool StagePeriodicSystem::Jacobian(double t, const Eigen::VectorXd& y, const Eigen::VectorXd&,
                                   Eigen::MatrixXd* jac) const {
  if (!(warm_valid_ && t == warm_t_ && y == warm_y_)) {
    if (!EvaluateAt(t, y, &scratch_)) return false;
    std::swap(warm_, scratch_);
    warm_valid_ = true;
    warm_t_ = t;
    warm_y_ = y;
  }
  const int n = model_.size();
  Eigen::MatrixXd dd, dv;
  model_.Jacobian(t, y.head(n), y.tail(n), warm_, &dd, &dv);
  jac->setZero(2 * n, 2 * n);
  jac->topRightCorner(n, n).setIdentity();
  jac->bottomLeftCorner(n, n) = dd;
  jac->bottomRightCorner(n, n) = dv;
  return jac->allFinite();
}

}  // namespace epicycle::dynamics
