// Friction laws against independent evaluations: Xu–Kahraman from docs/model.md's printed
// constants in log space and as the printed product in long double, Benedict–Kelley in its original
// US units, and μ along the path of contact of the paper's sun–planet mesh at 1500 rpm
// (docs/friction.md).
//
// No published numeric check point of the Xu et al. (2007) formula (a μ value with all of its
// inputs stated) was found, so the Xu–Kahraman rows check the implementation against other
// evaluations of the same printed formula (constants typed anew, a different arrangement). That
// catches transcription, unit and arrangement errors, not an error in the formula as printed.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "epicycle/transmission/friction.hpp"
#include "figures.hpp"

using namespace epicycle::transmission;
using epicycle::test::Figure;
using epicycle::test::Sci;
using epicycle::test::VerifyRow;

namespace {

constexpr double kEStar = 207e9 / (2 * (1 - 0.3 * 0.3));  // steel on steel [Pa]

// Builds a contact from the regression's own variables: P_h [GPa], SR, V_e [m/s], R [m]
// (F from P_h through the half-width a = 2F/(π p_h b), a² = 4FR/(π b E*) ⇒ F = π b R p_h²/E*).
FrictionContact FromRegressionVariables(double p_h_gpa, double sr, double v_e, double r, double b) {
  const double p_h = p_h_gpa * 1e9;
  FrictionContact c;
  c.normal_force = M_PI * b * r * p_h * p_h / kEStar;
  c.velocity_a = v_e * (1 + sr / 2);  // u_A − u_B = SR·V_e, (u_A + u_B)/2 = V_e
  c.velocity_b = v_e * (1 - sr / 2);
  c.reduced_radius = r;
  c.face_width = b;
  c.contact_modulus = kEStar;
  return c;
}

// ln μ of Xu et al. (2007), constants typed from docs/model.md §7, inputs in the paper's units.
double XuKahramanLog(double p_h_gpa, double sr, double v_e, double nu0_mpas, double r,
                     double s_um) {
  const double b[] = {-8.916465, 1.03303,  1.036077,  -0.354068, 2.812084,
                      -0.100601, 0.752755, -0.390958, 0.620305};
  const double x = sr * p_h_gpa * std::log10(nu0_mpas);
  return b[0] + b[3] * x + b[4] * std::exp(-x) + b[8] * std::exp(s_um) + b[1] * std::log(p_h_gpa) +
         b[2] * std::log(sr) + b[5] * std::log(v_e) + b[6] * std::log(nu0_mpas) +
         b[7] * std::log(r);
}

}  // namespace

TEST_CASE("Xu–Kahraman μ equals a log-space evaluation of the printed formula",
          "[reference][transmission][friction]") {
  struct Point {
    double p_h_gpa, sr, v_e, nu0_mpas, r, s_um;
  };
  // The paper's mesh (50 mPa·s, 0.8 µm) near its pitch point and at the ends of its path; a thin
  // oil and smooth flanks at high speed; low speed, high slip.
  const Point points[] = {{1.0, 0.3, 2.0, 50, 0.0095, 0.8},
                          {1.4, 1.2, 1.0, 50, 0.005, 0.8},
                          {1.5, 0.5, 10.0, 10, 0.015, 0.3},
                          {0.6, 1.8, 0.5, 100, 0.02, 0.5}};
  double worst = 0;
  for (const Point& p : points) {
    FrictionOptions o;
    o.law = FrictionLaw::kXuKahraman;
    o.max_coefficient = 1.0;  // no cap in play: compare the formula itself
    o.lubricant.dynamic_viscosity = p.nu0_mpas * 1e-3;
    o.lubricant.composite_roughness = p.s_um * 1e-6;
    const double mu =
        SignedFrictionCoefficient(o, FromRegressionVariables(p.p_h_gpa, p.sr, p.v_e, p.r, 0.025));
    const double expected =
        std::exp(XuKahramanLog(p.p_h_gpa, p.sr, p.v_e, p.nu0_mpas, p.r, p.s_um));
    INFO("P_h " << p.p_h_gpa << " SR " << p.sr << " mu " << mu << " expected " << expected);
    // Tolerance: the two arrangements round differently; each of the ~12 elementary functions
    // carries ≤ 1 ulp on terms of size ≤ 10 in ln μ, and F is reconstructed from P_h through a
    // square (≤ 4 ulp): |Δ ln μ| ≤ 20·10·ε ≈ 4e-14. 1e-12 bounds it with margin.
    CHECK(mu == Approx(expected).epsilon(1e-12));
    worst = std::max(worst, std::abs(mu / expected - 1));
    Figure("Xu-Kahraman check point: P_h " + std::to_string(p.p_h_gpa) + " GPa, SR " +
           std::to_string(p.sr) + ", V_e " + std::to_string(p.v_e) + " m/s, nu0 " +
           std::to_string(p.nu0_mpas) + " mPa s, R " + std::to_string(p.r) + " m, S " +
           std::to_string(p.s_um) + " um: mu = " + Sci(mu, 6));
  }
  VerifyRow("Xu-Kahraman mu, 4 check points (paper's lubricant, thin oil, high slip)",
            "same printed formula evaluated in log space (no published check point found)",
            "friction.cpp", Sci(worst, 2) + " relative", "1e-12", worst <= 1e-12);
}

TEST_CASE("Xu–Kahraman's log form matches the printed product to a few ulp",
          "[reference][transmission][friction]") {
  // The implementation sums logarithms (friction.cpp); the reference here is the printed product
  // e^f·P_h^b2·SR^b3·V_e^b6·ν0^b7·R^b8 factor by factor, in long double (64-bit significand, 2^11
  // times finer than double) from the contact's own double inputs, so that what is measured is
  // the rounding of the double evaluation. 6^6 points over the regression's range and beyond.
  const long double b1 = -8.916465L, b2 = 1.03303L, b3 = 1.036077L, b4 = -0.354068L, b5 = 2.812084L,
                    b6 = -0.100601L, b7 = 0.752755L, b8 = -0.390958L, b9 = 0.620305L;
  const double p_gpa[] = {0.2, 0.5, 0.9, 1.3, 1.8, 2.5};
  const double srs[] = {1e-3, 0.02, 0.2, 0.7, 1.4, 2.0};
  const double v_es[] = {0.1, 0.8, 3.0, 7.5, 15.0, 30.0};
  const double nu0s[] = {5, 20, 50, 80, 120, 200};  // [mPa·s]
  const double rs[] = {1e-3, 4e-3, 9.5e-3, 0.015, 0.03, 0.05};
  const double s_ums[] = {0.1, 0.3, 0.5, 0.8, 1.1, 1.5};
  double worst = 0;
  int points = 0;
  for (double nu0 : nu0s)
    for (double s_um : s_ums) {
      FrictionOptions o;
      o.law = FrictionLaw::kXuKahraman;
      o.max_coefficient = 1e3;  // no cap in play
      o.lubricant.dynamic_viscosity = nu0 * 1e-3;
      o.lubricant.composite_roughness = s_um * 1e-6;
      const FrictionModel law(o);
      for (double p : p_gpa)
        for (double sr : srs)
          for (double v_e : v_es)
            for (double r : rs) {
              const FrictionContact c = FromRegressionVariables(p, sr, v_e, r, 0.025);
              const double mu = law.SignedCoefficient(c);
              const long double nu = static_cast<long double>(o.lubricant.dynamic_viscosity) * 1e3L;
              const long double s =
                  static_cast<long double>(o.lubricant.composite_roughness) * 1e6L;
              const long double ph =
                  std::sqrt(
                      static_cast<long double>(c.normal_force) * c.contact_modulus /
                      (3.14159265358979323846264338327950288L * c.face_width * c.reduced_radius)) *
                  1e-9L;
              const long double ua = c.velocity_a, ub = c.velocity_b;
              const long double ve = std::abs((ua + ub) / 2), slip = std::abs(ua - ub) / ve;
              const long double x = slip * ph * std::log10(nu);
              const long double f = b1 + b4 * x + b5 * std::exp(-x) + b9 * std::exp(s);
              const long double expected = std::exp(f) * std::pow(ph, b2) * std::pow(slip, b3) *
                                           std::pow(ve, b6) * std::pow(nu, b7) *
                                           std::pow(static_cast<long double>(c.reduced_radius), b8);
              const double error = static_cast<double>(std::abs(mu / expected - 1));
              worst = std::max(worst, error);
              ++points;
            }
    }
  const double ulps = worst / std::numeric_limits<double>::epsilon();
  INFO("worst relative error " << worst << " = " << ulps << " ulp over " << points << " points");
  // Tolerance: the exponent has 6 terms of size ≲ 7 (b3·ln SR at SR = 1e-3), each with an
  // absolute error of about ε·|term|, plus the rounding of K and of e^(·): the observed worst is
  // 10.6 ulp (mean 1.6; the product of powers in double: 16, mean 3). 12 ulp bounds it and would
  // catch any change in the formula (a constant's last digit moves μ by more than 1e-7).
  CHECK(ulps <= 12);
  VerifyRow(
      "Xu-Kahraman mu in log space, 46656 points (P_h 0.2-2.5 GPa, SR 1e-3-2, V_e 0.1-30 m/s, "
      "nu0 5-200 mPa s, R 1-50 mm, S 0.1-1.5 um)",
      "the printed product, factor by factor in long double", "friction.cpp", Sci(ulps, 2) + " ulp",
      "12 ulp", ulps <= 12);
}

TEST_CASE("Benedict–Kelley μ equals the original formula in US units",
          "[reference][transmission][friction]") {
  // Benedict & Kelley (1961): μ = 0.0127·50/(50 − S)·log10(3.17e8·W/(η·V_s·V_r²)), W [lb/in],
  // η [cP], V [in/s], S [µin]; inputs converted here with 1 lbf = 4.4482216152605 N,
  // 1 in = 0.0254 m.
  FrictionOptions o;
  o.law = FrictionLaw::kBenedictKelley;
  o.max_coefficient = 1.0;
  double worst = 0;
  const double cases[][4] = {// F [N], u_A, u_B [m/s], b [m]
                             {6500, 3.0, 1.2, 0.025},
                             {2000, 8.0, 6.0, 0.025},
                             {12000, 1.5, 0.4, 0.02}};
  for (const auto& k : cases) {
    FrictionContact c;
    c.normal_force = k[0], c.velocity_a = k[1], c.velocity_b = k[2], c.face_width = k[3];
    c.reduced_radius = 0.01, c.contact_modulus = kEStar;
    const double w_lb_in = (k[0] / k[3]) / (4.4482216152605 / 0.0254);
    const double v_s = (k[1] - k[2]) / 0.0254, v_r = (k[1] + k[2]) / 0.0254;
    const double s_uin = o.lubricant.composite_roughness / 0.0254e-6;
    const double eta_cp = o.lubricant.dynamic_viscosity * 1e3;
    const double expected =
        0.0127 * 50 / (50 - s_uin) * std::log10(3.17e8 * w_lb_in / (eta_cp * v_s * v_r * v_r));
    const double mu = SignedFrictionCoefficient(o, c);  // v_s/v_ε ≥ 1100: tanh = 1 exactly
    INFO("mu " << mu << " expected " << expected);
    // Tolerance: unit conversions and one log10, a few ulp of μ ≈ 0.05–0.1.
    CHECK(mu == Approx(expected).epsilon(1e-12));
    worst = std::max(worst, std::abs(mu / expected - 1));
  }
  VerifyRow("Benedict-Kelley mu, 3 loads and speeds, S = 0.8 um, 50 mPa s",
            "the 1961 formula in lb/in, cP, in/s", "friction.cpp (SI)", Sci(worst, 2) + " relative",
            "1e-12", worst <= 1e-12);
}

TEST_CASE("μ along the path of contact of the paper's sun–planet mesh at 1500 rpm",
          "[reference][transmission][friction]") {
  // The shipped stage (docs/geometry.md): m = 4.23 mm, z 16/24, α = 25°, x_s = 0.30,
  // x_p = 0.18512, centre distance a = 86.715 mm, tip radii r + (x + 1) m; E = 207 GPa, ν = 0.3,
  // b = 25 mm. Sun speed 1500 rpm, carrier at ω_s·16/81; rolling velocities relative to the
  // carrier (the contact point moves along the line of action, so u = ω_rel·ρ). Load: 600 N·m on
  // the sun shared by 3 planets, carried by one tooth pair in the single-pair zone and split
  // evenly in the two-pair zones (an illustration, not the model's load sharing).
  const double m = 4.23e-3, alpha = 25 * M_PI / 180, a = 86.715e-3;
  const double r_bs = m * 16 * std::cos(alpha) / 2, r_bp = m * 24 * std::cos(alpha) / 2;
  const double r_as = m * 16 / 2 + 1.30 * m, r_ap = m * 24 / 2 + 1.18512 * m;
  const double alpha_w = std::acos((r_bs + r_bp) / a);
  const double length = a * std::sin(alpha_w);  // T_s T_p
  const double s_start = length - std::sqrt(r_ap * r_ap - r_bp * r_bp);
  const double s_end = std::sqrt(r_as * r_as - r_bs * r_bs);
  const double s_pitch = r_bs * std::tan(alpha_w);
  const double p_b = M_PI * m * std::cos(alpha);
  const double w_s = 1500 * 2 * M_PI / 60, w_rel = w_s * (1 - 16.0 / 81.0);
  const double f_mesh = 600.0 / 3 / r_bs;

  FrictionOptions xk, bk;
  xk.law = FrictionLaw::kXuKahraman;
  bk.law = FrictionLaw::kBenedictKelley;
  Figure("friction path: alpha_w " + Sci(alpha_w * 180 / M_PI, 5) + " deg, contact ratio " +
         Sci((s_end - s_start) / p_b, 5) + ", pitch point at s = " + Sci(s_pitch * 1e3, 5) + " mm");
  const int n = 24;
  int sign_changes = 0;
  double previous = 0, mu_max = 0;
  for (int k = 0; k <= n; ++k) {
    const double s = s_start + (s_end - s_start) * k / n;
    const double rho_s = s, rho_p = length - s;
    FrictionContact c;
    const bool two_pairs = s < s_end - p_b || s > s_start + p_b;
    c.normal_force = two_pairs ? f_mesh / 2 : f_mesh;
    c.velocity_a = w_rel * rho_s;                // sun
    c.velocity_b = w_rel * 16.0 / 24.0 * rho_p;  // planet: ω_p,rel = ω_rel z_s/z_p
    c.reduced_radius = rho_s * rho_p / (rho_s + rho_p);
    c.face_width = 0.025;
    c.contact_modulus = kEStar;
    const double mu_xk = SignedFrictionCoefficient(xk, c);
    const double mu_bk = SignedFrictionCoefficient(bk, c);
    CHECK(std::isfinite(mu_xk));
    CHECK(std::isfinite(mu_bk));
    // Before the pitch point the sun's flank is slower (dedendum of the sun): μ_s < 0.
    CHECK((s - s_pitch) * mu_xk >= 0);
    CHECK((s - s_pitch) * mu_bk >= 0);
    if (k > 0 && previous * mu_xk < 0) ++sign_changes;
    previous = mu_xk;
    mu_max = std::max(mu_max, std::abs(mu_xk));
    Figure("friction path: s " + Sci((s - s_pitch) * 1e3, 4) + " mm from pitch, F " +
           Sci(c.normal_force, 4) + " N, p_h " + Sci(MaxHertzPressure(c) * 1e-9, 4) +
           " GPa, u_sun " + Sci(c.velocity_a, 4) + " m/s, u_planet " + Sci(c.velocity_b, 4) +
           " m/s, mu_xk " + Sci(mu_xk, 4) + ", mu_bk " + Sci(mu_bk, 4));
  }
  CHECK(sign_changes == 1);
  // Xu–Kahraman stays below the cap along the whole path: the values are the formula's own.
  CHECK(mu_max < xk.max_coefficient);
  VerifyRow(
      "friction along the paper's sun-planet path, 1500 rpm, 25 points (xu-kahraman, "
      "benedict-kelley)",
      "sign of v_s: one reversal, at the pitch point",
      std::to_string(sign_changes) + " reversal(s), max |mu_xk| " + Sci(mu_max, 3),
      "sign per point", "exact", sign_changes == 1 && mu_max < xk.max_coefficient);
}
