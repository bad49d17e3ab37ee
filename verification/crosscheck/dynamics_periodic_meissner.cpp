// The periodic solver on the gear mesh's own parametric excitation (docs/periodic.md §3, "The
// gear pair with a rectangular mesh stiffness"): the relative coordinate of one gear pair,
// m ẍ + c ẋ + k(t) x = F, its mesh stiffness a rectangular wave, k̄(1 + ε) while two tooth pairs
// are in contact (the first (ε_α − 1)T of each mesh period T), k̄(1 − ε) over the rest (one pair):
// the Meissner equation. Its monodromy matrix is the product of the two constant-coefficient
// transfer matrices, M = exp(A₂t₂) exp(A₁t₁), each 2 × 2 exponential written here from its
// eigenvalues: a reference that owes nothing to the integrator. With the mesh frequency near
// twice the natural frequency a multiplier leaves the unit circle through −1 (the principal
// parametric instability); near that region's boundary, located from the closed form, a time
// integration grows (inside) or decays (outside) at log|μ|/T.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>

#include "epicycle/dynamics/periodic.hpp"
#include "figures.hpp"
#include "periodic_fixtures.hpp"

using namespace epicycle::dynamics;
using epicycle::test::ShootingWeight;
using epicycle::test::TightShooting;

namespace {

using Complex = std::complex<double>;

// Nondimensional: lengths over F/k̄, time over 1/ω_n with ω_n = √(k̄/m), so m = k̄ = F = 1 and
// c = 2ζ. Parameter "Omega" [-]: the mesh frequency over ω_n (T = 2π/Ω).
class RectangularMeshPair final : public PeriodicSystem {
 public:
  double stiffness_variation = 0.2;  ///< ε [-]
  double contact_ratio = 1.6;        ///< ε_α [-]: double contact over (ε_α − 1)T
  double damping_ratio = 0.02;       ///< ζ [-]
  int size() const override { return 2; }
  std::vector<PeriodicParameter> parameters() const override { return {{"Omega", "-", 2.0}}; }
  double Period(const Eigen::VectorXd& p) const override { return 2 * std::numbers::pi / p(0); }
  // k(t) over k̄: the mesh period's first (ε_α − 1) is double contact.
  double Stiffness(double t, double period) const {
    const double phase = std::fmod(t, period) / period;
    return phase < contact_ratio - 1 ? 1 + stiffness_variation : 1 - stiffness_variation;
  }
  bool Rhs(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& p,
           Eigen::VectorXd* f) const override {
    const double k = Stiffness(t, Period(p));
    *f = Eigen::Vector2d(y(1), 1.0 - 2 * damping_ratio * y(1) - k * y(0));
    return true;
  }
  bool has_jacobian() const override { return true; }
  bool Jacobian(double t, const Eigen::VectorXd&, const Eigen::VectorXd& p,
                Eigen::MatrixXd* jac) const override {
    const double k = Stiffness(t, Period(p));
    *jac = (Eigen::Matrix2d() << 0, 1, -k, -2 * damping_ratio).finished();
    return true;
  }
};

// exp(A t) for A = [0 1; −k −c], from its eigenvalues λ₁,₂ = (−c ± √(c² − 4k))/2 (distinct for
// c² ≠ 4k), by Sylvester's formula
// e^{At} = [(λ₁e^{λ₂t} − λ₂e^{λ₁t}) I + (e^{λ₁t} − e^{λ₂t}) A]/(λ₁ − λ₂).
Eigen::Matrix2d TransferMatrix(double k, double c, double t) {
  const Complex root = std::sqrt(Complex(c * c - 4 * k, 0));
  const Complex l1 = (-c + root) / 2.0, l2 = (-c - root) / 2.0;
  const Complex e1 = std::exp(l1 * t), e2 = std::exp(l2 * t);
  const double a = ((l1 * e2 - l2 * e1) / (l1 - l2)).real();
  const double b = ((e1 - e2) / (l1 - l2)).real();
  const Eigen::Matrix2d matrix = (Eigen::Matrix2d() << 0, 1, -k, -c).finished();
  return a * Eigen::Matrix2d::Identity() + b * matrix;
}

// The closed form: the monodromy matrix and the orbit's state at t = 0.
struct ClosedForm {
  Eigen::Matrix2d monodromy;
  Eigen::Vector2d orbit;
  double period = 0;
};

ClosedForm Meissner(const RectangularMeshPair& s, double omega) {
  ClosedForm out;
  out.period = 2 * std::numbers::pi / omega;
  const double t1 = (s.contact_ratio - 1) * out.period, t2 = out.period - t1;
  const double k1 = 1 + s.stiffness_variation, k2 = 1 - s.stiffness_variation;
  const double c = 2 * s.damping_ratio;
  const Eigen::Matrix2d e1 = TransferMatrix(k1, c, t1), e2 = TransferMatrix(k2, c, t2);
  out.monodromy = e2 * e1;
  // Over each part the static deflection p_i = (F/k_i, 0) is a particular solution:
  // y(t₁) = E₁(y₀ − p₁) + p₁, y(T) = E₂(y(t₁) − p₂) + p₂ = y₀, so
  // (I − M) y₀ = E₂(I − E₁) p₁ + (I − E₂) p₂.
  const Eigen::Vector2d p1(1 / k1, 0), p2(1 / k2, 0);
  const Eigen::Matrix2d id = Eigen::Matrix2d::Identity();
  out.orbit = (id - out.monodromy).partialPivLu().solve(e2 * (id - e1) * p1 + (id - e2) * p2);
  return out;
}

// tr M + 1 + det M: < 0 exactly when a real multiplier lies below −1 (the characteristic
// polynomial μ² − tr M μ + det M is negative at μ = −1), the principal region's inside.
double RegionFunction(const RectangularMeshPair& s, double omega) {
  const Eigen::Matrix2d m = Meissner(s, omega).monodromy;
  return m.trace() + 1 + m.determinant();
}

// The closed form's multipliers with each one's condition number κ = ‖r‖‖l‖/|lᵀr| (right and
// left eigenvectors), by decreasing modulus.
struct Multipliers {
  Complex mu[2];
  double kappa[2];
  Eigen::Matrix2cd vectors;  // right eigenvectors, columns in mu's order
};

Multipliers ClosedFormMultipliers(const Eigen::Matrix2d& m) {
  const Eigen::EigenSolver<Eigen::Matrix2d> eig(m);
  Eigen::Index order[2] = {0, 1};
  if (std::abs(eig.eigenvalues()(1)) > std::abs(eig.eigenvalues()(0)))
    std::swap(order[0], order[1]);
  const Eigen::Matrix2cd v = eig.eigenvectors();
  const Eigen::Matrix2cd w = v.inverse();  // rows: left eigenvectors with lᵀr = 1
  Multipliers out;
  for (int i = 0; i < 2; ++i) {
    const Eigen::Index j = order[i];
    out.mu[i] = eig.eigenvalues()(j);
    out.kappa[i] = v.col(j).norm() * w.row(j).norm();
    out.vectors.col(i) = v.col(j);
  }
  return out;
}

// Shooting at Ω from rest; its multipliers against the closed form's, its orbit against the
// closed form's. Returns the shooting.
ShootingResult CheckAgainstClosedForm(const RectangularMeshPair& s, double omega,
                                      const std::string& name) {
  const ShootingOptions o = TightShooting();
  const Eigen::VectorXd p = Eigen::VectorXd::Constant(1, omega);
  const ShootingResult r = SolvePeriodicOrbit(s, o, Eigen::Vector2d::Zero(), p);
  INFO(name << ": " << r.message);
  REQUIRE(r.status == ShootingStatus::kConverged);
  const ClosedForm exact = Meissner(s, omega);
  CHECK(r.period == Approx(exact.period).epsilon(1e-15));
  const Multipliers mu = ClosedFormMultipliers(exact.monodromy);
  REQUIRE(r.floquet.multipliers.size() == 2);
  // Tolerance: each entry of M carries at most steps × rtol (|M_ij| + 1) (the variational columns'
  // tolerances are rtol-relative, docs/periodic.md §2, and a step's local error is held to one
  // tolerance, also the steps that cross the stiffness's jumps, which the error test shrinks);
  // a simple eigenvalue moves by at most κ ‖δM‖₂ ≤ κ · 2 max|δM_ij| (2 × 2).
  const double steps = static_cast<double>(r.steps) / static_cast<double>(r.integrations);
  const double entry = steps * TightShooting().rtol * (exact.monodromy.cwiseAbs().maxCoeff() + 1);
  for (int i = 0; i < 2; ++i) {
    const double tol = mu.kappa[i] * 2 * entry;
    double nearest = std::abs(r.floquet.multipliers[0] - mu.mu[i]);
    nearest = std::min(nearest, std::abs(r.floquet.multipliers[1] - mu.mu[i]));
    INFO(name << ": closed-form multiplier " << mu.mu[i]);
    CHECK(nearest <= tol);
    epicycle::test::FigureValue(
        name + ": |mu - closed form| (multiplier " + std::to_string(i + 1) + ")", nearest, "-");
    epicycle::test::FigureValue(name + ": tolerance", tol, "-");
  }
  epicycle::test::FigureValue(name + ": closed-form |mu_1|", std::abs(mu.mu[0]), "-");
  epicycle::test::FigureValue(name + ": steps per period", steps, "-");
  // The orbit: Newton stops with R to newton_tolerance integrator tolerances, an orbit error of
  // ‖(M − I)⁻¹‖ times that, plus the period's global error (one local tolerance a step).
  const Eigen::Matrix2d inv = (exact.monodromy - Eigen::Matrix2d::Identity()).inverse();
  const double orbit_tol =
      (inv.norm() * o.newton_tolerance + steps) * ShootingWeight(o, exact.orbit);
  const double orbit_error = (r.initial_state - exact.orbit).cwiseAbs().maxCoeff();
  CHECK(orbit_error <= orbit_tol);
  epicycle::test::FigureValue(name + ": orbit error", orbit_error, "-");
  epicycle::test::FigureValue(name + ": orbit tolerance", orbit_tol, "-");
  return r;
}

// The upper boundary of the principal region from the closed form: a scan of the region function
// over Ω ∈ [1.6, 2.6] (a region around Ω = 2√k_mean) and bisection of each sign change to 1e-13.
std::vector<double> RegionBoundaries(const RectangularMeshPair& s) {
  std::vector<double> out;
  const int n = 1000;
  double a = 1.6, fa = RegionFunction(s, a);
  for (int i = 1; i <= n; ++i) {
    const double b = 1.6 + 1.0 * i / n, fb = RegionFunction(s, b);
    if ((fa < 0) != (fb < 0)) {
      double lo = a, hi = b;
      const bool lo_negative = fa < 0;
      while (hi - lo > 1e-13) {
        const double mid = (lo + hi) / 2;
        ((RegionFunction(s, mid) < 0) == lo_negative ? lo : hi) = mid;
      }
      out.push_back((lo + hi) / 2);
    }
    a = b;
    fa = fb;
  }
  return out;
}

}  // namespace

TEST_CASE(
    "gear pair with a rectangular-wave mesh stiffness (Meissner): the shooting's multipliers "
    "are the closed form's, one below -1 in the principal instability region",
    "[crosscheck][dynamics][periodic]") {
  const RectangularMeshPair s;
  // Away from the region (Ω = 1.2, 3.0): stable, both multipliers inside the circle.
  for (const double omega : {1.2, 3.0}) {
    const ShootingResult r =
        CheckAgainstClosedForm(s, omega, "Meissner Omega = " + std::to_string(omega));
    CHECK(r.floquet.stability == Stability::kStable);
  }
  // The region: between two boundaries of the closed form's region function.
  const std::vector<double> bounds = RegionBoundaries(s);
  REQUIRE(bounds.size() == 2);
  epicycle::test::FigureValue("Meissner principal region lower boundary", bounds[0], "-");
  epicycle::test::FigureValue("Meissner principal region upper boundary", bounds[1], "-");
  // It straddles twice the natural frequency of the mean stiffness, 2√(1 + ε(2(ε_α − 1) − 1)).
  const double k_mean = 1 + s.stiffness_variation * (2 * (s.contact_ratio - 1) - 1);
  CHECK(bounds[0] < 2 * std::sqrt(k_mean));
  CHECK(bounds[1] > 2 * std::sqrt(k_mean));
  const double middle = (bounds[0] + bounds[1]) / 2;
  const ShootingResult r = CheckAgainstClosedForm(s, middle, "Meissner region middle");
  CHECK(r.floquet.stability == Stability::kUnstable);
  CHECK(r.floquet.real_below_minus_one == 1);
  CHECK(r.floquet.multipliers[0].real() < -1);
  epicycle::test::FigureValue("Meissner region middle: shooting mu_1",
                              r.floquet.multipliers[0].real(), "-");
}

TEST_CASE(
    "gear pair with a rectangular-wave mesh stiffness (Meissner): just inside and just outside "
    "the principal region's boundary, a time integration grows and decays at log|mu|/T",
    "[crosscheck][dynamics][periodic]") {
  const RectangularMeshPair s;
  const std::vector<double> bounds = RegionBoundaries(s);
  REQUIRE(bounds.size() == 2);
  const ShootingOptions o = TightShooting();
  // 0.5 % of Ω on either side of the upper boundary.
  for (const int side : {-1, +1}) {
    const double omega = bounds[1] * (1 + side * 0.005);
    const std::string name = std::string("Meissner ") + (side < 0 ? "just inside" : "just outside");
    const ShootingResult r = CheckAgainstClosedForm(s, omega, name);
    const ClosedForm exact = Meissner(s, omega);
    const Multipliers mu = ClosedFormMultipliers(exact.monodromy);
    const double expected = std::log(std::abs(mu.mu[0])) / exact.period;  // [1/time]
    // Inside: a real multiplier below −1, growth; outside: both inside the circle, decay.
    CHECK((side < 0 ? expected > 0 : expected < 0));
    CHECK(r.floquet.stability == (side < 0 ? Stability::kUnstable : Stability::kStable));

    // A deviation d₀ = (1, 0) from the orbit, integrated over n and 2n periods: the orbit returns
    // to its state at whole periods, so y − y_orbit is the deviation d_k = M^k d₀. Its size is
    // measured in the closed form's eigenbasis, ‖V⁻¹d‖ (V the eigenvectors): there
    // V⁻¹d_k = (a μ₁^k, b μ₂^k), so ‖V⁻¹d_k‖² = |a|²|μ₁|^{2k}(1 + η² r^{2k}), η = |b|/|a|,
    // r = |μ₂/μ₁|, and log(‖V⁻¹d_2n‖/‖V⁻¹d_n‖) − n log|μ₁| = ½ log((1 + η²r^{4n})/(1 + η²r^{2n})),
    // at most ½η²|r^{4n} − r^{2n}|: the smaller multiplier's share inside, where both are real
    // (r < 1), and nothing outside, where they are a complex pair of one modulus (r = 1).
    // n: inside, enough periods for the smaller multiplier's share to fade (r^{2n} ≈ 1e-5);
    // outside, no share to fade, and few enough that the decayed deviation stays well above the
    // integrations' error (e^{−ζ 2nT} ≈ 0.1).
    const int n = side < 0 ? 100 : 20;
    const Eigen::VectorXd p = Eigen::VectorXd::Constant(1, omega);
    const Eigen::Vector2d d0(1, 0);
    const Eigen::VectorXd yn = IntegratePeriods(s, o, r.initial_state + d0, p, n);
    const Eigen::VectorXd y2n = IntegratePeriods(s, o, yn, p, n);
    const Eigen::Matrix2cd vinv = mu.vectors.inverse();
    const auto size = [&](const Eigen::VectorXd& d) { return (vinv * d.cast<Complex>()).norm(); };
    const double dn = size(yn - r.initial_state), d2n = size(y2n - r.initial_state);
    const double rate = std::log(d2n / dn) / (n * exact.period);
    const Eigen::Vector2cd coeffs = vinv * d0.cast<Complex>();
    const double eta = std::abs(coeffs(1)) / std::abs(coeffs(0));
    const double ratio = std::abs(mu.mu[1] / mu.mu[0]);
    const double share =
        0.5 * eta * eta * std::abs(std::pow(ratio, 4 * n) - std::pow(ratio, 2 * n));
    // The integrations add at most one local tolerance (rtol|y| + atol) a step, carried to the
    // end by at most max(1, |μ₁|)^{2n} ‖V‖‖V⁻¹‖ (M^k = V Λ^k V⁻¹), and the shooting's orbit error
    // (its bound above) at each end; ‖V⁻¹‖ times that over the smaller size is each logarithm's
    // relative error (|log(1 + x)| ≤ 2|x| for |x| ≤ 1/2).
    const double steps = static_cast<double>(r.steps) / static_cast<double>(r.integrations);
    const Eigen::Matrix2d inv = (exact.monodromy - Eigen::Matrix2d::Identity()).inverse();
    const double w = ShootingWeight(o, r.initial_state + d0);
    const double orbit_error = (inv.norm() * o.newton_tolerance + steps) * w;
    const double v_norm = mu.vectors.operatorNorm(), vinv_norm = vinv.operatorNorm();
    const double carried = std::pow(std::max(1.0, std::abs(mu.mu[0])), 2 * n) * v_norm * vinv_norm;
    const double relative =
        vinv_norm * (2 * n * steps * w * carried + 2 * orbit_error) / std::min(dn, d2n);
    REQUIRE(relative <= 0.5);
    const double tol = (share + 2 * 2 * relative) / (n * exact.period);
    if (side > 0) {
      // Outside, the pair's modulus is √det M = e^{−ζT} (Liouville: det M = e^{−2ζT}): the
      // closed form's rate is −ζ.
      CHECK(ratio == Approx(1).margin(1e-12));
      CHECK(expected == Approx(-s.damping_ratio).margin(1e-12));
    }
    epicycle::test::FigureValue(name + ": Omega", omega, "-");
    epicycle::test::FigureValue(name + ": growth rate, integration", rate, "1/time");
    epicycle::test::FigureValue(name + ": growth rate, log|mu|/T (closed form)", expected,
                                "1/time");
    epicycle::test::FigureValue(name + ": growth rate, log|mu|/T (shooting)",
                                std::log(r.floquet.spectral_radius) / r.period, "1/time");
    epicycle::test::FigureValue(name + ": growth rate tolerance", tol, "1/time");
    CHECK(rate == Approx(expected).margin(tol));
    CHECK((side < 0 ? rate > 0 : rate < 0));
  }
}
