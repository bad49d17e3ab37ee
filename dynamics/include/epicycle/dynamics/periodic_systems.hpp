// Small periodic systems with known answers (docs/periodic.md §3): the reference cases of the
// periodic solver's tests and benchmark, and examples of the PeriodicSystem interface. All are
// nondimensional (time in units of 1/ω_n where a natural frequency exists).
#pragma once

#include "epicycle/dynamics/periodic.hpp"

namespace epicycle::dynamics {

/// A damped oscillator under harmonic forcing: x'' + 2ζω_n x' + ω_n² x = a cos ωt, y = (x, x').
/// Parameter "omega" [rad/s] (T = 2π/ω). Steady state x = Re(a e^{iωt}/(ω_n² − ω² + 2iζω_nω));
/// eigenvalues λ = −ζω_n ± iω_n√(1 − ζ²).
class DrivenLinearOscillator : public PeriodicSystem {
 public:
  double natural_frequency = 2.0;  ///< ω_n [rad/s]
  double damping_ratio = 0.1;      ///< ζ [-]
  double amplitude = 1.0;          ///< a [1/s²] (force over mass)
  double omega = 3.0;              ///< ω's default [rad/s]
  int size() const override { return 2; }
  std::vector<PeriodicParameter> parameters() const override;
  double Period(const Eigen::VectorXd& p) const override;
  bool Rhs(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& p,
           Eigen::VectorXd* f) const override;
  bool has_jacobian() const override { return true; }
  bool Jacobian(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& p,
                Eigen::MatrixXd* jac) const override;
};

/// The gear pair with backlash of Kahraman & Singh (1990, JSV 142(1)), nondimensional (lengths
/// over half the backlash, time over 1/ω_n): x'' + 2ζx' + g(x) = F_m + F_a cos Ωt with
/// g(x) = x − 1 (x > 1, teeth in contact), 0 (|x| ≤ 1, separated), x + 1 (x < −1, back-side
/// contact). y = (x, x'). Parameters "Omega" [-] (forcing over natural frequency; T = 2π/Ω) and
/// "F_a" [-]. While the teeth stay in contact (x > 1 throughout) the response is the linear
/// oscillator's about x = 1 + F_m.
class BacklashOscillator : public PeriodicSystem {
 public:
  double damping_ratio = 0.05;      ///< ζ [-]
  double mean_force = 0.1;          ///< F_m [-]
  double alternating_force = 0.05;  ///< F_a's default [-]
  double omega = 1.0;               ///< Ω's default [-]
  int size() const override { return 2; }
  std::vector<PeriodicParameter> parameters() const override;
  double Period(const Eigen::VectorXd& p) const override;
  bool Rhs(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& p,
           Eigen::VectorXd* f) const override;
  bool has_jacobian() const override { return true; }
  bool Jacobian(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& p,
                Eigen::MatrixXd* jac) const override;
};

/// The damped Mathieu equation x'' + c x' + (δ + ε cos t) x = 0, y = (x, x'), T = 2π.
/// Parameters "delta", "epsilon", "damping" [-]. Without damping the first instability tongue
/// lies between δ = 1/4 ± ε/2 − ε²/8 ∓ ε³/32 + O(ε⁴) (Abramowitz & Stegun 20.2.25 with a = 4δ,
/// q = 2ε); det M = e^{−2πc} (Liouville). No Jacobian: the solver's differences are exercised.
class MathieuOscillator : public PeriodicSystem {
 public:
  double delta = 0.25, epsilon = 0.1, damping = 0.0;  ///< defaults [-]
  int size() const override { return 2; }
  std::vector<PeriodicParameter> parameters() const override;
  double Period(const Eigen::VectorXd& p) const override;
  bool Rhs(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& p,
           Eigen::VectorXd* f) const override;
};

}  // namespace epicycle::dynamics
