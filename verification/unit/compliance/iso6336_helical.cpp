// ISO 6336-1:2006 method B stiffness of helical pairs (compliance/iso6336.hpp) against hand values
// evaluated from the standard's formulas as printed (9.2, 9.3): q′ with z_n = z/cos³β,
// c′ = c′_th C_M C_R C_B cos β, c_γα = c′ (0.75 ε_α + 0.25). Numbers to 16 digits from an
// evaluation outside this code; tolerance 1e-12 relative (rounding).
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "epicycle/compliance/iso6336.hpp"

using namespace epicycle::compliance::iso6336;

TEST_CASE("ISO 6336-1 single-pair and mesh stiffness of a helical pair", "[unit][compliance]") {
  // z 21/39, x 0.2/−0.1, h_fP = 1.25 m on both tools (C_B = 0.975), α_P = 20°, solid discs,
  // ε_α = 1.6.
  PairData p;
  p.z1 = 21;
  p.z2 = 39;
  p.x1 = 0.2;
  p.x2 = -0.1;
  p.pressure_angle = 20.0 * std::numbers::pi / 180;
  p.contact_ratio = 1.6;
  // Spur (β = 0): q′ = 0.05991141538461538, c′ = 0.8 · 0.975/q′ = 13.01922171246677.
  CHECK(MinimumFlexibility(p) == Approx(0.059911415384615384).epsilon(1e-12));
  CHECK(SinglePairStiffness(p) == Approx(13.019221712466766).epsilon(1e-12));
  CHECK(MeshStiffness(p) == Approx(18.877871483076813).epsilon(1e-12));
  const double spur_c = SinglePairStiffness(p);
  // β = 15°: z_n = z/cos³15°; q′ = 0.05857507316508027, c′ = 0.8 · 0.975 cos 15°/q′.
  p.helix_angle = 15.0 * std::numbers::pi / 180;
  CHECK(MinimumFlexibility(p) == Approx(0.05857507316508027).epsilon(1e-12));
  CHECK(SinglePairStiffness(p) == Approx(12.862504539808727).epsilon(1e-12));
  CHECK(MeshStiffness(p) == Approx(18.650631582722657).epsilon(1e-12));
  // β = 0 exactly again: the spur value, bit for bit.
  p.helix_angle = 0;
  CHECK(SinglePairStiffness(p) == spur_c);
  p.helix_angle = std::numbers::pi / 4;
  CHECK_THROWS_WITH(SinglePairStiffness(p), Catch::Matchers::Contains("helix_angle"));
}
