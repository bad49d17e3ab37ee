// Must-show 1: every available back end reproduces the closed-form cases to 1e-8 relative in
// forces and multipliers. The references are computed here from the problem data (bisection on
// the scalar equation, statics by hand), independently of the generator's `expected` block.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>

#include "epicycle/solvers/contact_io.hpp"
#include "epicycle/solvers/contact_solver.hpp"
#include "epicycle/solvers/local_term.hpp"
#include "figures.hpp"
#include "solvers_support.hpp"

namespace epicycle::solvers {
namespace {

double Bisect(double c, const LocalTermParameters& p, double d) {
  double lo = 0.0, hi = d / c;  // c·hi + u(hi) ≥ d
  while (hi - lo > 1e-15 * hi) {
    const double mid = 0.5 * (lo + hi);
    (c * mid + LocalApproach(p, mid) > d ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

ContactSolution Reference(const ContactProblemData& d) {
  ContactSolution s;
  const std::string& name = d.name;
  s.multiplier = Eigen::VectorXd::Zero(d.equality_rhs.size());
  if (name == "cf_one_contact_overlap") {
    s.force = Eigen::VectorXd::Constant(1, Bisect(d.compliance(0, 0), d.local[0], d.overlap(0)));
  } else if (name == "cf_one_contact_load") {
    const double f = d.equality_rhs(0) / d.equality_matrix(0, 0);
    s.force = Eigen::VectorXd::Constant(1, f);
    s.multiplier(0) = (d.compliance(0, 0) * f + LocalApproach(d.local[0], f) - d.overlap(0)) /
                      d.equality_matrix(0, 0);
  } else if (name == "cf_one_contact_open") {
    s.force = Eigen::VectorXd::Zero(1);
  } else if (name == "cf_two_symmetric") {
    const double p = d.equality_rhs(0) / 2.0;
    s.force = Eigen::VectorXd::Constant(2, p);
    s.multiplier(0) =
        (d.compliance(0, 0) + d.compliance(0, 1)) * p + LocalApproach(d.local[0], p) - d.overlap(0);
  } else if (name == "cf_two_symmetric_overlap") {
    s.force = Eigen::VectorXd::Constant(
        2, Bisect(d.compliance(0, 0) + d.compliance(0, 1), d.local[0], d.overlap(0)));
  } else if (name == "cf_linear_springs") {
    // Contact 3 open: F1 + F2 = P, r1 F1 + r2 F2 = M; closed gaps c_j F_j − δ0_j = λ1 + r_j λ2.
    const double p = d.equality_rhs(0), m = d.equality_rhs(1);
    const double r1 = d.equality_matrix(1, 0), r2 = d.equality_matrix(1, 1);
    const double f1 = (m - r2 * p) / (r1 - r2), f2 = p - f1;
    const double a1 = d.compliance(0, 0) * f1 - d.overlap(0),
                 a2 = d.compliance(1, 1) * f2 - d.overlap(1);
    s.force = Eigen::Vector3d(f1, f2, 0.0);
    s.multiplier(1) = (a1 - a2) / (r1 - r2);
    s.multiplier(0) = a1 - r1 * s.multiplier(1);
  } else if (name == "cf_elastic_support") {
    const double c = d.compliance(0, 0), sc = d.support_stiffness(0, 0);
    const double f = (d.equality_rhs(0) + sc * d.overlap(0)) / (1.0 + sc * c);
    s.force = Eigen::VectorXd::Constant(1, f);
    s.multiplier(0) = c * f - d.overlap(0);
  } else {
    FAIL("no closed form written for " << name);
  }
  return s;
}

}  // namespace

TEST_CASE("every available back end matches the closed-form cases to 1e-8",
          "[crosscheck][solvers]") {
  const auto table = test::ReadExpectedFailures();
  int cases = 0;
  std::map<Backend, std::pair<int, double>> per_backend;  // converged cases, worst difference
  for (const std::string& path : test::CollectionFiles()) {
    const ContactProblemFile file = ReadContactProblemFile(path);
    if (file.category != "closed-form") continue;
    ++cases;
    const ContactProblem problem(file.data);
    const ContactSolution ref = Reference(file.data);
    for (Backend b : AvailableBackends()) {
      ContactOptions options;  // tolerance 1e-10 on the residual
      ContactSolution sol;
      const ContactReport r = MakeContactSolver(b)->Solve(problem, options, &sol);
      INFO(BackendName(b) << " on " << problem.name() << ": " << r.message);
      REQUIRE(sol.force.allFinite());
      REQUIRE(sol.multiplier.allFinite());
      if (r.status != ContactStatus::kConverged) {
        CHECK(test::IsExpected(table, b, problem.name(), "not-converged"));
        continue;
      }
      CHECK(r.residual.total <= options.tolerance);
      const SolutionDifference diff = CompareSolutions(problem, sol, ref);
      CHECK(diff.force <= 1e-8);
      CHECK(diff.multiplier <= 1e-8);
      auto& [n, worst] = per_backend[b];
      ++n;
      worst = std::max({worst, diff.force, diff.multiplier});
    }
  }
  CHECK(cases == 7);
  for (const auto& [b, figures] : per_backend) {
    epicycle::test::VerifyRow("closed-form contact problems: " + BackendName(b) + " (" +
                                  std::to_string(figures.first) + " of 7 converged)",
                              "statics and bisection written in the test",
                              "worst relative difference " + epicycle::test::Sci(figures.second),
                              epicycle::test::Sci(figures.second), "1e-8", figures.second <= 1e-8);
  }
}

}  // namespace epicycle::solvers
