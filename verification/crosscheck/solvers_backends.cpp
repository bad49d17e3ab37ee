// The Ipopt and NLopt back ends against closed-form contact problems, through the public
// MakeContactSolver(...)->Solve(...).
//
// Every case here has an independent answer written out by hand (a linear spring, a 2×2 or 3×3
// KKT system on a known active set, a symmetric pair, the local term evaluated from docs/model.md §4 at
// a chosen force). The solves run at the driver tolerance kTol = 1e-10 on the nondimensional
// residual. For a linear problem on a fixed active set the error is bounded by ‖K̃⁻¹‖∞ · residual,
// with K̃ the active-set KKT matrix in the driver's units (C divided by its largest diagonal entry,
// rows of G by their largest entry, forces of order one); each case computes that bound and
// requires it to lie below the acceptance figure kAccept = 1e-8 (relative, forces and
// multipliers), which is then asserted.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "epicycle/solvers/contact_problem.hpp"
#include "epicycle/solvers/contact_solver.hpp"

namespace {

using epicycle::solvers::Backend;
using epicycle::solvers::BackendName;
using epicycle::solvers::ContactOptions;
using epicycle::solvers::ContactProblem;
using epicycle::solvers::ContactProblemData;
using epicycle::solvers::ContactReport;
using epicycle::solvers::ContactSolution;
using epicycle::solvers::ContactStatus;
using epicycle::solvers::LocalTermParameters;
using epicycle::solvers::MakeContactSolver;
using epicycle::solvers::PlaneAssumption;
using epicycle::solvers::StatusName;

constexpr double kTol = 1e-10;    // driver residual tolerance used for every solve here
constexpr double kAccept = 1e-8;  // issue 3, "must show" 1: relative error in F and λ
constexpr double kPi = 3.14159265358979323846;

const std::vector<Backend> kBackends = {Backend::kIpopt, Backend::kNloptSlsqp, Backend::kNloptLbfgs,
                                        Backend::kNloptAuglag};

double RelativeError(const Eigen::VectorXd& got, const Eigen::VectorXd& want) {
  if (want.size() == 0) return got.size() == 0 ? 0.0 : 1.0;
  if (got.size() != want.size()) return 1.0;
  return (got - want).cwiseAbs().maxCoeff() / want.cwiseAbs().maxCoeff();
}

// Forward-error bound of an answer whose nondimensional residual is r, for a problem with the
// given active set (strict complementarity). In the driver's units (documented in
// solvers/src/backend.hpp: rows of G divided by r_i = max_j |G_ij|, force scale F* = max_i
// |W_i|/r_i, or max δ0⁺ / c_max without loads, length scale ℓ* = F*·c_max), the active-set KKT
// matrix is
//   K̃ = [ C_AA/c_max + diag(u'_A)/c_max   −G̃_Aᵀ ]
//       [ G̃_A                              S̃    ],
// an inactive contact's force is itself bounded by r, and its coupling adds ‖C̃_AI‖∞ r to the
// active rows, so ‖(Δx̃, Δλ̃)‖∞ ≤ ‖K̃⁻¹‖∞ (1 + ‖C̃_AI‖∞) r. Divided by ‖x̃‖∞ and ‖λ̃‖∞ this gives
// relative bounds for F and λ per unit residual.
struct ErrorBound {
  double force_per_residual = 0;       // relative error in F per unit residual
  double multiplier_per_residual = 0;  // relative error in λ per unit residual
};

ErrorBound ScaledErrorBound(const ContactProblemData& d, const Eigen::VectorXd& force,
                            const Eigen::VectorXd& multiplier,
                            const Eigen::VectorXd& local_slope = Eigen::VectorXd()) {
  const int n = static_cast<int>(force.size());
  const int m = static_cast<int>(d.equality_rhs.size());
  std::vector<int> active, inactive;
  for (int j = 0; j < n; ++j) (force(j) > 0 ? active : inactive).push_back(j);
  const int a = static_cast<int>(active.size());
  const double c_max = d.compliance.diagonal().maxCoeff();
  Eigen::VectorXd r = Eigen::VectorXd::Ones(m);
  for (int i = 0; i < m; ++i) r(i) = d.equality_matrix.row(i).cwiseAbs().maxCoeff();
  double f_scale = 0;
  for (int i = 0; i < m; ++i) f_scale = std::max(f_scale, std::abs(d.equality_rhs(i)) / r(i));
  if (f_scale == 0) f_scale = d.overlap.maxCoeff() / c_max;
  const double l_scale = f_scale * c_max;

  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(a + m, a + m);
  for (int p = 0; p < a; ++p) {
    for (int q = 0; q < a; ++q) k(p, q) = d.compliance(active[p], active[q]) / c_max;
    if (local_slope.size() > 0) k(p, p) += local_slope(active[p]) / c_max;
    for (int i = 0; i < m; ++i) {
      k(p, a + i) = -d.equality_matrix(i, active[p]) / r(i);
      k(a + i, p) = d.equality_matrix(i, active[p]) / r(i);
    }
  }
  if (d.support_stiffness.size() > 0) {
    for (int i = 0; i < m; ++i) {
      for (int l = 0; l < m; ++l) {
        k(a + i, a + l) = d.support_stiffness(i, l) * l_scale / (f_scale * r(i) * r(l));
      }
    }
  }
  double coupling = 0;
  for (int p = 0; p < a; ++p) {
    double row = 0;
    for (int q : inactive) row += std::abs(d.compliance(active[p], q)) / c_max;
    coupling = std::max(coupling, row);
  }
  const double kappa = k.inverse().cwiseAbs().rowwise().sum().maxCoeff() * (1.0 + coupling);
  ErrorBound bound;
  bound.force_per_residual = kappa / (force.cwiseAbs().maxCoeff() / f_scale);
  if (m > 0) {
    const Eigen::VectorXd scaled_lambda = r.cwiseProduct(multiplier) / l_scale;
    bound.multiplier_per_residual = kappa / scaled_lambda.cwiseAbs().maxCoeff();
  }
  return bound;
}

// u_local(F) of one contact from docs/model.md §4 (plane strain), written out independently of the
// library: Σ_B 2k_B F/(πb) [asinh(h_B/L) − c_B (h_B/L)(√(1+(h_B/L)²) − h_B/L)].
double LocalApproachByHand(const LocalTermParameters& p, double force) {
  double k[2], c[2];
  for (int b = 0; b < 2; ++b) {
    const double nu = p.body[b].poisson_ratio;
    k[b] = (1.0 - nu * nu) / p.body[b].youngs_modulus;
    c[b] = nu / (1.0 - nu);
  }
  const double e_star = 1.0 / (k[0] + k[1]);
  const double len = std::sqrt(4.0 * force * p.reduced_radius / (kPi * p.face_width * e_star));
  double u = 0.0;
  for (int b = 0; b < 2; ++b) {
    const double s = p.body[b].depth / len;
    u += 2.0 * k[b] * force / (kPi * p.face_width) *
         (std::asinh(s) - c[b] * s * (std::sqrt(1.0 + s * s) - s));
  }
  return u;
}

LocalTermParameters SteelPair(double depth) {
  LocalTermParameters p;
  p.enabled = true;
  p.face_width = 0.02;
  p.reduced_radius = 0.01;
  p.plane = PlaneAssumption::kPlaneStrain;
  for (auto& body : p.body) {
    body.youngs_modulus = 210e9;
    body.poisson_ratio = 0.3;
    body.depth = depth;
  }
  return p;
}

ContactReport SolveWith(Backend backend, const ContactProblem& problem, ContactSolution* out,
                        const ContactOptions& options = {}) {
  ContactOptions o = options;
  o.tolerance = kTol;
  auto solver = MakeContactSolver(backend);
  return solver->Solve(problem, o, out);
}

// L-BFGS and CCSAQ (inside AUGLAG) decide every step by comparing objective values. Near the
// answer a step that reduces the residual to r lowers Φ by only ~r² (Φ is O(1) in the driver's
// units), which drops below the rounding of Φ itself (≈ 1e-16) once r ≲ 1e-8. The back end's
// re-centred second pass (backend_nlopt.cpp) removes most of that floor, not all of it: on
// three of these cases they still stop at residuals 3e-10…3e-9, short of kTol = 1e-10. Their
// expected outcome at kTol is therefore "converged" or "converged-inaccurate" (residual ≤
// 100·kTol) with the error the residual allows; Ipopt and SLSQP must reach "converged".
bool RoundoffLimitedAtTightTolerance(Backend backend) {
  return backend == Backend::kNloptLbfgs || backend == Backend::kNloptAuglag;
}

// Checks one solve against the closed form: never NaN; the status expected of the back end; the
// error within what the driver's own residual allows (ErrorBound) and, once converged, within
// kAccept.
void CheckSolve(Backend backend, const ContactReport& report, const ContactSolution& solution,
                const Eigen::VectorXd& force, const Eigen::VectorXd& multiplier,
                const ErrorBound& bound) {
  INFO("status " << StatusName(report.status) << ": " << report.message);
  CHECK(solution.force.allFinite());
  CHECK(solution.multiplier.allFinite());
  if (RoundoffLimitedAtTightTolerance(backend)) {
    CHECK((report.status == ContactStatus::kConverged ||
           report.status == ContactStatus::kConvergedInaccurate));
  } else {
    CHECK(report.status == ContactStatus::kConverged);
  }
  const double r = report.residual.total;
  // 1.01 and 1e-13: second-order terms and the rounding of the closed-form reference.
  CHECK(RelativeError(solution.force, force) <= 1.01 * bound.force_per_residual * r + 1e-13);
  CHECK(RelativeError(solution.multiplier, multiplier) <=
        1.01 * bound.multiplier_per_residual * r + 1e-13);
  if (report.status == ContactStatus::kConverged) {
    CHECK(RelativeError(solution.force, force) <= kAccept);
    CHECK(RelativeError(solution.multiplier, multiplier) <= kAccept);
  }
}

// Runs every available back end on a problem with a known answer. nlopt-lbfgs is expected to
// decline problems with equalities (a failed status, never "converged").
void CheckAgainst(const ContactProblemData& data, const Eigen::VectorXd& force,
                  const Eigen::VectorXd& multiplier,
                  const Eigen::VectorXd& local_slope = Eigen::VectorXd()) {
  const ErrorBound bound = ScaledErrorBound(data, force, multiplier, local_slope);
  // A converged answer (r ≤ kTol) is then guaranteed within the 1e-8.
  REQUIRE(bound.force_per_residual * kTol <= kAccept);
  REQUIRE(bound.multiplier_per_residual * kTol <= kAccept);
  const ContactProblem problem(data);
  for (Backend backend : kBackends) {
    auto solver = MakeContactSolver(backend);
    INFO("back end " << BackendName(backend) << ", case " << data.name);
    ContactSolution solution;
    if (!solver->available()) {
      // Compiled out (*_unavailable.cpp): a status saying so, finite zeros, never "converged".
      const ContactReport report = SolveWith(backend, problem, &solution);
      CHECK(report.status == ContactStatus::kBackendUnavailable);
      CHECK(solution.force.allFinite());
      continue;
    }
    const ContactReport report = SolveWith(backend, problem, &solution);
    if (backend == Backend::kNloptLbfgs && data.equality_rhs.size() > 0) {
      INFO("status " << StatusName(report.status) << ": " << report.message);
      CHECK(solution.force.allFinite());
      CHECK(solution.multiplier.allFinite());
      CHECK(report.status != ContactStatus::kConverged);
      CHECK(report.message.find("only problems without equalities") != std::string::npos);
      continue;
    }
    CheckSolve(backend, report, solution, force, multiplier, bound);
  }
}

// du_local/dF by a central difference of LocalApproachByHand (only enters the error bound).
double LocalSlopeByHand(const LocalTermParameters& p, double force) {
  const double h = 1e-4 * force;
  return (LocalApproachByHand(p, force + h) - LocalApproachByHand(p, force - h)) / (2 * h);
}

}  // namespace

TEST_CASE("Ipopt and NLopt back ends: one contact, linear spring, SI magnitudes",
          "[crosscheck][solvers][backends]") {
  // c F = δ0 → F = δ0/c = 16 kN.
  ContactProblemData d;
  d.name = "one-spring";
  d.compliance = Eigen::MatrixXd::Constant(1, 1, 2.5e-9);  // [m/N]
  d.overlap = Eigen::VectorXd::Constant(1, 4e-5);          // [m]
  CheckAgainst(d, Eigen::VectorXd::Constant(1, 16000.0), Eigen::VectorXd());
}

TEST_CASE("Ipopt and NLopt back ends: three contacts without equalities, one opens",
          "[crosscheck][solvers][backends]") {
  // Active set {0, 1}: C_AA F_A = δ0_A, with C_AA = c[[4, 1], [1, 3]] → F_A = C_AA⁻¹ δ0_A by
  // Cramer's rule; contact 2's gap c(F_0 + F_1) − δ0_2 must be positive.
  const double c = 1e-9;
  ContactProblemData d;
  d.name = "three-one-open";
  d.compliance.resize(3, 3);
  d.compliance << 4, 1, 1, 1, 3, 1, 1, 1, 5;
  d.compliance *= c;
  d.overlap = Eigen::Vector3d(5e-6, 4e-6, -2e-6);
  const double det = c * c * (4 * 3 - 1 * 1);
  const double f0 = (d.overlap(0) * 3 * c - 1 * c * d.overlap(1)) / det;
  const double f1 = (4 * c * d.overlap(1) - 1 * c * d.overlap(0)) / det;
  REQUIRE(f0 > 0);
  REQUIRE(f1 > 0);
  REQUIRE(c * (f0 + f1) - d.overlap(2) > 0);  // contact 2 open
  CheckAgainst(d, Eigen::Vector3d(f0, f1, 0.0), Eigen::VectorXd());
}

TEST_CASE("Ipopt and NLopt back ends: two contacts sharing one load (one equality)",
          "[crosscheck][solvers][backends]") {
  // C F − λ 1 = δ0, F_0 + F_1 = P; with C = c[[2, 1], [1, 3]], C⁻¹ = [[3, −1], [−1, 2]]/(5c):
  //   λ = (P − 1ᵀC⁻¹δ0)/(1ᵀC⁻¹1),  1ᵀC⁻¹1 = 3/(5c),  F = C⁻¹(δ0 + λ1).
  const double c = 1e-9, p = 3000.0;
  ContactProblemData d;
  d.name = "two-one-equality";
  d.compliance.resize(2, 2);
  d.compliance << 2 * c, c, c, 3 * c;
  d.overlap = Eigen::Vector2d(1e-6, 2e-6);
  d.equality_matrix = Eigen::MatrixXd::Ones(1, 2);
  d.equality_rhs = Eigen::VectorXd::Constant(1, p);
  const auto c_inv = [&](double a, double b) {
    return Eigen::Vector2d((3 * a - b) / (5 * c), (-a + 2 * b) / (5 * c));
  };
  const double lambda = (p - c_inv(d.overlap(0), d.overlap(1)).sum()) / (3.0 / (5.0 * c));
  const Eigen::Vector2d force = c_inv(d.overlap(0) + lambda, d.overlap(1) + lambda);
  REQUIRE(force.minCoeff() > 0);
  CheckAgainst(d, force, Eigen::VectorXd::Constant(1, lambda));
}

TEST_CASE("Ipopt and NLopt back ends: one equality, the second contact opens",
          "[crosscheck][solvers][backends]") {
  // Contact 1 carries everything: F = (P, 0), λ = C_00 P − δ0_0; gap_1 = C_10 P − δ0_1 − λ > 0.
  const double c = 1e-9, p = 2000.0;
  ContactProblemData d;
  d.name = "two-one-equality-open";
  d.compliance.resize(2, 2);
  d.compliance << 2 * c, c, c, 3 * c;
  d.overlap = Eigen::Vector2d(0.0, -5 * c * p);
  d.equality_matrix = Eigen::MatrixXd::Ones(1, 2);
  d.equality_rhs = Eigen::VectorXd::Constant(1, p);
  const double lambda = 2 * c * p - d.overlap(0);
  REQUIRE(c * p - d.overlap(1) - lambda > 0);
  CheckAgainst(d, Eigen::Vector2d(p, 0.0), Eigen::VectorXd::Constant(1, lambda));
}

TEST_CASE("Ipopt and NLopt back ends: elastic support (G F + S λ = W)",
          "[crosscheck][solvers][backends]") {
  // One contact on a member held by a spring of compliance s: c F − δ0 − λ = 0 and F + s λ = P,
  // so F = (P + s δ0)/(1 + s c), λ = c F − δ0. Exercises the y variables (λ = y on range S).
  const double c = 2e-9, s = 3e-9, p = 1000.0, delta0 = 1e-6;
  ContactProblemData d;
  d.name = "one-elastic-support";
  d.compliance = Eigen::MatrixXd::Constant(1, 1, c);
  d.overlap = Eigen::VectorXd::Constant(1, delta0);
  d.equality_matrix = Eigen::MatrixXd::Ones(1, 1);
  d.equality_rhs = Eigen::VectorXd::Constant(1, p);
  d.support_stiffness = Eigen::MatrixXd::Constant(1, 1, s);
  const double force = (p + s * delta0) / (1 + s * c);
  CheckAgainst(d, Eigen::VectorXd::Constant(1, force),
               Eigen::VectorXd::Constant(1, c * force - delta0));
}

TEST_CASE("Ipopt and NLopt back ends: one contact with the local term",
          "[crosscheck][solvers][backends]") {
  // Choose F = 5 kN and set δ0 = c F + u_local(F) with u_local evaluated by hand (docs/model.md §4);
  // h/L ≈ 30, well inside the term's validity. u' > 0 only stiffens K̃, so the linear bound holds.
  const double c = 2e-9, force = 5000.0;
  ContactProblemData d;
  d.name = "one-local";
  d.compliance = Eigen::MatrixXd::Constant(1, 1, c);
  d.local = {SteelPair(5e-3)};
  d.overlap = Eigen::VectorXd::Constant(1, c * force + LocalApproachByHand(d.local[0], force));
  CheckAgainst(d, Eigen::VectorXd::Constant(1, force), Eigen::VectorXd(),
               Eigen::VectorXd::Constant(1, LocalSlopeByHand(d.local[0], force)));
}

TEST_CASE("Ipopt and NLopt back ends: symmetric pair with local terms and one equality",
          "[crosscheck][solvers][backends]") {
  // Symmetry gives F = (P/2, P/2); the gap equation then gives
  // λ = (C_00 + C_01) P/2 + u_local(P/2) − δ0.
  const double c = 1e-9, p = 8000.0, delta0 = 2e-6;
  ContactProblemData d;
  d.name = "two-local-symmetric";
  d.compliance.resize(2, 2);
  d.compliance << 3 * c, c, c, 3 * c;
  d.overlap = Eigen::Vector2d::Constant(delta0);
  d.local = {SteelPair(4e-3), SteelPair(4e-3)};
  d.equality_matrix = Eigen::MatrixXd::Ones(1, 2);
  d.equality_rhs = Eigen::VectorXd::Constant(1, p);
  const double lambda = 4 * c * p / 2 + LocalApproachByHand(d.local[0], p / 2) - delta0;
  CheckAgainst(d, Eigen::Vector2d::Constant(p / 2), Eigen::VectorXd::Constant(1, lambda),
               Eigen::Vector2d::Constant(LocalSlopeByHand(d.local[0], p / 2)));
}

TEST_CASE("Ipopt and NLopt back ends: infeasible equality gives no NaN and no 'converged'",
          "[crosscheck][solvers][backends]") {
  // F_0 + F_1 = −P has no solution with F ≥ 0.
  ContactProblemData d;
  d.name = "infeasible";
  d.compliance.resize(2, 2);
  d.compliance << 2e-9, 1e-9, 1e-9, 3e-9;
  d.overlap = Eigen::Vector2d(1e-6, 1e-6);
  d.equality_matrix = Eigen::MatrixXd::Ones(1, 2);
  d.equality_rhs = Eigen::VectorXd::Constant(1, -1000.0);
  const ContactProblem problem(d);
  for (Backend backend : kBackends) {
    if (!MakeContactSolver(backend)->available()) continue;
    INFO("back end " << BackendName(backend));
    ContactSolution solution;
    ContactOptions options;
    options.time_limit = 10.0;
    const ContactReport report = SolveWith(backend, problem, &solution, options);
    INFO("status " << StatusName(report.status) << ": " << report.message);
    CHECK(report.status != ContactStatus::kConverged);
    CHECK(report.status != ContactStatus::kConvergedInaccurate);
    CHECK(solution.force.allFinite());
    CHECK(solution.multiplier.allFinite());
    CHECK(!std::isnan(report.residual.total));
  }
}

TEST_CASE("Ipopt and NLopt back ends: warm start from the answer returns the answer",
          "[crosscheck][solvers][backends]") {
  // The two-contact, one-equality case of above, started from its own solution.
  const double c = 1e-9, p = 3000.0;
  ContactProblemData d;
  d.name = "warm";
  d.compliance.resize(2, 2);
  d.compliance << 2 * c, c, c, 3 * c;
  d.overlap = Eigen::Vector2d(0.0, 0.0);
  d.equality_matrix = Eigen::MatrixXd::Ones(1, 2);
  d.equality_rhs = Eigen::VectorXd::Constant(1, p);
  // δ0 = 0: F = λ C⁻¹1 = λ (2, 1)/(5c), λ = 5cP/3 → F = (2P/3, P/3).
  const Eigen::Vector2d force(2 * p / 3, p / 3);
  const Eigen::VectorXd lambda = Eigen::VectorXd::Constant(1, 5 * c * p / 3);
  const ErrorBound bound = ScaledErrorBound(d, force, lambda);
  REQUIRE(bound.force_per_residual * kTol <= kAccept);
  const ContactProblem problem(d);
  for (Backend backend : {Backend::kIpopt, Backend::kNloptSlsqp, Backend::kNloptAuglag}) {
    if (!MakeContactSolver(backend)->available()) continue;
    for (const bool with_multipliers : {false, true}) {
      INFO("back end " << BackendName(backend) << ", Ipopt multipliers " << with_multipliers);
      ContactOptions options;
      options.warm_start = true;
      if (backend == Backend::kIpopt && with_multipliers) {
        options.backend_options["ipopt.warm_start_init_point"] = "yes";
      }
      ContactSolution solution{force, lambda};
      const ContactReport report = SolveWith(backend, problem, &solution, options);
      CheckSolve(backend, report, solution, force, lambda, bound);
    }
  }
}

TEST_CASE("Ipopt and NLopt back ends: bad back-end options are rejected by name",
          "[unit][solvers][backends]") {
  ContactProblemData d;
  d.name = "options";
  d.compliance = Eigen::MatrixXd::Constant(1, 1, 1e-9);
  d.overlap = Eigen::VectorXd::Constant(1, 1e-6);
  const ContactProblem problem(d);
  struct Bad {
    Backend backend;
    const char* key;
    const char* value;
  };
  const Bad cases[] = {
      {Backend::kIpopt, "ipopt.no_such_option", "1"},
      {Backend::kIpopt, "ipopt.mu_init", "abc"},
      {Backend::kIpopt, "ipopt.mu_strategy", "sideways"},
      {Backend::kIpopt, "ipopt.max_iter", "2.5"},
      {Backend::kNloptSlsqp, "nlopt.xtol_rel", "fast"},
      {Backend::kNloptSlsqp, "nlopt.maxeval", "0"},
      {Backend::kNloptAuglag, "nlopt.no_such_option", "1"},
  };
  for (const Bad& bad : cases) {
    if (!MakeContactSolver(bad.backend)->available()) continue;
    INFO(bad.key << " = " << bad.value);
    ContactOptions options;
    options.backend_options[bad.key] = bad.value;
    ContactSolution solution;
    try {
      SolveWith(bad.backend, problem, &solution, options);
      FAIL("no exception");
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      INFO(what);
      CHECK(what.find(bad.key) != std::string::npos);
    }
  }
}

TEST_CASE("Ipopt and NLopt back ends: documented options are accepted",
          "[unit][solvers][backends]") {
  // The single spring of above, with the knobs the docs mention; the answer must not change.
  ContactProblemData d;
  d.name = "options-ok";
  d.compliance = Eigen::MatrixXd::Constant(1, 1, 2.5e-9);
  d.overlap = Eigen::VectorXd::Constant(1, 4e-5);
  const ContactProblem problem(d);
  const Eigen::VectorXd force = Eigen::VectorXd::Constant(1, 16000.0);
  ContactOptions ipopt;
  ipopt.backend_options = {{"ipopt.mu_strategy", "adaptive"},
                           {"ipopt.bound_relax_factor", "0"},
                           {"ipopt.linear_solver", "mumps"},
                           {"ipopt.warm_start_init_point", "yes"}};  // no warm start: ignored
  ContactOptions nlopt;
  nlopt.backend_options = {{"nlopt.xtol_rel", "1e-12"}, {"nlopt.maxeval", "500"}};
  for (const auto& [backend, options] :
       {std::pair{Backend::kIpopt, ipopt}, std::pair{Backend::kNloptSlsqp, nlopt},
        std::pair{Backend::kNloptLbfgs, nlopt}, std::pair{Backend::kNloptAuglag, nlopt}}) {
    if (!MakeContactSolver(backend)->available()) continue;
    INFO("back end " << BackendName(backend));
    ContactSolution solution;
    const ContactReport report = SolveWith(backend, problem, &solution, options);
    INFO("status " << StatusName(report.status) << ": " << report.message);
    CHECK(report.status == ContactStatus::kConverged);
    CHECK(RelativeError(solution.force, force) <= kAccept);
  }
}

TEST_CASE("Ipopt and NLopt back ends: one solver object reused across problems and options",
          "[crosscheck][solvers][backends]") {
  // The Ipopt back end keeps its IpoptApplication between solves and resets its options each
  // time: a 1-contact problem with a loose Ipopt tolerance, then a 2-contact problem with one
  // equality and default options, then the first again. Each answer must be that of a fresh solve.
  ContactProblemData one;
  one.name = "reuse-one";
  one.compliance = Eigen::MatrixXd::Constant(1, 1, 2.5e-9);
  one.overlap = Eigen::VectorXd::Constant(1, 4e-5);
  const double c = 1e-9, p = 3000.0;
  ContactProblemData two;
  two.name = "reuse-two";
  two.compliance.resize(2, 2);
  two.compliance << 2 * c, c, c, 3 * c;
  two.overlap = Eigen::Vector2d(0.0, 0.0);
  two.equality_matrix = Eigen::MatrixXd::Ones(1, 2);
  two.equality_rhs = Eigen::VectorXd::Constant(1, p);
  const ContactProblem problem_one(one), problem_two(two);
  for (Backend backend : {Backend::kIpopt, Backend::kNloptSlsqp}) {
    auto solver = MakeContactSolver(backend);
    if (!solver->available()) continue;
    INFO("back end " << BackendName(backend));
    ContactOptions loose;
    loose.tolerance = kTol;
    loose.backend_options[backend == Backend::kIpopt ? "ipopt.max_iter" : "nlopt.maxeval"] = "1";
    ContactOptions tight;
    tight.tolerance = kTol;
    ContactSolution a, b, c_again;
    const ContactReport ra = solver->Solve(problem_one, loose, &a);
    CHECK(ra.status != ContactStatus::kConverged);  // one iteration/evaluation is not enough
    const ContactReport rb = solver->Solve(problem_two, tight, &b);
    INFO("second solve: " << rb.message);
    CHECK(rb.status == ContactStatus::kConverged);
    CHECK(RelativeError(b.force, Eigen::Vector2d(2 * p / 3, p / 3)) <= kAccept);
    const ContactReport rc = solver->Solve(problem_one, tight, &c_again);
    INFO("third solve: " << rc.message);
    CHECK(rc.status == ContactStatus::kConverged);
    CHECK(RelativeError(c_again.force, Eigen::VectorXd::Constant(1, 16000.0)) <= kAccept);
  }
}
