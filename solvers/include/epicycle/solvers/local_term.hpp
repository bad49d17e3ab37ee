// Local (Hertzian) contact approach of one potential contact: docs/model.md §4, the paper's
// eq. 2 with its printed second term corrected.
#pragma once

#include <array>
#include <string>

#include "epicycle/io/enum_names.hpp"

namespace epicycle::solvers {

/// How the 2D elastic bodies are idealised (the same assumption must be used in FE and here).
enum class PlaneAssumption { kPlaneStrain, kPlaneStress };

/// The assumptions' names (the scene's model.plane, a problem file's and Python's plane): the one
/// table of every reader and writer of the word.
inline constexpr std::array<io::EnumName<PlaneAssumption>, 2> kPlaneAssumptionNames{{
    {PlaneAssumption::kPlaneStrain, "strain"},
    {PlaneAssumption::kPlaneStress, "stress"},
}};

/// One body's side of a contact.
struct LocalBody {
  double youngs_modulus = 0.0;  ///< E [Pa], > 0
  double poisson_ratio = 0.0;   ///< ν [-], in [0, 0.5)
  double depth = 0.0;           ///< h [m], depth where local and structural terms are joined, > 0
};

/// Parameters of the local term of one contact (two bodies).
///
///   u_local(F) = Σ_B 2 k_B F/(π b) · [ asinh(h_B/L) − c_B (h_B/L)(√(1+(h_B/L)²) − h_B/L) ]
///   L = √(4 F R_eq / (π b E*)),   1/E* = k_1 + k_2,
///   plane strain: k_B = (1−ν_B²)/E_B, c_B = ν_B/(1−ν_B);  plane stress: k_B = 1/E_B, c_B = ν_B.
struct LocalTermParameters {
  bool enabled = true;      ///< false: no local term (a purely linear problem)
  double face_width = 0.0;  ///< b [m], > 0
  double reduced_radius = 0.0;  ///< R_eq [m], > 0: ρ1ρ2/(ρ1+ρ2) external, ρ1ρ2/(ρ2−ρ1) internal
  PlaneAssumption plane = PlaneAssumption::kPlaneStrain;
  LocalBody body[2];
};

// Closed forms used below (per body B, s = h_B/L, w = √(1 + (L/h_B)²), a_B = 2k_B/(πb)):
//   value       u_B  = a_B F [asinh(s) − c_B/(1+w)]            (since s(√(1+s²) − s) = 1/(1+w))
//   derivative  u_B' = a_B [asinh(s) − (1+c_B)/(2w)]
//   integral    U_B  = ∫₀^F u_B = 2a_B F² [asinh(s)/4 + (w+2)/(12(1+w)²) − c_B(2w+1)/(6(1+w)²)]
// (the integral by the substitution s = h/L, F = h²/(l s²) with L² = lF, see docs/solvers.md).
// Since asinh(s)·√(1+s²)/s ≥ 1 for every s > 0, u_B' > 0 for every F > 0 whenever c_B < 1, i.e.
// ν < 0.5: the corrected term never loses monotonicity (the misprinted one does). What remains is
// u'(0⁺) = +∞ (logarithmically) and u' → 0 as F → ∞, and the physical validity limit L = h.

/// Throws std::invalid_argument naming `field` (e.g. "local[3]"), the value and the rule unless
/// face width, radius, moduli, depths > 0 and finite, 0 ≤ ν < 0.5. Disabled terms are not checked.
void ValidateLocalTerm(const LocalTermParameters& p, const std::string& field);
/// The same rules as a predicate, without building any message (true for a disabled term).
bool IsValidLocalTerm(const LocalTermParameters& p);

/// E* [Pa]: 1/E* = k_1 + k_2 (plane-strain or plane-stress k_B).
double EffectiveModulus(const LocalTermParameters& p);
/// Hertz half-width L [m] at force F [N] ≥ 0.
double HertzHalfWidth(const LocalTermParameters& p, double force);
/// Hertz's largest contact pressure p_H [Pa] at force F [N] ≥ 0 (docs/model.md §9): the line
/// contact's elliptical pressure p(x) = p_H √(1 − x²/L²) carries w = F/b = π L p_H / 2, so
///   p_H = 2F/(π b L) = √(F E*/(π b R_eq)),
/// with E* as in EffectiveModulus (two steel bodies in plane strain: E* = E/(2(1 − ν²))). 0 at
/// F ≤ 0. Defined for a disabled term too (its parameters still describe the contact).
double HertzPressure(const LocalTermParameters& p, double force);
/// u_local(F) [m], F [N] ≥ 0 (0 at F = 0 and when disabled).
double LocalApproach(const LocalTermParameters& p, double force);
/// du_local/dF [m/N]; +∞ at F = 0 (enabled term).
double LocalApproachDerivative(const LocalTermParameters& p, double force);
/// ∫₀^F u_local [J] (closed form, accurate to round-off).
double LocalApproachIntegral(const LocalTermParameters& p, double force);
/// The force [N] at which L reaches the smaller depth h_B: beyond it the half-plane idealisation
/// behind the local term is no longer valid (the result is still defined and monotone).
double ValidityLimitForce(const LocalTermParameters& p);
/// The smallest force [N] at which u_local' ≤ 0, +∞ if none (always +∞ for ν < 0.5, see above;
/// computed from the closed-form derivative, not assumed).
double NonMonotoneForce(const LocalTermParameters& p);

}  // namespace epicycle::solvers
