// Harmonic balance: the periodic orbit of a T-periodic system y' = f(t, y; p) (the form of
// periodic.hpp's PeriodicSystem) as a truncated Fourier series, a second back end beside shooting
// for systems whose orbit repeats with the forcing (no period map). Equations and method:
// docs/periodic.md §1 ("Harmonic balance") and §2; verification: docs/periodic.md §3.
//
// In the scaled time s = t/T ∈ [0, 1):
//   y(s) = a_0 + Σ_{k=1..H} (a_k cos 2πks + b_k sin 2πks),   c = (a_0, a_1, b_1, …, a_H, b_H) per
//   state component, the unknowns C ((2H + 1) × n).
// The residual by alternating frequency/time (AFT): the states at N ≥ 2H + 1 equally spaced
// instants s_j = j/N (Y = E C), the system's right-hand side there (F_j = f(T s_j, Y_j; p)), its
// coefficients by the discrete Fourier transform (P F, exact for harmonics below N/2):
//   R(C; p) = D C − T P F(E C) = 0,   D the derivative d/ds on the coefficients.
// Newton's matrix: ∂R/∂C = D − T P diag_j(J(T s_j, Y_j)) E per pair of components, J the system's
// Jacobian (the stage's: frozen contact geometry, docs/periodic.md §2) or forward differences.
//
// Stability by Hill's method: the eigenvalues ν of −∂R/∂C are the Floquet exponents times T,
// each repeated at ν + 2πik for the harmonics k kept; of each family the member whose eigenvector
// is centred on harmonic 0 (the smallest |Σ_k k w_k|, w_k the eigenvector's weight at complex
// harmonic k) is taken, n in all, and μ = exp(ν) (Lazarus & Thomas 2010, C. R. Mécanique 338(9)
// 510–517).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "epicycle/dynamics/periodic.hpp"

namespace epicycle::dynamics {

struct HarmonicBalanceOptions {
  int harmonics = 16;  ///< H, harmonics of the forcing frequency kept [-], ≥ 1
  /// N, instants per period of the AFT [-]: 0 for 4H (the products of harmonics up to H alias
  /// only above 3H); otherwise ≥ 2H + 1.
  int samples = 0;
  double rtol = 1e-8;  ///< relative part of the weights of the convergence test [-], in (0, 0.1]
  /// Absolute part per state component [units of y]; size 1: the same for every component.
  Eigen::VectorXd atol = Eigen::VectorXd::Constant(1, 1e-10);
  /// Newton stops when the weighted RMS norm of the update of the orbit's samples, each
  /// component over (rtol max_s |y_i| + atol_i), is ≤ this [-].
  double newton_tolerance = 1.0;
  int max_iterations = 40;  ///< Newton iterations [-], ≥ 1
  /// As ShootingOptions::unit_circle_tolerance [-].
  double unit_circle_tolerance = 1e-6;
  /// Compute the Floquet multipliers by Hill's method at the answer (one eigenproblem of size
  /// n(2H_s + 1)).
  bool stability = true;
  /// H_s, the harmonics of Hill's matrix [-]: 0 for H; otherwise in [1, H]: the rows and columns
  /// of harmonics ≤ H_s of ∂R/∂C, the Hill matrix of the same J(t) truncated at H_s (its
  /// eigenproblem costs (H_s/H)³ of the whole; docs/periodic.md §4).
  int hill_harmonics = 0;
  int HillHarmonics() const { return hill_harmonics > 0 ? hill_harmonics : harmonics; }
  int SampleCount() const { return samples > 0 ? samples : 4 * harmonics; }
  /// @throws std::invalid_argument naming the field, its value and the rule.
  void Validate(int n) const;
};

/// The real Fourier basis of H harmonics at N equally spaced instants of the scaled period and
/// the maps of the AFT (docs/periodic.md §1, "Harmonic balance").
struct FourierBasis {
  FourierBasis(int harmonics, int samples);
  int harmonics = 0, samples = 0;
  Eigen::MatrixXd synthesis;   ///< E (N × (2H + 1)): values of 1, cos 2πks, sin 2πks at s_j
  Eigen::MatrixXd analysis;    ///< P ((2H + 1) × N): the coefficients of N samples (P E = I)
  Eigen::MatrixXd derivative;  ///< D ((2H + 1) × (2H + 1)): d/ds on the coefficients
  /// y(s) of the coefficients C ((2H + 1) × n) at the scaled times `s` (rows: instants).
  Eigen::MatrixXd Evaluate(const Eigen::MatrixXd& coefficients, const Eigen::VectorXd& s) const;
};

struct HarmonicBalanceResult {
  ShootingStatus status = ShootingStatus::kIterationLimit;  ///< kIntegrationFailed: f failed
  std::string message;              ///< where and why it stopped, when not converged
  Eigen::MatrixXd coefficients;     ///< C ((2H + 1) × n) [units of y]
  Eigen::VectorXd initial_state;    ///< y(0) of the series [units of y]
  Eigen::VectorXd parameters;       ///< p
  double period = 0;                ///< T [s]
  FloquetReport floquet;            ///< by Hill's method (empty without `stability`)
  /// Floquet exponents times T, ν = λT, the n taken from the Hill matrix [-].
  std::vector<std::complex<double>> exponents;
  double update_norm = 0;   ///< weighted RMS of the last Newton update [-]
  double residual_norm = 0; ///< weighted RMS of R/(2π) at the answer (same weights) [-]
  int iterations = 0;       ///< Newton iterations [-]
  long rhs_evaluations = 0; ///< f evaluations (J's at the same instants not counted) [-]
};

/// Harmonic balance from the guess `guess` ((2H + 1) × n coefficients; a vector of size n: the
/// constant y(t) = guess) at parameters p (empty: the system's defaults).
/// @throws std::invalid_argument for bad options or sizes, a period that is not > 0 and finite,
///         or a system with a period map (its orbit is not periodic in its own coordinates).
HarmonicBalanceResult SolveHarmonicBalance(const PeriodicSystem& system,
                                           const HarmonicBalanceOptions& options,
                                           const Eigen::MatrixXd& guess,
                                           const Eigen::VectorXd& p = {});

/// The HB residual and, if `jacobian` is given, its Jacobian ∂R/∂C (m × m, m = n(2H + 1), the
/// unknowns ordered component by component, each component's 2H + 1 coefficients together) at
/// the coefficients C [units of y] and parameters p. R ((2H + 1) × n) [units of y].
/// false (with *message) if the system could not be evaluated at an instant.
bool HarmonicBalanceResidual(const PeriodicSystem& system, const FourierBasis& basis,
                             const Eigen::VectorXd& atol, double rtol, const Eigen::MatrixXd& C,
                             const Eigen::VectorXd& p, double period, Eigen::MatrixXd* residual,
                             Eigen::MatrixXd* jacobian, std::string* message);

/// Floquet exponents (times T) and multipliers by Hill's method from ∂R/∂C (any similarity
/// scaling of it component by component) of n components and H harmonics, truncated to its
/// harmonics ≤ hill_harmonics (in [1, H]).
FloquetReport HillStability(const Eigen::MatrixXd& jacobian, int n, int harmonics,
                            int hill_harmonics, double unit_circle_tolerance,
                            std::vector<std::complex<double>>* exponents = nullptr);

/// The options' absolute tolerance per component (size n).
Eigen::VectorXd ComponentTolerances(const Eigen::VectorXd& atol, int n);

}  // namespace epicycle::dynamics

namespace epicycle::dynamics {

/// Pseudo-arclength continuation of the harmonic-balance orbit (the loop of ContinuePeriodicOrbit,
/// docs/periodic.md §2, "Continuation", on the Fourier coefficients: the state scale of a component
/// scales all its coefficients; stability by Hill's method at every point). `continuation`'s
/// shooting options are not used but for unit_circle_tolerance's; `hb` gives the harmonics, the
/// samples and the convergence test. The first point from `guess` as SolveHarmonicBalance's;
/// ContinuationResult::start reports its Newton iterations and residual as a shooting's
/// (integrations: the linearisations, plain_integrations: the residual evaluations, steps: f
/// evaluations).
/// @throws as ContinuePeriodicOrbit and SolveHarmonicBalance.
ContinuationResult ContinueHarmonicBalance(
    const PeriodicSystem& system, const ContinuationOptions& continuation,
    const HarmonicBalanceOptions& hb, const Eigen::MatrixXd& guess, const Eigen::VectorXd& p = {},
    const std::function<void(const ContinuationResult&)>& on_point = {});

}  // namespace epicycle::dynamics
