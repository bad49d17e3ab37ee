// Local (Hertzian) contact approach of one potential contact: MODEL.md section 4, the paper's
// eq. 2 with its printed second term corrected.
#pragma once

namespace epicycle::solvers {

/// How the 2D elastic bodies are idealised (the same assumption must be used in FE and here).
enum class PlaneAssumption { kPlaneStrain, kPlaneStress };

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
  bool enabled = true;              ///< false: no local term (a purely linear problem)
  double face_width = 0.0;          ///< b [m], > 0
  double reduced_radius = 0.0;      ///< R_eq [m], > 0: ρ1ρ2/(ρ1+ρ2) external, ρ1ρ2/(ρ2−ρ1) internal
  PlaneAssumption plane = PlaneAssumption::kPlaneStrain;
  LocalBody body[2];
};

}  // namespace epicycle::solvers
