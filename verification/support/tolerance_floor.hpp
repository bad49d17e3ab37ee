// What an integrated run's outputs may be off by because of the integrator's tolerances: the floor
// of the dynamics tests that compare a run's outputs across speeds (dynamics_rest_friction.cpp,
// dynamics_rating.cpp).
#pragma once

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "dynamics_fixtures.hpp"
#include "epicycle/dynamics/dynamic_model.hpp"
#include "epicycle/dynamics/simulation.hpp"

namespace epicycle::test {

/// The outputs whose floor is wanted, from an evaluation of the model (appended to `out`, which
/// arrives empty); each output in the unit its test compares.
using EvaluationOutputs =
    std::function<void(const dynamics::Evaluation&, std::vector<double>& out)>;

// The largest change of an output that CVODE's error test lets through at the run's samples.
// CVODE accepts a step when its local error e has a weighted root mean square
// ‖e‖ = √(Σ_j (e_j/w_j)²/N) ≤ 1 over the N = 2n + 3 components of its state,
// w_j = rtol |y_j| + atol_j: atol_length for a translation, atol_angle for a rotation, those times
// the rate scale for their rates (the three works do not enter the forces). An output o (a load
// share, a mesh force) is a smooth function of the deviations (the contact forces through the
// compliance) and their rates (the damping and friction's surface speeds), linear at the scale of
// the tolerances (1e-10 m on deflections of micrometres: ~1e-5 of the forces), so such an error
// moves it by g·e with g = ∂o/∂y, and by Cauchy–Schwarz
//   |g·e| ≤ √N ‖g ∘ w‖₂ = √N √(Σ_j (g_j w_j)²).
// g_j w_j is taken as the difference of the model's own output after a step of w_j in y_j, at each
// sample (the contact solve's tolerance, 1e-10 of the nondimensional residual, moves the forces by
// ~1e-10 relative, below the steps' effect of ~1e-6). The bound depends on the tolerances only, not
// on how the integrator spends them (its Newton coefficient, order or step sequence change the draw
// of e within it). Returns the largest bound over the samples and the outputs.
inline double ToleranceFloor(const DynamicRig& rig, const dynamics::SimulationOptions& so,
                             double rate_scale, const std::vector<dynamics::DynamicSample>& samples,
                             const EvaluationOutputs& outputs) {
  const dynamics::DynamicModel& model = *rig.model;
  const int n = model.size();
  const double root_n = std::sqrt(2.0 * n + 3);
  auto solver = solvers::MakeContactSolver(so.backend);
  dynamics::Evaluation e;
  double floor = 0;
  std::vector<double> at, moved;  // the outputs at the sample's own state, after a step
  for (const dynamics::DynamicSample& s : samples) {
    model.Evaluate(s.time, s.d, s.v, *solver, so.contact, &s.evaluation, &e, /*energies=*/false);
    REQUIRE(e.ok);
    at.clear();
    outputs(e, at);
    std::vector<double> sum(at.size(), 0.0);
    for (int j = 0; j < 2 * n; ++j) {
      const int k = j % n;
      const double atol =
          (model.dofs()[k].axis == dynamics::MotionDof::kRotation ? so.atol_angle
                                                                  : so.atol_length) *
          (j < n ? 1.0 : rate_scale);
      Eigen::VectorXd d = s.d, v = s.v;
      double& y = j < n ? d(k) : v(k);
      const double w = so.rtol * std::abs(y) + atol;
      y += w;
      model.Evaluate(s.time, d, v, *solver, so.contact, &s.evaluation, &e, /*energies=*/false);
      REQUIRE(e.ok);
      moved.clear();
      outputs(e, moved);
      REQUIRE(moved.size() == at.size());
      for (std::size_t i = 0; i < sum.size(); ++i)
        sum[i] += (moved[i] - at[i]) * (moved[i] - at[i]);
    }
    for (double s2 : sum) floor = std::max(floor, root_n * std::sqrt(s2));
  }
  return floor;
}

}  // namespace epicycle::test
