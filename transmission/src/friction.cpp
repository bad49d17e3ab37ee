// Friction laws of one tooth contact (equations in friction.hpp).
#include "epicycle/transmission/friction.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "epicycle/io/number_format.hpp"

namespace epicycle::transmission {
namespace {

using io::Num;

constexpr double kPi = 3.14159265358979323846;

// Xu et al. (2007) regression constants b1..b9 (docs/model.md §7).
constexpr double kB1 = -8.916465, kB2 = 1.03303, kB3 = 1.036077, kB4 = -0.354068, kB5 = 2.812084,
                 kB6 = -0.100601, kB7 = 0.752755, kB8 = -0.390958, kB9 = 0.620305;
// The slide-to-roll ratio when one surface is at rest; the regression has no meaning beyond it.
constexpr double kMaxSlideToRoll = 2.0;

// Benedict & Kelley (1961): 0.0127·C_R·log10(3.17e8·W'/(η0·V_s·V_r²)) in lb/in, cP, in/s. The
// constant is converted exactly (1 lbf = 4.4482216152605 N, 1 in = 0.0254 m) rather than taken
// as the rounded 29.66, so that SI and US inputs give the same μ.
constexpr double kBkFactor = 0.0127;
constexpr double kInch = 0.0254;                                                // [m]
constexpr double kPoundPerInch = 4.4482216152605 / kInch;                       // [N/m]
constexpr double kBkConstant = 3.17e8 * kInch * kInch * kInch / kPoundPerInch;  // ≈ 29.66
constexpr double kMicroInch = kInch * 1e-6;                                     // [m]
constexpr double kMaxFinite = std::numeric_limits<double>::max();

// Literals, not strings: the message is built only when a rule fails (the contact checks run for
// every loaded contact at every right-hand side).
void Require(bool ok, const char* field, double value, const char* rule) {
  if (!ok) throw std::invalid_argument(std::string(field) + " = " + Num(value) + ": " + rule);
}

// p_h = √(F E*/(π b R)) [Pa] of a contact already validated.
double HertzPressure(const FrictionContact& c) {
  return std::sqrt(c.normal_force * c.contact_modulus / (kPi * c.face_width * c.reduced_radius));
}

}  // namespace

FrictionModel::FrictionModel(const FrictionOptions& options) : options_(options) {
  const Lubricant& l = options_.lubricant;
  nu0_ = l.dynamic_viscosity * 1e3;  // [mPa·s] (= cP), both lubricated laws
  // Xu & Kahraman: the factor that depends only on the lubricant, K = e^(b1 + b9·e^S)·ν0^b7
  // (S [µm], ν0 [mPa·s]), once per model in long double so that it is correctly rounded (where
  // long double is double it carries the ~2 ulp of the expression); log10 ν0 scales
  // x = SR·P_h·log10 ν0.
  const long double s_um = static_cast<long double>(l.composite_roughness) * 1e6L;
  xk_constant_ = static_cast<double>(std::exp(kB1 + kB9 * std::exp(s_um)) *
                                     std::pow(static_cast<long double>(nu0_), kB7));
  xk_log10_nu0_ = std::log10(nu0_);
  // Benedict & Kelley: 0.0127·C_R with the roughness factor C_R = 50/(50 − S[µin]).
  bk_factor_ = kBkFactor * (50.0 / (50.0 - l.composite_roughness / kMicroInch));
}

// Xu et al. (2007) (equations in friction.hpp) with the lubricant's factor
// K = e^(b1 + b9·e^S)·ν0^b7 evaluated once (constructor) and the rest as one exponential of a
// sum of logarithms:
//
//   μ = K · e^(b2·ln P_h + b3·ln SR + b6·ln V_e + b8·ln R + b4·x + b5·e^(−x)),
//   x = SR·P_h·log10 ν0,   P_h [GPa], SR [-], V_e [m/s], R [m], ν0 [mPa·s],
//
// four logarithms and two exponentials per contact instead of five pow (each a logarithm and an
// exponential inside) and three exponentials. It is the printed product rounded differently: each
// term of the sum (|term| ≲ 7) carries an absolute error of about ε·|term|, which e^(·) turns
// into a relative error of μ; over the regression's range the result is within 11 ulp of the
// exact product (mean 1.6 ulp; the product of powers in double: 16 ulp, mean 3), test "Xu–Kahraman
// 's log form matches the printed product to a few ulp".
double FrictionModel::XuKahraman(const FrictionContact& c) const {
  const double p_h = HertzPressure(c) * 1e-9;  // [GPa]
  if (p_h <= 0) return 0.0;
  const double v_s = c.velocity_a - c.velocity_b;
  // Rolling stops (V_e → 0): the floor v_ε keeps SR and V_e^b6 finite; SR then reaches its cap.
  const double v_e =
      std::max(std::abs(0.5 * (c.velocity_a + c.velocity_b)), options_.smoothing_velocity);
  const double sr = std::min(std::abs(v_s) / v_e, kMaxSlideToRoll);
  if (sr == 0.0) return 0.0;
  const double x = sr * p_h * xk_log10_nu0_;
  const double exponent = kB2 * std::log(p_h) + kB3 * std::log(sr) + kB6 * std::log(v_e) +
                          kB8 * std::log(c.reduced_radius) + kB4 * x + kB5 * std::exp(-x);
  const double mu = xk_constant_ * std::exp(exponent);
  return std::copysign(std::min(mu, options_.max_coefficient), v_s);
}

double FrictionModel::BenedictKelley(const FrictionContact& c) const {
  const double v_s = c.velocity_a - c.velocity_b;
  const double smooth_sign = std::tanh(v_s / options_.smoothing_velocity);
  const double load = c.normal_force / c.face_width;  // W' [N/m]
  if (load <= 0) return 0.0;                          // log10(0) = −∞: no friction
  const double v_r = c.velocity_a + c.velocity_b;
  const double denominator = nu0_ * std::abs(v_s) * v_r * v_r;
  double mu = options_.max_coefficient;  // the limit of the logarithm as v_s → 0 or V_r → 0
  if (denominator > 0) {
    const double argument = kBkConstant * load / denominator;
    mu = std::clamp(bk_factor_ * std::log10(argument), 0.0, options_.max_coefficient);
  }
  return mu * smooth_sign;
}

double FrictionModel::SignedCoefficient(const FrictionContact& c) const {
  ValidateFrictionContact(c);
  switch (options_.law) {
    case FrictionLaw::kOff:
      return 0.0;
    case FrictionLaw::kConstant:
      return options_.coefficient *
             std::tanh((c.velocity_a - c.velocity_b) / options_.smoothing_velocity);
    case FrictionLaw::kXuKahraman:
      return XuKahraman(c);
    case FrictionLaw::kBenedictKelley:
      return BenedictKelley(c);
  }
  throw std::invalid_argument("friction.law = " + std::to_string(static_cast<int>(options_.law)) +
                              ": not one of " + io::NameList(kFrictionLawNames));
}

std::string FrictionLawName(FrictionLaw law) {
  if (const char* name = io::NameOf(kFrictionLawNames, law)) return name;
  throw std::invalid_argument("friction law " + std::to_string(static_cast<int>(law)) +
                              ": not one of " + io::NameList(kFrictionLawNames));
}

FrictionLaw FrictionLawFromName(const std::string& name) {
  if (const std::optional<FrictionLaw> law = io::ValueOf(kFrictionLawNames, name)) return *law;
  throw std::invalid_argument("friction law \"" + name + "\": must be one of " +
                              io::NameList(kFrictionLawNames));
}

void FrictionOptions::Validate() const {
  FrictionLawName(law);  // throws for a value outside the enum
  Require(std::isfinite(max_coefficient) && max_coefficient > 0, "friction.max_coefficient",
          max_coefficient, "must be finite and > 0");
  Require(coefficient >= 0 && coefficient <= 1, "friction.coefficient", coefficient,
          "must be in [0, 1]");
  Require(std::isfinite(smoothing_velocity) && smoothing_velocity > 0,
          "friction.smoothing_velocity", smoothing_velocity, "must be finite and > 0 [m/s]");
  Require(std::isfinite(lubricant.dynamic_viscosity) && lubricant.dynamic_viscosity > 0,
          "friction.lubricant.dynamic_viscosity", lubricant.dynamic_viscosity,
          "must be finite and > 0 [Pa s]");
  Require(std::isfinite(lubricant.composite_roughness) && lubricant.composite_roughness >= 0,
          "friction.lubricant.composite_roughness", lubricant.composite_roughness,
          "must be finite and >= 0 [m]");
  if (law == FrictionLaw::kBenedictKelley)
    Require(lubricant.composite_roughness < 50 * kMicroInch,
            "friction.lubricant.composite_roughness", lubricant.composite_roughness,
            "must be < 50 microinch = 1.27e-06 m for benedict-kelley (roughness factor "
            "50/(50 - S))");
}

void ValidateFrictionContact(const FrictionContact& c) {
  // One test for the common case (NaN fails every comparison); the rules one by one, with their
  // messages, only when it fails.
  if (c.normal_force >= 0 && c.normal_force <= kMaxFinite && std::abs(c.velocity_a) <= kMaxFinite &&
      std::abs(c.velocity_b) <= kMaxFinite && c.reduced_radius > 0 &&
      c.reduced_radius <= kMaxFinite && c.face_width > 0 && c.face_width <= kMaxFinite &&
      c.contact_modulus > 0 && c.contact_modulus <= kMaxFinite)
    return;
  Require(std::isfinite(c.normal_force) && c.normal_force >= 0, "contact.normal_force",
          c.normal_force, "must be finite and >= 0 [N]");
  Require(std::isfinite(c.velocity_a), "contact.velocity_a", c.velocity_a, "must be finite [m/s]");
  Require(std::isfinite(c.velocity_b), "contact.velocity_b", c.velocity_b, "must be finite [m/s]");
  Require(std::isfinite(c.reduced_radius) && c.reduced_radius > 0, "contact.reduced_radius",
          c.reduced_radius, "must be finite and > 0 [m]");
  Require(std::isfinite(c.face_width) && c.face_width > 0, "contact.face_width", c.face_width,
          "must be finite and > 0 [m]");
  Require(std::isfinite(c.contact_modulus) && c.contact_modulus > 0, "contact.contact_modulus",
          c.contact_modulus, "must be finite and > 0 [Pa]");
}

double MaxHertzPressure(const FrictionContact& c) {
  ValidateFrictionContact(c);
  return HertzPressure(c);
}

double SignedFrictionCoefficient(const FrictionOptions& options, const FrictionContact& c) {
  return FrictionModel(options).SignedCoefficient(c);
}

}  // namespace epicycle::transmission
