// Adaptive Gauss–Kronrod (7/15) quadrature for the solvers' reference tests: an integrator
// independent of the closed forms it checks.
#pragma once

#include <cmath>
#include <functional>

namespace epicycle::solvers::test {

inline double GaussKronrod15(const std::function<double(double)>& f, double a, double b,
                             double* error) {
  static const double xk[8] = {
      0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
      0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
      0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
      0.207784955007898467600689403773245, 0.000000000000000000000000000000000};
  static const double wk[8] = {
      0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
      0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
      0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
      0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
  static const double wg[4] = {
      0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
      0.381830050505118944950369775488975, 0.417959183673469387755102040816327};
  const double c = 0.5 * (a + b), h = 0.5 * (b - a);
  double k = wk[7] * f(c), g = wg[3] * f(c);
  for (int i = 0; i < 7; ++i) {
    const double f1 = f(c - h * xk[i]), f2 = f(c + h * xk[i]);
    k += wk[i] * (f1 + f2);
    if (i % 2 == 1) g += wg[i / 2] * (f1 + f2);
  }
  *error = std::abs((k - g) * h);
  return k * h;
}

/// ∫_a^b f to |error| ≤ abs_tol (per-interval Kronrod–Gauss difference, bisection to depth 50).
inline double Integrate(const std::function<double(double)>& f, double a, double b, double abs_tol,
                        int depth = 0) {
  double err = 0.0;
  const double v = GaussKronrod15(f, a, b, &err);
  if (err <= abs_tol || depth >= 50) return v;
  const double m = 0.5 * (a + b);
  return Integrate(f, a, m, 0.5 * abs_tol, depth + 1) +
         Integrate(f, m, b, 0.5 * abs_tol, depth + 1);
}

}  // namespace epicycle::solvers::test
