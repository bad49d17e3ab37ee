// Hertz's contact pressure of a line contact (docs/model.md §9) against the closed form for two
// cylinders, written here from the half-width: a = √(4 w R/(π E*)), p_0 = 2w/(π a) (K. L. Johnson,
// Contact Mechanics, §4.2), external and internal, and the elliptical distribution carrying w.
#include <catch2/catch.hpp>

#include <cmath>

#include "epicycle/solvers/local_term.hpp"

using namespace epicycle::solvers;

namespace {

constexpr double kPi = 3.14159265358979323846;

LocalTermParameters Cylinders(double r1, double r2, bool internal, PlaneAssumption plane) {
  LocalTermParameters p;
  p.face_width = 0.010;
  p.reduced_radius = internal ? r1 * r2 / (r2 - r1) : r1 * r2 / (r1 + r2);
  p.plane = plane;
  p.body[0] = {210e9, 0.3, 1e-3};
  p.body[1] = {210e9, 0.3, 1e-3};
  return p;
}

}  // namespace

TEST_CASE("Hertz pressure of two steel cylinders against the closed form",
          "[reference][solvers][stress]") {
  const double force = 10e3, w = force / 0.010;  // 1000 N/mm
  for (const bool internal : {false, true}) {
    for (const PlaneAssumption plane :
         {PlaneAssumption::kPlaneStrain, PlaneAssumption::kPlaneStress}) {
      const LocalTermParameters p = Cylinders(0.020, 0.030, internal, plane);
      const double r = internal ? 0.020 * 0.030 / 0.010 : 0.020 * 0.030 / 0.050;
      const double k = plane == PlaneAssumption::kPlaneStrain ? (1 - 0.09) / 210e9 : 1 / 210e9;
      const double e_star = 1.0 / (2 * k);
      const double a = std::sqrt(4 * w * r / (kPi * e_star));
      const double p0 = 2 * w / (kPi * a);
      INFO((internal ? "internal" : "external")
           << ", plane " << (plane == PlaneAssumption::kPlaneStrain ? "strain" : "stress"));
      CHECK(HertzPressure(p, force) == Approx(p0).epsilon(1e-13));
      CHECK(HertzHalfWidth(p, force) == Approx(a).epsilon(1e-13));
      // The elliptical distribution p_0 √(1 − x²/a²) carries the line load (midpoint rule on
      // 20 000 cells: error below 1e-6 of w at the square-root ends).
      double carried = 0.0;
      const int cells = 20000;
      for (int i = 0; i < cells; ++i) {
        const double x = -a + (i + 0.5) * 2 * a / cells;
        carried += HertzPressure(p, force) * std::sqrt(1 - x * x / (a * a)) * 2 * a / cells;
      }
      CHECK(carried == Approx(w).epsilon(1e-6));
    }
  }
  // A hand value: external pair, plane strain, R = 12 mm, E* = 115.4 GPa, w = 1000 N/mm:
  // a = 0.3639 mm, p_0 = 1.7495 GPa.
  CHECK(HertzPressure(Cylinders(0.020, 0.030, false, PlaneAssumption::kPlaneStrain), force) / 1e9 ==
        Approx(1.7495).epsilon(1e-4));
  CHECK(HertzPressure(Cylinders(0.020, 0.030, false, PlaneAssumption::kPlaneStrain), 0.0) == 0.0);
}
