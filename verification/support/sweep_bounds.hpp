// The bounds within which two quasi-static solutions of one position may differ by where their
// stopping rules stop them (the geometric iteration's τ, the contact solver's ε): derived in
// verification/crosscheck/transmission_quasistatic_sweep.cpp's comment; shared by the sweep's
// warm-start check and the studies' warm start across cases.
#pragma once

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "epicycle/solvers/contact_problem.hpp"
#include "epicycle/solvers/contact_solver.hpp"
#include "epicycle/geometry/plane.hpp"
#include "epicycle/solvers/local_term.hpp"
#include "epicycle/transmission/quasistatic.hpp"

namespace epicycle::test {

using transmission::PositionResult;

/// The derived bounds (verification/crosscheck/transmission_quasistatic_sweep.cpp's comment) at
/// the cold result r: on the rigid displacements
/// [m, at the base circles] and on each LSR_i.
struct Bounds {
  double displacement = 0;
  std::vector<double> lsr;
};

inline Bounds DerivedBounds(const transmission::StageModel& m,
                            const transmission::QuasiStaticOptions& options, double sun_torque,
                            const PositionResult& r) {
  const solvers::ContactProblem problem(r.problem.data);
  const solvers::ContactScales scales = solvers::ComputeContactScales(problem);
  const double eps = options.contact.tolerance, tau = options.geometric_tolerance;
  Bounds b;
  b.displacement = 2.0 * (tau + eps * scales.length);
  std::vector<int> active;
  for (int j = 0; j < r.solution.force.size(); ++j)
    if (r.solution.force(j) > 0) active.push_back(j);
  const int a = static_cast<int>(active.size()), nd = static_cast<int>(m.dofs().size());
  Eigen::MatrixXd ct(a, a), ga(nd, a);
  for (int p = 0; p < a; ++p) {
    for (int q = 0; q < a; ++q) ct(p, q) = r.problem.data.compliance(active[p], active[q]);
    if (!r.problem.data.local.empty())
      ct(p, p) += solvers::LocalApproachDerivative(r.problem.data.local[active[p]],
                                                   r.solution.force(active[p]));
    ga.col(p) = r.problem.data.equality_matrix.col(active[p]);
  }
  // dF_A/dq = C_t⁻¹ G_Aᵀ, column k per DOF.
  const Eigen::MatrixXd dfdq = ct.ldlt().solve(ga.transpose());
  for (int i = 0; i < m.planets(); ++i) {
    Eigen::RowVectorXd levers = Eigen::RowVectorXd::Zero(a);
    for (int p = 0; p < a; ++p) {
      const transmission::StageContact& c = r.problem.contacts[active[p]];
      if (c.body_a == transmission::kSunBody && c.planet == i) levers(p) = c.contact.lever_a;
    }
    // The solver's force error may fall on any of the planet's sun-mesh contacts, loaded or not.
    double lever_sum = 0;
    for (const transmission::StageContact& c : r.problem.contacts)
      if (c.body_a == transmission::kSunBody && c.planet == i)
        lever_sum += std::abs(c.contact.lever_a);
    const Eigen::RowVectorXd dt = levers * dfdq;  // dT_i/dq_k
    double dtorque = 2.0 * eps * scales.force * lever_sum;
    for (int k = 0; k < nd; ++k) {
      const Eigen::VectorXd unit = Eigen::VectorXd::Unit(nd, k);
      const double per_length = 1.0 / m.DisplacementSize(m.dofs(), unit);  // 1/s_k
      dtorque += std::abs(dt(k)) * b.displacement * per_length;
    }
    b.lsr.push_back(dtorque / std::abs(sun_torque));
  }
  return b;
}

/// Largest difference of a against the reference ref, each relative to its derived bound.
struct Comparison {
  double displacement = 0, lsr = 0;              // largest |Δ|
  double displacement_ratio = 0, lsr_ratio = 0;  // largest |Δ|/bound
  int free_dofs = 0;                             // DOFs left out: no loaded contact moves them
};

inline Comparison CompareSweeps(const transmission::StageModel& model,
                                const transmission::QuasiStaticOptions& options,
                                double sun_torque, const std::vector<PositionResult>& a,
                                const std::vector<PositionResult>& ref) {
  Comparison c;
  REQUIRE(a.size() == ref.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    INFO("position " << k << " at " << geometry::Deg(ref[k].carrier_angle)
                     << " deg: " << a[k].message << " / " << ref[k].message);
    REQUIRE(a[k].converged);
    REQUIRE(ref[k].converged);
    const Bounds b = DerivedBounds(model, options, sun_torque, ref[k]);
    // Only the DOFs that equilibrium sets: a DOF that no loaded contact moves (the rotation of a
    // planet that has lost contact, free within its backlash) has no unique value.
    Eigen::VectorXd diff = a[k].displacements - ref[k].displacements;
    for (int d = 0; d < diff.size(); ++d) {
      bool set = false;
      for (int j = 0; j < ref[k].solution.force.size(); ++j)
        set =
            set || (ref[k].solution.force(j) > 0 && ref[k].problem.data.equality_matrix(d, j) != 0);
      if (!set) {
        // Only an unloaded planet's rotation may be free, and both runs must find it unloaded.
        const transmission::StageDof& dof = model.dofs()[static_cast<std::size_t>(d)];
        CHECK(dof.kind == transmission::StageDof::kPlanetRotation);
        CHECK(ref[k].load_sharing[dof.planet] == 0.0);
        CHECK(std::abs(a[k].load_sharing[dof.planet]) <= b.lsr[dof.planet]);
        diff(d) = 0;
        ++c.free_dofs;
      }
    }
    const double dq = model.DisplacementSize(model.dofs(), diff);
    c.displacement = std::max(c.displacement, dq);
    c.displacement_ratio = std::max(c.displacement_ratio, dq / b.displacement);
    for (int i = 0; i < model.planets(); ++i) {
      const double dl = std::abs(a[k].load_sharing[i] - ref[k].load_sharing[i]);
      c.lsr = std::max(c.lsr, dl);
      c.lsr_ratio = std::max(c.lsr_ratio, dl / b.lsr[i]);
    }
  }
  return c;
}

}  // namespace epicycle::test
