// The periodic solver's continuation on the gear pair with backlash of Kahraman & Singh (1990)
// (docs/periodic.md): the frequency response bends to lower frequencies once the teeth separate
// (the contact spring works one way), so that between two folds two stable orbits coexist with an
// unstable one. Checked against references outside the continuation: the linear oscillator's
// steady state where the teeth never separate, a multiplier at +1 at every fold (what a fold
// is), and time integrations from two initial states that settle on the two stable orbits.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include "epicycle/dynamics/periodic.hpp"
#include "epicycle/dynamics/periodic_systems.hpp"
#include "figures.hpp"
#include "periodic_fixtures.hpp"

using namespace epicycle::dynamics;

namespace {

ContinuationOptions Sweep() {
  ContinuationOptions c;
  c.parameter = "Omega";
  c.start = 1.5;  // above the resonance: one orbit, teeth in contact
  c.end = 0.4;
  c.max_step = 0.02;
  c.shooting.rtol = 1e-8;
  c.shooting.atol = Eigen::VectorXd::Constant(1, 1e-10);
  return c;
}

// The weighted tolerance of a state, rtol |y|_∞ + atol.
double Weight(const ShootingOptions& o, const Eigen::VectorXd& y) {
  return o.rtol * y.cwiseAbs().maxCoeff() + o.atol.maxCoeff();
}

// Half the peak-to-peak of x over one period from y0 (a time integration's samples).
double Amplitude(const BacklashOscillator& s, const ShootingOptions& o, const Eigen::VectorXd& y0,
                 const Eigen::VectorXd& p) {
  const Eigen::MatrixXd orbit = SampleOrbit(s, o, y0, p, 512);
  return (orbit.col(0).maxCoeff() - orbit.col(0).minCoeff()) / 2;
}

}  // namespace

TEST_CASE(
    "backlash oscillator: the continuation over the forcing frequency finds both folds, the "
    "unstable segment between them, and the linear steady state where the teeth stay in "
    "contact",
    "[crosscheck][dynamics][periodic]") {
  const BacklashOscillator s;
  const ContinuationOptions c = Sweep();
  const Eigen::Vector2d p0(c.start, s.alternating_force);
  const ContinuationResult r = ContinuePeriodicOrbit(s, c, Eigen::Vector2d(1.1, 0), p0);
  INFO(r.message);
  REQUIRE(r.status == ContinuationStatus::kCompleted);
  std::vector<Bifurcation> folds;
  for (const Bifurcation& b : r.bifurcations)
    if (b.kind == BifurcationKind::kFold) folds.push_back(b);
  REQUIRE(folds.size() == 2);
  // Down in frequency along the resonant branch to the lower fold, back up along the unstable
  // branch to the upper fold, down again along the branch where the teeth stay in contact.
  const Bifurcation& low = folds[0];
  const Bifurcation& high = folds[1];
  CHECK(low.parameter < high.parameter);
  CHECK(low.parameter > 0.4);
  CHECK(high.parameter < 1.0);  // below the linear resonance: the contact loss softens
  epicycle::test::FigureValue("backlash lower fold Omega", low.parameter, "-");
  epicycle::test::FigureValue("backlash upper fold Omega", high.parameter, "-");
  // Every point between the folds (in arclength) is unstable, every other stable (a fold is a
  // real multiplier through +1, and nothing else crosses here).
  for (std::size_t k = 0; k < r.points.size(); ++k) {
    const bool middle =
        static_cast<int>(k) >= low.after_point && static_cast<int>(k) < high.after_point;
    INFO("point " << k << " at Omega = " << r.points[k].parameter);
    CHECK((r.points[k].floquet.stability == Stability::kUnstable) == middle);
    if (middle) CHECK(r.points[k].floquet.real_above_one == 1);
  }
  // At each located fold a multiplier is +1. Tolerance: the secant stops with dλ/ds ≈ 0 to
  // ~1e-8, and M's entries carry the integration's error, ≤ steps·rtol·(|M| + 1) with ~10³ steps a
  // period at rtol 1e-8: 1e-5 × |M| (≤ 3 here), times the multiplier's condition.
  const double steps = static_cast<double>(r.steps) /
                       static_cast<double>(r.integrations + r.plain_integrations);
  const double mu_tol = 4 * steps * c.shooting.rtol * 3;
  for (const Bifurcation& f : folds) {
    epicycle::test::FigureValue("fold multiplier - 1", std::abs(f.multiplier - 1.0), "-");
    CHECK(std::abs(f.multiplier - 1.0) <= mu_tol);
  }
  epicycle::test::FigureValue("fold multiplier tolerance", mu_tol, "-");
  epicycle::test::FigureValue("branch points", static_cast<double>(r.points.size()), "-");
  epicycle::test::FigureValue("branch integrations", static_cast<double>(r.integrations), "-");

  // Where the teeth stay in contact (amplitude < F_m, x > 1 throughout), the orbit is the linear
  // oscillator's about x = 1 + F_m: x = 1 + F_m + Re(H e^{iΩt}), H = F_a/(1 − Ω² + 2iζΩ).
  int linear_points = 0;
  double worst_linear = 0;
  for (const BranchPoint& b : r.points) {
    if (b.amplitude >= 0.9 * s.mean_force) continue;
    const double w = b.parameter;
    const std::complex<double> h =
        s.alternating_force / std::complex<double>(1 - w * w, 2 * s.damping_ratio * w);
    const Eigen::Vector2d exact(1 + s.mean_force + h.real(), -w * h.imag());
    // Tolerance: the corrector stops with R to newton_tolerance local tolerances (an orbit error
    // ‖(M − I)⁻¹‖ ≤ 1/(1 − ρ) times that, ρ the spectral radius) plus the period's global error
    // (one local tolerance per step).
    const double tol = (c.shooting.newton_tolerance / (1 - b.floquet.spectral_radius) + steps) *
                       Weight(c.shooting, exact);
    INFO("Omega = " << w);
    CHECK((b.state - exact).cwiseAbs().maxCoeff() <= tol);
    worst_linear = std::max(worst_linear, (b.state - exact).cwiseAbs().maxCoeff() / tol);
    CHECK(b.amplitude == Approx(std::abs(h)).epsilon(1e-3));  // 256 samples: 1 − cos(π/256)
    ++linear_points;
  }
  CHECK(linear_points > 20);
  epicycle::test::FigureValue("linear branch worst error over tolerance", worst_linear, "-");
}

TEST_CASE(
    "backlash oscillator: between the folds, time integrations from two initial states "
    "settle on the two stable orbits of the continuation",
    "[crosscheck][dynamics][periodic]") {
  const BacklashOscillator s;
  const ContinuationOptions c = Sweep();
  const ContinuationResult r =
      ContinuePeriodicOrbit(s, c, Eigen::Vector2d(1.1, 0), Eigen::Vector2d(c.start, 0.05));
  REQUIRE(r.status == ContinuationStatus::kCompleted);
  const double omega = 0.6;  // between the folds (0.45, 0.75)
  const Eigen::Vector2d p(omega, s.alternating_force);
  // The continuation's two stable orbits at Ω = 0.6: the stable points that bracket it, the
  // nearer corrected onto Ω = 0.6 by shooting.
  std::vector<ShootingResult> branch;
  for (std::size_t k = 0; k + 1 < r.points.size(); ++k) {
    const BranchPoint& a = r.points[k];
    const BranchPoint& b = r.points[k + 1];
    if ((a.parameter - omega) * (b.parameter - omega) > 0) continue;
    if (a.floquet.stability != Stability::kStable || b.floquet.stability != Stability::kStable)
      continue;
    const BranchPoint& near = std::abs(a.parameter - omega) < std::abs(b.parameter - omega) ? a : b;
    branch.push_back(SolvePeriodicOrbit(s, c.shooting, near.state, p));
    REQUIRE(branch.back().status == ShootingStatus::kConverged);
  }
  REQUIRE(branch.size() == 2);
  std::sort(branch.begin(), branch.end(), [&](const auto& x, const auto& y) {
    return Amplitude(s, c.shooting, x.initial_state, p) <
           Amplitude(s, c.shooting, y.initial_state, p);
  });
  // From rest at the static deflection (x = 1 + F_m): the small orbit, teeth in contact. From a
  // displaced start that separates the teeth at once: the large orbit.
  const Eigen::Vector2d starts[2] = {Eigen::Vector2d(1 + s.mean_force, 0), Eigen::Vector2d(0.0, 0)};
  const int periods = 100;
  for (int k = 0; k < 2; ++k) {
    const Eigen::VectorXd settled = IntegratePeriods(s, c.shooting, starts[k], p, periods);
    const ShootingResult& orbit = branch[static_cast<std::size_t>(k)];
    // Tolerance: what is left of the transient, ρ^periods (ρ ≤ 0.7 here: 1e-15), plus the
    // integration's error: one local tolerance a step, steps a period, contracted by ρ each
    // period (1/(1 − ρ)), plus the shooting's own (as in the test above).
    const double rho = orbit.floquet.spectral_radius;
    const double steps = static_cast<double>(orbit.steps) / static_cast<double>(orbit.integrations);
    const double w = Weight(c.shooting, orbit.initial_state);
    const double tol = std::pow(rho, periods) * 2 +
                       (steps / (1 - rho) + c.shooting.newton_tolerance / (1 - rho)) * w;
    INFO("start " << k << ", settled " << settled.transpose() << ", branch "
                  << orbit.initial_state.transpose());
    CHECK((settled - orbit.initial_state).cwiseAbs().maxCoeff() <= tol);
    epicycle::test::FigureValue("settled - branch",
                                (settled - orbit.initial_state).cwiseAbs().maxCoeff(), "-");
    epicycle::test::FigureValue("settled tolerance", tol, "-");
    const double a_time = Amplitude(s, c.shooting, settled, p);
    const double a_branch = Amplitude(s, c.shooting, orbit.initial_state, p);
    epicycle::test::FigureValue(
        k == 0 ? "backlash small orbit amplitude at 0.6" : "backlash large orbit amplitude at 0.6",
        a_branch, "-");
    CHECK(a_time == Approx(a_branch).margin(tol));
  }
}


TEST_CASE(
    "backlash oscillator: shooting started at another phase of the forcing (T/3) finds the same "
    "orbit's state there, with the same multipliers",
    "[crosscheck][dynamics][periodic]") {
  const BacklashOscillator s;
  const ShootingOptions o = Sweep().shooting;
  const double omega = 0.6;  // between the folds: the large, separating orbit from x = 0
  const Eigen::Vector2d p(omega, s.alternating_force);
  // The orbit at phase 0: shooting from where a time integration from x = 0 settles.
  const Eigen::VectorXd settled = IntegratePeriods(s, o, Eigen::Vector2d(0.0, 0), p, 100);
  const ShootingResult a = SolvePeriodicOrbit(s, o, settled, p);
  REQUIRE(a.status == ShootingStatus::kConverged);
  REQUIRE(Amplitude(s, o, a.initial_state, p) > 0.5);  // the separating orbit (0.61)
  // Its state at t = T/3 by time integration from the orbit's state at 0.
  const Eigen::MatrixXd samples = SampleOrbit(s, o, a.initial_state, p, 3);
  const Eigen::VectorXd at_third = samples.row(1).transpose();
  // Shooting on the clock started at T/3, from its own start: where 3 periods of the shifted
  // system from x = 0 lead (a transient not yet settled). (From the orbit's state at t = 0, a
  // point of the orbit at the wrong phase for this section, Newton's line search stalls: the
  // impacting orbit's basin for Newton is narrower than that.)
  const epicycle::test::PhaseShifted shifted(s, 1.0 / 3);
  const Eigen::VectorXd guess = IntegratePeriods(shifted, o, Eigen::Vector2d(0.0, 0), p, 3);
  const ShootingResult b = SolvePeriodicOrbit(shifted, o, guess, p);
  INFO(b.message);
  REQUIRE(b.status == ShootingStatus::kConverged);
  epicycle::test::FigureValue("phase T/3: guess - answer",
                              (guess - at_third).cwiseAbs().maxCoeff(), "-");
  epicycle::test::FigureValue("phase T/3: Newton iterations", b.iterations, "-");
  // Tolerance. Each shooting is within e = (newton_tolerance/(1 − ρ) + steps) w of its exact
  // orbit (w = rtol|y| + atol; the bound of the tests above); the exact state at T/3 is the exact
  // state at 0 carried by Φ(T/3), whose norm is at most exp(μ₂[J] T/3), μ₂[J] ≤ 1/2 the
  // logarithmic norm of J = [0 1; −g' −2ζ] (g' ∈ {0, 1}: the largest eigenvalue of (J + Jᵀ)/2 =
  // [0 (1 − g')/2; (1 − g')/2 −2ζ]); the integration to T/3 adds one local tolerance a step.
  const double rho = std::max(a.floquet.spectral_radius, b.floquet.spectral_radius);
  const double steps =
      std::max(static_cast<double>(a.steps) / static_cast<double>(a.integrations),
               static_cast<double>(b.steps) / static_cast<double>(b.integrations));
  const double w = Weight(o, a.initial_state);
  const double e = (o.newton_tolerance / (1 - rho) + steps) * w;
  const double carry = std::exp(0.5 * a.period / 3);
  const double tol = e + carry * e + steps * w;
  const double error = (b.initial_state - at_third).cwiseAbs().maxCoeff();
  epicycle::test::FigureValue("phase T/3: shifted shooting - orbit at T/3", error, "-");
  epicycle::test::FigureValue("phase T/3: tolerance", tol, "-");
  CHECK(error <= tol);
  // The multipliers: M_φ is similar to M, so tr and det agree; det M = e^{−2ζT} (Liouville:
  // tr J = −2ζ whatever g). Each entry of either carries at most steps·rtol(|M| + 1) (`entry`):
  // a trace two of them, a determinant Σ|cofactor_ij||δM_ij| ≤ 4 max|M| entry.
  const double entry = steps * o.rtol * (a.monodromy.cwiseAbs().maxCoeff() + 1);
  CHECK(std::abs(b.monodromy.trace() - a.monodromy.trace()) <= 4 * entry);
  const double det_tol = 4 * entry * a.monodromy.cwiseAbs().maxCoeff();
  CHECK(std::abs(b.monodromy.determinant() -
                 std::exp(-2 * s.damping_ratio * a.period)) <= det_tol);
  CHECK(std::abs(a.monodromy.determinant() -
                 std::exp(-2 * s.damping_ratio * a.period)) <= det_tol);
  CHECK(b.floquet.stability == a.floquet.stability);
  epicycle::test::FigureValue("phase T/3: |tr M_phi - tr M|",
                              std::abs(b.monodromy.trace() - a.monodromy.trace()), "-");
  epicycle::test::FigureValue("phase T/3: trace tolerance", 4 * entry, "-");
}

// The same system read as 2T-periodic (T the forcing's period): its periodic orbits include the
// period-2 responses, and its monodromy is the 2T map's.
class DoublePeriod final : public PeriodicSystem {
 public:
  explicit DoublePeriod(const PeriodicSystem& base) : base_(base) {}
  int size() const override { return base_.size(); }
  std::vector<PeriodicParameter> parameters() const override { return base_.parameters(); }
  double Period(const Eigen::VectorXd& p) const override { return 2 * base_.Period(p); }
  bool Rhs(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& p,
           Eigen::VectorXd* f) const override {
    return base_.Rhs(t, y, p, f);
  }
  bool has_jacobian() const override { return base_.has_jacobian(); }
  bool Jacobian(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& p,
                Eigen::MatrixXd* jac) const override {
    return base_.Jacobian(t, y, p, jac);
  }

 private:
  const PeriodicSystem& base_;
};

TEST_CASE(
    "backlash oscillator, F_a = 0.2: the continuation over the forcing frequency flags a "
    "multiplier through -1, and past it a time integration settles on a period-2 response",
    "[crosscheck][dynamics][periodic]") {
  const BacklashOscillator s;
  ContinuationOptions c = Sweep();
  c.start = 3.0;  // well above the resonances: a small orbit, teeth in contact
  c.end = 1.5;    // past the period doubling, before the response's further doublings (Ω ≈ 1.4)
  const double fa = 0.2;
  const ContinuationResult r =
      ContinuePeriodicOrbit(s, c, Eigen::Vector2d(1.1, 0), Eigen::Vector2d(c.start, fa));
  INFO(r.message);
  REQUIRE(r.status == ContinuationStatus::kCompleted);
  REQUIRE(r.bifurcations.size() == 1);
  const Bifurcation& pd = r.bifurcations.front();
  CHECK(pd.kind == BifurcationKind::kPeriodDoubling);
  CHECK(pd.multiplier.real() < -1);
  CHECK(pd.multiplier.imag() == 0);
  epicycle::test::FigureValue("backlash F_a = 0.2: period doubling at Omega", pd.parameter, "-");
  epicycle::test::FigureValue("backlash F_a = 0.2: multiplier after it", pd.multiplier.real(), "-");
  // Stable before it, one real multiplier below −1 after it (nothing else crosses).
  for (std::size_t k = 0; k < r.points.size(); ++k) {
    const bool after = static_cast<int>(k) >= pd.after_point;
    INFO("point " << k << " at Omega = " << r.points[k].parameter);
    CHECK((r.points[k].floquet.stability == Stability::kUnstable) == after);
    CHECK(r.points[k].floquet.real_below_minus_one == (after ? 1 : 0));
  }

  // Past it (Ω = 1.55), the period-1 orbit corrected from the branch is unstable; a time
  // integration from rest at x = 1.1 settles on a response that repeats every two periods.
  const double omega = 1.55;
  REQUIRE(omega < pd.parameter);
  const Eigen::Vector2d p(omega, fa);
  const ShootingOptions& o = c.shooting;
  const BranchPoint* near = &r.points.front();
  for (const BranchPoint& b : r.points)
    if (std::abs(b.parameter - omega) < std::abs(near->parameter - omega)) near = &b;
  const ShootingResult one = SolvePeriodicOrbit(s, o, near->state, p);
  REQUIRE(one.status == ShootingStatus::kConverged);
  CHECK(one.floquet.real_below_minus_one == 1);
  const int settle = 300;
  const Eigen::VectorXd y0 = IntegratePeriods(s, o, Eigen::Vector2d(1.1, 0), p, settle);
  const Eigen::VectorXd y1 = IntegratePeriods(s, o, y0, p, 1);
  const Eigen::VectorXd y2 = IntegratePeriods(s, o, y1, p, 1);
  // The period-2 orbit by shooting over 2T, from where 20 periods from the same start lead (a
  // transient not yet settled): stable, and the settled state is it. Tolerance as for the settled states above: what is left of the transient,
  // ρ₂^{settle/2} times the start's distance (≤ 2), plus the integration's error (steps a 2T
  // period, contracted by ρ₂ each) and the shooting's own, over (1 − ρ₂).
  const DoublePeriod twice(s);
  const Eigen::VectorXd guess = IntegratePeriods(s, o, Eigen::Vector2d(1.1, 0), p, 20);
  const ShootingResult two = SolvePeriodicOrbit(twice, o, guess, p);
  INFO(two.message);
  REQUIRE(two.status == ShootingStatus::kConverged);
  CHECK(two.floquet.stability == Stability::kStable);
  const double rho = two.floquet.spectral_radius;
  const double steps = static_cast<double>(two.steps) / static_cast<double>(two.integrations);
  const double w = Weight(o, two.initial_state);
  const double tol = std::pow(rho, settle / 2) * 2 + (steps + o.newton_tolerance) / (1 - rho) * w;
  const double repeat = (y2 - y0).cwiseAbs().maxCoeff();
  const double split = (y1 - y0).cwiseAbs().maxCoeff();
  const double to_two = (y0 - two.initial_state).cwiseAbs().maxCoeff();
  epicycle::test::FigureValue("backlash period 2 at 1.55: |y(t+2T) - y(t)|", repeat, "-");
  epicycle::test::FigureValue("backlash period 2 at 1.55: |y(t+T) - y(t)|", split, "-");
  epicycle::test::FigureValue("backlash period 2 at 1.55: guess - 2T shooting",
                              (guess - two.initial_state).cwiseAbs().maxCoeff(), "-");
  epicycle::test::FigureValue("backlash period 2 at 1.55: settled - 2T shooting", to_two, "-");
  epicycle::test::FigureValue("backlash period 2 at 1.55: tolerance", tol, "-");
  epicycle::test::FigureValue("backlash period 2 at 1.55: spectral radius of the 2T map", rho,
                              "-");
  CHECK(to_two <= tol);
  CHECK(repeat <= 2 * tol);
  // Not period 1: a period apart the states differ by far more than the tolerance, and neither
  // is the unstable period-1 orbit's.
  CHECK(split > 100 * tol);
  CHECK((y0 - one.initial_state).cwiseAbs().maxCoeff() > 100 * tol);
  CHECK((y1 - one.initial_state).cwiseAbs().maxCoeff() > 100 * tol);
}
