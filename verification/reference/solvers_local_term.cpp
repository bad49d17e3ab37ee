// The closed-form local term (docs/model.md §4) against the elastic half-plane it stands for:
// the approach between the surface and depth h on the load axis under a Hertzian pressure,
// obtained here by superposing Flamant line loads (double numerical quadrature), and against
// Weber's asymptote, finite differences and quadrature of its own value.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "epicycle/solvers/local_term.hpp"
#include "solvers_quadrature.hpp"

namespace epicycle::solvers {
namespace {

constexpr double kPi = 3.14159265358979323846;

LocalTermParameters Steel(PlaneAssumption plane, double h1, double h2) {
  LocalTermParameters p;
  p.face_width = 0.025;
  p.reduced_radius = 0.010;
  p.plane = plane;
  p.body[0] = {207e9, 0.3, h1};
  p.body[1] = {207e9, 0.3, h2};
  return p;
}

// Approach of one body between its surface and depth h under the Hertzian pressure of total force
// F on face width b with half-width a: ∫_0^h −ε_zz(0, z) dz, stresses by Flamant superposition:
//   σ_z(0,z) = −(2/π) ∫ p(s) z³/(s²+z²)² ds,  σ_x(0,z) = −(2/π) ∫ p(s) z s²/(s²+z²)² ds,
//   p(s) = p0 √(1 − s²/a²), p0 = 2F/(π a b); s = a sin θ removes the square-root end points.
double HalfPlaneApproach(double force, double b, double a, double e, double nu, double h,
                         PlaneAssumption plane) {
  const double p0 = 2.0 * force / (kPi * a * b);
  auto stresses = [&](double z, double* sz, double* sx) {
    // The kernel concentrates in |s| ≲ z: split the θ range there.
    const double th = std::asin(std::min(1.0, 4.0 * z / a));
    auto fz = [&](double t) {
      const double s = a * std::sin(t), ct = std::cos(t);
      const double d = s * s + z * z;
      return p0 * ct * a * ct * z * z * z / (d * d);
    };
    auto fx = [&](double t) {
      const double s = a * std::sin(t), ct = std::cos(t);
      const double d = s * s + z * z;
      return p0 * ct * a * ct * z * s * s / (d * d);
    };
    const double tol = 1e-15 * p0;
    // Both integrands are even in θ.
    *sz =
        -(4.0 / kPi) * (test::Integrate(fz, 0.0, th, tol) + test::Integrate(fz, th, kPi / 2, tol));
    *sx =
        -(4.0 / kPi) * (test::Integrate(fx, 0.0, th, tol) + test::Integrate(fx, th, kPi / 2, tol));
  };
  auto minus_strain = [&](double z) {
    if (z <= 0.0) z = 1e-300;
    double sz = 0, sx = 0;
    stresses(z, &sz, &sx);
    if (plane == PlaneAssumption::kPlaneStrain)
      return -((1.0 - nu * nu) * sz - nu * (1.0 + nu) * sx) / e;
    return -(sz - nu * sx) / e;
  };
  const double scale = force / (e * b);
  // Integrate in t with z = a·sinh(t): the 1/z tail becomes smooth.
  auto integrand = [&](double t) { return minus_strain(a * std::sinh(t)) * a * std::cosh(t); };
  return test::Integrate(integrand, 0.0, std::asinh(h / a), 1e-12 * scale);
}

}  // namespace

TEST_CASE("local term equals the half-plane (Flamant) integration", "[reference][solvers]") {
  for (PlaneAssumption plane : {PlaneAssumption::kPlaneStrain, PlaneAssumption::kPlaneStress}) {
    // h/L from ~0.5 (load so high that L passes h) to ~200.
    for (double force : {50.0, 1e3, 2e4, 3e5, 3e6}) {
      LocalTermParameters p = Steel(plane, 1.5e-3, 2.5e-3);
      p.body[1].youngs_modulus = 110e9;  // unlike bodies: each keeps its own E, ν, h
      p.body[1].poisson_ratio = 0.34;
      const double a = HertzHalfWidth(p, force);
      double reference = 0.0;
      for (int b = 0; b < 2; ++b)
        reference += HalfPlaneApproach(force, p.face_width, a, p.body[b].youngs_modulus,
                                       p.body[b].poisson_ratio, p.body[b].depth, plane);
      const double closed = LocalApproach(p, force);
      INFO("plane " << static_cast<int>(plane) << " F = " << force << " h/L = "
                    << p.body[0].depth / a << " closed " << closed << " half-plane " << reference);
      CHECK(std::abs(closed - reference) <= 1e-6 * std::abs(reference));
    }
  }
}

TEST_CASE("local term tends to Weber's ln(2h/L) - nu/(2(1-nu)) for h >> L",
          "[reference][solvers]") {
  LocalTermParameters p = Steel(PlaneAssumption::kPlaneStrain, 2e-3, 2e-3);
  for (double ratio : {1e2, 1e3, 1e4}) {
    // Choose F so that h/L = ratio.
    const double l = 2e-3 / ratio;
    const double force =
        l * l / (4.0 * p.reduced_radius / (kPi * p.face_width * EffectiveModulus(p)));
    const double k = (1.0 - 0.09) / 207e9;
    const double weber =
        2.0 * 2.0 * k * force / (kPi * p.face_width) * (std::log(2.0 * ratio) - 0.3 / (2.0 * 0.7));
    // Next term of the expansion: asinh(s) = ln 2s + 1/(4s²) + …, c/(1+w) = c/2 − c/(8s²) + …
    // so the relative difference is O(1/s²)/ln(2s).
    const double bound = 1.0 / (ratio * ratio);
    INFO("h/L = " << ratio);
    CHECK(std::abs(LocalApproach(p, force) - weber) <= bound * std::abs(weber));
  }
}

TEST_CASE("local term derivative and integral against differences and quadrature",
          "[unit][solvers]") {
  for (PlaneAssumption plane : {PlaneAssumption::kPlaneStrain, PlaneAssumption::kPlaneStress}) {
    const LocalTermParameters p = Steel(plane, 1e-3, 3e-3);
    for (double force : {1e-3, 1.0, 1e3, 1e5, 1e7}) {
      // Five-point stencil: truncation O(δ⁴) ≈ 1e-12, round-off ≈ eps/δ ≈ 1e-13 relative.
      const double d = 1e-3 * force;
      const double fd = (-LocalApproach(p, force + 2 * d) + 8 * LocalApproach(p, force + d) -
                         8 * LocalApproach(p, force - d) + LocalApproach(p, force - 2 * d)) /
                        (12 * d);
      const double du = LocalApproachDerivative(p, force);
      INFO("F = " << force);
      CHECK(std::abs(fd - du) <= 1e-9 * std::abs(du));
      const double quad = test::Integrate([&](double f) { return LocalApproach(p, f); }, 0.0, force,
                                          1e-15 * force * LocalApproach(p, force));
      const double big_u = LocalApproachIntegral(p, force);
      CHECK(std::abs(quad - big_u) <= 1e-12 * std::abs(big_u));
    }
    CHECK(std::isinf(LocalApproachDerivative(p, 0.0)));
    CHECK(LocalApproach(p, 0.0) == 0.0);
    CHECK(LocalApproachIntegral(p, 0.0) == 0.0);
  }
}

TEST_CASE("corrected local term stays monotone, validity limit is L = h", "[unit][solvers]") {
  for (double nu : {0.0, 0.3, 0.45, 0.499}) {
    LocalTermParameters p = Steel(PlaneAssumption::kPlaneStrain, 1e-3, 2e-3);
    p.body[0].poisson_ratio = p.body[1].poisson_ratio = nu;
    CHECK(std::isinf(NonMonotoneForce(p)));
    const double f_ref = ValidityLimitForce(p);
    CHECK(std::abs(HertzHalfWidth(p, f_ref) - 1e-3) <= 1e-12);
    for (int k = -120; k <= 120; ++k) {
      const double f = f_ref * std::pow(10.0, k / 10.0);
      INFO("nu = " << nu << " F = " << f);
      REQUIRE(LocalApproachDerivative(p, f) > 0.0);
    }
  }
}

TEST_CASE("local term parameters are validated with named fields", "[unit][solvers]") {
  LocalTermParameters p = Steel(PlaneAssumption::kPlaneStrain, 1e-3, 1e-3);
  p.face_width = -0.025;
  CHECK_THROWS_WITH(ValidateLocalTerm(p, "local[2]"),
                    Catch::Contains("local[2].face_width = -0.025") && Catch::Contains("> 0"));
  p = Steel(PlaneAssumption::kPlaneStrain, 1e-3, 1e-3);
  p.body[1].poisson_ratio = 0.5;
  CHECK_THROWS_WITH(
      ValidateLocalTerm(p, "local[0]"),
      Catch::Contains("local[0].body[1].poisson_ratio = 0.5") && Catch::Contains("0 <= nu < 0.5"));
  p = Steel(PlaneAssumption::kPlaneStrain, 1e-3, 1e-3);
  p.body[0].depth = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(ValidateLocalTerm(p, "local[1]"), Catch::Contains("local[1].body[0].depth"));
}

}  // namespace epicycle::solvers
