#include "epicycle/dynamics/periodic_systems.hpp"

#include <cmath>
#include <numbers>

namespace epicycle::dynamics {

namespace {
double TwoPiOver(double omega) { return 2 * std::numbers::pi / omega; }
}  // namespace

std::vector<PeriodicParameter> DrivenLinearOscillator::parameters() const {
  return {{"omega", "rad/s", omega}};
}
double DrivenLinearOscillator::Period(const Eigen::VectorXd& p) const { return TwoPiOver(p(0)); }
bool DrivenLinearOscillator::Rhs(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& p,
                                 Eigen::VectorXd* f) const {
  const double wn = natural_frequency;
  (*f)(0) = y(1);
  (*f)(1) = amplitude * std::cos(p(0) * t) - 2 * damping_ratio * wn * y(1) - wn * wn * y(0);
  return true;
}
bool DrivenLinearOscillator::Jacobian(double, const Eigen::VectorXd&, const Eigen::VectorXd&,
                                      Eigen::MatrixXd* jac) const {
  const double wn = natural_frequency;
  jac->resize(2, 2);
  *jac << 0, 1, -wn * wn, -2 * damping_ratio * wn;
  return true;
}

std::vector<PeriodicParameter> BacklashOscillator::parameters() const {
  return {{"Omega", "-", omega}, {"F_a", "-", alternating_force}};
}
double BacklashOscillator::Period(const Eigen::VectorXd& p) const { return TwoPiOver(p(0)); }
bool BacklashOscillator::Rhs(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& p,
                             Eigen::VectorXd* f) const {
  const double x = y(0);
  const double g = x > 1 ? x - 1 : (x < -1 ? x + 1 : 0.0);
  (*f)(0) = y(1);
  (*f)(1) = mean_force + p(1) * std::cos(p(0) * t) - 2 * damping_ratio * y(1) - g;
  return true;
}
bool BacklashOscillator::Jacobian(double, const Eigen::VectorXd& y, const Eigen::VectorXd&,
                                  Eigen::MatrixXd* jac) const {
  jac->resize(2, 2);
  *jac << 0, 1, std::abs(y(0)) > 1 ? -1.0 : 0.0, -2 * damping_ratio;
  return true;
}

std::vector<PeriodicParameter> MathieuOscillator::parameters() const {
  return {{"delta", "-", delta}, {"epsilon", "-", epsilon}, {"damping", "-", damping}};
}
double MathieuOscillator::Period(const Eigen::VectorXd&) const { return 2 * std::numbers::pi; }
bool MathieuOscillator::Rhs(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& p,
                            Eigen::VectorXd* f) const {
  (*f)(0) = y(1);
  (*f)(1) = -p(2) * y(1) - (p(0) + p(1) * std::cos(t)) * y(0);
  return true;
}

}  // namespace epicycle::dynamics
