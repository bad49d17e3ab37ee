// Closed-form spur-gear relations (ISO 21771 notation). Pair (1, 2): external, or internal with 2
// the internal gear (ring) and x2 its shift in this project's convention (x2 > 0 widens the space).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "epicycle/geometry/gear.hpp"

namespace epicycle::geometry::iso {

/// Operating pressure angle of a zero-backlash pair:
///   inv α_w = inv α + 2 tan α (x1 ± x2)/(z2 ± z1)   (+ external, − internal)
double ZeroBacklashPressureAngle(int z1, int z2, double x1, double x2, double alpha, bool internal);
/// Centre distance of a zero-backlash pair: a_w = m (z2 ± z1)/2 · cos α / cos α_w [m].
double ZeroBacklashCentreDistance(double module, int z1, int z2, double x1, double x2, double alpha,
                                  bool internal);
/// Operating pressure angle at centre distance a: cos α_w = m (z2 ± z1) cos α / (2a).
double PressureAngleAt(double module, int z1, int z2, double alpha, double a, bool internal);
/// Normal backlash j_n [m] at centre distance a: j_wt = p_w − s_w1 − s_w2 (external) or
/// e_w2 − s_w1 (internal), s_w = 2 r_w (s/(2r) + inv α − inv α_w), j_n = j_wt cos α_w − Δs1 − Δs2
/// (Δs the normal tooth-thickness errors).
double NormalBacklash(double module, int z1, int z2, double x1, double x2, double alpha, double a,
                      bool internal, double ds1 = 0, double ds2 = 0);
/// Transverse contact ratio from the radii where the involutes end (r_a: tip circles for ISO;
/// tip-form radii for the involute actually present):
///   ε_α = [√(r_a1² − r_b1²) ± √(r_a2² − r_b2²) ∓ a sin α_w]/p_b.
double ContactRatio(double rb1, double ra1, double rb2, double ra2, double a, double alpha_w,
                    double base_pitch, bool internal);
/// The profile shift of gear `unknown` (1 or 2) that gives normal backlash j_n at centre distance
/// a, the other gear's shift as in its spec. j_n is linear in either shift.
double FitProfileShift(const GearSpec& g1, const GearSpec& g2, bool internal, int unknown,
                       double centre_distance, double normal_backlash);

/// ISO 1328-1:2013 (§5.3) tolerances of a flank tolerance class A = 1..11, with d the reference
/// diameter and m the (normal) module in mm, values in µm, unrounded (the standard rounds them):
///   single pitch       f_pT = (0.001 d + 0.4 m + 5) · √2^(A − 5)
///   cumulative pitch   F_pT = (0.002 d + 0.55 √d + 0.7 m + 12) · √2^(A − 5)
/// Arguments and results in SI [m].
/// @throws std::invalid_argument (naming the scene key `key`) for a class outside 1..11.
double SinglePitchTolerance(double module, double reference_diameter, int grade,
                            const std::string& key = "iso1328_grade");
double CumulativePitchTolerance(double module, double reference_diameter, int grade,
                                const std::string& key = "iso1328_grade");

/// A random set of cumulative pitch deviations F_p,k (k = 0..z−1, F_p,0 = 0) of a gear of class
/// `grade`: single pitch deviations drawn uniformly in ±f_pT (a 64-bit Mersenne twister seeded
/// with `seed`), their mean removed so that they close the circle, then the whole set scaled down
/// if needed so that max |f_pt| ≤ f_pT and max F_p − min F_p ≤ F_pT. [m]
std::vector<double> RandomPitchDeviations(int teeth, double module, int grade, std::uint64_t seed,
                                          const std::string& key = "iso1328_grade");

/// Cumulative deviations from z single pitch deviations: F_p,0 = 0, F_p,k = Σ_{j=1..k} f_pt,j
/// (f_pt,k the pitch from tooth k−1 to tooth k; f_pt,0 closes the circle from tooth z−1).
/// @throws std::invalid_argument (naming `key`) unless Σ f_pt = 0 within 1e-12 m.
std::vector<double> CumulativeFromSingle(const std::vector<double>& single, const std::string& key);

/// The ISO 1328-1 figures of a gear's cumulative pitch deviations F_p,k (k = 0..z−1) [m].
struct PitchStatistics {
  /// Largest single pitch deviation max_k |f_pt,k| = max_k |F_p,k+1 − F_p,k|, the circle closed
  /// (k + 1 taken mod z) [m].
  double largest_single = 0;
  /// Total cumulative pitch deviation F_p = max_k F_p,k − min_k F_p,k [m].
  double total_cumulative = 0;
};
/// The statistics of `cumulative` (GearSpec::pitch_deviations); empty: no deviation, zeros.
PitchStatistics PitchDeviationStatistics(const std::vector<double>& cumulative);

/// ISO 6336-3:2006 method B form factors of an external spur gear cut by a rack without
/// protuberance, load at the outer point of single pair contact. With h_fP, ρ_fP the rack's
/// dedendum and tip radius (the tool's, cutting the gear's root), x the profile shift:
///   E = π m/4 − h_fP tan α − (1 − sin α) ρ_fP / cos α
///   G = ρ_fP/m − h_fP/m + x,   H = 2/z (π/2 − E/m) − π/3
///   θ = 2G/z tan θ − H   (fixed point from π/6: the 30° tangent of the fillet)
///   s_Fn/m = z sin(π/3 − θ) + √3 (G/cos θ − ρ_fP/m)
///   ρ_F/m = ρ_fP/m + 2G²/(cos θ (z cos²θ − 2G))
///   d_en = 2 √{[√((d_a/2)² − (d_b/2)²) − π m cos α (ε_α − 1)]² + (d_b/2)²}
///   α_en = acos(d_b/d_en),  γ_e = (π/2 + 2x tan α)/z + inv α − inv α_en,  α_Fen = α_en − γ_e
///   h_Fe/m = ½[(cos γ_e − sin γ_e tan α_Fen) d_en/m − z cos(π/3 − θ) − G/cos θ + ρ_fP/m]
///   Y_F = (6 h_Fe/m) cos α_Fen / ((s_Fn/m)² cos α)
///   Y_S = (1.2 + 0.13 L) q_s^(1/(1.21 + 2.3/L)),  L = s_Fn/h_Fe,  q_s = s_Fn/(2ρ_F)
/// so that the nominal root stress is σ_F0 = F_t/(b m) Y_F Y_S (spur, solid rim: Y_β = Y_B = 1,
/// Y_DT = 1 for ε_α < 2.05).
struct RootFormFactors {
  double y_f = 0;        ///< Y_F [-]
  double y_s = 0;        ///< Y_S [-]
  double s_fn = 0;       ///< root chord at the 30° tangents [m]
  double rho_f = 0;      ///< fillet radius there [m]
  double h_fe = 0;       ///< bending arm [m]
  double alpha_fen = 0;  ///< load angle α_Fen [rad]
  double d_en = 0;       ///< diameter of the outer point of single pair contact [m]
  double theta = 0;      ///< θ [rad]
};
/// @throws std::invalid_argument (naming the argument) for z < 5, non-positive or non-finite
///         lengths, ε_α outside (1, 2.5), or a fixed point that does not settle.
/// `teeth` may be a virtual number of teeth (a helical gear's z_n, HelicalRootFormFactorsB).
RootFormFactors RootFormFactorsB(double teeth, double module, double alpha, double profile_shift,
                                 double rack_dedendum, double rack_tip_radius, double tip_diameter,
                                 double contact_ratio);

/// ISO 6336-2:2006 method B factors of a spur mesh, pinion 1 with wheel 2 (2 may be internal),
/// at the operating pressure angle α_w and centre distance a, with the tip radii r_a and base
/// radii r_b of both gears and the contact ratio ε_α:
///   Z_H = √(2 cos α_w / (cos²α sin α_w))                        (zone factor, β = 0)
///   Z_ε = √((4 − ε_α)/3)                                         (contact ratio factor, spur)
///   M_1 = ρ-ratio at the pinion's inner point of single pair contact B:
///         M_1² = ρ_1C ρ_2C / (ρ_1B ρ_2B),  ρ_1C = r_b1 tan α_w, ρ_2C = r_b2 tan α_w,
///         ρ_1B = r_b1 tan α_a1 − p_b (p_b = 2π r_b1/z_1),  ρ_2B = a sin α_w ∓ ρ_1B  (− external, + internal)
///   (the standard's M_1 = tan α_w / √{[√(d_a1²/d_b1² − 1) − 2π/z_1][√(d_a2²/d_b2² − 1) −
///   (ε_α − 1) 2π/z_2]} written with the radii of curvature, which holds for internal meshes
///   too); M_2 the same at the wheel's inner point D (ρ_2D = r_b2 tan α_a2 − p_b);
///   Z_B = max(1, M_1), Z_D = max(1, M_2) for an external wheel, Z_D = 1 for an internal one.
struct ContactFactors {
  double z_h = 0;    ///< Z_H [-]
  double z_eps = 0;  ///< Z_ε [-]
  double m1 = 0;     ///< M_1 [-]
  double m2 = 0;     ///< M_2 [-] (0 for an internal wheel: not defined)
  double z_b = 1;    ///< Z_B [-] (pinion)
  double z_d = 1;    ///< Z_D [-] (wheel)
  double z_beta = 1;  ///< Z_β [-] (1: spur; HelicalContactFactorsB)
};
/// z_1 the pinion's teeth; angles [rad], lengths [m]; ε_α as ContactRatio gives it from the tip
/// circles.
/// @throws std::invalid_argument (naming the argument) for non-finite or non-positive lengths or
///         angles, ε_α outside (1, 2.5), or a single-pair point that falls below a base circle.
ContactFactors ContactFactorsB(int pinion_teeth, double alpha, double alpha_w,
                               double centre_distance, double rb1, double ra1, double rb2,
                               double ra2, double contact_ratio, bool internal);

/// ISO 6336-2:2006 method B factors of a helical mesh: ContactFactorsB of its transverse section
/// (α = α_t, α_w = α_wt, ε_α transverse; the base pitch p_bt = 2π r_b1/z_1), then
///   Z_H = √(2 cos β_b cos α_wt / (cos²α_t sin α_wt))
///   Z_ε = √((4 − ε_α)(1 − ε_β)/3 + ε_β/ε_α)  for ε_β < 1,   √(1/ε_α)  for ε_β ≥ 1
///   Z_β = 1/√cos β
///   Z_B = M_1 − ε_β (M_1 − 1) for ε_β < 1 (at least 1), 1 for ε_β ≥ 1; Z_D alike with M_2.
/// β = 0 (ε_β = 0, β_b = 0) gives ContactFactorsB's values.
ContactFactors HelicalContactFactorsB(int pinion_teeth, double alpha_t, double alpha_wt,
                                      double centre_distance, double rb1, double ra1, double rb2,
                                      double ra2, double contact_ratio, bool internal,
                                      double helix_angle, double base_helix_angle,
                                      double overlap_ratio);

/// ISO 6336-3:2006 helical factors of one gear:
///   z_n = z / (cos²β_b cos β)        virtual number of teeth (for Y_F and Y_S)
///   ε_αn = ε_α / cos²β_b             virtual contact ratio
///   Y_β = 1 − ε_β β/120°             with ε_β taken ≤ 1 and β ≤ 30° (so Y_β ≥ 0.75)
///   Y_ε = 0.25 + 0.75/ε_αn           contact ratio factor of the load at the tip (method C of
///                                    ISO 6336-3:1996); method B of 2006 loads the outer point of
///                                    single pair contact of the virtual gear instead, so σ_F0
///                                    there does not take Y_ε (reported beside it)
struct HelicalBendingFactors {
  double virtual_teeth = 0;          ///< z_n [-]
  double virtual_contact_ratio = 0;  ///< ε_αn [-]
  double y_beta = 1;                 ///< Y_β [-]
  double y_eps = 0;                  ///< Y_ε [-]
};
/// @throws std::invalid_argument for z < 1, β outside [0, 45°), β_b outside [0, β], ε_α ≤ 0 or
///         ε_β < 0.
HelicalBendingFactors HelicalBending(int teeth, double helix_angle, double base_helix_angle,
                                     double contact_ratio, double overlap_ratio);

/// ISO 6336-3:2006 method B form factors of a helical gear: RootFormFactorsB of its virtual spur
/// gear in the normal section, z_n (HelicalBending), m_n, α_n, x_n, the tip diameter
/// d_an = d_n + d_a − d (d_n = m_n z_n, d = z m_n / cos β) and ε_αn.
RootFormFactors HelicalRootFormFactorsB(int teeth, double normal_module, double normal_alpha,
                                        double normal_shift, double helix_angle,
                                        double base_helix_angle, double rack_dedendum,
                                        double rack_tip_radius, double tip_diameter,
                                        double contact_ratio);

/// ISO 6336-2's elasticity factor Z_E = √(1 / (π [(1 − ν_1²)/E_1 + (1 − ν_2²)/E_2])) [√Pa]
/// (E [Pa]; steel on steel, E = 206 GPa, ν = 0.3: 189.8 √MPa).
/// @throws std::invalid_argument for E ≤ 0 or ν outside [0, 0.5).
double ElasticityFactor(double e1, double nu1, double e2, double nu2);

}  // namespace epicycle::geometry::iso
