// Friction laws: names, validation, the pitch point (zero, sign change, continuity), smoothing
// and caps, and finite values where rolling stops or the load vanishes.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "epicycle/transmission/friction.hpp"
#include "thrown_message.hpp"

using namespace epicycle::transmission;
using epicycle::test::ThrownMessage;

namespace {

// A loaded contact of the paper's sun–planet mesh near its pitch point (E = 207 GPa, ν = 0.3,
// b = 25 mm, F ≈ one planet's share of 600 N·m on the sun base circle).
FrictionContact PaperContact(double u_a, double u_b) {
  FrictionContact c;
  c.normal_force = 6500;
  c.velocity_a = u_a;
  c.velocity_b = u_b;
  c.reduced_radius = 0.0095;
  c.face_width = 0.025;
  c.contact_modulus = 207e9 / (2 * (1 - 0.3 * 0.3));
  return c;
}

FrictionOptions Law(FrictionLaw law) {
  FrictionOptions o;
  o.law = law;
  return o;
}

const FrictionLaw kOnLaws[] = {FrictionLaw::kConstant, FrictionLaw::kXuKahraman,
                               FrictionLaw::kBenedictKelley};

}  // namespace

TEST_CASE("friction law names round-trip, an unknown name lists the allowed ones",
          "[unit][transmission][friction]") {
  for (FrictionLaw law : {FrictionLaw::kOff, FrictionLaw::kConstant, FrictionLaw::kXuKahraman,
                          FrictionLaw::kBenedictKelley})
    CHECK(FrictionLawFromName(FrictionLawName(law)) == law);
  CHECK(FrictionLawName(FrictionLaw::kXuKahraman) == "xu-kahraman");
  CHECK(FrictionLawName(FrictionLaw::kBenedictKelley) == "benedict-kelley");
  const std::string msg = ThrownMessage([] { FrictionLawFromName("coulomb"); });
  CHECK(msg.find("coulomb") != std::string::npos);
  CHECK(msg.find("off, constant, xu-kahraman, benedict-kelley") != std::string::npos);
}

TEST_CASE("bad friction options and contacts are named with value and rule",
          "[unit][transmission][friction]") {
  CHECK_NOTHROW(FrictionOptions{}.Validate());
  struct Case {
    const char* field;
    void (*spoil)(FrictionOptions&);
  };
  const Case cases[] = {
      {"friction.coefficient", [](FrictionOptions& o) { o.coefficient = -0.1; }},
      {"friction.coefficient", [](FrictionOptions& o) { o.coefficient = 1.5; }},  // > 1
      {"friction.smoothing_velocity", [](FrictionOptions& o) { o.smoothing_velocity = 0; }},
      {"friction.max_coefficient",
       [](FrictionOptions& o) { o.max_coefficient = std::numeric_limits<double>::infinity(); }},
      {"friction.lubricant.dynamic_viscosity",
       [](FrictionOptions& o) { o.lubricant.dynamic_viscosity = 0; }},
      {"friction.lubricant.composite_roughness",
       [](FrictionOptions& o) { o.lubricant.composite_roughness = -1e-6; }},
      {"friction.lubricant.composite_roughness", [](FrictionOptions& o) {
         o.law = FrictionLaw::kBenedictKelley;
         o.lubricant.composite_roughness = 1.3e-6;  // ≥ 50 µin
       }}};
  for (const Case& c : cases) {
    FrictionOptions o;
    c.spoil(o);
    const std::string msg = ThrownMessage([&] { o.Validate(); });
    INFO(msg);
    CHECK(msg.find(c.field) != std::string::npos);
    CHECK(msg.find("must be") != std::string::npos);
  }
  FrictionContact bad = PaperContact(2, 1);
  bad.reduced_radius = 0;
  const std::string msg = ThrownMessage([&] { SignedFrictionCoefficient(FrictionOptions{}, bad); });
  CHECK(msg.find("contact.reduced_radius = 0") != std::string::npos);
  bad = PaperContact(2, 1);
  bad.normal_force = -1;
  CHECK(ThrownMessage([&] { MaxHertzPressure(bad); }).find("contact.normal_force") !=
        std::string::npos);
}

TEST_CASE("Hertz pressure equals 2F/(π a b) with the half-width a = √(4FR/(π b E*))",
          "[unit][transmission][friction]") {
  // Johnson, Contact Mechanics §4.2, written the other way round: through the half-width.
  const FrictionContact c = PaperContact(2, 1);
  const double a =
      std::sqrt(4 * c.normal_force * c.reduced_radius / (M_PI * c.face_width * c.contact_modulus));
  const double expected = 2 * c.normal_force / (M_PI * a * c.face_width);
  CHECK(MaxHertzPressure(c) == Approx(expected).epsilon(1e-14));
  FrictionContact unloaded = c;
  unloaded.normal_force = 0;
  CHECK(MaxHertzPressure(unloaded) == 0.0);
}

TEST_CASE("off returns 0, every law is 0 at the pitch point and changes sign across it",
          "[unit][transmission][friction]") {
  CHECK(SignedFrictionCoefficient(Law(FrictionLaw::kOff), PaperContact(3, 1)) == 0.0);
  for (FrictionLaw law : kOnLaws) {
    INFO(FrictionLawName(law));
    const FrictionOptions o = Law(law);
    CHECK(SignedFrictionCoefficient(o, PaperContact(2, 2)) == 0.0);
    // Across the pitch point v_s = u_A − u_B changes sign; μ_s follows it, and so do the
    // friction moments about both gear centres (M_A = −μ_s F ρ_A, M_B = +μ_s F ρ_B by the power
    // balance M ω = force · surface velocity, ρ > 0 on both sides of the pitch point).
    const double before = SignedFrictionCoefficient(o, PaperContact(2.0 - 0.05, 2.0 + 0.05));
    const double after = SignedFrictionCoefficient(o, PaperContact(2.0 + 0.05, 2.0 - 0.05));
    CHECK(before < 0);
    CHECK(after > 0);
    const double f = 6500, rho_a = 0.02, rho_b = 0.03;
    CHECK((-before * f * rho_a) * (-after * f * rho_a) < 0);
    CHECK((before * f * rho_b) * (after * f * rho_b) < 0);
  }
}

TEST_CASE("Xu–Kahraman is continuous through the pitch point: |μ| ∝ |v_s|^b3 as v_s → 0",
          "[unit][transmission][friction]") {
  // Close to the pitch point SR·P_h·log10 ν0 → 0, so f → b1 + b5 + b9 e^S and μ ∝ SR^b3 with
  // b3 = 1.036077: halving v_s divides μ by 2^b3 up to the O(SR) change of f. At v_s = 1e-6 m/s
  // (SR ≈ 1e-6) that change is |b4 − b5|·ΔSR·P_h·log10 ν0 ≈ 3.2·5e-7·1.0·1.7 ≈ 3e-6 relative
  // (P_h ≈ 1.0 GPa here).
  const FrictionOptions o = Law(FrictionLaw::kXuKahraman);
  for (double sign : {1.0, -1.0}) {
    const double dv = sign * 1e-6;
    const double mu1 = SignedFrictionCoefficient(o, PaperContact(2 + dv, 2 - dv));
    const double mu2 = SignedFrictionCoefficient(o, PaperContact(2 + dv / 2, 2 - dv / 2));
    CHECK(mu1 / mu2 == Approx(std::pow(2.0, 1.036077)).epsilon(1e-5));
    CHECK(std::abs(mu1) < 1e-6);  // → 0 (μ ≈ 1e-7 at SR = 1e-6): no jump at the pitch point
  }
}

TEST_CASE("constant and Benedict–Kelley laws are smoothed by tanh(v_s/v_ε) and capped",
          "[unit][transmission][friction]") {
  FrictionOptions c = Law(FrictionLaw::kConstant);
  c.coefficient = 0.08;
  // Far from the pitch point the constant law is μ; at v_s = v_ε it is μ tanh 1.
  CHECK(SignedFrictionCoefficient(c, PaperContact(3, 1)) == Approx(0.08).epsilon(1e-12));
  CHECK(SignedFrictionCoefficient(c, PaperContact(2 + 0.5e-3, 2 - 0.5e-3)) ==
        Approx(0.08 * std::tanh(1.0)).epsilon(1e-12));
  // The lubricated laws' cap does not bound the constant law: dry flanks (μ = 0.4) keep their μ.
  c.coefficient = 0.4;
  CHECK(SignedFrictionCoefficient(c, PaperContact(3, 1)) == Approx(0.4).epsilon(1e-12));

  FrictionOptions bk = Law(FrictionLaw::kBenedictKelley);
  // Near the pitch point B&K's logarithm diverges: the coefficient is the cap times the smoothed
  // sign, never above the cap, and finite.
  for (double dv : {1e-9, 1e-6, 1e-4, 1e-3, 1e-2}) {
    const FrictionContact near_pitch = PaperContact(2 + dv / 2, 2 - dv / 2);
    const double v_s = near_pitch.velocity_a - near_pitch.velocity_b;  // dv, up to rounding
    const double mu = SignedFrictionCoefficient(bk, near_pitch);
    INFO("v_s = " << v_s);
    CHECK(std::isfinite(mu));
    CHECK(mu > 0);
    CHECK(mu <= bk.max_coefficient * std::tanh(v_s / bk.smoothing_velocity));
  }
  // Light load at high speed: the logarithm's argument drops below 1, μ is clamped at 0.
  FrictionContact light = PaperContact(40, 10);
  light.normal_force = 1e-3;
  CHECK(SignedFrictionCoefficient(bk, light) == 0.0);
  // A cap lower than the XK value caps it too.
  FrictionOptions xk = Law(FrictionLaw::kXuKahraman);
  xk.max_coefficient = 1e-3;
  CHECK(SignedFrictionCoefficient(xk, PaperContact(3, 1)) == 1e-3);
  CHECK(SignedFrictionCoefficient(xk, PaperContact(1, 3)) == -1e-3);
}

TEST_CASE("no NaN when rolling stops or the load vanishes", "[unit][transmission][friction]") {
  const double velocities[][2] = {{0, 0}, {1e-12, -1e-12}, {1, -1}, {-2, -1}, {0.5, 0}};
  for (FrictionLaw law : kOnLaws) {
    const FrictionOptions o = Law(law);
    for (const auto& v : velocities) {
      INFO(FrictionLawName(law) << " u_A = " << v[0] << " u_B = " << v[1]);
      const FrictionContact c = PaperContact(v[0], v[1]);
      const double mu = SignedFrictionCoefficient(o, c);
      CHECK(std::isfinite(mu));
      CHECK(std::abs(mu) <= o.max_coefficient);
      if (v[0] == v[1]) CHECK(mu == 0.0);
      if (v[0] != v[1]) CHECK(mu * (v[0] - v[1]) >= 0);  // the sign of the sliding velocity
      FrictionContact unloaded = c;
      unloaded.normal_force = 0;
      const double mu0 = SignedFrictionCoefficient(o, unloaded);
      CHECK(std::isfinite(mu0));
      if (law != FrictionLaw::kConstant) CHECK(mu0 == 0.0);
    }
  }
}
