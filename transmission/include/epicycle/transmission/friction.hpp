// Tooth friction laws of the dynamic model (docs/model.md §7, docs/friction.md): the
// signed Coulomb coefficient of one tooth contact from its load, its surface velocities and the
// lubricant.
#pragma once

#include <array>
#include <string>

#include "epicycle/io/enum_names.hpp"

namespace epicycle::transmission {

/// Which friction law gives the coefficient of a tooth contact.
enum class FrictionLaw { kOff, kConstant, kXuKahraman, kBenedictKelley };

/// The laws' names (the scene's [dynamics] friction, the programs' --friction): the one table of
/// FrictionLawName and FrictionLawFromName.
inline constexpr std::array<io::EnumName<FrictionLaw>, 4> kFrictionLawNames{{
    {FrictionLaw::kOff, "off"},
    {FrictionLaw::kConstant, "constant"},
    {FrictionLaw::kXuKahraman, "xu-kahraman"},
    {FrictionLaw::kBenedictKelley, "benedict-kelley"},
}};

/// "off", "constant", "xu-kahraman", "benedict-kelley".
/// @throws std::invalid_argument for a value outside the enum.
std::string FrictionLawName(FrictionLaw law);
/// The inverse of FrictionLawName.
/// @throws std::invalid_argument naming the value and the allowed names.
FrictionLaw FrictionLawFromName(const std::string& name);

/// The lubricant and surface data the lubricated laws need.
struct Lubricant {
  /// η0 [Pa·s]: dynamic (absolute) viscosity at the inlet temperature and ambient pressure
  /// (paper: 50 mPa·s). Xu & Kahraman and Benedict & Kelley both take it in mPa·s (= cP).
  double dynamic_viscosity = 0.05;
  /// S [m] ≥ 0: composite roughness of the two flanks (paper: 0.8 µm). Xu & Kahraman take it in
  /// µm; Benedict & Kelley's roughness factor takes the mean roughness of the two surfaces in
  /// µin, for which the same S is used (a choice, docs/dynamic.md).
  double composite_roughness = 0.8e-6;
};

/// Options of the friction law. Defaults: Xu & Kahraman with the paper's lubricant.
struct FrictionOptions {
  FrictionLaw law = FrictionLaw::kXuKahraman;
  double coefficient = 0.05;         ///< μ [-] of kConstant, in [0, 1]
  double smoothing_velocity = 1e-3;  ///< v_ε [m/s] > 0: sign(v_s) ≈ tanh(v_s/v_ε) (constant, B&K)
  /// μ_max [-] > 0: cap of |μ_s| for the lubricated laws (the constant law's μ is its own
  /// bound). Benedict & Kelley diverges at the pitch point (v_s → 0) and at standstill; Xu &
  /// Kahraman stays at a few hundredths (≤ 0.08 along the paper's sun–planet path, docs/dynamic.md)
  /// and meets the cap only far outside its range.
  double max_coefficient = 0.15;
  Lubricant lubricant;

  /// Rules: the law is one of the enum; coefficient, smoothing velocity, cap, viscosity finite;
  /// 0 ≤ coefficient ≤ 1; smoothing velocity, cap, viscosity > 0; roughness ≥ 0;
  /// Benedict & Kelley also needs S < 50 µin = 1.27 µm (its roughness factor 50/(50 − S)).
  /// @throws std::invalid_argument naming the field ("friction.coefficient", ...), value, rule.
  void Validate() const;
};

/// The default options with the law off (no friction).
inline FrictionOptions NoFriction() {
  FrictionOptions o;
  o.law = FrictionLaw::kOff;
  return o;
}

/// The state of one tooth contact that friction depends on.
struct FrictionContact {
  double normal_force = 0;  ///< F [N], ≥ 0
  double velocity_a = 0;    ///< u_A [m/s]: rolling velocity of body A's surface along t
  double velocity_b = 0;    ///< u_B [m/s]: the same for body B, along the same t
  double reduced_radius = 0;  ///< R [m] > 0: ρ_Aρ_B/(ρ_A + ρ_B) (external), ρ_Aρ_B/(ρ_B − ρ_A)
  double face_width = 0;       ///< b [m] > 0
  double contact_modulus = 0;  ///< E* [Pa] > 0: 1/E* = (1−ν_A²)/E_A + (1−ν_B²)/E_B
  /// F/F_c [-] ≥ 1: the flank's normal force per unit of the force the contact problem solves
  /// for, which FrictionForce turns into F (1/cos β_b on a helical slice, whose unknown is the
  /// transverse force, docs/model.md §10; 1 otherwise). The laws themselves do not read it.
  double normal_per_contact_force = 1;
};

/// Throws std::invalid_argument naming the field ("contact.normal_force", ...), value and rule
/// unless every field is finite, F ≥ 0 and R, b, E* > 0.
void ValidateFrictionContact(const FrictionContact& contact);

/// Maximum Hertz pressure of a line contact [Pa] (Johnson, Contact Mechanics, §4.2):
///
///   p_h = √(F E* / (π b R))
///
/// 0 at F = 0. @throws std::invalid_argument as ValidateFrictionContact.
double MaxHertzPressure(const FrictionContact& contact);

/// Signed friction coefficient μ_s [-] of one contact: the friction force on B is μ_s·F·t and on
/// A it is −μ_s·F·t. μ_s has the sign of the sliding velocity v_s = u_A − u_B (kinetic friction
/// drags the slower surface along), so it vanishes at the pitch point (u_A = u_B) and changes
/// sign across it; |μ_s| ≤ μ (kConstant) or max_coefficient (the lubricated laws). With
///
///   v_s = u_A − u_B,   V_e = (u_A + u_B)/2 (entrainment),   W' = F/b,   p_h as MaxHertzPressure,
///
/// the laws are:
///
/// - kOff: μ_s = 0.
/// - kConstant: μ_s = μ·tanh(v_s/v_ε).
/// - kXuKahraman (Xu, Kahraman, Anderson & Maddock 2007, "Prediction of mechanical efficiency of
///   parallel-axis gear pairs", J. Mech. Des. 129(1) 58–68; docs/model.md §7):
///
///     μ = e^f · P_h^b2 · SR^b3 · V_e^b6 · ν0^b7 · R^b8,
///     f = b1 + b4·SR·P_h·log10(ν0) + b5·e^(−SR·P_h·log10 ν0) + b9·e^S,
///     μ_s = min(μ, μ_max)·sign(v_s),
///
///   b1..b9 = −8.916465, 1.03303, 1.036077, −0.354068, 2.812084, −0.100601, 0.752755, −0.390958,
///   0.620305; in the regression's units P_h [GPa], SR = |v_s|/V_e [-], V_e [m/s], ν0 [mPa·s],
///   R [m], S [µm]. μ ∝ SR^1.036 → 0 at the pitch point: continuous, no smoothing. Guards (why:
///   the regression is undefined there, and the right-hand side must stay finite): V_e is
///   replaced by max(|V_e|, v_ε) (rolling stops: V_e → 0), SR is clamped to 2 (its value when one
///   surface is at rest; larger only if the surfaces move in opposite directions); F = 0 gives
///   P_h = 0 and μ = 0.
/// - kBenedictKelley (Benedict & Kelley 1961, "Instantaneous coefficients of gear tooth friction",
///   ASLE Trans. 4(1) 59–70; in US units 0.0127·C_R·log10(3.17e8·W'/(η0·V_s·V_r²)) with W' [lb/in],
///   η0 [cP], V_s, V_r [in/s]; converted to SI the constant becomes 3.17e8/(175.127·39.3701³) =
///   29.66, computed exactly from 1 in = 0.0254 m and 1 lbf = 4.4482216152605 N):
///
///     μ = 0.0127 · C_R · log10( 29.66 · W' / (η0 · |v_s| · V_r²) ),   V_r = u_A + u_B = 2V_e,
///     C_R = 50/(50 − S),   μ_s = clamp(μ, 0, μ_max) · tanh(v_s/v_ε),
///
///   W' [N/m], η0 [mPa·s], v_s, V_r [m/s], S [µin]. μ → ∞ as v_s → 0 or V_r → 0 (then μ_max),
///   and a negative logarithm (light load, high speed) gives 0.
///
/// Evaluated as FrictionModel(options).SignedCoefficient(contact); a caller with many contacts
/// keeps one FrictionModel.
/// @throws std::invalid_argument as ValidateFrictionContact (options are validated by the
///   caller once, with FrictionOptions::Validate; they are not re-checked per call).
double SignedFrictionCoefficient(const FrictionOptions& options, const FrictionContact& contact);

/// The friction law of `options` ready for many contacts: the factors that depend only on the
/// options (Xu & Kahraman's e^(b1 + b9·e^S)·ν0^b7 and log10 ν0, Benedict & Kelley's 0.0127·C_R)
/// are evaluated once here. SignedCoefficient(c) is SignedFrictionCoefficient(options, c) (the
/// same laws and guards); Xu & Kahraman's product is evaluated as K times one exponential of a sum
/// of logarithms, which rounds differently from a product of powers (within 11 ulp of the exact
/// product over the regression's range). The options
/// must be valid (FrictionOptions::Validate; not re-checked). Copyable, immutable: one instance
/// may serve several threads.
class FrictionModel {
 public:
  explicit FrictionModel(const FrictionOptions& options);
  const FrictionOptions& options() const { return options_; }
  /// μ_s [-] as SignedFrictionCoefficient. @throws std::invalid_argument as
  /// ValidateFrictionContact.
  double SignedCoefficient(const FrictionContact& contact) const;

 private:
  double XuKahraman(const FrictionContact& c) const;
  double BenedictKelley(const FrictionContact& c) const;
  FrictionOptions options_;
  double nu0_ = 0;           // ν0 [mPa·s]
  double xk_constant_ = 0;   // K = e^(b1 + b9·e^S)·ν0^b7 [-] (S [µm], ν0 [mPa·s])
  double xk_log10_nu0_ = 0;  // log10 ν0 [-]
  double bk_factor_ = 0;     // 0.0127·C_R [-]
};

}  // namespace epicycle::transmission
