// ISO 6336-1 method B stiffness, against hand calculations from the standard's formula.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "epicycle/compliance/iso6336.hpp"

using namespace epicycle::compliance::iso6336;

TEST_CASE("ISO 6336-1 c' and c_gamma_alpha of a standard 20/40 pair", "[reference][compliance]") {
  PairData p;
  p.z1 = 20;
  p.z2 = 40;
  p.pressure_angle = 20.0 * std::numbers::pi / 180.0;
  p.contact_ratio = 1.6;
  // q' = 0.04723 + 0.15551/20 + 0.25791/40 = 0.06145325; C_B = 1 + 0.5(1.2 − 1.25) = 0.975.
  CHECK(MinimumFlexibility(p) == Approx(0.06145325).epsilon(1e-12));
  CHECK(BasicRackFactor(p) == Approx(0.975).epsilon(1e-12));
  CHECK(SinglePairStiffness(p) == Approx(0.8 * 0.975 / 0.06145325).epsilon(1e-12));
  CHECK(MeshStiffness(p) == Approx(0.8 * 0.975 / 0.06145325 * (0.75 * 1.6 + 0.25)).epsilon(1e-12));
}

TEST_CASE("ISO 6336-1 with shifts, a 25 deg tool and an internal mate", "[reference][compliance]") {
  PairData p;
  p.z1 = 16;
  p.z2 = 24;
  p.x1 = 0.3;
  p.x2 = 0.2;
  p.dedendum1 = p.dedendum2 = 1.35;
  p.pressure_angle = 25.0 * std::numbers::pi / 180.0;
  const double q = 0.04723 + 0.15551 / 16 + 0.25791 / 24 - 0.00635 * 0.3 - 0.11654 * 0.3 / 16 -
                   0.00193 * 0.2 - 0.24188 * 0.2 / 24 + 0.00529 * 0.09 + 0.00182 * 0.04;
  CHECK(MinimumFlexibility(p) == Approx(q).epsilon(1e-12));
  // C_B = [1 + 0.5(1.2 − 1.35)]·[1 − 0.02(20 − 25)] = 0.925 · 1.1.
  CHECK(BasicRackFactor(p) == Approx(0.925 * 1.1).epsilon(1e-12));
  p.internal = true;  // z_n2 = ∞, x2 out of the formula
  CHECK(MinimumFlexibility(p) ==
        Approx(0.04723 + 0.15551 / 16 - 0.00635 * 0.3 - 0.11654 * 0.3 / 16 + 0.00529 * 0.09)
            .epsilon(1e-12));
  p.z1 = 2;
  CHECK_THROWS_WITH(MinimumFlexibility(p), Catch::Matchers::Contains("z1 = 2"));
}
