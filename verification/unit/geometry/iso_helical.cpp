// ISO 6336 factors of helical gears (geometry/iso.hpp) against hand values: each expected number
// below was evaluated from the standard's formula as printed (ISO 6336-2:2006 and ISO
// 6336-3:2006; ISO 6336-3:1996 for Y_ε), outside this code, and written here to 16 digits; the
// tolerance 1e-12 relative is rounding.
#include <catch2/catch.hpp>

#include <cmath>

#include "epicycle/geometry/iso.hpp"
#include "epicycle/geometry/plane.hpp"

using namespace epicycle::geometry;

TEST_CASE("ISO 6336-3 helical bending factors: z_n, eps_alpha_n, Y_beta, Y_eps",
          "[unit][geometry]") {
  // z = 21, β = 15°, α_n = 20°: tan α_t = tan 20°/cos 15°, tan β_b = tan 15° cos α_t
  // (β_b = 14.07609542166249°); ε_α = 1.5, ε_β = 0.8.
  const double beta = Rad(15), at = std::atan(std::tan(Rad(20)) / std::cos(beta));
  const double beta_b = std::atan(std::tan(beta) * std::cos(at));
  CHECK(Deg(beta_b) == Approx(14.076095421662487).epsilon(1e-12));
  const iso::HelicalBendingFactors f = iso::HelicalBending(21, beta, beta_b, 1.5, 0.8);
  CHECK(f.virtual_teeth == Approx(23.10764648969068).epsilon(1e-12));  // z/(cos²β_b cos β)
  CHECK(f.virtual_contact_ratio == Approx(1.5943051806535828).epsilon(1e-12));  // ε_α/cos²β_b
  CHECK(f.y_beta == Approx(0.9).epsilon(1e-12));                // 1 − 0.8 · 15/120
  CHECK(f.y_eps == Approx(0.7204243636042997).epsilon(1e-12));  // 0.25 + 0.75/ε_αn
  // ε_β taken as 1 above 1, β as 30° above 30°: Y_β = 1 − 30/120 = 0.75.
  CHECK(iso::HelicalBending(21, Rad(35), Rad(33), 1.5, 1.3).y_beta == Approx(0.75).epsilon(1e-12));
  // A spur gear: z_n = z, ε_αn = ε_α, Y_β = 1.
  const iso::HelicalBendingFactors spur = iso::HelicalBending(21, 0, 0, 1.5, 0);
  CHECK(spur.virtual_teeth == 21);
  CHECK(spur.y_beta == 1);
  CHECK_THROWS_WITH(iso::HelicalBending(21, Rad(10), Rad(11), 1.5, 0.5),
                    Catch::Matchers::Contains("base helix angle [deg] = 11"));
}

TEST_CASE("ISO 6336-2 helical contact factors: Z_H, Z_eps, Z_beta, Z_B, Z_D", "[unit][geometry]") {
  // The 20/40 pair of m = 4 mm, α = 20°, a = 120 mm, tips r + m: ε_α = 1.635185963571462,
  // Z_H = 2.494573171394588, M_1 = 1.062338666814336, M_2 = 0.9739664806485453 (spur). As helical
  // factors with β = 13°, β_b = 12°, ε_β = 0.6:
  //   Z_H √cos β_b = 2.467166414045009,  Z_ε = √((4 − ε_α)(1 − ε_β)/3 + ε_β/ε_α) =
  //   0.8259777726126627, Z_β = 1/√cos 13° = 1.013066684771240,  Z_B = M_1 − ε_β (M_1 − 1)
  //   = 1.024935466725735, Z_D = max(1, M_2 − ε_β (M_2 − 1)) = 1.
  const double a20 = Rad(20), rb1 = 0.037587704831436336, rb2 = 0.07517540966287267;
  const double ea = 1.635185963571462;
  const iso::ContactFactors spur =
      iso::ContactFactorsB(20, a20, a20, 0.12, rb1, 0.044, rb2, 0.084, ea, false);
  CHECK(spur.z_h == Approx(2.494573171394588).epsilon(1e-12));
  CHECK(spur.m1 == Approx(1.0623386668143364).epsilon(1e-12));
  const iso::ContactFactors h = iso::HelicalContactFactorsB(
      20, a20, a20, 0.12, rb1, 0.044, rb2, 0.084, ea, false, Rad(13), Rad(12), 0.6);
  CHECK(h.z_h == Approx(2.467166414045009).epsilon(1e-12));
  CHECK(h.z_eps == Approx(0.8259777726126627).epsilon(1e-12));
  CHECK(h.z_beta == Approx(1.0130666847712404).epsilon(1e-12));
  CHECK(h.z_b == Approx(1.0249354667257347).epsilon(1e-12));
  CHECK(h.z_d == 1);
  // ε_β ≥ 1: Z_ε = √(1/ε_α), Z_B = Z_D = 1.
  const iso::ContactFactors wide = iso::HelicalContactFactorsB(
      20, a20, a20, 0.12, rb1, 0.044, rb2, 0.084, ea, false, Rad(13), Rad(12), 1.2);
  CHECK(wide.z_eps == Approx(std::sqrt(1 / ea)).epsilon(1e-12));
  CHECK(wide.z_b == 1);
  // β = 0 is the spur computation, bit for bit.
  const iso::ContactFactors zero =
      iso::HelicalContactFactorsB(20, a20, a20, 0.12, rb1, 0.044, rb2, 0.084, ea, false, 0, 0, 0);
  CHECK(zero.z_h == spur.z_h);
  CHECK(zero.z_eps == spur.z_eps);
  CHECK(zero.z_b == spur.z_b);
  CHECK(zero.z_beta == 1);
}

TEST_CASE("ISO 6336-3 helical form factors are those of the virtual spur gear",
          "[unit][geometry]") {
  // The virtual gear in the normal section: z_n = z/(cos²β_b cos β), m_n, α_n, x_n,
  // d_an = m_n z_n + d_a − z m_n/cos β, ε_αn = ε_α/cos²β_b (ISO 6336-3:2006).
  const int z = 21;
  const double mn = 10e-3, an = Rad(20), beta = Rad(7.5), xn = 0.1;
  const double at = std::atan(std::tan(an) / std::cos(beta));
  const double bb = std::atan(std::tan(beta) * std::cos(at));
  const double d = z * mn / std::cos(beta), da = d + 2 * (xn + 1) * mn;
  const double zn = z / (std::cos(bb) * std::cos(bb) * std::cos(beta));
  const iso::RootFormFactors h =
      iso::HelicalRootFormFactorsB(z, mn, an, xn, beta, bb, 1.25 * mn, 0.38 * mn, da, 1.55);
  const iso::RootFormFactors v = iso::RootFormFactorsB(
      zn, mn, an, xn, 1.25 * mn, 0.38 * mn, mn * zn + da - d, 1.55 / std::pow(std::cos(bb), 2));
  CHECK(h.y_f == Approx(v.y_f).epsilon(1e-14));
  CHECK(h.y_s == Approx(v.y_s).epsilon(1e-14));
  // A helical gear's virtual gear has more teeth: a smaller form factor than the spur gear's.
  const iso::RootFormFactors spur =
      iso::RootFormFactorsB(z, mn, an, xn, 1.25 * mn, 0.38 * mn, z * mn + 2 * (xn + 1) * mn, 1.55);
  CHECK(h.y_f < spur.y_f);
}
