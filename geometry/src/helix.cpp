#include "epicycle/geometry/helix.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "epicycle/geometry/plane.hpp"
#include "messages.hpp"

namespace epicycle::geometry {

const char* HandName(Hand hand) { return hand == Hand::kRight ? "right" : "left"; }

TransverseQuantities Transverse(int teeth, double normal_module, double normal_pressure_angle,
                                double normal_profile_shift, double helix_angle) {
  if (teeth < 1) Fail("helix", "teeth", std::to_string(teeth), "must be >= 1");
  RequirePositive("helix", "normal_module", normal_module);
  if (!(normal_pressure_angle > 0 && normal_pressure_angle < kPi / 2))
    Fail("helix", "normal_pressure_angle_deg", Num(Deg(normal_pressure_angle)),
         "must be in (0, 90)");
  if (!(helix_angle >= 0 && helix_angle < kPi / 4))
    Fail("helix", "helix_angle_deg", Num(Deg(helix_angle)), "must be in [0, 45)");
  TransverseQuantities t;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  if (helix_angle == 0) {  // exactly the spur values: the spur scene of today, bit for bit
    t.module = normal_module;
    t.pressure_angle = normal_pressure_angle;
    t.profile_shift = normal_profile_shift;
    t.axial_pitch = t.lead = kInf;
  } else {
    const double c = std::cos(helix_angle);
    t.module = normal_module / c;
    t.pressure_angle = std::atan(std::tan(normal_pressure_angle) / c);
    t.profile_shift = normal_profile_shift * c;
    t.axial_pitch = kPi * normal_module / std::sin(helix_angle);
  }
  t.reference_diameter = teeth * t.module;
  t.base_diameter = t.reference_diameter * std::cos(t.pressure_angle);
  if (helix_angle != 0) {
    t.base_helix_angle = std::atan(std::tan(helix_angle) * std::cos(t.pressure_angle));
    t.lead = kPi * t.reference_diameter / std::tan(helix_angle);
  }
  return t;
}

double WorkingHelixAngle(double base_helix_angle, double working_pressure_angle) {
  return std::atan(std::tan(base_helix_angle) / std::cos(working_pressure_angle));
}

double OverlapRatio(double face_width, double helix_angle, double normal_module) {
  return face_width * std::sin(helix_angle) / (kPi * normal_module);
}

}  // namespace epicycle::geometry
