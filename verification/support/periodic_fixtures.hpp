// Shared pieces of the periodic solver's tests (docs/periodic.md §3): the tight tolerances of the
// small systems with closed forms, and the integrator's tolerance of a state.
#pragma once

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

}  // namespace epicycle::test
