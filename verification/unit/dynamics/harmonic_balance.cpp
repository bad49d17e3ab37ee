// Harmonic balance (dynamics/harmonic_balance.hpp, docs/periodic.md §1 "Harmonic balance"): the
// Fourier maps of the AFT, a linear system that one harmonic holds exactly, Hill's method against
// closed forms and shooting on a smooth system, and bad input.
#include <catch2/catch.hpp>

#include <cmath>
#include <complex>
#include <limits>
#include <numbers>

#include "epicycle/dynamics/harmonic_balance.hpp"
#include "epicycle/dynamics/periodic_systems.hpp"

using namespace epicycle::dynamics;

namespace {
constexpr double kEps = std::numeric_limits<double>::epsilon();
}

TEST_CASE("Fourier basis: analysis inverts synthesis, the derivative is exact on a series",
          "[unit][dynamics][harmonic_balance]") {
  const int h = 5, n = 16;
  const FourierBasis b(h, n);
  // P E = I for harmonics below N/2 (discrete orthogonality of the sampled cos and sin): to the
  // round-off of N-term sums of order-1 products, a few N ε.
  CHECK((b.analysis * b.synthesis - Eigen::MatrixXd::Identity(2 * h + 1, 2 * h + 1))
            .cwiseAbs()
            .maxCoeff() <= 10 * n * kEps);
  // y(s) = 0.3 + 2 cos 2π3s − sin 2π5s: y'(s) = −12π sin 2π3s − 10π cos 2π5s, at s = 0.1.
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(2 * h + 1, 1);
  c(0, 0) = 0.3;
  c(5, 0) = 2;
  c(10, 0) = -1;
  const Eigen::VectorXd s = Eigen::VectorXd::Constant(1, 0.1);
  const double pi = std::numbers::pi;
  const double y = 0.3 + 2 * std::cos(2 * pi * 0.3) - std::sin(2 * pi * 0.5);
  const double dy = -12 * pi * std::sin(2 * pi * 0.3) - 10 * pi * std::cos(2 * pi * 0.5);
  CHECK(std::abs(b.Evaluate(c, s)(0, 0) - y) <= 10 * kEps);
  CHECK(std::abs(b.Evaluate(b.derivative * c, s)(0, 0) - dy) <= 100 * kEps);
}

TEST_CASE("harmonic balance: a driven linear oscillator is one harmonic, its multipliers exp(λT)",
          "[unit][dynamics][harmonic_balance]") {
  const DrivenLinearOscillator s;  // ω_n = 2, ζ = 0.1, a = 1, ω = 3
  HarmonicBalanceOptions o;
  o.harmonics = 1;
  o.rtol = 1e-12;
  o.atol = Eigen::VectorXd::Constant(1, 1e-14);
  const HarmonicBalanceResult r = SolveHarmonicBalance(s, o, Eigen::Vector2d(0, 0));
  INFO(r.message);
  REQUIRE(r.status == ShootingStatus::kConverged);
  // Steady state Re(X e^{iωt}), X = a/(ω_n² − ω² + 2iζω_nω): a linear system's Newton step lands
  // on it at once; what remains is the LU's round-off on the 3 × 3 blocks, scaled by |X| ≈ 0.2.
  const std::complex<double> x = 1.0 / std::complex<double>(4 - 9, 2 * 0.1 * 2 * 3);
  const std::complex<double> v = std::complex<double>(0, 3) * x;
  CHECK(std::abs(r.initial_state(0) - x.real()) <= 1e3 * kEps);
  CHECK(std::abs(r.initial_state(1) - v.real()) <= 1e3 * kEps);
  CHECK(r.iterations <= 2);
  // Hill's matrix of a time-invariant system is block-diagonal, J − 2πik/T per harmonic: its
  // centred eigenvalues are λT exactly, λ = −ζω_n ± iω_n√(1 − ζ²); μ = exp(λT) to the
  // eigensolver's round-off relative to |λT| ≈ 4.
  const double t = 2 * std::numbers::pi / 3;
  const std::complex<double> lambda(-0.2, 2 * std::sqrt(1 - 0.01));
  REQUIRE(r.floquet.multipliers.size() == 2);
  for (const std::complex<double> mu : r.floquet.multipliers) {
    const std::complex<double> expected = mu.imag() > 0 ? std::exp(std::conj(lambda) * t)
                                                        : std::exp(lambda * t);
    // exp(λT) with Im λT < 0 has Im μ = e^{σT} sin(Im λT) of either sign: compare with both.
    const double err = std::min(std::abs(mu - expected), std::abs(mu - std::conj(expected)));
    CHECK(err <= 1e3 * kEps);
  }
  CHECK(r.floquet.stability == Stability::kStable);
}

TEST_CASE("Hill's method on the Mathieu equation matches shooting inside and outside the tongue",
          "[unit][dynamics][harmonic_balance]") {
  const MathieuOscillator s;
  ShootingOptions so;
  so.rtol = 1e-10;
  so.atol = Eigen::VectorXd::Constant(1, 1e-12);
  for (const double delta : {0.25, 0.1}) {
    const Eigen::Vector3d p(delta, 0.1, 0.0);
    const ShootingResult shot = SolvePeriodicOrbit(s, so, Eigen::Vector2d(0, 0), p);
    REQUIRE(shot.status == ShootingStatus::kConverged);
    HarmonicBalanceOptions o;
    o.harmonics = 8;
    const HarmonicBalanceResult r = SolveHarmonicBalance(s, o, Eigen::Vector2d(0, 0), p);
    REQUIRE(r.status == ShootingStatus::kConverged);
    REQUIRE(r.floquet.multipliers.size() == 2);
    // The coefficient ε cos t couples harmonic k to k ± 1 with ε/2 against (k/2)² − δ: the Hill
    // determinant's truncation error falls like (ε/2)^{2H}/Π((k/2)² − δ)² — far below the
    // shooting's multipliers' own error, 1e-6 of |μ| (docs/periodic.md §3, Mathieu rows).
    for (std::size_t k = 0; k < 2; ++k)
      CHECK(std::abs(r.floquet.multipliers[k] - shot.floquet.multipliers[k]) <= 1e-6);
    CHECK(r.floquet.real_below_minus_one == shot.floquet.real_below_minus_one);
    CHECK(r.floquet.stability == shot.floquet.stability);
  }
}

TEST_CASE("harmonic balance: bad input names the field, its value and the rule",
          "[unit][dynamics][harmonic_balance]") {
  const DrivenLinearOscillator s;
  HarmonicBalanceOptions o;
  o.harmonics = 4;
  o.samples = 8;
  CHECK_THROWS_WITH(SolveHarmonicBalance(s, o, Eigen::Vector2d(0, 0)),
                    "harmonic balance: samples = 8: must be 0 (4 harmonics) or >= 2 harmonics + "
                    "1 = 9");
  o.samples = 0;
  o.hill_harmonics = 5;
  CHECK_THROWS_WITH(SolveHarmonicBalance(s, o, Eigen::Vector2d(0, 0)),
                    "harmonic balance: hill_harmonics = 5: must lie in [0, harmonics = 4] (0: "
                    "harmonics)");
  o.hill_harmonics = 0;
  CHECK_THROWS_WITH(SolveHarmonicBalance(s, o, Eigen::Vector3d(0, 0, 0)),
                    "harmonic balance: the guess is 3 × 1: must be 2 × 1 (a state) or 9 × 2 "
                    "(coefficients)");
  CHECK_THROWS_WITH(SolveHarmonicBalance(s, o, Eigen::Vector2d(0, 0), Eigen::VectorXd::Constant(1, -3.0)),
                    "harmonic balance: the period T [s] = -2.0944: must be > 0 and finite");
}
