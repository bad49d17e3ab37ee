#include "epicycle/geometry/iso.hpp"

#include <cmath>
#include <stdexcept>

#include "messages.hpp"

namespace epicycle::geometry::iso {

double ZeroBacklashPressureAngle(int z1, int z2, double x1, double x2, double alpha,
                                 bool internal) {
  const double zs = internal ? z2 - z1 : z2 + z1;
  const double xs = internal ? x2 - x1 : x2 + x1;
  return InvInverse(Inv(alpha) + 2.0 * std::tan(alpha) * xs / zs);
}

double ZeroBacklashCentreDistance(double module, int z1, int z2, double x1, double x2, double alpha,
                                  bool internal) {
  const double aw = ZeroBacklashPressureAngle(z1, z2, x1, x2, alpha, internal);
  const double zs = internal ? z2 - z1 : z2 + z1;
  return module * zs / 2.0 * std::cos(alpha) / std::cos(aw);
}

double PressureAngleAt(double module, int z1, int z2, double alpha, double a, bool internal) {
  const double zs = internal ? z2 - z1 : z2 + z1;
  const double c = module * zs * std::cos(alpha) / (2.0 * a);
  if (!(c < 1.0)) {
    throw std::invalid_argument("centre distance " + Mm(a) + " mm is too small for this pair");
  }
  return std::acos(c);
}

double NormalBacklash(double module, int z1, int z2, double x1, double x2, double alpha, double a,
                      bool internal, double ds1, double ds2) {
  const double aw = PressureAngleAt(module, z1, z2, alpha, a, internal);
  const double r1 = module * z1 / 2.0, r2 = module * z2 / 2.0;
  const double rw1 = r1 * std::cos(alpha) / std::cos(aw), rw2 = r2 * std::cos(alpha) / std::cos(aw);
  const double t = std::tan(alpha), ia = Inv(alpha), iw = Inv(aw);
  const double s1 = module * (kPi / 2.0 + 2.0 * x1 * t);
  const double sw1 = 2.0 * rw1 * (s1 / (2.0 * r1) + ia - iw);
  double jwt;
  if (internal) {
    const double e2 = module * (kPi / 2.0 + 2.0 * x2 * t);  // the ring's space
    const double ew2 = 2.0 * rw2 * (e2 / (2.0 * r2) + ia - iw);
    jwt = ew2 - sw1;
  } else {
    const double s2 = module * (kPi / 2.0 + 2.0 * x2 * t);
    const double sw2 = 2.0 * rw2 * (s2 / (2.0 * r2) + ia - iw);
    jwt = 2.0 * kPi * rw1 / z1 - sw1 - sw2;
  }
  return jwt * std::cos(aw) - ds1 - ds2;
}

double ContactRatio(double rb1, double ra1, double rb2, double ra2, double a, double alpha_w,
                    double base_pitch, bool internal) {
  const double l1 = std::sqrt(ra1 * ra1 - rb1 * rb1);
  const double l2 = std::sqrt(ra2 * ra2 - rb2 * rb2);
  const double la = a * std::sin(alpha_w);
  return (internal ? l1 - l2 + la : l1 + l2 - la) / base_pitch;
}

double FitProfileShift(const GearSpec& g1, const GearSpec& g2, bool internal, int unknown,
                       double centre_distance, double normal_backlash) {
  if (unknown != 1 && unknown != 2) {
    throw std::invalid_argument("FitProfileShift: unknown = " + std::to_string(unknown) +
                                ": must be 1 or 2");
  }
  auto jn = [&](double x) {
    const double x1 = unknown == 1 ? x : g1.profile_shift;
    const double x2 = unknown == 2 ? x : g2.profile_shift;
    return NormalBacklash(g1.module, g1.teeth, g2.teeth, x1, x2, g1.pressure_angle, centre_distance,
                          internal, g1.thickness_error, g2.thickness_error);
  };
  const double j0 = jn(0.0), j1 = jn(1.0);
  return (normal_backlash - j0) / (j1 - j0);
}

}  // namespace epicycle::geometry::iso
