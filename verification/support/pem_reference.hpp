// Potential-energy-method (PEM) mesh stiffness of an external spur-gear pair: the suite's own,
// independent reference for the FE + local-contact mesh stiffness (docs/model.md §8). Plain C++ and the
// standard library only; nothing here uses the project's geometry or compliance code.
//
// Model (all SI; compliances in m/N, stiffnesses in N/m):
//
//   1/k_pair(s) = 1/k_h + Σ_{gear 1, 2} ( 1/k_b + 1/k_s + 1/k_a + 1/k_f )
//
// * k_h, Hertzian (Yang & Lin 1987, J. Mech. Transm. Autom. Des. 109:189):
//   k_h = π b / (2 [(1−ν1²)/E1 + (1−ν2²)/E2]), which is π E b / (4(1−ν²)) for equal materials;
//   independent of load and position.
// * k_b, k_s, k_a (Tian 2004, MSc thesis, U. Alberta; Wu, Zuo & Parey 2008, J. Sound Vib.
//   317:608): each tooth is a cantilever on its centre line (axis y from the gear centre),
//   clamped at the root circle, of rectangular section of half-thickness h(y) and width b. A unit
//   force along the line of action acts at the contact point (y_c, h_c) at the angle β to the
//   perpendicular of the centre line; with M(y) = cos β (y_c − y) − sin β h_c:
//       1/k_b = ∫ M² / (E' I) dy,   I = (2h)³ b / 12
//       1/k_s = ∫ 1.2 cos²β / (G A) dy,   A = 2 h b
//       1/k_a = ∫ sin²β / (E' A) dy
//   from the root section to the contact section. β = α_c − ψ_c: the involute pressure angle at the
//   contact radius MINUS the tooth's half-angle there (the load line is the tangent to the base
//   circle, which makes the angle α_c with the normal to the contact radius, and that radius is
//   itself turned by ψ_c from the centre line). β is negative near the base circle (the force then
//   pulls the section outward) and largest at the tip; this is Tian's α1, with tan α_c = α1 + α2.
// * k_f, fillet foundation (Sainsot, Velex & Duverger 2004, J. Mech. Des. 126:748, and its
//   Table 1; as used by Chaari et al. 2009, Eur. J. Mech. A 28:461, and Ma et al. 2015):
//       1/k_f = cos²β / (E b) [ L*(u_f/S_f)² + M*(u_f/S_f) + P*(1 + Q* tan²β) ]
//       X*(h_fi, θ_f) = A/θ_f² + B h_fi² + C h_fi/θ_f + D/θ_f + E h_fi + F,  h_fi = r_f/r_int
//   u_f the distance along the centre line from the root circle to the point where the load line
//   crosses the centre line (= r_b/cos β − r_f), S_f = 2 r_f θ_f the root thickness, θ_f the
//   half-angle of the tooth at the root circle (fillets included; see RootHalfAngle()).
//
// Choices (each stated where it is implemented):
// * Plane strain by default: E' = E/(1−ν²) in the bending and compression terms, G = E/(2(1+ν))
//   (the shear modulus is the same in plane stress and plane strain); plane stress: E' = E. The
//   Hertzian term is Yang & Lin's as printed, and the fillet-foundation term uses E as Sainsot et
//   al. published it (a fit to 2D FE bodies of steel, ν = 0.3; no E' correction is applied).
// * Root region: the model has no trochoid. Between the root circle and the base circle (when
//   r_f < r_b) the flank is a straight line PARALLEL to the centre line, half-thickness
//   r_b sin ψ_b (the straight-line root of Liang, Zuo & Pandey 2014 and Wan et al. 2014), the beam
//   clamped where that line meets the root circle. RootModel::kRadialLine instead continues the
//   flank along the radius through its base-circle point (a narrower, softer root). When r_f > r_b
//   the involute runs down to the root circle.
// * Face width: the pair works over b = min(b1, b2), used in every term (a 2D model).
// * Position on the path: s, the distance along the line of action from T1, the point where it
//   touches gear 1's base circle (s = r_b1 · roll angle of gear 1's contact point). The contact
//   radii are r1 = √(r_b1² + s²) and r2 = √(r_b2² + (g − s)²), g = T1T2 = a sin α_w.
// * Numerical integration: adaptive 20-point Gauss–Legendre, relative tolerance 1e-11 by default.
//   The involute part is integrated over the roll angle t = tan α_r, in which every integrand is
//   analytic (in r it has a √(r − r_b) branch at the base circle).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace epicycle::verification::pem {

// ---------------------------------------------------------------------------------------------
// Data

enum class PlaneModel { kPlaneStrain, kPlaneStress };
enum class RootModel { kParallelLine, kRadialLine };

/// One external spur gear of a pair, SI units.
struct Gear {
  int teeth = 0;                    ///< z [-]
  double module_m = 0.0;            ///< m [m]
  double pressure_angle_rad = 0.0;  ///< α, of the generating rack [rad]
  double profile_shift = 0.0;       ///< x [-]
  double tip_radius_m = 0.0;        ///< r_a, as made (input: tips may be shortened) [m]
  double root_radius_m = 0.0;       ///< r_f [m]
  double bore_radius_m = 0.0;       ///< r_int, hub bore, Sainsot's inner radius [m]
  double face_width_m = 0.0;        ///< b [m]
  double youngs_modulus_pa = 0.0;   ///< E [Pa]
  double poisson_ratio = 0.0;       ///< ν [-]
  /// ρ_fP/m, tip radius of the generating rack [-]; 0.38 is ISO 53 profile A. Used only for θ_f.
  double tool_tip_radius_coefficient = 0.38;
  /// θ_f [rad]; 0 (default): from the rack that cut the gear, see RootHalfAngle().
  double root_half_angle_rad = 0.0;
};

struct Options {
  PlaneModel plane = PlaneModel::kPlaneStrain;
  RootModel root = RootModel::kParallelLine;
  double relative_tolerance = 1e-11;  ///< of every numerical integral [-]
};

/// An external pair at a given centre distance (shifted pairs at a non-standard distance work: the
/// operating pressure angle follows from a and the base radii).
struct GearPair {
  Gear gear1;
  Gear gear2;
  double centre_distance_m = 0.0;  ///< a [m]
  Options options;
};

// ---------------------------------------------------------------------------------------------
// Quadrature

namespace detail {

struct GaussRule {
  static constexpr int kPoints = 20;
  std::array<double, kPoints> x{};
  std::array<double, kPoints> w{};
};

/// 20-point Gauss–Legendre nodes and weights on [−1, 1] (Newton on P_n, Golub–Welsch not needed).
inline const GaussRule& Rule() {
  static const GaussRule rule = [] {
    GaussRule r;
    const int n = GaussRule::kPoints;
    for (int i = 0; i < n; ++i) {
      double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
      double dp = 0.0;
      for (int iter = 0; iter < 100; ++iter) {
        double p0 = 1.0, p1 = x;
        for (int k = 2; k <= n; ++k) {
          const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        dp = n * (x * p1 - p0) / (x * x - 1.0);
        const double dx = p1 / dp;
        x -= dx;
        if (std::abs(dx) < 1e-16) break;
      }
      const auto k = static_cast<std::size_t>(i);
      r.x[k] = x;
      r.w[k] = 2.0 / ((1.0 - x * x) * dp * dp);
    }
    return r;
  }();
  return rule;
}

template <std::size_t N>
using Vec = std::array<double, N>;

template <std::size_t N, class F>
Vec<N> Panel(const F& f, double a, double b) {
  const GaussRule& rule = Rule();
  const double c = 0.5 * (a + b), h = 0.5 * (b - a);
  Vec<N> sum{};
  for (std::size_t i = 0; i < rule.x.size(); ++i) {
    const Vec<N> v = f(c + h * rule.x[i]);
    for (std::size_t k = 0; k < N; ++k) sum[k] += rule.w[i] * v[k];
  }
  for (double& s : sum) s *= h;
  return sum;
}

template <std::size_t N, class F>
Vec<N> Refine(const F& f, double a, double b, const Vec<N>& whole, const Vec<N>& abs_tol,
              int depth) {
  const double m = 0.5 * (a + b);
  const Vec<N> left = Panel<N>(f, a, m), right = Panel<N>(f, m, b);
  Vec<N> both{};
  bool converged = true;
  for (std::size_t k = 0; k < N; ++k) {
    both[k] = left[k] + right[k];
    const double floor = 8.0 * std::numeric_limits<double>::epsilon() * std::abs(both[k]);
    if (std::abs(both[k] - whole[k]) > std::max(abs_tol[k], floor)) converged = false;
  }
  if (converged || depth >= 40) return both;
  Vec<N> half_tol{};
  for (std::size_t k = 0; k < N; ++k) half_tol[k] = 0.5 * abs_tol[k];
  const Vec<N> l = Refine<N>(f, a, m, left, half_tol, depth + 1);
  const Vec<N> r = Refine<N>(f, m, b, right, half_tol, depth + 1);
  for (std::size_t k = 0; k < N; ++k) both[k] = l[k] + r[k];
  return both;
}

}  // namespace detail

/// ∫_a^b f for f: double → std::array<double, N>, adaptive 20-point Gauss–Legendre; each component
/// to `relative_tolerance` of its own magnitude (estimated on the whole interval first).
template <std::size_t N, class F>
std::array<double, N> IntegrateAdaptive(const F& f, double a, double b, double relative_tolerance) {
  if (a == b) return {};
  const detail::Vec<N> whole = detail::Panel<N>(f, a, b);
  detail::Vec<N> abs_tol{};
  for (std::size_t k = 0; k < N; ++k) abs_tol[k] = relative_tolerance * std::abs(whole[k]);
  return detail::Refine<N>(f, a, b, whole, abs_tol, 0);
}

inline double IntegrateAdaptive(const std::function<double(double)>& f, double a, double b,
                                double relative_tolerance) {
  return IntegrateAdaptive<1>([&](double p) { return std::array<double, 1>{f(p)}; }, a, b,
                              relative_tolerance)[0];
}

// ---------------------------------------------------------------------------------------------
// Cantilever energy integrals (general section, so that closed forms can test them)

/// The beam's section at the integration parameter p: its position on the centre line, dy/dp and
/// the half-thickness of the section there.
struct BeamSection {
  double y_m = 0.0;               ///< y(p), distance from the gear centre along the centre line [m]
  double dy_dp = 0.0;             ///< dy/dp [m per unit of p]
  double half_thickness_m = 0.0;  ///< h(p) [m]
};

/// A unit force at (y_m, offset_m) directed at angle_rad below the perpendicular to the centre line
/// (towards the root), i.e. bending component cos β, compressive component sin β.
struct BeamLoad {
  double y_m = 0.0;        ///< y_c [m]
  double offset_m = 0.0;   ///< h_c, distance of the load point from the centre line [m]
  double angle_rad = 0.0;  ///< β [rad]
};

struct BeamElasticity {
  double bending_modulus_pa = 0.0;  ///< E' for bending and compression [Pa]
  double shear_modulus_pa = 0.0;    ///< G [Pa]
  double face_width_m = 0.0;        ///< b [m]
};

/// Compliances along the load direction [m/N].
struct BeamCompliance {
  double bending_m_per_n = 0.0;      ///< 1/k_b
  double shear_m_per_n = 0.0;        ///< 1/k_s
  double compression_m_per_n = 0.0;  ///< 1/k_a
  double Total() const { return bending_m_per_n + shear_m_per_n + compression_m_per_n; }
};

/// 1/k_b, 1/k_s, 1/k_a of the cantilever whose section is `section(p)`, p from p0 (root) to p1
/// (the load section), under the unit load `load`:
///   1/k_b = ∫ [cos β (y_c − y) − sin β h_c]² / (E' (2/3) h³ b) dy
///   1/k_s = ∫ 1.2 cos²β / (G 2 h b) dy,   1/k_a = ∫ sin²β / (E' 2 h b) dy.
/// Timoshenko cantilever: constant h and β = 0 give F L³/(3E'I) and 1.2 F L/(G A).
inline BeamCompliance BeamEnergyCompliance(const std::function<BeamSection(double)>& section,
                                           double p0, double p1, const BeamLoad& load,
                                           const BeamElasticity& elasticity,
                                           double relative_tolerance) {
  const double c = std::cos(load.angle_rad), s = std::sin(load.angle_rad);
  const double e = elasticity.bending_modulus_pa, g = elasticity.shear_modulus_pa;
  const double b = elasticity.face_width_m;
  const auto integrand = [&](double p) {
    const BeamSection q = section(p);
    const double h = q.half_thickness_m;
    const double area = 2.0 * h * b, inertia = 2.0 / 3.0 * h * h * h * b;
    const double moment = c * (load.y_m - q.y_m) - s * load.offset_m;
    return std::array<double, 3>{moment * moment / (e * inertia) * q.dy_dp,
                                 1.2 * c * c / (g * area) * q.dy_dp, s * s / (e * area) * q.dy_dp};
  };
  const auto r = IntegrateAdaptive<3>(integrand, p0, p1, relative_tolerance);
  return {r[0], r[1], r[2]};
}

// ---------------------------------------------------------------------------------------------
// Gear geometry

inline double Involute(double angle_rad) { return std::tan(angle_rad) - angle_rad; }

inline std::string Describe(const std::string& field, double value, const std::string& rule) {
  std::ostringstream s;
  s.precision(10);
  s << "pem: " << field << " = " << value << ": " << rule;
  return s.str();
}

/// Throws std::invalid_argument naming the field, its value and the rule it breaks.
inline void ValidateGear(const Gear& g, const std::string& name) {
  const auto require = [&](bool ok, const std::string& field, double value,
                           const std::string& rule) {
    if (!ok) throw std::invalid_argument(Describe(name + "." + field, value, rule));
  };
  require(g.teeth >= 3, "teeth", g.teeth, "need z >= 3");
  require(g.module_m > 0.0, "module_m", g.module_m, "must be > 0");
  require(g.pressure_angle_rad > 0.0 && g.pressure_angle_rad < std::numbers::pi / 2,
          "pressure_angle_rad", g.pressure_angle_rad, "must be in (0, pi/2)");
  const double r_ref = 0.5 * g.teeth * g.module_m;
  const double r_b = r_ref * std::cos(g.pressure_angle_rad);
  require(g.tip_radius_m > r_b, "tip_radius_m", g.tip_radius_m, "must exceed the base radius");
  require(g.root_radius_m > 0.0 && g.root_radius_m < g.tip_radius_m, "root_radius_m",
          g.root_radius_m, "must be in (0, tip radius)");
  require(g.bore_radius_m > 0.0 && g.bore_radius_m < g.root_radius_m, "bore_radius_m",
          g.bore_radius_m, "must be in (0, root radius)");
  require(g.face_width_m > 0.0, "face_width_m", g.face_width_m, "must be > 0");
  require(g.youngs_modulus_pa > 0.0, "youngs_modulus_pa", g.youngs_modulus_pa, "must be > 0");
  require(g.poisson_ratio > -1.0 && g.poisson_ratio < 0.5, "poisson_ratio", g.poisson_ratio,
          "must be in (-1, 0.5)");
  require(g.tool_tip_radius_coefficient >= 0.0, "tool_tip_radius_coefficient",
          g.tool_tip_radius_coefficient, "must be >= 0");
  require(g.root_half_angle_rad >= 0.0 && g.root_half_angle_rad < std::numbers::pi / g.teeth,
          "root_half_angle_rad", g.root_half_angle_rad, "must be in [0, pi/z) (0: from the rack)");
}

inline double ReferenceRadius(const Gear& g) {
  return 0.5 * static_cast<double>(g.teeth) * g.module_m;
}
inline double BaseRadius(const Gear& g) {
  return ReferenceRadius(g) * std::cos(g.pressure_angle_rad);
}
/// p_b = π m cos α [m].
inline double BasePitch(const Gear& g) {
  return std::numbers::pi * g.module_m * std::cos(g.pressure_angle_rad);
}

/// Arc tooth thickness at radius r ≥ r_b [m]: s(r) = 2r (s/(2 r_ref) + inv α − inv α_r),
/// cos α_r = r_b/r, with the reference thickness s = m (π/2 + 2 x tan α).
inline double ToothThicknessAt(const Gear& g, double radius_m) {
  const double r_b = BaseRadius(g);
  if (!(radius_m >= r_b)) {
    throw std::invalid_argument(Describe("radius_m", radius_m, "must be >= the base radius"));
  }
  const double s_ref =
      g.module_m * (std::numbers::pi / 2 + 2.0 * g.profile_shift * std::tan(g.pressure_angle_rad));
  const double alpha_r = std::acos(std::min(1.0, r_b / radius_m));
  return 2.0 * radius_m *
         (s_ref / (2.0 * ReferenceRadius(g)) + Involute(g.pressure_angle_rad) - Involute(alpha_r));
}

/// ψ_b, the half-angle of the tooth at the base circle [rad]: π/(2z) + 2 x tan α / z + inv α.
inline double BaseHalfAngle(const Gear& g) {
  const double z = static_cast<double>(g.teeth);
  return std::numbers::pi / (2.0 * z) + 2.0 * g.profile_shift * std::tan(g.pressure_angle_rad) / z +
         Involute(g.pressure_angle_rad);
}

/// θ_f, the half-angle of the tooth at the root circle, fillets included [rad]. Unless given, the
/// fillet is that of the rack with tip radius ρ = ρ_fP that cut the gear: the point where the
/// rack's tip round touches its tip line (which cuts the root circle r_f) lies, in the rack, at
///   X_f = s/2 + (D − ρ) tan α + ρ/cos α   from the tooth's centre line,  D = r_ref − r_f,
/// and rolling the reference circle on the rack maps X to the angle X/r_ref: θ_f = X_f/r_ref: the
/// angle between the centre line and the junction of fillet and root circle, with which Sainsot et
/// al. define S_f = 2 r_f θ_f (their FE teeth have real fillets). Ma et al. 2015 and the ROSS code
/// print the same formula with D = h_a instead of h_a + c (6 % smaller θ_f for the ISO rack, about
/// 2.5 % less mesh stiffness); the fit is sensitive to θ_f, so pass root_half_angle_rad to match an
/// FE model's actual root if it differs.
inline double RootHalfAngle(const Gear& g) {
  if (g.root_half_angle_rad > 0.0) return g.root_half_angle_rad;
  const double a = g.pressure_angle_rad, rho = g.tool_tip_radius_coefficient * g.module_m;
  const double half_s = g.module_m * (std::numbers::pi / 4 + g.profile_shift * std::tan(a));
  const double depth = ReferenceRadius(g) - g.root_radius_m;
  return (half_s + (depth - rho) * std::tan(a) + rho / std::cos(a)) / ReferenceRadius(g);
}

/// A point of the flank (the one on the +x side of the centre line), parametrised by the roll angle
/// t = tan α_r: r = r_b √(1 + t²), half-angle ψ = ψ_b − inv α_r, y = r cos ψ, h = r sin ψ.
struct FlankPoint {
  double radius_m = 0.0;            ///< r [m]
  double pressure_angle_rad = 0.0;  ///< α_r [rad]
  double half_angle_rad = 0.0;      ///< ψ [rad]
  double y_m = 0.0;                 ///< along the centre line [m]
  double half_thickness_m = 0.0;    ///< h, distance from the centre line [m]
  double dy_dt = 0.0;               ///< dy/dt [m]
  /// β = α_r − ψ, angle of the line of action (the base tangent through the point, pointing into
  /// the tooth) below the perpendicular to the centre line [rad].
  double load_angle_rad = 0.0;
};

inline FlankPoint FlankAtRoll(const Gear& g, double roll) {
  const double r_b = BaseRadius(g);
  FlankPoint p;
  const double q = std::sqrt(1.0 + roll * roll);
  p.radius_m = r_b * q;
  p.pressure_angle_rad = std::atan(roll);
  p.half_angle_rad = BaseHalfAngle(g) - (roll - p.pressure_angle_rad);
  p.y_m = p.radius_m * std::cos(p.half_angle_rad);
  p.half_thickness_m = p.radius_m * std::sin(p.half_angle_rad);
  // dr/dt = r_b t/√(1+t²), dψ/dt = −t²/(1+t²).
  const double dr = r_b * roll / q, dpsi = -roll * roll / (q * q);
  p.dy_dt = dr * std::cos(p.half_angle_rad) - p.radius_m * std::sin(p.half_angle_rad) * dpsi;
  p.load_angle_rad = p.pressure_angle_rad - p.half_angle_rad;
  return p;
}

/// Roll angle at radius r ≥ r_b: t = √((r/r_b)² − 1).
inline double RollAtRadius(const Gear& g, double radius_m) {
  const double q = radius_m / BaseRadius(g);
  return std::sqrt(std::max(0.0, q * q - 1.0));
}

// ---------------------------------------------------------------------------------------------
// One tooth

/// Compliances of one tooth along the line of action [m/N], and the quantities behind them.
struct ToothCompliance {
  double bending_m_per_n = 0.0;      ///< 1/k_b
  double shear_m_per_n = 0.0;        ///< 1/k_s
  double compression_m_per_n = 0.0;  ///< 1/k_a
  double foundation_m_per_n = 0.0;   ///< 1/k_f (Sainsot)
  double contact_radius_m = 0.0;     ///< r_c [m]
  double load_angle_rad = 0.0;       ///< β = α_c − ψ_c [rad]
  double fillet_u_m = 0.0;           ///< u_f [m]
  double fillet_s_m = 0.0;           ///< S_f [m]
  double Total() const {
    return bending_m_per_n + shear_m_per_n + compression_m_per_n + foundation_m_per_n;
  }
};

/// Sainsot et al. 2004, Table 1: rows L*, M*, P*, Q*; columns A, B, C, D, E, F of
/// X* = A/θ_f² + B h_fi² + C h_fi/θ_f + D/θ_f + E h_fi + F. (The same values are reprinted by
/// Chaari et al. 2009 and used by the ROSS rotordynamics code, GearElementTVMS, which flags
/// extrapolation outside L* ∈ [6.82, 6.94], M* ∈ [1.08, 3.29], P* ∈ [2.56, 13.47],
/// Q* ∈ [0.141, 0.62], the span of Sainsot's fitted gear bodies.)
inline constexpr std::array<std::array<double, 6>, 4> kSainsotTable = {{
    {-5.574e-5, -1.9986e-3, -2.3015e-4, 4.7702e-3, 0.0271, 6.8045},
    {60.111e-5, 28.100e-3, -83.431e-4, -9.9256e-3, 0.1624, 0.9086},
    {-50.952e-5, 185.50e-3, 0.0538e-4, 53.300e-3, 0.2895, 0.9236},
    {-6.2042e-5, 9.0889e-3, -4.0964e-4, 7.8297e-3, -0.1472, 0.6904},
}};

/// {L*, M*, P*, Q*} at h_fi = r_f/r_int and θ_f [rad].
inline std::array<double, 4> SainsotCoefficients(double h_fi, double theta_f) {
  std::array<double, 4> x{};
  for (std::size_t i = 0; i < 4; ++i) {
    const auto& c = kSainsotTable[i];
    x[i] = c[0] / (theta_f * theta_f) + c[1] * h_fi * h_fi + c[2] * h_fi / theta_f +
           c[3] / theta_f + c[4] * h_fi + c[5];
  }
  return x;
}

/// Sainsot's fillet-foundation compliance 1/k_f [m/N] for a unit load at angle β, crossing the
/// centre line at u_f above the root circle: cos²β/(E b) [L*(u_f/S_f)² + M*(u_f/S_f) +
/// P*(1 + Q* tan²β)], S_f = 2 r_f θ_f.
inline double SainsotFoundationCompliance(double load_angle_rad, double u_f_m, double root_radius_m,
                                          double bore_radius_m, double theta_f_rad,
                                          double youngs_modulus_pa, double face_width_m) {
  const auto [l, m, p, q] = SainsotCoefficients(root_radius_m / bore_radius_m, theta_f_rad);
  const double ratio = u_f_m / (2.0 * root_radius_m * theta_f_rad);
  const double c = std::cos(load_angle_rad), t = std::tan(load_angle_rad);
  return c * c / (youngs_modulus_pa * face_width_m) *
         (l * ratio * ratio + m * ratio + p * (1.0 + q * t * t));
}

/// Compliance of one tooth loaded at the flank point of radius `contact_radius_m`, over the face
/// width `face_width_m` (the pair's working width).
/// @throws std::invalid_argument if the point is not on the flank (below max(r_b, r_f) or above
///         the tip) or the tooth is pointed there.
inline ToothCompliance ToothComplianceAt(const Gear& g, double contact_radius_m,
                                         double face_width_m, const Options& options = {}) {
  const double r_b = BaseRadius(g), r_f = g.root_radius_m;
  const double form = std::max(r_b, r_f);
  const double slack = 1e-9 * g.tip_radius_m;
  if (!(contact_radius_m >= form - slack && contact_radius_m <= g.tip_radius_m + slack)) {
    throw std::invalid_argument(Describe("contact_radius_m", contact_radius_m,
                                         "must lie on the involute flank, between max(r_b, r_f) "
                                         "and the tip radius"));
  }
  const double t0 = RollAtRadius(g, form);
  const double tc = std::max(t0, RollAtRadius(g, contact_radius_m));
  const FlankPoint c = FlankAtRoll(g, tc);
  if (!(c.half_thickness_m > 0.0)) {
    throw std::invalid_argument(
        Describe("contact_radius_m", contact_radius_m, "the tooth is pointed there"));
  }
  const double e = g.youngs_modulus_pa, nu = g.poisson_ratio;
  BeamElasticity el;
  el.bending_modulus_pa = options.plane == PlaneModel::kPlaneStrain ? e / (1.0 - nu * nu) : e;
  el.shear_modulus_pa = e / (2.0 * (1.0 + nu));
  el.face_width_m = face_width_m;
  const BeamLoad load{c.y_m, c.half_thickness_m, c.load_angle_rad};

  // Involute part: from the form circle to the contact point, over the roll angle.
  BeamCompliance beam = BeamEnergyCompliance(
      [&](double t) {
        const FlankPoint p = FlankAtRoll(g, t);
        return BeamSection{p.y_m, p.dy_dt, p.half_thickness_m};
      },
      t0, tc, load, el, options.relative_tolerance);

  // Root part, r_f < r_b: a straight flank from the base circle down to the root circle.
  if (r_f < r_b) {
    const double psi_b = BaseHalfAngle(g), y_b = r_b * std::cos(psi_b);
    BeamCompliance root;
    if (options.root == RootModel::kParallelLine) {
      const double h = r_b * std::sin(psi_b);
      const double y_f = std::sqrt(r_f * r_f - h * h);
      root = BeamEnergyCompliance(
          [&](double y) {
            return BeamSection{y, 1.0, h};
          },
          y_f, y_b, load, el, options.relative_tolerance);
    } else {
      const double tan_psi = std::tan(psi_b);
      root = BeamEnergyCompliance(
          [&](double y) {
            return BeamSection{y, 1.0, y * tan_psi};
          },
          r_f * std::cos(psi_b), y_b, load, el, options.relative_tolerance);
    }
    beam.bending_m_per_n += root.bending_m_per_n;
    beam.shear_m_per_n += root.shear_m_per_n;
    beam.compression_m_per_n += root.compression_m_per_n;
  }

  ToothCompliance out;
  out.bending_m_per_n = beam.bending_m_per_n;
  out.shear_m_per_n = beam.shear_m_per_n;
  out.compression_m_per_n = beam.compression_m_per_n;
  out.contact_radius_m = c.radius_m;
  out.load_angle_rad = c.load_angle_rad;
  // The load line crosses the centre line at y_c − h_c tan β = r_c cos α_c / cos β = r_b / cos β.
  out.fillet_u_m = r_b / std::cos(c.load_angle_rad) - r_f;
  const double theta_f = RootHalfAngle(g);
  out.fillet_s_m = 2.0 * r_f * theta_f;
  out.foundation_m_per_n = SainsotFoundationCompliance(c.load_angle_rad, out.fillet_u_m, r_f,
                                                       g.bore_radius_m, theta_f, e, face_width_m);
  return out;
}

// ---------------------------------------------------------------------------------------------
// The pair

/// The mesh's kinematic data.
struct MeshGeometry {
  double base_radius1_m = 0.0;                ///< r_b1 [m]
  double base_radius2_m = 0.0;                ///< r_b2 [m]
  double operating_pressure_angle_rad = 0.0;  ///< α_w, cos α_w = (r_b1 + r_b2)/a [rad]
  double line_of_action_length_m = 0.0;       ///< g = T1T2 = a sin α_w [m]
  /// s_A, start of the active path (gear 2's tip circle, or gear 1's form circle if higher) [m]
  double path_start_m = 0.0;
  /// s_E, end of the active path (gear 1's tip circle, or gear 2's form circle if lower) [m]
  double path_end_m = 0.0;
  double base_pitch_m = 0.0;   ///< p_b [m]
  double contact_ratio = 0.0;  ///< ε_α = (s_E − s_A)/p_b [-]
  double face_width_m = 0.0;   ///< b = min(b1, b2) [m]
};

/// @throws std::invalid_argument on invalid gears, unequal base pitches, a ≤ r_b1 + r_b2 or an
///         empty active path.
inline MeshGeometry Geometry(const GearPair& pair) {
  ValidateGear(pair.gear1, "gear1");
  ValidateGear(pair.gear2, "gear2");
  MeshGeometry m;
  m.base_radius1_m = BaseRadius(pair.gear1);
  m.base_radius2_m = BaseRadius(pair.gear2);
  m.base_pitch_m = BasePitch(pair.gear1);
  if (std::abs(BasePitch(pair.gear2) - m.base_pitch_m) > 1e-9 * m.base_pitch_m) {
    throw std::invalid_argument(
        Describe("gear2 base pitch", BasePitch(pair.gear2), "must equal gear1's (π m cos α)"));
  }
  const double rb = m.base_radius1_m + m.base_radius2_m, a = pair.centre_distance_m;
  if (!(a > rb)) {
    throw std::invalid_argument(
        Describe("centre_distance_m", a, "must exceed the sum of the base radii"));
  }
  m.operating_pressure_angle_rad = std::acos(rb / a);
  m.line_of_action_length_m = std::sqrt(a * a - rb * rb);
  const auto along = [](double r, double r_b) {
    return std::sqrt(std::max(0.0, r * r - r_b * r_b));
  };
  const double g = m.line_of_action_length_m;
  const double form1 = std::max(m.base_radius1_m, pair.gear1.root_radius_m);
  const double form2 = std::max(m.base_radius2_m, pair.gear2.root_radius_m);
  m.path_start_m = std::max(g - along(pair.gear2.tip_radius_m, m.base_radius2_m),
                            along(form1, m.base_radius1_m));
  m.path_end_m = std::min(along(pair.gear1.tip_radius_m, m.base_radius1_m),
                          g - along(form2, m.base_radius2_m));
  if (!(m.path_end_m > m.path_start_m)) {
    throw std::invalid_argument(
        Describe("active path length", m.path_end_m - m.path_start_m, "must be > 0"));
  }
  m.contact_ratio = (m.path_end_m - m.path_start_m) / m.base_pitch_m;
  m.face_width_m = std::min(pair.gear1.face_width_m, pair.gear2.face_width_m);
  return m;
}

/// Yang & Lin's Hertzian stiffness [N/m]: π b / (2 [(1−ν1²)/E1 + (1−ν2²)/E2]), b = min(b1, b2).
inline double HertzStiffness(const GearPair& pair) {
  const Gear &g1 = pair.gear1, &g2 = pair.gear2;
  const double b = std::min(g1.face_width_m, g2.face_width_m);
  return std::numbers::pi * b /
         (2.0 * ((1.0 - g1.poisson_ratio * g1.poisson_ratio) / g1.youngs_modulus_pa +
                 (1.0 - g2.poisson_ratio * g2.poisson_ratio) / g2.youngs_modulus_pa));
}

/// Compliance of one tooth pair along the line of action [m/N].
struct PairCompliance {
  double position_m = 0.0;     ///< s, from T1 along the line of action [m]
  double hertz_m_per_n = 0.0;  ///< 1/k_h
  ToothCompliance tooth1;
  ToothCompliance tooth2;
  double Total() const { return hertz_m_per_n + tooth1.Total() + tooth2.Total(); }
  double Stiffness() const { return 1.0 / Total(); }  ///< k_pair [N/m]
};

/// The tooth pair in contact at s (distance along the line of action from T1, the tangency point on
/// gear 1's base circle; s/r_b1 is gear 1's roll angle of the contact point):
///   1/k = 1/k_h + Σ_gears (1/k_b + 1/k_s + 1/k_a + 1/k_f).
/// s may lie anywhere both contact points are on their flanks (not only on the active path).
inline PairCompliance SinglePairCompliance(const GearPair& pair, double position_m) {
  const MeshGeometry m = Geometry(pair);
  const double g = m.line_of_action_length_m;
  const double s2 = g - position_m;
  PairCompliance c;
  c.position_m = position_m;
  c.hertz_m_per_n = 1.0 / HertzStiffness(pair);
  c.tooth1 = ToothComplianceAt(pair.gear1, std::hypot(m.base_radius1_m, position_m), m.face_width_m,
                               pair.options);
  c.tooth2 =
      ToothComplianceAt(pair.gear2, std::hypot(m.base_radius2_m, s2), m.face_width_m, pair.options);
  return c;
}

/// s of the contact point whose roll angle on gear 1 is `gear1_roll_rad` (tan of its pressure
/// angle): s = r_b1 · roll. A rotation Δφ of gear 1 moves every contact by r_b1 Δφ along the line.
inline double LineOfActionPosition(const GearPair& pair, double gear1_roll_rad) {
  return BaseRadius(pair.gear1) * gear1_roll_rad;
}

inline double SinglePairStiffness(const GearPair& pair, double position_m) {
  return SinglePairCompliance(pair, position_m).Stiffness();
}

/// One instant of the mesh cycle.
struct MeshSample {
  double cycle_position_m = 0.0;        ///< s_0 − s_A ∈ [0, p_b): newest pair's travel [m]
  double mesh_stiffness_n_per_m = 0.0;  ///< k = Σ k_pair [N/m]
  std::vector<double> pair_position_m;  ///< s of each pair in contact, newest first [m]
  std::vector<double> pair_stiffness_n_per_m;  ///< k_pair [N/m]
  std::vector<double> load_share;              ///< k_pair / k (equal approach of all pairs) [-]
};

struct MeshCurve {
  MeshGeometry geometry;
  std::vector<MeshSample> samples;
  double sampled_mean_n_per_m = 0.0;  ///< mean over the samples [N/m]
  double min_n_per_m = 0.0;           ///< [N/m]
  double max_n_per_m = 0.0;           ///< [N/m]
};

/// The mesh stiffness over one mesh cycle (the newest pair moving from s_A over one base pitch),
/// `samples` equally spaced instants s_0 = s_A + i p_b/samples, i = 0 … samples−1. Pairs sit at
/// s_0 + j p_b, j = 0, 1, …, and are in contact while s_A ≤ s ≤ s_E.
inline MeshCurve MeshStiffnessCurve(const GearPair& pair, int samples) {
  if (samples < 1) throw std::invalid_argument(Describe("samples", samples, "must be >= 1"));
  MeshCurve curve;
  curve.geometry = Geometry(pair);
  const MeshGeometry& m = curve.geometry;
  const double slack = 1e-12 * m.base_pitch_m;
  curve.min_n_per_m = std::numeric_limits<double>::infinity();
  curve.max_n_per_m = 0.0;
  double sum = 0.0;
  for (int i = 0; i < samples; ++i) {
    MeshSample sample;
    sample.cycle_position_m = m.base_pitch_m * i / samples;
    for (double s = m.path_start_m + sample.cycle_position_m; s <= m.path_end_m + slack;
         s += m.base_pitch_m) {
      const double k = SinglePairStiffness(pair, std::min(s, m.path_end_m));
      sample.pair_position_m.push_back(s);
      sample.pair_stiffness_n_per_m.push_back(k);
      sample.mesh_stiffness_n_per_m += k;
    }
    for (double k : sample.pair_stiffness_n_per_m) {
      sample.load_share.push_back(k / sample.mesh_stiffness_n_per_m);
    }
    sum += sample.mesh_stiffness_n_per_m;
    curve.min_n_per_m = std::min(curve.min_n_per_m, sample.mesh_stiffness_n_per_m);
    curve.max_n_per_m = std::max(curve.max_n_per_m, sample.mesh_stiffness_n_per_m);
    curve.samples.push_back(std::move(sample));
  }
  curve.sampled_mean_n_per_m = sum / samples;
  return curve;
}

/// The exact cycle mean of the mesh stiffness [N/m]: every pair crosses the active path once per
/// p_b of travel, so  k̄ = (1/p_b) ∫_{s_A}^{s_E} k_pair(s) ds  (integrated adaptively; the sampled
/// mean of MeshStiffnessCurve converges to it only at O(1/samples) because of the jumps).
inline double MeanMeshStiffness(const GearPair& pair) {
  const MeshGeometry m = Geometry(pair);
  return IntegrateAdaptive([&](double s) { return SinglePairStiffness(pair, s); }, m.path_start_m,
                           m.path_end_m, pair.options.relative_tolerance) /
         m.base_pitch_m;
}

struct SinglePairPeak {
  double stiffness_n_per_m = 0.0;  ///< max over the active path of k_pair [N/m]
  double position_m = 0.0;         ///< where, s from T1 [m]
  /// The peak lies in the single-contact zone [s_E − p_b, s_A + p_b] (nonempty when ε_α < 2).
  bool in_single_contact_zone = false;
  double single_zone_max_n_per_m = 0.0;  ///< max of k_pair over that zone (0 if ε_α ≥ 2) [N/m]
};

namespace detail {

/// Max of a smooth function on [a, b]: 64-point scan, then golden section around the best point.
inline std::pair<double, double> Maximise(const std::function<double(double)>& f, double a,
                                          double b) {
  const int n = 64;
  double best_x = a, best_f = f(a);
  for (int i = 1; i <= n; ++i) {
    const double x = a + (b - a) * i / n, v = f(x);
    if (v > best_f) {
      best_f = v;
      best_x = x;
    }
  }
  double lo = std::max(a, best_x - (b - a) / n), hi = std::min(b, best_x + (b - a) / n);
  const double phi = 0.5 * (std::sqrt(5.0) - 1.0);
  double x1 = hi - phi * (hi - lo), x2 = lo + phi * (hi - lo);
  double f1 = f(x1), f2 = f(x2);
  while (hi - lo > 1e-12 * (b - a)) {
    if (f1 < f2) {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + phi * (hi - lo);
      f2 = f(x2);
    } else {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - phi * (hi - lo);
      f1 = f(x1);
    }
  }
  const double x = 0.5 * (lo + hi), v = f(x);
  if (v > best_f) {
    best_f = v;
    best_x = x;
  }
  return {best_x, best_f};
}

}  // namespace detail

/// The largest single-pair stiffness over the whole active path (where k_pair is largest; for
/// ε_α < 2 that is normally inside the single-contact zone, which is reported), and the largest
/// within the single-contact zone.
inline SinglePairPeak PeakSinglePairStiffness(const GearPair& pair) {
  const MeshGeometry m = Geometry(pair);
  const auto k = [&](double s) { return SinglePairStiffness(pair, s); };
  SinglePairPeak peak;
  std::tie(peak.position_m, peak.stiffness_n_per_m) =
      detail::Maximise(k, m.path_start_m, m.path_end_m);
  const double lo = m.path_end_m - m.base_pitch_m, hi = m.path_start_m + m.base_pitch_m;
  if (hi > lo) {
    peak.in_single_contact_zone = peak.position_m >= lo && peak.position_m <= hi;
    peak.single_zone_max_n_per_m = detail::Maximise(k, lo, hi).second;
  }
  return peak;
}

/// N/m → N/(mm·µm) per unit face width: 1 N/(mm·µm) = 1e9 N/m².
inline double PerUnitWidth(double stiffness_n_per_m, double face_width_m) {
  return stiffness_n_per_m / face_width_m * 1e-9;
}

struct MeshStiffnessSummary {
  double mean_mesh_stiffness_n_per_m = 0.0;         ///< k̄ [N/m]
  double peak_single_pair_stiffness_n_per_m = 0.0;  ///< max k_pair [N/m]
  double face_width_m = 0.0;                        ///< b [m]
  double mean_per_width = 0.0;                      ///< k̄/b [N/(mm·µm)]
  double peak_single_pair_per_width = 0.0;          ///< max k_pair / b [N/(mm·µm)]
  double contact_ratio = 0.0;                       ///< ε_α [-]
  SinglePairPeak peak;
};

inline MeshStiffnessSummary Summarise(const GearPair& pair) {
  const MeshGeometry m = Geometry(pair);
  MeshStiffnessSummary out;
  out.mean_mesh_stiffness_n_per_m = MeanMeshStiffness(pair);
  out.peak = PeakSinglePairStiffness(pair);
  out.peak_single_pair_stiffness_n_per_m = out.peak.stiffness_n_per_m;
  out.face_width_m = m.face_width_m;
  out.mean_per_width = PerUnitWidth(out.mean_mesh_stiffness_n_per_m, m.face_width_m);
  out.peak_single_pair_per_width = PerUnitWidth(out.peak.stiffness_n_per_m, m.face_width_m);
  out.contact_ratio = m.contact_ratio;
  return out;
}

}  // namespace epicycle::verification::pem
