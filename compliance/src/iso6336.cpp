#include "epicycle/compliance/iso6336.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace epicycle::compliance::iso6336 {

double MinimumFlexibility(const PairData& p) {
  if (p.z1 < 3 || p.z2 < 3) {
    throw std::invalid_argument("iso6336: z1 = " + std::to_string(p.z1) + ", z2 = " +
                                std::to_string(p.z2) + ": tooth counts must be >= 3");
  }
  constexpr double c[9] = {0.04723, 0.15551, 0.25791, -0.00635, -0.11654,
                           -0.00193, -0.24188, 0.00529, 0.00182};
  if (!(p.helix_angle >= 0 && p.helix_angle < std::numbers::pi / 4)) {
    throw std::invalid_argument("iso6336: helix_angle = " + std::to_string(p.helix_angle) +
                                " rad: must be in [0, pi/4)");
  }
  // Virtual numbers of teeth z_n = z/cos³β (z itself for a spur pair).
  const double c3 = p.helix_angle == 0 ? 1.0 : std::pow(std::cos(p.helix_angle), 3);
  const double zn1 = p.z1 / c3;
  const double inv_zn2 = p.internal ? 0.0 : c3 / p.z2;
  const double x1 = p.x1, x2 = p.internal ? 0.0 : p.x2;
  return c[0] + c[1] / zn1 + c[2] * inv_zn2 + c[3] * x1 + c[4] * x1 / zn1 + c[5] * x2 +
         c[6] * x2 * inv_zn2 + c[7] * x1 * x1 + c[8] * x2 * x2;
}

double BasicRackFactor(const PairData& p) {
  const double alpha_deg = p.pressure_angle * 180.0 / std::numbers::pi;
  auto cb = [&](double hfp) { return (1 + 0.5 * (1.2 - hfp)) * (1 - 0.02 * (20.0 - alpha_deg)); };
  return 0.5 * (cb(p.dedendum1) + cb(p.dedendum2));
}

double SinglePairStiffness(const PairData& p) {
  constexpr double kCm = 0.8;
  const double c = kCm * p.blank_factor * BasicRackFactor(p) / MinimumFlexibility(p);
  return p.helix_angle == 0 ? c : c * std::cos(p.helix_angle);
}

double MeshStiffness(const PairData& p) {
  if (!(p.contact_ratio >= 1.0)) {
    throw std::invalid_argument("iso6336: contact_ratio = " + std::to_string(p.contact_ratio) +
                                ": must be >= 1");
  }
  return SinglePairStiffness(p) * (0.75 * p.contact_ratio + 0.25);
}

}  // namespace epicycle::compliance::iso6336
