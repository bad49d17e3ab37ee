// The 8-node serendipity quadrilateral (Q8) of 2D linear elasticity: shape functions, 3×3 Gauss
// quadrature, isoparametric mapping with Jacobian checks, element stiffness, stress recovery.
#pragma once

#include <array>

#include <Eigen/Core>

#include "epicycle/compliance/material.hpp"

namespace epicycle::compliance {

/// Number of nodes of a Q8 element.
inline constexpr int kQ8Nodes = 8;

/// Node positions [m] of one element, column a = node a.
using Q8Coordinates = Eigen::Matrix<double, 2, kQ8Nodes>;
/// Element stiffness [N/m], DOF order (u_x0, u_y0, u_x1, u_y1, ...).
using Q8Stiffness = Eigen::Matrix<double, 2 * kQ8Nodes, 2 * kQ8Nodes>;

/// Reference coordinates (ξ, η) of the Q8 nodes, in this local order:
///
///     3 --- 6 --- 2        corners 0..3 counter-clockwise at (∓1, ∓1),
///     |           |        mid-side nodes 4 (side 0–1), 5 (1–2), 6 (2–3), 7 (3–0).
///     7           5
///     |           |
///     0 --- 4 --- 1
inline constexpr std::array<std::array<double, 2>, kQ8Nodes> kQ8NodeXiEta = {{{-1.0, -1.0},
                                                                              {1.0, -1.0},
                                                                              {1.0, 1.0},
                                                                              {-1.0, 1.0},
                                                                              {0.0, -1.0},
                                                                              {1.0, 0.0},
                                                                              {0.0, 1.0},
                                                                              {-1.0, 0.0}}};

/// Local node triples (first corner, mid-side, second corner) of the four sides, counter-clockwise.
inline constexpr std::array<std::array<int, 3>, 4> kQ8Sides = {
    {{0, 4, 1}, {1, 5, 2}, {2, 6, 3}, {3, 7, 0}}};

/// Serendipity shape functions N_a(ξ, η):
///   corners (ξa, ηa = ±1): N = ¼(1+ξξa)(1+ηηa)(ξξa+ηηa−1)
///   mid-sides ξa = 0:      N = ½(1−ξ²)(1+ηηa)
///   mid-sides ηa = 0:      N = ½(1+ξξa)(1−η²)
Eigen::Matrix<double, kQ8Nodes, 1> Q8ShapeFunctions(double xi, double eta);

/// ∂N_a/∂ξ (row 0) and ∂N_a/∂η (row 1).
Eigen::Matrix<double, 2, kQ8Nodes> Q8ShapeDerivatives(double xi, double eta);

/// Shape functions of a quadratic 3-node edge (first corner, mid-side, second corner) at ξ ∈ [−1,
/// 1]:
///   N = (ξ(ξ−1)/2, 1−ξ², ξ(ξ+1)/2).
/// A Q8's shape functions restricted to one of its sides are exactly these (the other five vanish).
Eigen::Vector3d EdgeShapeFunctions(double xi);
/// dN/dξ of the 3-node edge: (ξ−½, −2ξ, ξ+½).
Eigen::Vector3d EdgeShapeDerivatives(double xi);

/// One-dimensional Gauss–Legendre rule on [−1, 1].
struct GaussRule {
  std::array<double, 5> points{};   ///< abscissae ξ_g [-]
  std::array<double, 5> weights{};  ///< weights w_g [-]
  int size = 0;                     ///< number of points used (1..5)
};
/// The n-point Gauss–Legendre rule, n = 1..5 (exact for polynomials of degree 2n−1).
/// @throws std::invalid_argument for n outside 1..5.
GaussRule GaussLegendre(int n);

/// Number of Gauss points per direction of the element stiffness: 3×3 ("full") integration.
/// For an undistorted Q8 the integrand BᵀDB is a polynomial of degree 4 per direction, integrated
/// exactly; 2×2 ("reduced") would leave a spurious zero-energy mode. With a distorted element the
/// integrand is rational; the constant-stress patch test still passes to round-off because
/// ∫ Bᵀ σ₀ dA only needs the polynomial cofactors of J (degree ≤ 3 per direction).
inline constexpr int kQ8GaussPointsPerDirection = 3;

/// Checks that the isoparametric map x(ξ, η) = Σ N_a x_a of element `element_index` is valid:
/// det J > kRelativeJacobianTolerance · (element size)² at the 3×3 Gauss points and at the four
/// corners, where J = ∂x/∂ξ and the size is the diagonal of the corners' bounding box.
/// @throws std::invalid_argument naming the element, det J, the point (ξ, η) and its position,
///         and the rule (inverted: det J < 0, clockwise nodes; degenerate: det J ≈ 0).
void CheckQ8Jacobian(const Q8Coordinates& x, int element_index);
inline constexpr double kRelativeJacobianTolerance = 1e-10;

/// Strain–displacement matrix B (3×16) and det J at (ξ, η); ε = B u_e.
///   B = [[∂N/∂x, 0], [0, ∂N/∂y], [∂N/∂y, ∂N/∂x]] per node, ∂N/∂x = J⁻ᵀ ∂N/∂ξ.
Eigen::Matrix<double, 3, 2 * kQ8Nodes> Q8StrainDisplacement(const Q8Coordinates& x, double xi,
                                                            double eta, double* det_j);

/// K_e = b ∫∫ Bᵀ D B det J dξ dη with 3×3 Gauss quadrature [N/m].
Q8Stiffness Q8ElementStiffness(const Q8Coordinates& x, const Eigen::Matrix3d& d, double thickness);

/// Position x(ξ, η) [m].
Eigen::Vector2d Q8Position(const Q8Coordinates& x, double xi, double eta);

}  // namespace epicycle::compliance
