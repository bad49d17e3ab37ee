// Time integration of the dynamic model (docs/model.md §7) behind one options struct: CVODE BDF
// with a dense linear solver and the Jacobian from the contact solution's sensitivity (the
// workhorse: the low-speed limit is stiff), or ARKODE's explicit Dormand–Prince 5(4) method as the
// second opinion. The state is y = [d, ḋ, W_ext, W_diss]: the deviations from the rigid kinematics,
// their rates, and the accumulated external work and dissipated energy [J] (for the energy
// balance E(t) − E(0) = W_ext − W_diss, E kinetic plus stored elastic energy).
//
// A contact solve that fails inside the right-hand side, or a pose the stage model cannot evaluate
// (a trial step that swung a member past where its meshes have a line of action), is recoverable:
// CVODE retries with a smaller step (return > 0); ERKStep treats any non-zero return as fatal, so
// the explicit driver restarts from the last output with a ten times smaller first step, at most 8
// times in a row. Every failure is counted. Outputs are produced at given times from the
// integrator's solution there (CVODE's and ERKStep's NORMAL mode), each handed to the caller as
// soon as it is computed.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "epicycle/dynamics/dynamic_model.hpp"
#include "epicycle/transmission/face_width.hpp"
#include "epicycle/transmission/helical_slices.hpp"
#include "epicycle/transmission/root_stress.hpp"
#include "epicycle/transmission/run_status.hpp"

namespace epicycle::dynamics {

enum class Integrator {
  kCvodeBdf,   ///< "cvode-bdf": variable-order BDF, dense linear solver
  kArkodeErk,  ///< "arkode-erk": explicit Dormand–Prince 5(4), adaptive
};
std::string IntegratorName(Integrator integrator);
/// @throws std::invalid_argument naming the value and the names allowed.
Integrator IntegratorFromName(const std::string& name);

struct SimulationOptions {
  Integrator integrator = Integrator::kCvodeBdf;
  double rtol = 1e-6;          ///< relative tolerance [-], in (0, 0.1]
  double atol_length = 1e-10;  ///< absolute tolerance on translations [m]
  double atol_angle = 1e-9;    ///< absolute tolerance on rotations [rad]
  /// Absolute tolerances of the rates: the position tolerance times this [1/s]. The default,
  /// 1e4, is the work-precision study's choice (docs/dynamic_cost.md, "Error against run time"): with
  /// it rtol 1e-6 keeps the paper stage's LSR to 1e-4 over a planet revolution. 0: the stage's
  /// highest linearised natural frequency at t = 0, √max|λ(∂d̈/∂d)| (4.3e4 on the paper stage),
  /// which weighs a vibration's velocity as its amplitude: ~25 % fewer steps at equal rtol, and a
  /// 2–3× larger error; at equal error the two cost the same. SimulationStats::rate_scale reports
  /// the value used.
  double rate_scale = 1e4;
  double atol_energy = 1e-6;  ///< absolute tolerance of the accumulated works [J]
  /// CVODE: the Jacobian from the contact sensitivity (true) or CVODE's difference quotients.
  bool analytic_jacobian = true;
  /// CVODE: largest BDF order (1..5). Orders above 2 are not A-stable: lightly damped stiff modes
  /// (mesh modes of kHz at a mesh frequency of Hz) then cap the step unless the order drops.
  int max_order = 5;
  /// CVODE: the safety factor of the Newton iteration's convergence test (CVodeSetNonlinConvCoef):
  /// a step's nonlinear solve stops when its estimated error, in the error test's weighted norm,
  /// is below this [-], in (0, 1]. 0.3 (CVODE's own default is 0.1) takes ~7 % fewer evaluations
  /// for the same error on the work-precision study's curve (docs/dynamic_cost.md, "Error against
  /// run time").
  double nonlinear_convergence = 0.3;
  /// CVODE's BDF stability-limit detection (drops the order when the step nears the stability
  /// boundary of an oscillatory mode).
  bool stability_limit_detection = true;
  long max_steps = 2000000;  ///< per output interval [-]
  double max_step = 0;       ///< largest step [s]; 0: no limit
  double initial_step = 0;   ///< first step tried [s]; 0: the integrator's own estimate
  /// Wall-time budget of the whole run [s]; 0: none. When spent, the run stops at the next
  /// right-hand side (completed = false, the message says so) and keeps the outputs it has: for
  /// studies that must not hang on a back end that keeps failing.
  double time_limit = 0;
  solvers::Backend backend = solvers::Backend::kActiveSetNewton;
  solvers::ContactOptions contact;  ///< the contact solve inside every evaluation
  /// Keep every output in SimulationResult::samples (true), or only hand each to the caller's
  /// `on_sample` (false: a run's memory then does not grow with its length; the command-line
  /// program streams its files, summary and plots this way).
  bool keep_samples = true;
  void Validate() const;            ///< @throws std::invalid_argument naming the field
};

/// One output step.
struct DynamicSample {
  double time = 0;                   ///< t [s]
  double carrier_angle = 0;          ///< φ_c of the reference motion [rad]
  Eigen::VectorXd d, v;              ///< deviations [m, rad] and their rates [m/s, rad/s], per DOF
  std::vector<double> load_sharing;  ///< LSR_i = T_mesh(P_i–S)/T_input (eq. 4) [-], per planet
  /// The share of the normal forces alone: Σ F of sun–planet i's contacts over Σ F of every
  /// sun–planet contact (F with its damping, no friction, no lever arm) [-], per planet; papers
  /// that define the load sharing by mesh forces mean this. Equal to LSR_i for a stage without
  /// friction whose contacts lie on the line of action and without sun inertia.
  std::vector<double> force_sharing;
  double transmission_error = 0;  ///< dynamic TE at the sun: θ_s − θ_s,kinematic [rad]
  Eigen::Vector2d sun_centre = Eigen::Vector2d::Zero();  ///< from nominal [m] (orbit)
  double sun_acceleration = 0;  ///< θ̈_s from the integrator's interpolant [rad/s²]
  /// K_γ at this step: max(0, max_i n·LSR_i) with n planets [-].
  double k_gamma = 0;
  /// The sun's rotational balance Σ_i T_mesh,i + T_in − J_s θ̈_s [N·m]: the moments of the
  /// sun-planet meshes (Evaluation::sun_mesh_torque), the input torque and the inertia torque
  /// with θ̈_s from the interpolant; 0 for a speed-driven sun, whose drive balances the meshes
  /// exactly. Its size against T_in measures the interpolant's and the solver's error.
  double sun_torque_balance = 0;
  double external_work = 0;    ///< W_ext since t = 0 [J]
  double dissipated_work = 0;  ///< W_diss since t = 0 [J]
  /// W_C since t = 0 [J]: the change of the contacts' stored energy less the work the elastic
  /// contact forces took from the bodies, −∫½FᵀĊF dt, the energy the compliance's change along
  /// the flanks adds (the model's contact forces omit −½Fᵀ(∂C/∂q)F; docs/dynamic.md, "Energy
  /// balance"). E(t) − E(0) = W_ext − W_diss + W_C to the integrator's tolerance.
  double compliance_work = 0;
  Evaluation evaluation;       ///< forces, energies, contacts at this step
  /// Root stresses of this step's state (docs/model.md §9) under the contact forces with their
  /// damping, when the stage's tables carry them (the scene's [model] stresses), else empty.
  std::vector<compliance::FilletStress> fillet_stress;
  /// Each gear's extremes of fillet_stress (SummariseRootStress, body order; empty with it).
  std::vector<transmission::GearRootStress> root_stress;
  /// With slices of the face width (the scene's [face_width], docs/face_width.md), each mesh's
  /// load per unit width across the face under the contact forces with their damping, its K_Hβ
  /// and where the largest sits (transmission::FaceLoads); empty for the plane model.
  std::vector<transmission::MeshFaceLoad> face_loads;
  /// A helical stage (docs/model.md §10): the axial forces [N] and each planet's tilting moments
  /// [N·m] of the contact forces with their damping (transmission::HelicalLoadsOf; the axial and
  /// tilting motions held); no planets for a spur stage.
  transmission::HelicalLoads helical;
};

struct SimulationStats {
  long steps = 0;                 ///< accepted steps
  long rhs_evaluations = 0;       ///< right-hand sides (each with a contact solve)
  long jacobian_evaluations = 0;  ///< analytic Jacobians (CVODE)
  long fd_rhs_evaluations = 0;    ///< right-hand sides spent on finite-difference Jacobians
  long failed_solves = 0;         ///< contact solves that failed (recoverable retries)
  /// Evaluations at poses the stage model could not evaluate (Evaluation::geometry; recoverable
  /// retries: a trial step that swung a member past where its meshes work).
  long failed_geometry = 0;
  long error_test_failures = 0;
  long nonlinear_failures = 0;  ///< CVODE Newton convergence failures
  long restarts = 0;            ///< explicit method: restarts after a failed evaluation
  double rhs_seconds = 0;       ///< wall time in evaluations (a steady clock) [s]
  double jacobian_seconds = 0;  ///< wall time in the analytic Jacobian [s]
  double wall_seconds = 0;      ///< the whole run [s]
  double rate_scale = 0;        ///< the rates' tolerance factor used [rad/s] (see the options)
};

struct SimulationResult {
  /// kCompleted: every output time reached; else why the run stopped early (contact failure,
  /// geometry, integrator failure, time limit).
  transmission::RunStatus status = transmission::RunStatus::kIntegratorFailure;
  std::string message;  ///< where and why a run stopped early
  bool completed() const { return status == transmission::RunStatus::kCompleted; }
  /// Every output step, in order (empty with SimulationOptions::keep_samples = false).
  std::vector<DynamicSample> samples;
  int outputs = 0;  ///< output steps computed (and handed to `on_sample`) [-]
  SimulationStats stats;
};

/// Integrates from t = 0 (state d0, ḋ0) through the increasing output times (> 0). Each output
/// goes to `on_sample` as soon as it is computed; a run that fails midway returns what it has,
/// with completed = false and the time and reason in `message`. An exception thrown by
/// `on_sample` (a result that cannot be written) stops the run and is rethrown as it is: it says
/// where it happened, and no later write can take its place.
/// @throws std::invalid_argument for bad options or sizes; whatever `on_sample` throws.
SimulationResult Simulate(const DynamicModel& model, const SimulationOptions& options,
                          const Eigen::VectorXd& d0, const Eigen::VectorXd& v0,
                          const std::vector<double>& output_times,
                          const std::function<void(const DynamicSample&)>& on_sample = {});

}  // namespace epicycle::dynamics
