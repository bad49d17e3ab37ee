// Private interface between the contact driver and its back ends. A back end sees only the
// nondimensional problem built by the driver; the driver scales back, recovers multipliers the
// back end does not return, computes the one residual and decides the status.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Dense>

#include "epicycle/solvers/contact_solver.hpp"

namespace epicycle::solvers::internal {

/// The nondimensional problem: forces in units of force_scale [N], lengths in length_scale [m]
/// (so C is in length_scale/force_scale, δ0 in length_scale, W in force_scale (force rows) or
/// force_scale·moment_arm_scale (moment rows) as chosen by the driver).
///
///   Φ(x)  = ½xᵀCx + Σ_j U_j(x_j) − δ0ᵀx,   U_j = ∫₀^{x_j} u_local,j
///   ∇Φ(x) = Cx + u(x) − δ0 = g(x) + Gᵀλ
///   ∇²Φ   = C + diag(u'(x))           (u'(0⁺) = +∞: the local term's hazard)
///   s.t. x ≥ 0,  G x + S λ = W  (S = 0: hard equalities)
struct ScaledProblem {
  Eigen::MatrixXd C;         ///< N×N, SPD
  Eigen::VectorXd delta0;    ///< N
  Eigen::MatrixXd G;         ///< m×N (m may be 0)
  Eigen::VectorXd W;         ///< m
  Eigen::MatrixXd S;         ///< m×m PSD (all zero when there are no elastic supports)
  bool has_support = false;  ///< S has a non-zero entry
  bool has_local = false;    ///< any local term enabled
  /// Slices S of the compliance's Kronecker structure (ContactProblem::compliance_terms; 1
  /// without one) and the group of every slice: slices s, t in different groups have
  /// kernel_st = 0 in every term, so C has no entry between contacts of different groups and the
  /// Newton's C_AA + diag u' is block diagonal over the groups (contact i in group
  /// slice_group[i mod S]). slice_groups = 1: one dense block.
  int slices = 1;
  int slice_groups = 1;
  std::vector<int> slice_group;
  /// With one Kronecker term whose kernel couples every slice (slice_groups = 1, S > 1): its
  /// factors, C ≈ kron_source ⊗ kron_kernel (the source scaled as C, n×n; the kernel S×S, [-]);
  /// both empty otherwise. The dense C stays the definition (it matches to 1e-10·max|C|).
  Eigen::MatrixXd kron_source, kron_kernel;

  int num_contacts() const { return static_cast<int>(C.rows()); }
  int num_equalities() const { return static_cast<int>(G.rows()); }

  // Implemented by the driver (scaled_problem.cpp) for every back end to use. For x_j < 0 the
  // local term is extended oddly (u(−x) = −u(x), U even, u' even), which keeps Φ convex and the
  // Newton iteration defined; every back end's answer is judged at max(x, 0) anyway.
  double Objective(const Eigen::VectorXd& x) const;                           ///< Φ(x), x ≥ 0
  void Gradient(const Eigen::VectorXd& x, Eigen::VectorXd* grad) const;       ///< ∇Φ(x)
  void LocalValue(const Eigen::VectorXd& x, Eigen::VectorXd* u) const;        ///< u_local(x)
  void LocalDerivative(const Eigen::VectorXd& x, Eigen::VectorXd* du) const;  ///< u'(x), +inf at 0
  double LocalDerivativeAt(int j, double x) const;  ///< u_j'(x) of one contact, +inf at 0

  // Scaled local-term parameters, one per contact (filled by the driver).
  struct Local {
    bool enabled = false;
    double a[2] = {0, 0};  ///< 2k_B/(πb) in scaled units
    double c[2] = {0, 0};  ///< c_B
    double h[2] = {0, 0};  ///< h_B in scaled length
    double l2 = 0;         ///< L² = l2 · F (scaled)
    // Derived once per problem for the evaluation (scaled_problem.cpp):
    double inv_h[2] = {0, 0};  ///< 1/h_B
    double ac[2] = {0, 0};     ///< a_B c_B
    double a1c[2] = {0, 0};    ///< a_B (1 + c_B)/2
    bool same_a = false;       ///< a_1 = a_2: Σ_B a_B asinh(s_B) with one logarithm
  };
  std::vector<Local> local;

  // The driver's scales (informative for back ends; the scaled problem is self-contained).
  double force_scale = 1.0;   ///< [N]
  double length_scale = 1.0;  ///< [m]
  Eigen::VectorXd row_scale;  ///< m: G_i [SI] = row_scale_i · G_i [scaled] ([-] or [m])

  /// u_j(x) and u_j'(x) of one contact from one evaluation (the odd extension for x < 0; u' at
  /// max(|x|, floor) so that a contact entering from zero force gets a finite, large derivative).
  /// Both 0 without a local term.
  void LocalAt(int j, double x, double floor, double* u, double* du) const;
  /// u_j''(x) for x > 0 (< 0: u' falls with the force; no logarithm needed); 0 without a local
  /// term or for x ≤ 0.
  double LocalSecondDerivativeAt(int j, double x) const;

  /// Natural-map and equilibrium residuals at (x, λ), evaluated at max(x, 0).
  ContactResiduals Residuals(const Eigen::VectorXd& x, const Eigen::VectorXd& lambda) const;
  /// The residuals of a problem without equalities at x ≥ 0 from its gap g = ∇Φ(x) = Cx + u − δ0
  /// (the part of Residuals after the gradient, for a caller that has the gradient already).
  static ContactResiduals ResidualsFromGap(const Eigen::VectorXd& x, const Eigen::VectorXd& g);
  /// The same, also returning the gap g = ∇Φ(max(x, 0)) − Gᵀλ it was computed from (the driver
  /// counts the active contacts from it instead of evaluating the local terms a second time).
  ContactResiduals Residuals(const Eigen::VectorXd& x, const Eigen::VectorXd& lambda,
                             Eigen::VectorXd* gap) const;
  /// The driver's residual of a problem without equalities at x, in the callers' storage (no
  /// temporaries): u_j and u'_j = u'(max(|x_j|, floor)) of the contacts with a force (both 0 at
  /// x_j = 0), the gap g = u − δ0 + C x by the columns of C with a force, and
  /// ‖min(x, g)‖∞ (the natural map; not finite if g is not). `negative`: some x_j < 0. The
  /// Newton's direct path steps from the same g and u' (the driver computes them once per
  /// iterate and judges by them; the path has no stopping test of its own).
  double NaturalResidual(const Eigen::VectorXd& x, double floor, Eigen::VectorXd* u,
                         Eigen::VectorXd* du, Eigen::VectorXd* g, bool* negative) const;
};

/// The driver's nondimensionalisation (scaled_problem.cpp):
///   row scale r_i = max_j |G_ij| (a lever arm for moment rows, 1 for unit-normal force rows),
///   force scale F* = max(max_i |W_i|/r_i, max_j δ0_j⁺ / max diag C), or 1 N if both vanish,
///   length scale ℓ* = F*·max diag C (a deflection scale),
///   C̃ = C F*/ℓ*, δ̃0 = δ0/ℓ*, G̃_i = G_i/r_i, W̃_i = W_i/(r_i F*), S̃_ik = S_ik ℓ*/(F* r_i r_k),
///   x = F/F*, λ̃_i = r_i λ_i/ℓ*.
ScaledProblem MakeScaledProblem(const ContactProblem& problem);
/// The same, written into *sp, whose storage is reused when the sizes have not changed (a solver
/// object called again and again on problems of one size allocates nothing here).
void MakeScaledProblem(const ContactProblem& problem, ScaledProblem* sp);
/// Back to SI: F = F*·x, λ_i = ℓ*·λ̃_i/r_i, and the inverse of those.
void Unscale(const ScaledProblem& sp, const Eigen::VectorXd& x, const Eigen::VectorXd& lambda,
             ContactSolution* out);
void Scale(const ScaledProblem& sp, const ContactSolution& in, Eigen::VectorXd* x,
           Eigen::VectorXd* lambda);

/// min ‖G x − W‖ over x ≥ 0 (Lawson–Hanson); returns ‖G x − W‖∞ and x if x_out is not null.
double NonNegativeLeastSquares(const Eigen::MatrixXd& G, const Eigen::VectorXd& W,
                               Eigen::VectorXd* x_out);
/// True when no x ≥ 0 satisfies G̃x = W̃: the non-negative least-squares residual exceeds
/// 1e-6·max(1, ‖W̃‖∞) (scaled_problem.cpp).
bool EqualitiesInfeasible(const ScaledProblem& sp);

/// What a back end returns: raw, unjudged.
struct BackendResult {
  Eigen::VectorXd force;       ///< x (scaled), N
  Eigen::VectorXd multiplier;  ///< λ (scaled), m; empty if the back end does not return it
  int iterations = 0;
  int code = 0;                ///< the back end's own return code
  std::string message;         ///< the back end's own words
  bool failed = false;         ///< the back end reports a hard failure (no usable point)
  bool limit_reached = false;  ///< iteration or time limit
};

class BackendImpl {
 public:
  virtual ~BackendImpl() = default;
  virtual bool available() const = 0;
  /// @param x0, lambda0 warm start (scaled) or nullptr.
  virtual BackendResult Run(const ScaledProblem& problem, const ContactOptions& options,
                            const Eigen::VectorXd* x0, const Eigen::VectorXd* lambda0) = 0;
  /// Back-end option keys this back end accepts (without the namespace), for Validate().
  virtual std::vector<std::string> option_keys() const { return {}; }
};

/// The active-set Newton's direct path for problems without equalities (positions given, only
/// F ≥ 0: the dynamic model's problem at every right-hand side): the semismooth Newton of phase 1
/// without line search, equality blocks or option parsing, on storage kept between calls. With
/// A = {j : x_j > g_j}, x_I = 0 and the Newton step on g_A = 0,
///   (C_AA + diag u'(x_A)) dx_A = −g_A + C_AI x_I,
/// until ‖min(x, g)‖∞ ≤ target at x ≥ 0. From a warm start of the previous time step it takes
/// one or two steps. It gives up (returns false) when the residual has not decreased for three
/// iterations, after `max_iterations`, or when C_AA + diag u' is not positive definite: the
/// caller then runs the globalised back end, which is slower but converges.
///
/// The smallest scaled force at which a local term's derivative u' is evaluated: u'(0⁺) = +∞
/// (logarithmically), so a contact entering the active set from zero force sees u' at this floor
/// (or, on the direct path, a secant).
inline constexpr double kDerivativeFloor = 1e-12;

// Factories, one per source file. The Ipopt / NLopt ones are compiled from either the real file
// or its *_unavailable.cpp, whose available() is false.
std::unique_ptr<BackendImpl> MakeActiveSetNewtonBackend();     // active_set_newton.cpp
std::unique_ptr<BackendImpl> MakeIpoptBackend();               // backend_ipopt[_unavailable].cpp
std::unique_ptr<BackendImpl> MakeNloptBackend(Backend which);  // backend_nlopt[_unavailable].cpp

}  // namespace epicycle::solvers::internal
