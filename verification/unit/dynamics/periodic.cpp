// The periodic solver (docs/periodic.md) on systems with closed-form answers: a damped linear
// oscillator under harmonic forcing (the steady state and exp(λT)), the Mathieu equation (its
// first instability tongue, Liouville's det M, the growth of a long integration), and its
// answers to bad input and to failed steps.
#include <catch2/catch.hpp>

#include <cmath>
#include <complex>
#include <numbers>
#include <string>

#include "epicycle/dynamics/periodic.hpp"
#include "epicycle/dynamics/periodic_systems.hpp"
#include "figures.hpp"
#include "periodic_fixtures.hpp"
#include "thrown_message.hpp"

using namespace epicycle::dynamics;
using epicycle::test::ShootingWeight;
using epicycle::test::ThrownMessage;
using epicycle::test::TightShooting;

namespace {

// The first-tongue boundary of the undamped Mathieu equation at ε, upper (+1) or lower (−1), by
// bisection on the multipliers' verdict (unstable inside, marginal outside) to `width`.
double TongueBoundary(const MathieuOscillator& m, double epsilon, int side, double width) {
  const ShootingOptions o = TightShooting();
  double inside = 0.25, outside = 0.25 + side * 2 * epsilon;
  while (std::abs(outside - inside) > width) {
    const double mid = (inside + outside) / 2;
    const ShootingResult r =
        SolvePeriodicOrbit(m, o, Eigen::Vector2d::Zero(), Eigen::Vector3d(mid, epsilon, 0));
    (r.floquet.stability == Stability::kUnstable ? inside : outside) = mid;
  }
  return (inside + outside) / 2;
}

// Fails (Rhs returns false) once omega exceeds `limit`: a model that cannot be evaluated there.
struct FailsAbove : DrivenLinearOscillator {
  double limit = 3.5;
  bool Rhs(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& p,
           Eigen::VectorXd* f) const override {
    if (p(0) > limit) return false;
    return DrivenLinearOscillator::Rhs(t, y, p, f);
  }
};

// A period that is not > 0.
struct NegativePeriod : DrivenLinearOscillator {
  double Period(const Eigen::VectorXd&) const override { return -1.0; }
};

}  // namespace

TEST_CASE(
    "a damped oscillator under harmonic forcing: the orbit is the analytic steady state, "
    "the multipliers exp(λ_k T)",
    "[unit][dynamics][periodic]") {
  const DrivenLinearOscillator s;
  const ShootingOptions o = TightShooting();
  const ShootingResult r = SolvePeriodicOrbit(s, o, Eigen::Vector2d::Zero());
  REQUIRE(r.status == ShootingStatus::kConverged);
  const double wn = s.natural_frequency, z = s.damping_ratio, w = s.omega;
  // x(t) = Re(H e^{iωt}), H = a/(ω_n² − ω² + 2iζω_nω): x(0) = Re H, x'(0) = −ω Im H.
  const std::complex<double> h =
      s.amplitude / std::complex<double>(wn * wn - w * w, 2 * z * wn * w);
  const Eigen::Vector2d exact(h.real(), -w * h.imag());
  // Tolerance: Newton stops with R to newton_tolerance integrator tolerances, an orbit error of
  // ‖(M − I)⁻¹‖ times that; R itself carries the integration's global error over a period, at
  // most one local tolerance per step (steps per period: the run's steps over its integrations).
  const double steps = static_cast<double>(r.steps) / static_cast<double>(r.integrations);
  const Eigen::MatrixXd inv = (r.monodromy - Eigen::MatrixXd::Identity(2, 2)).inverse();
  const double tol = (inv.norm() * o.newton_tolerance + steps) * ShootingWeight(o, exact);
  CHECK((r.initial_state - exact).cwiseAbs().maxCoeff() <= tol);
  epicycle::test::FigureValue("linear orbit error", (r.initial_state - exact).cwiseAbs().maxCoeff(),
                              "-");
  epicycle::test::FigureValue("linear orbit tolerance", tol, "-");
  CHECK(r.period == Approx(2 * std::numbers::pi / w).epsilon(1e-15));

  // λ = −ζω_n ± iω_n√(1 − ζ²); μ = e^{λT}.
  const std::complex<double> lambda(-z * wn, wn * std::sqrt(1 - z * z));
  const std::complex<double> mu = std::exp(lambda * r.period);
  REQUIRE(r.floquet.multipliers.size() == 2);
  // Tolerance: each entry of M carries at most steps × rtol (|Φ_ij| + 1) (the variational
  // columns' tolerances are rtol-relative, docs/periodic.md); a simple eigenvalue moves by its
  // condition number κ = ‖l‖‖r‖/|lᵀr| times ‖δM‖₂ ≤ 2 max|δM_ij| (2 × 2). κ from the analytic
  // eigenvectors (1, λ) of the companion matrix and their left partners.
  const std::complex<double> l1 = lambda, l2 = std::conj(lambda);
  const double kappa = std::abs(l1 - l2) > 0 ? std::sqrt(1 + std::norm(l1)) *
                                                   std::sqrt(1 + std::norm(l2)) / std::abs(l1 - l2)
                                             : 1.0;
  const double mu_tol = kappa * 2 * steps * o.rtol * (r.monodromy.cwiseAbs().maxCoeff() + 1);
  bool upper_found = false, lower_found = false;
  epicycle::test::FigureValue("linear multiplier error",
                              std::min(std::abs(r.floquet.multipliers[0] - mu),
                                       std::abs(r.floquet.multipliers[0] - std::conj(mu))),
                              "-");
  epicycle::test::FigureValue("linear multiplier tolerance", mu_tol, "-");
  for (const std::complex<double> m : r.floquet.multipliers) {
    upper_found |= std::abs(m - mu) <= mu_tol;
    lower_found |= std::abs(m - std::conj(mu)) <= mu_tol;
  }
  CHECK(upper_found);
  CHECK(lower_found);
  CHECK(r.floquet.stability == Stability::kStable);
  CHECK(r.floquet.spectral_radius == Approx(std::abs(mu)).margin(mu_tol));
}

TEST_CASE(
    "the Mathieu equation: multipliers outside the unit circle inside the first tongue, on "
    "it outside, the tongue's boundary at δ = 1/4 ± ε/2 to the expansion's next terms",
    "[unit][dynamics][periodic]") {
  const MathieuOscillator m;
  const ShootingOptions o = TightShooting();
  const double eps = 0.1;
  // Inside (δ = 1/4): a real multiplier below −1 (the response at half the forcing frequency).
  const ShootingResult in =
      SolvePeriodicOrbit(m, o, Eigen::Vector2d::Zero(), Eigen::Vector3d(0.25, eps, 0));
  REQUIRE(in.status == ShootingStatus::kConverged);
  CHECK(in.floquet.stability == Stability::kUnstable);
  CHECK(in.floquet.real_below_minus_one == 1);
  // Outside (δ = 0.4, 0.1): both on the unit circle (Hamiltonian: det M = 1, a complex pair).
  for (const double delta : {0.1, 0.4}) {
    const ShootingResult out =
        SolvePeriodicOrbit(m, o, Eigen::Vector2d::Zero(), Eigen::Vector3d(delta, eps, 0));
    REQUIRE(out.status == ShootingStatus::kConverged);
    CHECK(out.floquet.stability == Stability::kMarginal);
    for (const auto mu : out.floquet.multipliers)
      CHECK(std::abs(mu) == Approx(1).margin(o.unit_circle_tolerance));
  }
  // The boundaries. δ = 1/4 ± ε/2 − ε²/8 ∓ ε³/32 − ε⁴/384 + O(ε⁵) (A&S 20.2.25, a = 4δ, q = 2ε):
  // the first-order formula is off by the rest of the series, ≤ ε²/8 + ε³/32 + ε⁴/384 (ε = 0.1);
  // against the third-order formula the rest is ε⁴/384 + |ε⁵ term| (11·32ε⁵/(4·36864) = 2.4e-8).
  // The bisection's width 1e-9 and the integration's error in δ (|δtr M| ≤ steps·rtol ≈ 3e-8 over
  // d tr M/dδ ≈ 3.6: 1e-8) add to it.
  const double width = 1e-9;
  for (const int side : {+1, -1}) {
    const double boundary = TongueBoundary(m, eps, side, width);
    const double first = 0.25 + side * eps / 2;
    const double third = first - eps * eps / 8 - side * std::pow(eps, 3) / 32;
    const double rest1 = eps * eps / 8 + std::pow(eps, 3) / 32 + std::pow(eps, 4) / 384;
    const double rest3 = std::pow(eps, 4) / 384 + 11.0 * 32 * std::pow(eps, 5) / (4 * 36864);
    epicycle::test::FigureValue(side > 0 ? "Mathieu upper boundary" : "Mathieu lower boundary",
                                boundary, "-");
    epicycle::test::FigureValue("  minus third-order formula", boundary - third, "-");
    CHECK(std::abs(boundary - first) <= rest1);
    CHECK(std::abs(boundary - third) <= rest3 + width + 1e-8);
  }
}

TEST_CASE(
    "the damped Mathieu equation: |μ|² = det M = exp(−2πc) outside the tongue, and inside, a "
    "long integration grows at log|μ|/T per unit time",
    "[unit][dynamics][periodic]") {
  const MathieuOscillator m;
  const ShootingOptions o = TightShooting();
  const double c = 0.02, eps = 0.1;
  // Outside (δ = 0.4): a complex pair, each |μ| = √det M = e^{−πc} (Liouville: det M =
  // exp(∫ tr J) = e^{−2πc}).
  const ShootingResult out =
      SolvePeriodicOrbit(m, o, Eigen::Vector2d::Zero(), Eigen::Vector3d(0.4, eps, c));
  REQUIRE(out.status == ShootingStatus::kConverged);
  CHECK(out.floquet.stability == Stability::kStable);
  const double steps = static_cast<double>(out.steps) / static_cast<double>(out.integrations);
  // Tolerance: M's entries to steps·rtol·(|Φ| + 1) each; |μ| of a complex pair is √det M, whose
  // error is at most ‖δM‖ times the sum of the entries' cofactors over 2√det ≈ 2 max|M|/(2|μ|).
  const double det_tol = 2 * steps * o.rtol * (out.monodromy.cwiseAbs().maxCoeff() + 1) *
                         out.monodromy.cwiseAbs().maxCoeff();
  CHECK(out.monodromy.determinant() == Approx(std::exp(-2 * std::numbers::pi * c)).margin(det_tol));
  epicycle::test::FigureValue("damped Mathieu det M error",
                              out.monodromy.determinant() - std::exp(-2 * std::numbers::pi * c),
                              "-");
  epicycle::test::FigureValue("damped Mathieu det M tolerance", det_tol, "-");
  for (const auto mu : out.floquet.multipliers)
    CHECK(std::abs(mu) == Approx(std::exp(-std::numbers::pi * c)).margin(det_tol));

  // Inside (δ = 1/4): the largest multiplier μ₁ < −1; a time integration from (1, 0) over n
  // periods grows as |μ₁|ⁿ, the other mode's share decaying as (|μ₂|/|μ₁|)ⁿ.
  const ShootingResult in =
      SolvePeriodicOrbit(m, o, Eigen::Vector2d::Zero(), Eigen::Vector3d(0.25, eps, c));
  REQUIRE(in.status == ShootingStatus::kConverged);
  REQUIRE(in.floquet.stability == Stability::kUnstable);
  const double mu1 = std::abs(in.floquet.multipliers[0]), mu2 = std::abs(in.floquet.multipliers[1]);
  const int n = 20;
  const Eigen::Vector3d p(0.25, eps, c);
  const Eigen::VectorXd y20 = IntegratePeriods(m, o, Eigen::Vector2d(1, 0), p, n);
  const Eigen::VectorXd y40 = IntegratePeriods(m, o, y20, p, n);
  const double rate = std::log(y40.norm() / y20.norm()) / (n * in.period);  // [1/time]
  // Tolerance: the other mode's share after 20 periods, (μ₂/μ₁)²⁰ relative (≈ 1e-6 at c = 0.02),
  // over the 20 periods' time, plus the integrations' relative error (steps·rtol per period).
  const double rate_tol = (std::pow(mu2 / mu1, n) + 2 * n * steps * o.rtol) / (n * in.period);
  epicycle::test::FigureValue("Mathieu growth rate, integration", rate, "1/time");
  epicycle::test::FigureValue("Mathieu growth rate, log|mu|/T", std::log(mu1) / in.period,
                              "1/time");
  epicycle::test::FigureValue("Mathieu growth rate tolerance", rate_tol, "1/time");
  CHECK(rate == Approx(std::log(mu1) / in.period).margin(rate_tol));
}

TEST_CASE("periodic solver: bad input names the field, its value and the rule",
          "[unit][dynamics][periodic]") {
  const DrivenLinearOscillator s;
  ContinuationOptions c;
  c.parameter = "speed";
  c.start = 2;
  c.end = 4;
  CHECK(ThrownMessage([&] { ContinuePeriodicOrbit(s, c, Eigen::Vector2d::Zero()); }) ==
        "continuation: parameter = 'speed': not a parameter of the system (its parameters: "
        "omega)");
  c.parameter = "omega";
  c.end = 2;
  CHECK(ThrownMessage([&] { ContinuePeriodicOrbit(s, c, Eigen::Vector2d::Zero()); }) ==
        "continuation: end = 2: equals start = 2: the range must have non-zero width");
  c.end = 4;
  c.initial_step = 0.5;
  CHECK(ThrownMessage([&] { ContinuePeriodicOrbit(s, c, Eigen::Vector2d::Zero()); }) ==
        "continuation: initial_step = 0.5: must lie in [min_step, max_step] = [1e-06, 0.1]");
  const NegativePeriod negative;
  CHECK(ThrownMessage([&] {
          SolvePeriodicOrbit(negative, ShootingOptions{}, Eigen::Vector2d::Zero());
        }) == "periodic system: period T = -1 s at omega = 3 rad/s: must be > 0 and finite");
  // ω through 0 on a continuation: T = 2π/ω is not > 0 at the start.
  c.start = -1;
  c.initial_step = 0.02;
  CHECK(ThrownMessage([&] { ContinuePeriodicOrbit(s, c, Eigen::Vector2d::Zero()); }) ==
        "periodic system: period T = -6.28319 s at omega = -1 rad/s: must be > 0 and finite");
  ShootingOptions o;
  o.rtol = 0;
  CHECK(ThrownMessage([&] { SolvePeriodicOrbit(s, o, Eigen::Vector2d::Zero()); }) ==
        "shooting: rtol = 0: must lie in (0, 0.1]");
  o = ShootingOptions{};
  o.atol = Eigen::VectorXd::Constant(3, 1e-9);
  CHECK(ThrownMessage([&] { SolvePeriodicOrbit(s, o, Eigen::Vector2d::Zero()); }) ==
        "shooting: atol's size = 3: must be 1 or the state's size 2");
  CHECK(ThrownMessage([&] { SolvePeriodicOrbit(s, ShootingOptions{}, Eigen::Vector3d::Zero()); }) ==
        "shooting: the initial state has 3 entries, the system 2");
}

TEST_CASE(
    "periodic solver: a failed Newton or continuation step says where it stopped and keeps "
    "the branch so far",
    "[unit][dynamics][periodic]") {
  // Newton: the model cannot be evaluated at the shooting's parameters.
  FailsAbove s;
  s.limit = 2.0;  // the default ω = 3 lies above
  const ShootingResult r = SolvePeriodicOrbit(s, TightShooting(), Eigen::Vector2d::Zero());
  CHECK(r.status == ShootingStatus::kIntegrationFailed);
  CHECK_THAT(r.message, Catch::Contains("shooting from the initial guess: the integration stopped "
                                        "at t = 0 s"));
  // Newton: one iteration allowed on a nonlinear orbit.
  const BacklashOscillator b;
  ShootingOptions one;
  one.max_iterations = 1;
  const ShootingResult r1 = SolvePeriodicOrbit(b, one, Eigen::Vector2d(0, 0));
  CHECK(r1.status == ShootingStatus::kIterationLimit);
  CHECK_THAT(r1.message, Catch::Contains("1 Newton iterations spent"));
  CHECK(r1.iterations == 1);

  // Continuation: the model fails beyond ω = 3.5; the branch from 3 stops just below it.
  s.limit = 3.5;
  ContinuationOptions c;
  c.parameter = "omega";
  c.start = 3;
  c.end = 4;
  c.shooting = TightShooting();
  const ContinuationResult cr = ContinuePeriodicOrbit(s, c, Eigen::Vector2d::Zero());
  CHECK(cr.status == ContinuationStatus::kStepTooSmall);
  REQUIRE(cr.points.size() >= 2);
  const double last = cr.points.back().parameter;
  CHECK(last <= 3.5);
  CHECK(last > 3.5 - 3 * c.max_step * (c.end - c.start));
  CHECK_THAT(cr.message,
             Catch::Contains("continuation stopped after omega = ") &&
                 Catch::Contains("rad/s (point " + std::to_string(cr.points.size() - 1)) &&
                 Catch::Contains("the integration stopped at t = 0 s"));
  // The start failing is its own status, with the shooting's record.
  s.limit = 2.0;
  const ContinuationResult start = ContinuePeriodicOrbit(s, c, Eigen::Vector2d::Zero());
  CHECK(start.status == ContinuationStatus::kStartFailed);
  CHECK(start.points.empty());
  CHECK_THAT(start.message, Catch::Contains("the first orbit, at omega = 3 rad/s, was not found"));
}

TEST_CASE(
    "continuation on the Mathieu equation: period doublings flagged at the first tongue's "
    "boundaries, a Neimark–Sacker where the damping changes sign",
    "[unit][dynamics][periodic]") {
  const MathieuOscillator m;
  const double eps = 0.1;
  // The trivial orbit y = 0 over δ from 0.4 down to 0.1 crosses the first tongue: a real
  // multiplier leaves through −1 at its upper boundary and comes back at its lower one.
  ContinuationOptions c;
  c.parameter = "delta";
  c.start = 0.4;
  c.end = 0.1;
  c.max_step = 0.02;
  c.shooting.rtol = 1e-10;
  c.shooting.atol = Eigen::VectorXd::Constant(1, 1e-12);
  const ContinuationResult r =
      ContinuePeriodicOrbit(m, c, Eigen::Vector2d::Zero(), Eigen::Vector3d(0.4, eps, 0));
  REQUIRE(r.status == ContinuationStatus::kCompleted);
  std::vector<Bifurcation> pd;
  for (const Bifurcation& b : r.bifurcations) {
    CHECK(b.kind == BifurcationKind::kPeriodDoubling);
    if (b.kind == BifurcationKind::kPeriodDoubling) pd.push_back(b);
  }
  REQUIRE(pd.size() == 2);
  for (int k = 0; k < 2; ++k) {
    const int side = k == 0 ? +1 : -1;  // upper boundary first (δ decreasing)
    const double third = 0.25 + side * eps / 2 - eps * eps / 8 - side * std::pow(eps, 3) / 32;
    // Tolerance: the crossing is interpolated between the two points that bracket it (the
    // outside one has a complex pair, so the midpoint): half their distance, plus the
    // expansion's rest (ε⁴/384).
    const BranchPoint& before = r.points[static_cast<std::size_t>(pd[k].after_point) - 1];
    const BranchPoint& after = r.points[static_cast<std::size_t>(pd[k].after_point)];
    const double tol = std::abs(after.parameter - before.parameter) / 2 + std::pow(eps, 4) / 384;
    CHECK(std::abs(pd[k].parameter - third) <= tol);
    CHECK(pd[k].multiplier.real() <= -1);
  }
  // Between the flags the points are unstable, outside marginal (no damping).
  for (const BranchPoint& b : r.points) {
    const bool inside = b.parameter < pd[0].parameter && b.parameter > pd[1].parameter;
    if (std::abs(b.parameter - pd[0].parameter) < 0.01 ||
        std::abs(b.parameter - pd[1].parameter) < 0.01)
      continue;  // near a boundary the interpolated flag may sit on either side of a point
    INFO("delta = " << b.parameter);
    CHECK(b.floquet.stability == (inside ? Stability::kUnstable : Stability::kMarginal));
  }

  // Over the damping c from 0.02 to −0.02 at δ = 0.4: the complex pair |μ| = e^{−πc} leaves the
  // unit circle at c = 0.
  c.parameter = "damping";
  c.start = 0.02;
  c.end = -0.02;
  const ContinuationResult ns =
      ContinuePeriodicOrbit(m, c, Eigen::Vector2d::Zero(), Eigen::Vector3d(0.4, eps, 0.02));
  REQUIRE(ns.status == ContinuationStatus::kCompleted);
  REQUIRE(ns.bifurcations.size() == 1);
  const Bifurcation& b = ns.bifurcations[0];
  CHECK(b.kind == BifurcationKind::kNeimarkSacker);
  CHECK(std::abs(b.multiplier) > 1);
  // Tolerance: |μ| − 1 = e^{−πc} − 1 interpolated linearly between the bracketing c_a, c_b: the
  // root moves by |f''/(2f')| |c_a c_b| = (π/2)|c_a c_b|; the unit-circle tolerance 1e-6 shifts
  // the flagged crossing by 1e-6/π; M's error (steps·rtol) is smaller still.
  const double ca = ns.points[static_cast<std::size_t>(b.after_point) - 1].parameter;
  const double cb = ns.points[static_cast<std::size_t>(b.after_point)].parameter;
  CHECK(std::abs(b.parameter) <=
        std::numbers::pi / 2 * std::abs(ca * cb) + c.shooting.unit_circle_tolerance);
}
