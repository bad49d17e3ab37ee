// A local term whose validity limit is known in closed form, for the result-warning tests: plane
// strain, equal steel bodies (E = 207 GPa, ν = 0.3, joining depth h = 1 mm), b = 25 mm,
// R_eq = 10 mm. The limit is where the Hertz half-width reaches h, L = h:
// F = h² π b E* / (4 R_eq), with 1/E* = 2 (1 − ν²)/E.
#pragma once

#include "epicycle/geometry/plane.hpp"
#include "epicycle/solvers/local_term.hpp"

namespace epicycle::test {

struct LocalTermWithLimit {
  solvers::LocalTermParameters parameters;
  double limit_force = 0;  ///< [N]
};

inline LocalTermWithLimit SteelLocalTerm() {
  LocalTermWithLimit t;
  t.parameters.face_width = 25e-3;
  t.parameters.reduced_radius = 10e-3;
  for (auto& b : t.parameters.body) b = {207e9, 0.3, 1e-3};
  const double e_star = 207e9 / (2.0 * (1.0 - 0.09));
  t.limit_force = 1e-6 * geometry::kPi * 25e-3 * e_star / (4.0 * 10e-3);
  return t;
}

}  // namespace epicycle::test
