// Q8 element: shape functions, quadrature, stiffness, Jacobian checks, material input.
#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>

#include <Eigen/Eigenvalues>

#include "epicycle/compliance/q8_element.hpp"

using namespace epicycle::compliance;
using Catch::Matchers::Contains;

TEST_CASE("Q8 shape functions: Kronecker property and partition of unity", "[unit]") {
  for (int b = 0; b < kQ8Nodes; ++b) {
    const auto n = Q8ShapeFunctions(kQ8NodeXiEta[b][0], kQ8NodeXiEta[b][1]);
    for (int a = 0; a < kQ8Nodes; ++a) CHECK(n(a) == Approx(a == b ? 1.0 : 0.0).margin(1e-15));
  }
  for (double xi : {-0.7, 0.1, 0.93}) {
    for (double eta : {-0.4, 0.55}) {
      CHECK(Q8ShapeFunctions(xi, eta).sum() == Approx(1.0).margin(1e-15));
      // Derivatives against central differences: truncation h² × (third derivative ≤ 1.5).
      const double h = 1e-5;
      const auto dn = Q8ShapeDerivatives(xi, eta);
      const Eigen::Matrix<double, 8, 1> fx =
          (Q8ShapeFunctions(xi + h, eta) - Q8ShapeFunctions(xi - h, eta)) / (2 * h);
      const Eigen::Matrix<double, 8, 1> fy =
          (Q8ShapeFunctions(xi, eta + h) - Q8ShapeFunctions(xi, eta - h)) / (2 * h);
      CHECK((dn.row(0).transpose() - fx).cwiseAbs().maxCoeff() < 1e-9);
      CHECK((dn.row(1).transpose() - fy).cwiseAbs().maxCoeff() < 1e-9);
      CHECK(dn.rowwise().sum().cwiseAbs().maxCoeff() < 1e-15);
    }
  }
}

TEST_CASE("Gauss-Legendre rules integrate polynomials of degree 2n-1 exactly", "[unit]") {
  for (int n = 1; n <= 5; ++n) {
    const GaussRule g = GaussLegendre(n);
    for (int degree = 0; degree <= 2 * n - 1; ++degree) {
      double sum = 0.0;
      for (int i = 0; i < g.size; ++i) sum += g.weights[i] * std::pow(g.points[i], degree);
      const double exact = degree % 2 == 1 ? 0.0 : 2.0 / (degree + 1);
      CHECK(sum == Approx(exact).margin(1e-15));
    }
  }
  CHECK_THROWS_WITH(GaussLegendre(6), Contains("n = 6") && Contains("1..5"));
}

TEST_CASE("Q8 stiffness: symmetric, three rigid-body modes, area and energy", "[unit]") {
  ElasticMaterial mat{210e9, 0.3, 0.025, PlaneAssumption::kPlaneStress};
  // A distorted element with one curved side.
  Q8Coordinates x;
  x << 0.0, 2.0, 2.2, -0.1, 1.0, 2.15, 1.0, -0.02,  //
      0.0, 0.1, 1.5, 1.0, -0.1, 0.8, 1.3, 0.5;
  x *= 0.01;
  const Q8Stiffness k = Q8ElementStiffness(x, mat.ElasticityMatrix(), mat.thickness);
  CHECK((k - k.transpose()).norm() <= 1e-14 * k.norm());
  Eigen::SelfAdjointEigenSolver<Q8Stiffness> eig(k);
  const auto ev = eig.eigenvalues();
  // Three zero eigenvalues (rigid motions) at round-off, the fourth clearly positive: full 3×3
  // integration leaves no spurious mode.
  CHECK(std::abs(ev(2)) < 1e-12 * ev(15));
  CHECK(ev(3) > 1e-3 * ev(15));
  // Rigid rotation gives no force.
  Eigen::Matrix<double, 16, 1> rot;
  for (int a = 0; a < 8; ++a) {
    rot(2 * a) = -x(1, a);
    rot(2 * a + 1) = x(0, a);
  }
  CHECK((k * rot).norm() <= 1e-12 * k.norm() * rot.norm());
  // Uniform strain εxx = e on a unit-thickness rectangle: energy ½ b A σ·ε with σ = D ε.
  Q8Coordinates r;
  r << 0, 3, 3, 0, 1.5, 3, 1.5, 0,  //
      0, 0, 2, 2, 0, 1, 2, 1;
  Eigen::Matrix<double, 16, 1> ux = Eigen::Matrix<double, 16, 1>::Zero();
  for (int a = 0; a < 8; ++a) ux(2 * a) = 1e-3 * r(0, a);
  const Q8Stiffness kr = Q8ElementStiffness(r, mat.ElasticityMatrix(), 1.0);
  const double energy = 0.5 * ux.dot(kr * ux);
  const double exact = 0.5 * 6.0 * mat.ElasticityMatrix()(0, 0) * 1e-6;
  CHECK(energy == Approx(exact).epsilon(1e-13));
}

TEST_CASE("Q8 Jacobian check names the inverted or degenerate element", "[unit]") {
  Q8Coordinates good;
  good << 0, 1, 1, 0, 0.5, 1, 0.5, 0,  //
      0, 0, 1, 1, 0, 0.5, 1, 0.5;
  CHECK_NOTHROW(CheckQ8Jacobian(good, 0));
  Q8Coordinates clockwise = good;
  clockwise.row(1) = -good.row(1);  // mirror: nodes now clockwise
  CHECK_THROWS_WITH(CheckQ8Jacobian(clockwise, 17),
                    Contains("element 17") && Contains("det J = -") && Contains("inverted"));
  Q8Coordinates collapsed = good;  // corner 2 onto corner 3: a triangle, det J = 0 at the corner
  collapsed.col(2) = collapsed.col(3);
  collapsed.col(6) = collapsed.col(3);
  collapsed.col(5) = 0.5 * (collapsed.col(1) + collapsed.col(2));
  CHECK_THROWS_WITH(CheckQ8Jacobian(collapsed, 4),
                    Contains("element 4") && Contains("degenerate") && Contains("det J"));
  Q8Coordinates pulled = good;  // mid-side node past the quarter point folds the map
  pulled.col(4) << 0.9, 0.0;
  CHECK_THROWS_WITH(CheckQ8Jacobian(pulled, 2), Contains("element 2") && Contains("det J"));
}

TEST_CASE("Elastic material: matrices and clear messages for bad input", "[unit]") {
  ElasticMaterial m{200e9, 0.25, 0.01, PlaneAssumption::kPlaneStrain};
  CHECK_NOTHROW(m.Validate());
  // Plane strain D equals the plane-stress D of E' = E/(1−ν²), ν' = ν/(1−ν).
  ElasticMaterial equivalent{m.EffectiveModulus(), m.EffectivePoissonRatio(), 0.01,
                             PlaneAssumption::kPlaneStress};
  CHECK((m.ElasticityMatrix() - equivalent.ElasticityMatrix()).norm() <=
        1e-15 * m.ElasticityMatrix().norm());
  // D ε for a uniaxial plane-stress state σ = (σ, 0, 0): ε = (σ/E, −νσ/E, 0).
  ElasticMaterial s{200e9, 0.25, 0.01, PlaneAssumption::kPlaneStress};
  const Eigen::Vector3d sig = s.ElasticityMatrix() * Eigen::Vector3d(1e-3, -0.25e-3, 0.0);
  CHECK(sig(0) == Approx(200e6).epsilon(1e-14));
  CHECK(std::abs(sig(1)) < 1e-6);

  ElasticMaterial bad = m;
  bad.youngs_modulus = -1.0;
  CHECK_THROWS_WITH(bad.Validate(),
                    Contains("youngs_modulus") && Contains("-1") && Contains("> 0"));
  bad = m;
  bad.youngs_modulus = 0.0;
  CHECK_THROWS_AS(bad.Validate(), std::invalid_argument);
  bad = m;
  bad.poisson_ratio = 0.5;
  CHECK_THROWS_WITH(bad.Validate(),
                    Contains("poisson_ratio") && Contains("0.5") && Contains("[0, 0.5)"));
  bad = m;
  bad.poisson_ratio = -0.1;
  CHECK_THROWS_WITH(bad.Validate(), Contains("poisson_ratio") && Contains("-0.1"));
  bad = m;
  bad.thickness = 0.0;
  CHECK_THROWS_WITH(bad.Validate(), Contains("thickness") && Contains("> 0"));
  bad = m;
  bad.thickness = std::nan("");
  CHECK_THROWS_WITH(bad.Validate(), Contains("thickness") && Contains("finite"));
}
