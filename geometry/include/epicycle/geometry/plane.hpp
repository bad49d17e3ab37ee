// Small plane-geometry helpers shared by the geometry layer.
#pragma once

#include <cmath>
#include <numbers>

#include <Eigen/Core>

namespace epicycle::geometry {

using Vec2 = Eigen::Vector2d;

inline constexpr double kPi = std::numbers::pi;

/// Unit vector at angle a [rad] from +x, counter-clockwise.
inline Vec2 Dir(double a) { return {std::cos(a), std::sin(a)}; }
/// Unit vector perpendicular to Dir(a), rotated +90°.
inline Vec2 DirPerp(double a) { return {-std::sin(a), std::cos(a)}; }
/// z-component of the cross product a × b.
inline double Cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }
/// v rotated counter-clockwise by a [rad].
inline Vec2 Rotate(const Vec2& v, double a) {
  const double c = std::cos(a), s = std::sin(a);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}
/// v rotated counter-clockwise by the angle of the unit vector e = Dir(a) (no sine or cosine).
inline Vec2 RotateBy(const Vec2& v, const Vec2& e) {
  return {e.x() * v.x() - e.y() * v.y(), e.y() * v.x() + e.x() * v.y()};
}
/// Polar angle of v in (−π, π].
inline double Angle(const Vec2& v) { return std::atan2(v.y(), v.x()); }
/// a wrapped into (−π, π].
inline double WrapAngle(double a) {
  // a − 2π·round(a/2π) with an inlined truncation (std::remainder is a library call and this
  // sits on the contact search's hot path); exact enough for |a| < 1e9.
  const double turns = a * (0.5 / kPi);
  return a - 2.0 * kPi * static_cast<double>(static_cast<long>(turns + (turns >= 0 ? 0.5 : -0.5)));
}

/// Involute function inv α = tan α − α.
inline double Inv(double alpha) { return std::tan(alpha) - alpha; }
/// Inverse of the involute function on [0, π/2): α with tan α − α = v (v ≥ 0). Newton, to
/// round-off.
double InvInverse(double v);

/// Radians → degrees. The one name for this direction in the project (its inverse is Rad).
inline double Deg(double rad) { return rad * 180.0 / kPi; }
/// Degrees → radians. The one name for this direction in the project (its inverse is Deg).
inline double Rad(double deg) { return deg * kPi / 180.0; }

}  // namespace epicycle::geometry
