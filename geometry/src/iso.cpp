#include "epicycle/geometry/iso.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <stdexcept>
#include <utility>

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

namespace {

double GradeFactor(int grade, const std::string& key) {
  if (grade < 1 || grade > 11) {
    throw std::invalid_argument(key + " = " + std::to_string(grade) +
                                ": must be an ISO 1328-1:2013 flank tolerance class, 1 to 11");
  }
  return std::pow(std::sqrt(2.0), grade - 5);
}

}  // namespace

double SinglePitchTolerance(double module, double reference_diameter, int grade,
                            const std::string& key) {
  const double d = reference_diameter * 1e3, m = module * 1e3;
  return (0.001 * d + 0.4 * m + 5.0) * GradeFactor(grade, key) * 1e-6;
}

double CumulativePitchTolerance(double module, double reference_diameter, int grade,
                                const std::string& key) {
  const double d = reference_diameter * 1e3, m = module * 1e3;
  return (0.002 * d + 0.55 * std::sqrt(d) + 0.7 * m + 12.0) * GradeFactor(grade, key) * 1e-6;
}

std::vector<double> CumulativeFromSingle(const std::vector<double>& single,
                                         const std::string& key) {
  double sum = 0;
  for (double f : single) sum += f;
  if (std::abs(sum) > 1e-12) {
    throw std::invalid_argument(
        key + " = [" + std::to_string(single.size()) +
        " entries]: single pitch deviations must sum to zero (the pitches close the circle); "
        "their sum is " +
        Num(sum * 1e6) + " um");
  }
  std::vector<double> cumulative(single.size(), 0.0);
  for (std::size_t k = 1; k < single.size(); ++k) cumulative[k] = cumulative[k - 1] + single[k];
  return cumulative;
}

PitchStatistics PitchDeviationStatistics(const std::vector<double>& fp) {
  PitchStatistics s;
  if (fp.empty()) return s;
  double lo = fp[0], hi = fp[0];
  for (std::size_t k = 0; k < fp.size(); ++k) {
    s.largest_single = std::max(s.largest_single, std::abs(fp[(k + 1) % fp.size()] - fp[k]));
    lo = std::min(lo, fp[k]);
    hi = std::max(hi, fp[k]);
  }
  s.total_cumulative = hi - lo;
  return s;
}

std::vector<double> RandomPitchDeviations(int teeth, double module, int grade, std::uint64_t seed,
                                          const std::string& key) {
  const double d = module * teeth;
  const double fpt = SinglePitchTolerance(module, d, grade, key);
  const double Fp = CumulativePitchTolerance(module, d, grade, key);
  std::mt19937_64 rng(seed);
  std::vector<double> single(teeth);
  double mean = 0;
  for (double& f : single) {
    // 53 random bits → [0, 1): the same sequence on every platform.
    const double unit = static_cast<double>(rng() >> 11) * 0x1.0p-53;
    f = fpt * (2.0 * unit - 1.0);
    mean += f / teeth;
  }
  double largest = 0;
  for (double& f : single) {
    f -= mean;
    largest = std::max(largest, std::abs(f));
  }
  single[0] -= std::accumulate(single.begin(), single.end(), 0.0);  // round-off of the closure
  std::vector<double> cumulative = CumulativeFromSingle(single, key);
  const auto [lo, hi] = std::minmax_element(cumulative.begin(), cumulative.end());
  const double scale = std::min({1.0, fpt / largest, Fp / (*hi - *lo)});
  for (double& c : cumulative) c *= scale;
  return cumulative;
}

RootFormFactors RootFormFactorsB(double teeth, double module, double alpha, double profile_shift,
                                 double rack_dedendum, double rack_tip_radius, double tip_diameter,
                                 double contact_ratio) {
  const auto fail = [](const std::string& what, double v, const std::string& rule) {
    throw std::invalid_argument("ISO 6336-3 form factors: " + what + " = " + internal::Num(v) +
                                ": " + rule);
  };
  if (teeth < 5) fail("teeth", teeth, "must be >= 5 (external gear)");
  for (const auto& [name, v] : {std::pair{"module [m]", module},
                                {"rack dedendum [m]", rack_dedendum},
                                {"tip diameter [m]", tip_diameter},
                                {"pressure angle [rad]", alpha}})
    if (!(std::isfinite(v) && v > 0)) fail(name, v, "must be finite and > 0");
  if (!(std::isfinite(rack_tip_radius) && rack_tip_radius >= 0))
    fail("rack tip radius [m]", rack_tip_radius, "must be finite and >= 0");
  if (!(contact_ratio > 1.0 && contact_ratio < 2.5))
    fail("contact ratio", contact_ratio, "must lie in (1, 2.5) (a single pair contact exists)");
  const double pi = 3.14159265358979323846, z = teeth, m = module;
  const double e = pi * m / 4 - rack_dedendum * std::tan(alpha) -
                   (1 - std::sin(alpha)) * rack_tip_radius / std::cos(alpha);
  const double g = rack_tip_radius / m - rack_dedendum / m + profile_shift;
  const double h = 2 / z * (pi / 2 - e / m) - pi / 3;
  double theta = pi / 6;
  bool settled = false;
  for (int it = 0; it < 200 && !settled; ++it) {
    const double next = 2 * g / z * std::tan(theta) - h;
    settled = std::abs(next - theta) < 1e-14;
    theta = next;
  }
  if (!settled)
    fail("theta [rad]", theta, "the fixed point theta = 2G/z tan(theta) - H did not settle");
  RootFormFactors r;
  r.theta = theta;
  r.s_fn = m * (z * std::sin(pi / 3 - theta) +
                std::sqrt(3.0) * (g / std::cos(theta) - rack_tip_radius / m));
  r.rho_f = m * (rack_tip_radius / m +
                 2 * g * g / (std::cos(theta) * (z * std::cos(theta) * std::cos(theta) - 2 * g)));
  const double d = m * z, db = d * std::cos(alpha);
  const double along = std::sqrt(tip_diameter * tip_diameter / 4 - db * db / 4) -
                       pi * m * std::cos(alpha) * (contact_ratio - 1);
  r.d_en = 2 * std::sqrt(along * along + db * db / 4);
  const double alpha_en = std::acos(db / r.d_en);
  const double gamma_e =
      (pi / 2 + 2 * profile_shift * std::tan(alpha)) / z + Inv(alpha) - Inv(alpha_en);
  r.alpha_fen = alpha_en - gamma_e;
  r.h_fe = m / 2 *
           ((std::cos(gamma_e) - std::sin(gamma_e) * std::tan(r.alpha_fen)) * r.d_en / m -
            z * std::cos(pi / 3 - theta) - g / std::cos(theta) + rack_tip_radius / m);
  r.y_f = 6 * r.h_fe / m * std::cos(r.alpha_fen) / ((r.s_fn / m) * (r.s_fn / m) * std::cos(alpha));
  const double l = r.s_fn / r.h_fe, qs = r.s_fn / (2 * r.rho_f);
  r.y_s = (1.2 + 0.13 * l) * std::pow(qs, 1.0 / (1.21 + 2.3 / l));
  return r;
}

ContactFactors ContactFactorsB(int pinion_teeth, double alpha, double alpha_w,
                               double centre_distance, double rb1, double ra1, double rb2,
                               double ra2, double contact_ratio, bool internal) {
  const auto fail = [](const std::string& what, double v, const std::string& rule) {
    throw std::invalid_argument("ISO 6336-2 contact factors: " + what + " = " + internal::Num(v) +
                                ": " + rule);
  };
  if (pinion_teeth < 3) fail("pinion teeth", pinion_teeth, "must be >= 3");
  for (const auto& [name, v] :
       {std::pair{"pressure angle [rad]", alpha}, {"operating pressure angle [rad]", alpha_w},
        {"centre distance [m]", centre_distance}, {"base radius 1 [m]", rb1},
        {"tip radius 1 [m]", ra1}, {"base radius 2 [m]", rb2}, {"tip radius 2 [m]", ra2}})
    if (!(std::isfinite(v) && v > 0)) fail(name, v, "must be finite and > 0");
  if (!(contact_ratio > 1.0 && contact_ratio < 2.5))
    fail("contact ratio", contact_ratio, "must lie in (1, 2.5) (a single pair contact exists)");
  const double pi = 3.14159265358979323846;
  ContactFactors f;
  f.z_h = std::sqrt(2 * std::cos(alpha_w) /
                    (std::cos(alpha) * std::cos(alpha) * std::sin(alpha_w)));
  f.z_eps = std::sqrt((4 - contact_ratio) / 3);
  const double line = centre_distance * std::sin(alpha_w);  // T_1 T_2 along the line of action
  const double base_pitch = 2 * pi * rb1 / pinion_teeth;  // p_b, the same on both gears
  const double rho1_tip = std::sqrt(ra1 * ra1 - rb1 * rb1);  // ρ_1 at the pinion's tip (E)
  const double rho2_tip = std::sqrt(ra2 * ra2 - rb2 * rb2);  // ρ_2 at the wheel's tip (A)
  const double rho1c = rb1 * std::tan(alpha_w), rho2c = rb2 * std::tan(alpha_w);
  const double rho1b = rho1_tip - base_pitch;
  const double rho2b = internal ? line + rho1b : line - rho1b;
  if (!(rho1b > 0 && rho2b > 0))
    fail("pinion's inner point of single pair contact, radius of curvature [m]",
         std::min(rho1b, rho2b), "must be > 0 (inside both involutes)");
  f.m1 = std::sqrt(rho1c * rho2c / (rho1b * rho2b));
  f.z_b = std::max(1.0, f.m1);
  if (!internal) {
    const double rho2d = rho2_tip - base_pitch, rho1d = line - rho2d;
    if (!(rho1d > 0 && rho2d > 0))
      fail("wheel's inner point of single pair contact, radius of curvature [m]",
           std::min(rho1d, rho2d), "must be > 0 (inside both involutes)");
    f.m2 = std::sqrt(rho1c * rho2c / (rho1d * rho2d));
    f.z_d = std::max(1.0, f.m2);
  }
  return f;
}

ContactFactors HelicalContactFactorsB(int pinion_teeth, double alpha_t, double alpha_wt,
                                      double centre_distance, double rb1, double ra1, double rb2,
                                      double ra2, double contact_ratio, bool internal,
                                      double helix_angle, double base_helix_angle,
                                      double overlap_ratio) {
  ContactFactors f = ContactFactorsB(pinion_teeth, alpha_t, alpha_wt, centre_distance, rb1, ra1,
                                     rb2, ra2, contact_ratio, internal);
  if (helix_angle == 0) return f;
  if (!(overlap_ratio >= 0))
    throw std::invalid_argument("ISO 6336-2 contact factors: overlap ratio = " +
                                internal::Num(overlap_ratio) + ": must be >= 0");
  const double eb = overlap_ratio, ea = contact_ratio;
  f.z_h *= std::sqrt(std::cos(base_helix_angle));
  f.z_eps = eb < 1 ? std::sqrt((4 - ea) * (1 - eb) / 3 + eb / ea) : std::sqrt(1 / ea);
  f.z_beta = 1 / std::sqrt(std::cos(helix_angle));
  const auto single_pair = [&](double m) { return eb < 1 ? std::max(1.0, m - eb * (m - 1)) : 1.0; };
  f.z_b = single_pair(f.m1);
  if (!internal) f.z_d = single_pair(f.m2);
  return f;
}

HelicalBendingFactors HelicalBending(int teeth, double helix_angle, double base_helix_angle,
                                     double contact_ratio, double overlap_ratio) {
  const auto fail = [](const std::string& what, double v, const std::string& rule) {
    throw std::invalid_argument("ISO 6336-3 helical factors: " + what + " = " + internal::Num(v) +
                                ": " + rule);
  };
  if (teeth < 1) fail("teeth", teeth, "must be >= 1");
  if (!(helix_angle >= 0 && helix_angle < kPi / 4))
    fail("helix angle [deg]", Deg(helix_angle), "must be in [0, 45)");
  if (!(base_helix_angle >= 0 && base_helix_angle <= helix_angle))
    fail("base helix angle [deg]", Deg(base_helix_angle), "must be in [0, beta]");
  if (!(contact_ratio > 0)) fail("contact ratio", contact_ratio, "must be > 0");
  if (!(overlap_ratio >= 0)) fail("overlap ratio", overlap_ratio, "must be >= 0");
  const double cb = std::cos(base_helix_angle);
  HelicalBendingFactors h;
  h.virtual_teeth = teeth / (cb * cb * std::cos(helix_angle));
  h.virtual_contact_ratio = contact_ratio / (cb * cb);
  h.y_beta = 1 - std::min(overlap_ratio, 1.0) * std::min(Deg(helix_angle), 30.0) / 120.0;
  h.y_eps = 0.25 + 0.75 / h.virtual_contact_ratio;
  return h;
}

RootFormFactors HelicalRootFormFactorsB(int teeth, double normal_module, double normal_alpha,
                                        double normal_shift, double helix_angle,
                                        double base_helix_angle, double rack_dedendum,
                                        double rack_tip_radius, double tip_diameter,
                                        double contact_ratio) {
  const HelicalBendingFactors h =
      HelicalBending(teeth, helix_angle, base_helix_angle, contact_ratio, 0.0);
  const double d = teeth * normal_module / std::cos(helix_angle);
  const double d_n = normal_module * h.virtual_teeth;
  return RootFormFactorsB(h.virtual_teeth, normal_module, normal_alpha, normal_shift, rack_dedendum,
                          rack_tip_radius, d_n + tip_diameter - d, h.virtual_contact_ratio);
}

double ElasticityFactor(double e1, double nu1, double e2, double nu2) {
  for (double e : {e1, e2})
    if (!(std::isfinite(e) && e > 0))
      throw std::invalid_argument("ISO 6336-2 elasticity factor: E = " + internal::Num(e) +
                                  " Pa: must be finite and > 0");
  for (double nu : {nu1, nu2})
    if (!(nu >= 0 && nu < 0.5))
      throw std::invalid_argument("ISO 6336-2 elasticity factor: nu = " + internal::Num(nu) +
                                  ": must lie in [0, 0.5)");
  const double pi = 3.14159265358979323846;
  return std::sqrt(1 / (pi * ((1 - nu1 * nu1) / e1 + (1 - nu2 * nu2) / e2)));
}

}  // namespace epicycle::geometry::iso
