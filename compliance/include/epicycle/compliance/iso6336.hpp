// ISO 6336-1 (method B) tooth stiffness of spur gears, the reference the mesh stiffness computed
// by the model is compared with.
//
//   q′ = C1 + C2/z_n1 + C3/z_n2 + C4 x1 + C5 x1/z_n1 + C6 x2 + C7 x2/z_n2 + C8 x1² + C9 x2²
//        [mm·µm/N], C1..C9 = 0.04723, 0.15551, 0.25791, −0.00635, −0.11654, −0.00193,
//        −0.24188, 0.00529, 0.00182
//   c′_th = 1/q′,   c′ = c′_th C_M C_R C_B cos β   (single pair, per unit face width)
//   C_M = 0.8,  C_B = [1 + 0.5(1.2 − h_fP/m)][1 − 0.02(20° − α_P)] (mean of the two tools)
//   c_γα = c′ (0.75 ε_α + 0.25)   (mesh stiffness, mean over a mesh cycle)
// Helical pairs (ISO 6336-1:2006, 9.3): z_n = z/cos³β in q′, c′ takes cos β and the basic rack is
// the normal section's (h_fP/m_n, α_n); β = 0 is the spur pair.
// Stiffnesses are per unit face width in N/(mm·µm) = 1e9 N/m². Internal gears: z_n2 = ∞ and the
// ring's shift is not in the formula (x2 = 0), as ISO 6336-1 prescribes for internal gears.
#pragma once

namespace epicycle::compliance::iso6336 {

struct PairData {
  int z1 = 0, z2 = 0;            ///< tooth counts [-] (2: the wheel, or the ring)
  double x1 = 0, x2 = 0;         ///< profile shifts [-]
  bool internal = false;         ///< 2 is an internal gear
  double dedendum1 = 1.25;       ///< basic-rack dedendum h_fP/m of gear 1's tool [-]
  double dedendum2 = 1.25;       ///< same, gear 2 [-]
  double pressure_angle = 0;     ///< α_P of the tool [rad]
  double blank_factor = 1.0;     ///< C_R [-] (1: solid disc)
  double contact_ratio = 0;      ///< ε_α [-] (for c_γα; transverse for a helical pair)
  double helix_angle = 0;        ///< β [rad] at the reference cylinder (0: spur)
};

/// q′ [mm·µm/N]. @throws std::invalid_argument for z < 3 or β outside [0, 45°).
double MinimumFlexibility(const PairData& p);
/// C_B [-].
double BasicRackFactor(const PairData& p);
/// c′ [N/(mm·µm)].
double SinglePairStiffness(const PairData& p);
/// c_γα [N/(mm·µm)].
double MeshStiffness(const PairData& p);

inline constexpr double kPerMmMicron = 1e9;  ///< 1 N/(mm·µm) in N/m² (per unit face width)

}  // namespace epicycle::compliance::iso6336
