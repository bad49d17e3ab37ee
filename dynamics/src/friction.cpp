// Friction laws of one tooth contact (equations in friction.hpp).
#include "epicycle/dynamics/friction.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "number_format.hpp"

namespace epicycle::dynamics {
namespace {

using internal::Num;

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

// Literals, not strings: the message is built only when a rule fails (the contact checks run for
// every loaded contact at every right-hand side).
void Require(bool ok, const char* field, double value, const char* rule) {
  if (!ok) throw std::invalid_argument(std::string(field) + " = " + Num(value) + ": " + rule);
}

double XuKahraman(const FrictionOptions& o, const FrictionContact& c) {
  const double p_h = MaxHertzPressure(c) * 1e-9;  // [GPa]
  if (p_h <= 0) return 0.0;
  const double v_s = c.velocity_a - c.velocity_b;
  // Rolling stops (V_e → 0): the floor v_ε keeps SR and V_e^b6 finite; SR then reaches its cap.
  const double v_e = std::max(std::abs(0.5 * (c.velocity_a + c.velocity_b)), o.smoothing_velocity);
  const double sr = std::min(std::abs(v_s) / v_e, kMaxSlideToRoll);
  if (sr == 0.0) return 0.0;
  const double nu0 = o.lubricant.dynamic_viscosity * 1e3;  // [mPa·s]
  const double s_um = o.lubricant.composite_roughness * 1e6;
  const double x = sr * p_h * std::log10(nu0);
  const double f = kB1 + kB4 * x + kB5 * std::exp(-x) + kB9 * std::exp(s_um);
  const double mu = std::exp(f) * std::pow(p_h, kB2) * std::pow(sr, kB3) * std::pow(v_e, kB6) *
                    std::pow(nu0, kB7) * std::pow(c.reduced_radius, kB8);
  return std::copysign(std::min(mu, o.max_coefficient), v_s);
}

double BenedictKelley(const FrictionOptions& o, const FrictionContact& c) {
  const double v_s = c.velocity_a - c.velocity_b;
  const double smooth_sign = std::tanh(v_s / o.smoothing_velocity);
  const double load = c.normal_force / c.face_width;  // W' [N/m]
  if (load <= 0) return 0.0;                          // log10(0) = −∞: no friction
  const double v_r = c.velocity_a + c.velocity_b;
  const double nu0 = o.lubricant.dynamic_viscosity * 1e3;  // [mPa·s]
  const double denominator = nu0 * std::abs(v_s) * v_r * v_r;
  const double roughness_factor = 50.0 / (50.0 - o.lubricant.composite_roughness / kMicroInch);
  double mu = o.max_coefficient;  // the limit of the logarithm as v_s → 0 or V_r → 0
  if (denominator > 0) {
    const double argument = kBkConstant * load / denominator;
    mu = std::clamp(kBkFactor * roughness_factor * std::log10(argument), 0.0, o.max_coefficient);
  }
  return mu * smooth_sign;
}

}  // namespace

std::string FrictionLawName(FrictionLaw law) {
  switch (law) {
    case FrictionLaw::kOff:
      return "off";
    case FrictionLaw::kConstant:
      return "constant";
    case FrictionLaw::kXuKahraman:
      return "xu-kahraman";
    case FrictionLaw::kBenedictKelley:
      return "benedict-kelley";
  }
  throw std::invalid_argument("friction law " + std::to_string(static_cast<int>(law)) +
                              ": not one of off, constant, xu-kahraman, benedict-kelley");
}

FrictionLaw FrictionLawFromName(const std::string& name) {
  for (FrictionLaw law : {FrictionLaw::kOff, FrictionLaw::kConstant, FrictionLaw::kXuKahraman,
                          FrictionLaw::kBenedictKelley})
    if (FrictionLawName(law) == name) return law;
  throw std::invalid_argument("friction law \"" + name +
                              "\": must be one of off, constant, xu-kahraman, benedict-kelley");
}

void FrictionOptions::Validate() const {
  FrictionLawName(law);  // throws for a value outside the enum
  Require(std::isfinite(max_coefficient) && max_coefficient > 0, "friction.max_coefficient",
          max_coefficient, "must be finite and > 0");
  if (!(std::isfinite(coefficient) && coefficient >= 0 && coefficient <= max_coefficient))
    throw std::invalid_argument(
        "friction.coefficient = " + Num(coefficient) +
        ": must be finite, >= 0 and <= friction.max_coefficient = " + Num(max_coefficient));
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
  return std::sqrt(c.normal_force * c.contact_modulus / (kPi * c.face_width * c.reduced_radius));
}

double SignedFrictionCoefficient(const FrictionOptions& options, const FrictionContact& c) {
  ValidateFrictionContact(c);
  switch (options.law) {
    case FrictionLaw::kOff:
      return 0.0;
    case FrictionLaw::kConstant:
      return std::min(options.coefficient, options.max_coefficient) *
             std::tanh((c.velocity_a - c.velocity_b) / options.smoothing_velocity);
    case FrictionLaw::kXuKahraman:
      return XuKahraman(options, c);
    case FrictionLaw::kBenedictKelley:
      return BenedictKelley(options, c);
  }
  throw std::invalid_argument("friction.law = " + std::to_string(static_cast<int>(options.law)) +
                              ": not one of off, constant, xu-kahraman, benedict-kelley");
}

}  // namespace epicycle::dynamics
