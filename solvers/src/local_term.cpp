// The local (Hertzian) approach of docs/model.md §4 in closed form.
#include "epicycle/solvers/local_term.hpp"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace epicycle::solvers {
namespace {

constexpr double kPi = 3.14159265358979323846;

double Compliance(const LocalTermParameters& p, int b) {  // k_B [1/Pa]
  const LocalBody& body = p.body[b];
  return p.plane == PlaneAssumption::kPlaneStrain
             ? (1.0 - body.poisson_ratio * body.poisson_ratio) / body.youngs_modulus
             : 1.0 / body.youngs_modulus;
}

double PoissonFactor(const LocalTermParameters& p, int b) {  // c_B [-]
  const double nu = p.body[b].poisson_ratio;
  return p.plane == PlaneAssumption::kPlaneStrain ? nu / (1.0 - nu) : nu;
}

// L² = l2 · F.
double HalfWidthSquaredPerForce(const LocalTermParameters& p) {
  return 4.0 * p.reduced_radius / (kPi * p.face_width * EffectiveModulus(p));
}

void Fail(const std::string& field, double value, const char* rule) {
  std::ostringstream os;
  os.precision(17);
  os << field << " = " << value << ": " << rule;
  throw std::invalid_argument(os.str());
}

}  // namespace

bool IsValidLocalTerm(const LocalTermParameters& p) {
  if (!p.enabled) return true;
  auto ok = [](double v) { return std::isfinite(v) && v > 0.0; };
  auto ok_nu = [](double nu) { return std::isfinite(nu) && nu >= 0.0 && nu < 0.5; };
  return ok(p.face_width) && ok(p.reduced_radius) && ok(p.body[0].youngs_modulus) &&
         ok(p.body[0].depth) && ok_nu(p.body[0].poisson_ratio) && ok(p.body[1].youngs_modulus) &&
         ok(p.body[1].depth) && ok_nu(p.body[1].poisson_ratio);
}

void ValidateLocalTerm(const LocalTermParameters& p, const std::string& field) {
  if (IsValidLocalTerm(p)) return;
  auto positive = [&](double v, const std::string& name) {
    if (!std::isfinite(v) || !(v > 0.0)) Fail(field + "." + name, v, "must be finite and > 0");
  };
  positive(p.face_width, "face_width");
  positive(p.reduced_radius, "reduced_radius");
  for (int b = 0; b < 2; ++b) {
    const std::string pre = "body[" + std::to_string(b) + "].";
    positive(p.body[b].youngs_modulus, pre + "youngs_modulus");
    positive(p.body[b].depth, pre + "depth");
    const double nu = p.body[b].poisson_ratio;
    if (!std::isfinite(nu) || nu < 0.0 || nu >= 0.5)
      Fail(field + "." + pre + "poisson_ratio", nu, "must satisfy 0 <= nu < 0.5");
  }
}

double EffectiveModulus(const LocalTermParameters& p) {
  return 1.0 / (Compliance(p, 0) + Compliance(p, 1));
}

double HertzHalfWidth(const LocalTermParameters& p, double force) {
  return std::sqrt(HalfWidthSquaredPerForce(p) * std::max(force, 0.0));
}

double HertzPressure(const LocalTermParameters& p, double force) {
  if (!(force > 0.0)) return 0.0;
  return std::sqrt(force * EffectiveModulus(p) / (kPi * p.face_width * p.reduced_radius));
}

double LocalApproach(const LocalTermParameters& p, double force) {
  if (!p.enabled || force <= 0.0) return 0.0;
  const double l = HertzHalfWidth(p, force);
  double u = 0.0;
  for (int b = 0; b < 2; ++b) {
    const double a = 2.0 * Compliance(p, b) / (kPi * p.face_width);
    const double s = p.body[b].depth / l;
    const double w = std::hypot(1.0, l / p.body[b].depth);
    u += a * force * (std::asinh(s) - PoissonFactor(p, b) / (1.0 + w));
  }
  return u;
}

double LocalApproachDerivative(const LocalTermParameters& p, double force) {
  if (!p.enabled) return 0.0;
  if (force <= 0.0) return std::numeric_limits<double>::infinity();
  const double l = HertzHalfWidth(p, force);
  double du = 0.0;
  for (int b = 0; b < 2; ++b) {
    const double a = 2.0 * Compliance(p, b) / (kPi * p.face_width);
    const double s = p.body[b].depth / l;
    const double w = std::hypot(1.0, l / p.body[b].depth);
    du += a * (std::asinh(s) - (1.0 + PoissonFactor(p, b)) / (2.0 * w));
  }
  return du;
}

double LocalApproachIntegral(const LocalTermParameters& p, double force) {
  if (!p.enabled || force <= 0.0) return 0.0;
  const double l = HertzHalfWidth(p, force);
  double big_u = 0.0;
  for (int b = 0; b < 2; ++b) {
    const double a = 2.0 * Compliance(p, b) / (kPi * p.face_width);
    const double s = p.body[b].depth / l;
    const double w = std::hypot(1.0, l / p.body[b].depth);
    const double w1 = (1.0 + w) * (1.0 + w);
    big_u += 2.0 * a * force * force *
             (std::asinh(s) / 4.0 + (w + 2.0) / (12.0 * w1) -
              PoissonFactor(p, b) * (2.0 * w + 1.0) / (6.0 * w1));
  }
  return big_u;
}

double ValidityLimitForce(const LocalTermParameters& p) {
  if (!p.enabled) return std::numeric_limits<double>::infinity();
  const double h = std::min(p.body[0].depth, p.body[1].depth);
  return h * h / HalfWidthSquaredPerForce(p);
}

double NonMonotoneForce(const LocalTermParameters& p) {
  const double inf = std::numeric_limits<double>::infinity();
  if (!p.enabled) return inf;
  // Each body's u_B' = a_B [asinh(s) − (1+c_B)/(2w)] with asinh(s)/(1/w) = asinh(s)√(1+s²)/s ≥ 1:
  // strictly positive for every F when c_B < 1. Only a body with c_B ≥ 1 (ν ≥ 0.5, rejected by
  // validation) can make the sum vanish; then scan the force range and bisect.
  if (PoissonFactor(p, 0) < 1.0 && PoissonFactor(p, 1) < 1.0) return inf;
  const double f_ref = ValidityLimitForce(p);
  double lo = 0.0;
  for (int k = -12; k <= 12; ++k) {
    const double f = f_ref * std::pow(10.0, k);
    if (LocalApproachDerivative(p, f) <= 0.0) {
      double hi = f;
      for (int it = 0; it < 200 && hi - lo > 1e-14 * hi; ++it) {
        const double mid = 0.5 * (lo + hi);
        (LocalApproachDerivative(p, mid) <= 0.0 ? hi : lo) = mid;
      }
      return hi;
    }
    lo = f;
  }
  return inf;
}

}  // namespace epicycle::solvers
