// The nonlinear constrained contact problem (MODEL.md section 5): data only, validated on
// construction. It knows nothing of gears: plain Eigen data in SI units.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "epicycle/solvers/local_term.hpp"

namespace epicycle::solvers {

/// Unknowns: contact forces F ∈ ℝᴺ and multipliers λ ∈ ℝᵐ (rigid displacements of the members
/// whose position is set by equilibrium). With u(F) = C F + u_local(F):
///
///   gap:          g = C F + u_local(F) − δ0 − Gᵀλ ≥ 0,   F ≥ 0,   Fᵀg = 0
///   equilibrium:  G F + S λ = W
///
/// S = 0 (the default) makes G F = W hard equalities; a positive semidefinite S is the compliance
/// of elastic supports (rows with S = 0 stay hard). This is the KKT system of the convex program
///   min Φ(F) = ½FᵀCF + Σ_j ∫₀^{F_j} u_local,j − δ0ᵀF (+ ½(GF−W)ᵀS⁻¹(GF−W))  s.t. F ≥ 0, (GF = W).
struct ContactProblemData {
  std::string name;                         ///< free text, used in reports and file names
  Eigen::MatrixXd compliance;               ///< C [m/N], N×N, symmetric positive definite
  Eigen::VectorXd overlap;                  ///< δ0 [m], N; > 0 interpenetration, < 0 gap
  std::vector<LocalTermParameters> local;   ///< empty (no local terms) or N entries
  Eigen::MatrixXd equality_matrix;          ///< G, m×N [-] (force rows) or [m] (moment rows); m may be 0
  Eigen::VectorXd equality_rhs;             ///< W, m [N] or [N·m]
  Eigen::MatrixXd support_compliance;       ///< S, m×m [m/N] or [rad/(N·m)]; empty means 0
  std::vector<std::string> contact_labels;  ///< empty or N labels (e.g. "sun-planet1 tooth 3 drive")
  std::vector<std::string> multiplier_labels;  ///< empty or m labels (e.g. "sun rotation [rad]")
};
