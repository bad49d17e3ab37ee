// Periodic steady state of a T-periodic system y' = f(t, y; p): shooting with the monodromy
// matrix from the variational equations, Floquet multipliers, and pseudo-arclength continuation
// over one named parameter with folds located and period doubling / Neimark–Sacker flagged.
// Equations: docs/periodic.md §1; the method and its choices: docs/periodic.md §2; verification:
// docs/periodic.md §3; the stage's model it is meant for: docs/model.md §7.
//
// Time is scaled to the period: s = t/T(p) ∈ [0, 1], dy/ds = T f(T s, y; p), so that a parameter
// that changes the period (a forcing frequency ω, T = 2π/ω) is an ordinary parameter of a fixed
// interval. Shooting solves R(y0; p) = φ(1; y0, p) − y0 = 0 by Newton with a backtracking line
// search; the Jacobian M − I comes from the same integration as R: the variational equations
// Φ' = T J(T s, y) Φ, Φ(0) = I, integrated with the state by CVODE (BDF, banded Newton matrix).
// M = Φ(1) is the monodromy matrix, its eigenvalues the Floquet multipliers.
#pragma once

#include <complex>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace epicycle::dynamics {

/// One parameter of a periodic system: its name, unit and the value the system starts from.
struct PeriodicParameter {
  std::string name;  ///< as a continuation names it ("omega")
  std::string unit;  ///< "rad/s", "-", ...
  double value = 0;  ///< default value [unit]
};

/// A T-periodic right-hand side y' = f(t, y; p): the form the periodic solver takes. The state's
/// units are the system's own; p holds every parameter in the order of parameters().
class PeriodicSystem {
 public:
  virtual ~PeriodicSystem() = default;
  virtual int size() const = 0;                                   ///< n, the state's size [-]
  virtual std::vector<PeriodicParameter> parameters() const = 0;  ///< may be empty
  /// T(p) [s], the forcing period.
  virtual double Period(const Eigen::VectorXd& p) const = 0;
  /// f(t, y; p) into *f (size n). false: the state cannot be evaluated (the integrator retries
  /// with a smaller step).
  virtual bool Rhs(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& p,
                   Eigen::VectorXd* f) const = 0;
  /// Whether Jacobian() is implemented; otherwise the solver takes forward differences of Rhs.
  virtual bool has_jacobian() const { return false; }
  /// ∂f/∂y at (t, y; p) into *jac (n × n). false as for Rhs.
  virtual bool Jacobian(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& p,
                        Eigen::MatrixXd* jac) const;
  /// The period map S of a system with a symmetry (docs/periodic.md §1, "Symmetry"): its orbits
  /// repeat as y(t + T) = S⁻¹ y(t), so the shooting solves S φ_T(y0) = y0 and the Floquet
  /// multipliers are the eigenvalues of S Φ(T) (n × n, orthogonal). Empty (the default): S = I.
  /// A stage whose translations are in the inertial frame repeats a mesh cycle later turned by the
  /// carrier's advance: S turns them back.
  virtual Eigen::MatrixXd PeriodMap(const Eigen::VectorXd& p) const {
    (void)p;
    return {};
  }
  /// The index of the parameter named `name`.
  /// @throws std::invalid_argument naming the name and the parameters there are.
  int ParameterIndex(const std::string& name) const;
  /// Every parameter's default value, in order.
  Eigen::VectorXd DefaultParameters() const;
};

struct ShootingOptions {
  double rtol = 1e-8;  ///< integrator's relative tolerance [-], in (0, 0.1]
  /// Integrator's absolute tolerance per state component [units of y]; size 1: the same for
  /// every component.
  Eigen::VectorXd atol = Eigen::VectorXd::Constant(1, 1e-10);
  /// Newton stops when the weighted RMS norm of R or of the Newton update, each component over
  /// (rtol |y_i| + atol_i), is ≤ this [-]. The integrator holds its local error per step to 1 in
  /// that norm; its global error over a period is tens of times larger (the backlash oscillator of
  /// docs/periodic.md: R stagnates at 1–50 on the unstable branch), so a Newton tolerance of 1
  /// chases noise. 100: R to 100 local tolerances.
  double newton_tolerance = 100.0;
  int max_iterations = 25;   ///< Newton iterations [-], ≥ 1
  long max_steps = 1000000;  ///< integrator steps over one period [-], ≥ 1
  /// A multiplier is outside (inside) the unit circle when |μ| > 1 + this (< 1 − this) [-];
  /// between, it is on it (a marginal orbit, e.g. a conservative system's).
  double unit_circle_tolerance = 1e-6;
  /// @throws std::invalid_argument naming the field, its value and the rule.
  void Validate(int n) const;
};

enum class ShootingStatus {
  kConverged,          ///< R and/or the update to newton_tolerance
  kIterationLimit,     ///< max_iterations spent
  kLineSearchFailed,   ///< no step along the Newton direction decreased |R|
  kSingularJacobian,   ///< M − I singular (a multiplier at +1)
  kIntegrationFailed,  ///< CVODE stopped inside the period (message says where)
};
std::string ShootingStatusName(ShootingStatus status);

enum class Stability {
  kStable,    ///< every |μ| < 1 − tol
  kMarginal,  ///< none outside, some on the unit circle
  kUnstable,  ///< some |μ| > 1 + tol
};
std::string StabilityName(Stability stability);

/// Floquet multipliers of one orbit and what they say.
struct FloquetReport {
  std::vector<std::complex<double>> multipliers;  ///< eigenvalues of M, by decreasing |μ| [-]
  double spectral_radius = 0;                     ///< max |μ| [-]
  Stability stability = Stability::kStable;
  int real_above_one = 0;        ///< real μ > 1 + tol (a fold's unstable side) [-]
  int real_below_minus_one = 0;  ///< real μ < −1 − tol (past a period doubling) [-]
  int complex_outside = 0;       ///< complex μ with |μ| > 1 + tol, counted singly [-]
};
/// Classifies the eigenvalues of a monodromy matrix.
FloquetReport FloquetMultipliers(const Eigen::MatrixXd& monodromy, double unit_circle_tolerance);
/// Classifies multipliers found otherwise (harmonic balance's Hill method).
FloquetReport ClassifyMultipliers(std::vector<std::complex<double>> multipliers,
                                  double unit_circle_tolerance);

struct ShootingResult {
  ShootingStatus status = ShootingStatus::kIntegrationFailed;
  std::string message;            ///< where and why it stopped, when not converged
  Eigen::VectorXd initial_state;  ///< y0 on the orbit, at t = 0 [units of y]
  Eigen::VectorXd parameters;     ///< p of the orbit
  double period = 0;              ///< T [s]
  Eigen::MatrixXd monodromy;      ///< M = ∂φ_T/∂y0 [-]
  FloquetReport floquet;
  double residual_norm = 0;  ///< weighted RMS of φ_T(y0) − y0 at the answer [-]
  int iterations = 0;        ///< Newton iterations [-]
  long integrations = 0;     ///< periods integrated (each with its variational equations) [-]
  long steps = 0;            ///< integrator steps, summed [-]
  long rhs_evaluations = 0;  ///< f evaluations, summed [-]
};

/// Shooting from the guess y0 at parameters p (empty: the system's defaults).
/// @throws std::invalid_argument for bad options, sizes or a period that is not > 0 and finite.
ShootingResult SolvePeriodicOrbit(const PeriodicSystem& system, const ShootingOptions& options,
                                  const Eigen::VectorXd& y0, const Eigen::VectorXd& p = {});

/// One period of the orbit from y0, sampled at `samples` instants t_k = k T/samples,
/// k = 0..samples [units of y] (rows: instants). For plots and for comparing with other
/// solutions. @throws std::runtime_error if the integration fails.
Eigen::MatrixXd SampleOrbit(const PeriodicSystem& system, const ShootingOptions& options,
                            const Eigen::VectorXd& y0, const Eigen::VectorXd& p, int samples);

/// Integrates y' = f(t, y; p) from t = 0 over `periods` whole periods (CVODE, the options'
/// tolerances) and returns y at their end: the settled state a time integration reaches.
/// @throws std::runtime_error if the integration fails.
Eigen::VectorXd IntegratePeriods(const PeriodicSystem& system, const ShootingOptions& options,
                                 const Eigen::VectorXd& y0, const Eigen::VectorXd& p, int periods);

struct ContinuationOptions {
  std::string parameter;  ///< the parameter continued (one of the system's names)
  double start = 0;       ///< λ_0 [its unit]
  double end = 1;         ///< λ at which the branch stops [its unit]; ≠ start
  /// Arclength steps, in the scaled coordinates (y_i/state_scale_i, λ/|end − start|) [-].
  double initial_step = 0.02;
  double min_step = 1e-6;
  double max_step = 0.1;
  /// The state's scale per component [units of y] (size 1: for every component).
  Eigen::VectorXd state_scale = Eigen::VectorXd::Ones(1);
  int max_points = 500;              ///< points of the branch [-]
  int max_corrector_iterations = 8;  ///< Newton iterations per point [-]
  /// A step whose corrector took ≤ this many iterations lets the next grow 1.5× [-].
  int fast_iterations = 3;
  int fold_refinements = 10;    ///< secant steps locating a fold [-]
  int amplitude_component = 0;  ///< c of BranchPoint::amplitude [-]
  /// Instants per period for BranchPoint::amplitude [-], ≥ 4; 0: no amplitude (0), which saves
  /// a period's integration a point.
  int amplitude_samples = 256;
  ShootingOptions shooting;     ///< tolerances, Newton of the first point, unit circle
  /// @throws std::invalid_argument naming the field, its value and the rule.
  void Validate(int n) const;
};

enum class ContinuationStatus {
  kCompleted,     ///< the branch reached `end` (or left the range)
  kPointLimit,    ///< max_points reached first
  kStartFailed,   ///< shooting at λ_0 did not converge (ContinuationResult::start says why)
  kStepTooSmall,  ///< the corrector failed with the step at min_step
};
std::string ContinuationStatusName(ContinuationStatus status);

enum class BifurcationKind {
  kFold,            ///< dλ/ds changes sign; a real multiplier at +1
  kPeriodDoubling,  ///< a real multiplier through −1
  kNeimarkSacker,   ///< a complex pair through the unit circle
};
std::string BifurcationKindName(BifurcationKind kind);

struct BranchPoint {
  double parameter = 0;   ///< λ [its unit]
  double period = 0;      ///< T [s]
  Eigen::VectorXd state;  ///< y0 on the orbit [units of y]
  /// Harmonic balance's orbit: its Fourier coefficients C ((2H + 1) × n, harmonic_balance.hpp)
  /// [units of y]; empty for shooting.
  Eigen::MatrixXd coefficients;
  /// Half the peak-to-peak of y_c over the period, c = ContinuationOptions::amplitude_component,
  /// from amplitude_samples + 1 equally spaced instants [units of y_c].
  double amplitude = 0;
  FloquetReport floquet;
  double tangent_parameter = 0;  ///< dλ/ds of the unit tangent (scaled) [-]
  double arclength = 0;          ///< s from the first point (scaled) [-]
  int corrector_iterations = 0;  ///< [-]
};

struct Bifurcation {
  BifurcationKind kind = BifurcationKind::kFold;
  double parameter = 0;   ///< λ where it is (fold: located; others: interpolated) [its unit]
  Eigen::VectorXd state;  ///< y0 there (fold) or at the point after it [units of y]
  int after_point = 0;    ///< index of the branch point it lies just before [-]
  /// Fold: the real multiplier nearest +1 at the located point; others: the crossing
  /// multiplier at the point after [-].
  std::complex<double> multiplier;
};

struct ContinuationResult {
  ContinuationStatus status = ContinuationStatus::kStartFailed;
  std::string message;  ///< where and why it stopped, when not completed
  std::string parameter, unit;
  std::vector<BranchPoint> points;  ///< the branch, stable and unstable, in arclength order
  std::vector<Bifurcation> bifurcations;
  ShootingResult start;    ///< the first point's shooting
  long integrations = 0;   ///< periods integrated with the variational equations [-]
  /// Periods integrated without them (the chord corrector's iterations) [-].
  long plain_integrations = 0;
  long steps = 0;          ///< integrator steps of both kinds [-]
  int rejected_steps = 0;  ///< corrector failures that halved the step [-]
};

/// Pseudo-arclength continuation of the periodic orbit from (y0 guess, λ = start) towards `end`,
/// the other parameters at `p` (empty: the system's defaults). Returns the branch so far whatever
/// happens.
/// `on_point`, if given, is called with the branch so far after each point is added (its last
/// point the new one, with the bifurcations found up to it): a caller streams the branch.
/// @throws std::invalid_argument for bad options, an unknown parameter, or a period that is not
/// > 0 and finite at a point asked for; what `on_point` throws.
ContinuationResult ContinuePeriodicOrbit(
    const PeriodicSystem& system, const ContinuationOptions& options, const Eigen::VectorXd& y0,
    const Eigen::VectorXd& p = {},
    const std::function<void(const ContinuationResult&)>& on_point = {});

}  // namespace epicycle::dynamics
