// Second-order forward-mode differentiation: a value with its first and second derivatives with
// respect to one parameter. Used to evaluate generated (envelope) curves with exact derivatives.
#pragma once

#include <cmath>

namespace epicycle::geometry::internal {

struct Jet {
  double v = 0, d = 0, dd = 0;  // value, first and second derivative
  Jet() = default;
  Jet(double value) : v(value) {}  // NOLINT: constants promote implicitly
  Jet(double value, double d1, double d2) : v(value), d(d1), dd(d2) {}
  static Jet Variable(double x) { return {x, 1.0, 0.0}; }
};

inline Jet operator+(const Jet& a, const Jet& b) { return {a.v + b.v, a.d + b.d, a.dd + b.dd}; }
inline Jet operator-(const Jet& a, const Jet& b) { return {a.v - b.v, a.d - b.d, a.dd - b.dd}; }
inline Jet operator-(const Jet& a) { return {-a.v, -a.d, -a.dd}; }
inline Jet operator*(const Jet& a, const Jet& b) {
  return {a.v * b.v, a.d * b.v + a.v * b.d, a.dd * b.v + 2.0 * a.d * b.d + a.v * b.dd};
}
inline Jet operator/(const Jet& a, const Jet& b) {
  const double q = a.v / b.v;
  const double qd = (a.d - q * b.d) / b.v;
  const double qdd = (a.dd - 2.0 * qd * b.d - q * b.dd) / b.v;
  return {q, qd, qdd};
}
inline Jet sin(const Jet& a) {
  const double s = std::sin(a.v), c = std::cos(a.v);
  return {s, c * a.d, c * a.dd - s * a.d * a.d};
}
inline Jet cos(const Jet& a) {
  const double s = std::sin(a.v), c = std::cos(a.v);
  return {c, -s * a.d, -s * a.dd - c * a.d * a.d};
}
inline Jet sqrt(const Jet& a) {
  const double r = std::sqrt(a.v);
  const double rd = a.d / (2.0 * r);
  return {r, rd, (a.dd - 2.0 * rd * rd) / (2.0 * r)};
}

/// A plane point whose coordinates carry derivatives.
struct JetVec {
  Jet x, y;
};
inline JetVec operator+(const JetVec& a, const JetVec& b) { return {a.x + b.x, a.y + b.y}; }
inline JetVec operator-(const JetVec& a, const JetVec& b) { return {a.x - b.x, a.y - b.y}; }
inline JetVec operator*(const Jet& s, const JetVec& a) { return {s * a.x, s * a.y}; }
inline JetVec RotateJet(const JetVec& p, const Jet& angle) {
  const Jet c = cos(angle), s = sin(angle);
  return {c * p.x - s * p.y, s * p.x + c * p.y};
}
inline Jet Norm(const JetVec& p) { return sqrt(p.x * p.x + p.y * p.y); }

}  // namespace epicycle::geometry::internal
