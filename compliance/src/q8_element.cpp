#include "epicycle/compliance/q8_element.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include <Eigen/LU>

namespace epicycle::compliance {

Eigen::Matrix<double, kQ8Nodes, 1> Q8ShapeFunctions(double xi, double eta) {
  Eigen::Matrix<double, kQ8Nodes, 1> n;
  for (int a = 0; a < 4; ++a) {
    const double xa = kQ8NodeXiEta[a][0];
    const double ea = kQ8NodeXiEta[a][1];
    n(a) = 0.25 * (1.0 + xi * xa) * (1.0 + eta * ea) * (xi * xa + eta * ea - 1.0);
  }
  n(4) = 0.5 * (1.0 - xi * xi) * (1.0 - eta);
  n(5) = 0.5 * (1.0 + xi) * (1.0 - eta * eta);
  n(6) = 0.5 * (1.0 - xi * xi) * (1.0 + eta);
  n(7) = 0.5 * (1.0 - xi) * (1.0 - eta * eta);
  return n;
}

Eigen::Matrix<double, 2, kQ8Nodes> Q8ShapeDerivatives(double xi, double eta) {
  Eigen::Matrix<double, 2, kQ8Nodes> dn;
  for (int a = 0; a < 4; ++a) {
    const double xa = kQ8NodeXiEta[a][0];
    const double ea = kQ8NodeXiEta[a][1];
    dn(0, a) = 0.25 * xa * (1.0 + eta * ea) * (2.0 * xi * xa + eta * ea);
    dn(1, a) = 0.25 * ea * (1.0 + xi * xa) * (xi * xa + 2.0 * eta * ea);
  }
  dn(0, 4) = -xi * (1.0 - eta);
  dn(1, 4) = -0.5 * (1.0 - xi * xi);
  dn(0, 5) = 0.5 * (1.0 - eta * eta);
  dn(1, 5) = -eta * (1.0 + xi);
  dn(0, 6) = -xi * (1.0 + eta);
  dn(1, 6) = 0.5 * (1.0 - xi * xi);
  dn(0, 7) = -0.5 * (1.0 - eta * eta);
  dn(1, 7) = -eta * (1.0 - xi);
  return dn;
}

Eigen::Vector3d EdgeShapeFunctions(double xi) {
  return {0.5 * xi * (xi - 1.0), 1.0 - xi * xi, 0.5 * xi * (xi + 1.0)};
}

Eigen::Vector3d EdgeShapeDerivatives(double xi) { return {xi - 0.5, -2.0 * xi, xi + 0.5}; }

GaussRule GaussLegendre(int n) {
  GaussRule rule;
  rule.size = n;
  switch (n) {
    case 1:
      rule.points = {0.0};
      rule.weights = {2.0};
      break;
    case 2: {
      const double p = 1.0 / std::sqrt(3.0);
      rule.points = {-p, p};
      rule.weights = {1.0, 1.0};
      break;
    }
    case 3: {
      const double p = std::sqrt(0.6);
      rule.points = {-p, 0.0, p};
      rule.weights = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
      break;
    }
    case 4: {
      const double a = std::sqrt(3.0 / 7.0 - 2.0 / 7.0 * std::sqrt(6.0 / 5.0));
      const double b = std::sqrt(3.0 / 7.0 + 2.0 / 7.0 * std::sqrt(6.0 / 5.0));
      const double wa = (18.0 + std::sqrt(30.0)) / 36.0;
      const double wb = (18.0 - std::sqrt(30.0)) / 36.0;
      rule.points = {-b, -a, a, b};
      rule.weights = {wb, wa, wa, wb};
      break;
    }
    case 5: {
      const double a = std::sqrt(5.0 - 2.0 * std::sqrt(10.0 / 7.0)) / 3.0;
      const double b = std::sqrt(5.0 + 2.0 * std::sqrt(10.0 / 7.0)) / 3.0;
      const double wa = (322.0 + 13.0 * std::sqrt(70.0)) / 900.0;
      const double wb = (322.0 - 13.0 * std::sqrt(70.0)) / 900.0;
      rule.points = {-b, -a, 0.0, a, b};
      rule.weights = {wb, wa, 128.0 / 225.0, wa, wb};
      break;
    }
    default: {
      std::ostringstream msg;
      msg << "GaussLegendre: number of points n = " << n << " must be 1..5";
      throw std::invalid_argument(msg.str());
    }
  }
  return rule;
}

Eigen::Vector2d Q8Position(const Q8Coordinates& x, double xi, double eta) {
  return x * Q8ShapeFunctions(xi, eta);
}

void CheckQ8Jacobian(const Q8Coordinates& x, int element_index) {
  const Eigen::Vector2d lo = x.leftCols<4>().rowwise().minCoeff();
  const Eigen::Vector2d hi = x.leftCols<4>().rowwise().maxCoeff();
  const double size = (hi - lo).norm();
  const double tolerance = kRelativeJacobianTolerance * size * size;
  const GaussRule g = GaussLegendre(kQ8GaussPointsPerDirection);
  auto check = [&](double xi, double eta, const char* where) {
    const Eigen::Matrix2d j = Q8ShapeDerivatives(xi, eta) * x.transpose();  // rows: ∂/∂ξ, ∂/∂η
    const double det = j.determinant();
    if (std::isfinite(det) && det > tolerance) return;
    const Eigen::Vector2d p = Q8Position(x, xi, eta);
    std::ostringstream msg;
    msg.precision(6);
    msg << "element " << element_index << ": Jacobian determinant det J = " << det << " m^2 at "
        << where << " (xi, eta) = (" << xi << ", " << eta << "), position (" << p.x() << ", "
        << p.y() << ") m; the rule is det J > " << tolerance << " m^2 ("
        << kRelativeJacobianTolerance << " x element size^2) everywhere: the element is "
        << (det < 0.0 ? "inverted (nodes clockwise, or a mid-side node pulled past the middle half "
                        "of its side)"
                      : "degenerate (collapsed side or corner)");
    throw std::invalid_argument(msg.str());
  };
  if (!(size > 0.0) || !std::isfinite(size)) {
    std::ostringstream msg;
    msg << "element " << element_index << ": corner nodes coincide or are not finite (size " << size
        << " m); the element is degenerate";
    throw std::invalid_argument(msg.str());
  }
  for (int a = 0; a < 4; ++a) check(kQ8NodeXiEta[a][0], kQ8NodeXiEta[a][1], "corner");
  for (int i = 0; i < g.size; ++i) {
    for (int k = 0; k < g.size; ++k) check(g.points[i], g.points[k], "Gauss point");
  }
}

Eigen::Matrix<double, 3, 2 * kQ8Nodes> Q8StrainDisplacement(const Q8Coordinates& x, double xi,
                                                            double eta, double* det_j) {
  const Eigen::Matrix<double, 2, kQ8Nodes> dn = Q8ShapeDerivatives(xi, eta);
  const Eigen::Matrix2d j = dn * x.transpose();  // J(r, c) = ∂x_c/∂ξ_r
  const double det = j.determinant();
  if (det_j != nullptr) *det_j = det;
  const Eigen::Matrix<double, 2, kQ8Nodes> dx = j.inverse() * dn;  // rows ∂N/∂x, ∂N/∂y
  Eigen::Matrix<double, 3, 2 * kQ8Nodes> b = Eigen::Matrix<double, 3, 2 * kQ8Nodes>::Zero();
  for (int a = 0; a < kQ8Nodes; ++a) {
    b(0, 2 * a) = dx(0, a);
    b(1, 2 * a + 1) = dx(1, a);
    b(2, 2 * a) = dx(1, a);
    b(2, 2 * a + 1) = dx(0, a);
  }
  return b;
}

Q8Stiffness Q8ElementStiffness(const Q8Coordinates& x, const Eigen::Matrix3d& d, double thickness) {
  const GaussRule g = GaussLegendre(kQ8GaussPointsPerDirection);
  Q8Stiffness k = Q8Stiffness::Zero();
  for (int i = 0; i < g.size; ++i) {
    for (int m = 0; m < g.size; ++m) {
      double det = 0.0;
      const auto b = Q8StrainDisplacement(x, g.points[i], g.points[m], &det);
      k.noalias() += (g.weights[i] * g.weights[m] * det * thickness) * (b.transpose() * d * b);
    }
  }
  return k;
}

}  // namespace epicycle::compliance
