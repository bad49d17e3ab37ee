// A branch of the stage's periodic orbits (docs/periodic.md §3, "The stage's branch"): the
// stage's dynamic model as a StagePeriodicSystem, continued over the sun speed or another of its
// parameters (the scene's sun_torque_Nm, mesh_damping_ratio) by ContinuePeriodicOrbit, each
// point with its stability and the figures a speed sweep reads off a run (docs/speed_sweeps.md),
// here over exactly one period of the orbit:
//   K_γ      = max over the period's samples of DynamicSample::k_gamma       [-]
//   TE amp.  = ½ (max − min) of the dynamic transmission error at the sun    [rad]
//   orbit    = max |sun centre − nominal|                                     [m]
// from `Simulate` over one period from the orbit's state with `samples_per_period` outputs.
// The driver's request is the base model plus StageBranchOptions; its record StageBranchRecord;
// points are handed to a sink as they are computed.
#pragma once

#include <complex>
#include <functional>
#include <string>
#include <vector>

#include "epicycle/dynamics/dynamic_model.hpp"
#include "epicycle/dynamics/periodic.hpp"
#include "epicycle/dynamics/simulation.hpp"
#include "epicycle/dynamics/stage_periodic.hpp"

namespace epicycle::dynamics {

/// The periodic back end of a branch (docs/periodic.md §2): shooting with its Floquet multipliers,
/// or harmonic balance with Hill's method, for a stage whose orbit repeats with the mesh.
enum class PeriodicMethod { kShooting, kHarmonicBalance };
/// "shooting", "hb".
std::string PeriodicMethodName(PeriodicMethod method);
/// @throws std::invalid_argument naming `what`, the word and the words there are.
PeriodicMethod ParsePeriodicMethod(const std::string& word, const std::string& what);

struct StageBranchOptions {
  /// The parameter continued: StagePeriodicSystem::kSunSpeed ("sun_speed_rpm"), kSunTorque
  /// ("sun_torque_Nm"), kMeshDampingRatio ("mesh_damping_ratio") or an error amplitude's key
  /// (ParseStageErrorKey: "errors.pin.planet1.tangential_um", ...).
  std::string parameter = StagePeriodicSystem::kSunSpeed;
  double start = 0;  ///< λ_0 [the parameter's unit]
  double end = 0;    ///< λ where the branch stops [its unit]; ≠ start
  PeriodicMethod method = PeriodicMethod::kShooting;
  /// Harmonic balance: H, harmonics of the period kept [-], ≥ 1, and N, the AFT's instants per
  /// period (0: 4H) [-] (HarmonicBalanceOptions). Each point's figures are read off the series at
  /// samples_per_period instants (no time integration).
  int harmonics = 24;
  int hb_samples = 0;
  /// Hill's matrix's harmonics H_s (HarmonicBalanceOptions::hill_harmonics; 0: H) [-].
  int hill_harmonics = 8;
  /// The stage's period (StagePeriodMeshCycles of the scene's stage and damage).
  StagePeriod period;
  /// A period of more mesh cycles than this is refused: shooting integrates it, with the
  /// variational equations, once per Newton iteration, while a time integration settles in a
  /// number of mesh cycles that does not grow with it (docs/periodic.md §4) [-], ≥ 1.
  long max_period_mesh_cycles = 4;
  /// Arclength steps in the scaled coordinates (docs/periodic.md §1) [-].
  double initial_step = 0.02;
  double max_step = 0.05;
  double min_step = 1e-5;
  int max_points = 400;         ///< [-]
  int samples_per_period = 64;  ///< outputs of each point's period for its figures [-], ≥ 4
  /// rtol, the absolute tolerances (atol_length, atol_angle, rates × rate_scale; rate_scale > 0),
  /// the contact back end and its options of the shooting and of each point's period.
  SimulationOptions simulation;
  /// @throws std::invalid_argument naming the field, its value and the rule.
  void Validate() const;
};

struct StageBranchPoint {
  int index = 0;               ///< in arclength order [-]
  double parameter = 0;        ///< λ [the record's unit]
  double sun_speed_rpm = 0;    ///< [rpm]
  double period = 0;           ///< T [s]
  double k_gamma = 0;          ///< over the period [-]
  double te_amplitude = 0;     ///< [rad]
  double orbit_radius = 0;     ///< [m]
  /// A helical stage: the axial forces [N] and tilting moments [N·m] over the period's samples,
  /// their means and largest magnitudes (as a speed sweep's window); empty for a spur stage.
  transmission::HelicalLoadRange helical;
  double spectral_radius = 0;  ///< max |μ| [-]
  Stability stability = Stability::kStable;
  int real_above_one = 0;        ///< real μ > 1 [-]
  int real_below_minus_one = 0;  ///< real μ < −1 [-]
  int complex_outside = 0;       ///< complex μ with |μ| > 1 [-]
  double arclength = 0;          ///< scaled [-]
  int corrector_iterations = 0;  ///< [-]
  Eigen::VectorXd state;         ///< y0 = (d, ḋ) on the orbit at t = 0 [m, rad, m/s, rad/s]
};

struct StageBranchBifurcation {
  BifurcationKind kind = BifurcationKind::kFold;
  double parameter = 0;             ///< λ [the record's unit]
  int after_point = 0;              ///< the branch point it lies just before [-]
  std::complex<double> multiplier;  ///< as Bifurcation::multiplier [-]
};

struct StageBranchRecord {
  std::string parameter, unit;  ///< the parameter continued and its unit
  PeriodicMethod method = PeriodicMethod::kShooting;
  int harmonics = 0;  ///< H of harmonic balance [-] (0: shooting)
  ContinuationStatus status = ContinuationStatus::kStartFailed;
  std::string message;          ///< where and why it stopped, when not completed
  long period_mesh_cycles = 1;  ///< k [-]
  std::vector<std::string> period_reasons;
  std::vector<std::string> dof_labels;  ///< the state's components (d, then ḋ), with units
  std::vector<StageBranchPoint> points;
  std::vector<StageBranchBifurcation> bifurcations;
  /// Shooting: periods integrated with the variational equations; harmonic balance: the
  /// residual's linearisations (Jacobian and ∂R/∂λ) [-].
  long integrations = 0;
  /// Periods integrated without them (chord iterations); harmonic balance: residuals alone [-].
  long plain_integrations = 0;
  /// The integrator steps of both; harmonic balance: the stage's evaluations in them [-].
  long steps = 0;
  /// Continued over an error amplitude: the stages rebuilt with a value of it (one per parameter
  /// value the continuation evaluated the stage at, StagePeriodicSystem::rebuilds) [-].
  long rebuilds = 0;
  double cpu_seconds = 0;   ///< CPU of the run (one thread) [s]
  double wall_seconds = 0;  ///< [s]
  /// Non-empty: a point's period figures could not be integrated (the first such point and why);
  /// the point keeps the figures of the samples before the failure.
  std::string figures_message;
  /// The branch reached its end and every point has its figures.
  bool ok() const { return status == ContinuationStatus::kCompleted && figures_message.empty(); }
};

/// Why shooting does not pay for a stage of this period (docs/periodic.md §4): the period, why it
/// is that long (StagePeriod::reasons) and the rule, when period.mesh_cycles >
/// max_period_mesh_cycles; empty otherwise.
std::string BranchPeriodRefusal(const StagePeriod& period, long max_period_mesh_cycles);

/// @throws std::invalid_argument with BranchPeriodRefusal's message when it is not empty.
void CheckBranchPeriod(const StagePeriod& period, long max_period_mesh_cycles);

/// The branch from the quasi-static start at λ = start (shooting, then the continuation to end).
/// `on_point` gets the record after each new point (its last point; bifurcations up to it).
/// @throws std::invalid_argument for bad options (naming the field), an unknown parameter (an
///         error key of a gear the stage does not have), a period over max_period_mesh_cycles,
///         a parameter value the model refuses;
///         std::runtime_error if the quasi-static start fails; what `on_point` throws.
StageBranchRecord ContinueStageBranch(
    const DynamicModel& base, const StageBranchOptions& options,
    const std::function<void(const StageBranchRecord&)>& on_point = {});

/// The TE amplitude [rad] that separates two stable orbits coexisting between two folds: midway
/// between the largest TE amplitude of `from_below`'s points up to its first fold (the orbit that
/// ends at the upper fold) and the smallest of `from_above`'s up to its first fold at speeds no
/// higher than `from_below`'s fold (the orbit that ends at the lower fold), for a response whose
/// upper orbit's amplitude exceeds the lower's between the folds (docs/periodic.md §3, "Jumps").
/// @throws std::invalid_argument when either branch has no fold or the second has no point
///         below the first's fold.
double SeparatingTeAmplitude(const StageBranchRecord& from_below,
                             const StageBranchRecord& from_above);

}  // namespace epicycle::dynamics
