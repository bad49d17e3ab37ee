// Shared pieces of the periodic solver's tests (docs/periodic.md §3): the tight tolerances of the
// small systems with closed forms, the integrator's tolerance of a state, and a system read on a
// clock started at another phase of its period.
#pragma once

#include <vector>

#include <Eigen/Dense>

#include "epicycle/dynamics/periodic.hpp"

namespace epicycle::test {

/// rtol 1e-10, atol 1e-12: the closed-form systems' shooting.
inline dynamics::ShootingOptions TightShooting() {
  dynamics::ShootingOptions o;
  o.rtol = 1e-10;
  o.atol = Eigen::VectorXd::Constant(1, 1e-12);
  return o;
}

/// The integrator's tolerance of a state, rtol |y|_∞ + max atol.
inline double ShootingWeight(const dynamics::ShootingOptions& o, const Eigen::VectorXd& y) {
  return o.rtol * y.cwiseAbs().maxCoeff() + o.atol.maxCoeff();
}

// The system on a clock started at t = φT (φ = `fraction`): f_φ(t, y; p) = f(t + φT, y; p). A
// non-autonomous orbit is pinned to its forcing's phase, so "another point of the orbit" is the
// orbit's state at another phase of the forcing: shooting f_φ solves for the state at t = φT of
// the same orbit, and its monodromy Φ(φT + T, φT) = Φ(φT) M Φ(φT)⁻¹ is similar to M.
class PhaseShifted final : public dynamics::PeriodicSystem {
 public:
  PhaseShifted(const dynamics::PeriodicSystem& base, double fraction)
      : base_(base), fraction_(fraction) {}
  int size() const override { return base_.size(); }
  std::vector<dynamics::PeriodicParameter> parameters() const override {
    return base_.parameters();
  }
  double Period(const Eigen::VectorXd& p) const override { return base_.Period(p); }
  bool Rhs(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& p,
           Eigen::VectorXd* f) const override {
    return base_.Rhs(t + fraction_ * base_.Period(p), y, p, f);
  }
  bool has_jacobian() const override { return base_.has_jacobian(); }
  bool Jacobian(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& p,
                Eigen::MatrixXd* jac) const override {
    return base_.Jacobian(t + fraction_ * base_.Period(p), y, p, jac);
  }
  Eigen::MatrixXd PeriodMap(const Eigen::VectorXd& p) const override { return base_.PeriodMap(p); }

 private:
  const dynamics::PeriodicSystem& base_;
  double fraction_;
};

}  // namespace epicycle::test
