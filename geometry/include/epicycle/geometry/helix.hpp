// The helix of a cylindrical gear and the transverse quantities ISO 21771:2007 derives from its
// normal-section data (docs/geometry.md, "Helical gears"; docs/model.md §3). A helical gear is
// cut by a rack whose module m_n, pressure angle α_n and profile shift x_n are those of the normal
// section; its transverse section is a spur profile cut by the transverse rack (m_t, α_t, x_t),
// and the section at axial position z is that profile turned by (2 tan β / d) z.
#pragma once

namespace epicycle::geometry {

/// The hand of a helical gear's teeth: seen along the axis, a right-hand tooth turns clockwise
/// as it recedes (a right-hand screw thread). With z the gear axis out of the plane of the planar
/// model, the transverse section of a right-hand gear turns counter-clockwise as z grows.
enum class Hand { kRight, kLeft };

/// "right" or "left".
const char* HandName(Hand hand);

/// A gear's helix at its reference cylinder.
struct Helix {
  double angle = 0;          ///< β [rad], in [0, π/4); 0: a spur gear
  Hand hand = Hand::kRight;  ///< the hand of the teeth (meaningful for β > 0)
  /// +1 for a right-hand helix, −1 for a left-hand one [-].
  int sign() const { return hand == Hand::kRight ? 1 : -1; }
  bool helical() const { return angle != 0; }
};

/// ISO 21771:2007 transverse quantities of a gear of z teeth given in the normal section:
///   m_t = m_n / cos β,   tan α_t = tan α_n / cos β,   x_t = x_n cos β   (x_t m_t = x_n m_n),
///   d = z m_t,   d_b = d cos α_t,   tan β_b = tan β cos α_t,
///   p_x = π m_n / sin β (axial pitch),   p_z = π d / tan β (lead).
/// β = 0 returns the spur values exactly (m_t = m_n, α_t = α_n, x_t = x_n, β_b = 0) and infinite
/// p_x and p_z.
struct TransverseQuantities {
  double module = 0;              ///< m_t [m]
  double pressure_angle = 0;      ///< α_t [rad]
  double profile_shift = 0;       ///< x_t [-]
  double reference_diameter = 0;  ///< d [m]
  double base_diameter = 0;       ///< d_b [m]
  double base_helix_angle = 0;    ///< β_b [rad]
  double axial_pitch = 0;         ///< p_x [m]
  double lead = 0;                ///< p_z [m]
};

/// @throws std::invalid_argument for z < 1, m_n ≤ 0, α_n outside (0, π/2) or β outside [0, π/4)
///         (the message names the argument, its value and the rule).
TransverseQuantities Transverse(int teeth, double normal_module, double normal_pressure_angle,
                                double normal_profile_shift, double helix_angle);

/// Working helix angle at the operating pitch cylinder of a mesh [rad]:
///   tan β_w = tan β_b / cos α_wt   (d_w = d_b / cos α_wt, tan β_w = tan β d_w / d).
double WorkingHelixAngle(double base_helix_angle, double working_pressure_angle);

/// Overlap ratio ε_β = b sin β / (π m_n) [-] of a mesh of common face width b [m].
double OverlapRatio(double face_width, double helix_angle, double normal_module);

}  // namespace epicycle::geometry
