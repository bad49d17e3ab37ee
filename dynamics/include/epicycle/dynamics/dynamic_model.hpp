// The dynamic model of the stage (docs/model.md §7, the paper's eq. 3): planar lumped masses in
// the inertial frame,
//
//   M q̈ = f_ext(t) − f_bearings(q, q̇) − f_mesh(q, q̇),
//
// every member (sun, ring, carrier, each planet) with x [m], y [m], θ [rad] where it is not held.
// The model integrates deviations d from the rigid kinematics, q = q_ref(t) + d, so that absolute
// tolerances (1e-10 m, 1e-9 rad) mean something: with the carrier turned at ω_c, the sun's
// reference turns at ω_s = (1 + z_r/z_s) ω_c, each planet's at (1 − z_r/z_p) ω_c, and a planet's
// reference centre is its pin, carrier centre + R(φ_c)(r_c e(ψ_i) + pin error).
//
// Mesh forces, at every evaluation: the contact search at the current poses, the FE compliance and
// local terms of the stage model, and the contact problem with the positions given (F ≥ 0, no
// equalities), warm-started from the last accepted step. Force j acts on body B along +n_j and on
// A along −n_j at the contact point, with the lever arms of the search (tip-round contacts off the
// line of action included). In generalised coordinates f_mesh = G F with G_kj = ∂δ_j/∂q_k.
//
// Mesh damping (per active contact, along its normal):
//   F_j,total = max(0, F_j + c_j δ̇_j),  δ̇_j = n_j·(v_A(p_j) − v_B(p_j)),
//   c_j = c_m F_j / Σ_{k∈mesh} F_k  (the mesh's coefficient shared in proportion to the load, so a
//   pair entering contact enters with zero damping),
//   c_m = 2 ζ √(k_m m_eq),  m_eq = J_A J_B / (J_A r_bB² + J_B r_bA²)  (or c_m given),
// with k_m the mesh's mean stiffness. No Rayleigh damping of the whole system.
//
// Friction (Coulomb along the tooth surface, friction.hpp): the force on B is μ_s F_j,total t_j
// and on A −μ_s F_j,total t_j, t_j ⊥ n_j oriented so that the entrainment velocity is ≥ 0; its
// moments about each gear's rotation centre are the exact cross products (for involute contacts
// the lever is the profile's curvature radius). Friction off evaluates no friction code.
//
// Bearings (linear, per axis, isotropic in the plane):
//   sun (fixed, floating, elastic k_s, c_s), ring (fixed, or elastic k_r, c_r and torsional
//   k_rt, c_rt), planet pins (rigid: the planet's centre is its pin; elastic: k_p, c_p between
//   centre and pin), carrier (turned at a prescribed speed, or free in rotation carrying the output
//   torque T_c = −T_s (z_s + z_r)/z_s with its inertia plus a load inertia; translation held or
//   elastic k_c, c_c). The sun carries the input torque T_s, or turns at a prescribed speed with
//   the carrier free (the input torque is then the reaction of the meshes).
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "epicycle/dynamics/modes.hpp"
#include "epicycle/solvers/contact_solver.hpp"
#include "epicycle/transmission/contact_kinematics.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/mesh_stiffness.hpp"
#include "epicycle/transmission/rating.hpp"
#include "epicycle/transmission/run_status.hpp"
#include "epicycle/transmission/scene.hpp"
#include "epicycle/transmission/stage_mesh_stiffness.hpp"
#include "epicycle/transmission/stage_model.hpp"

namespace epicycle::dynamics {

/// A coordinate of the motion (a deviation from the rigid kinematics).
struct MotionDof {
  enum Member { kSun, kRing, kCarrier, kPlanet } member = kSun;
  enum Axis { kX, kY, kRotation } axis = kRotation;
  int planet = 0;
  std::string Label() const;  ///< with its unit: "planet2 x [m]"
};

/// Velocity state of a gear body in the inertial frame (the contact kinematics' own, shared with
/// the quasi-static friction).
using transmission::BodyMotion;

/// Buffers that DynamicModel::Evaluate reuses from one call to the next (Evaluation::work): with
/// the same Evaluation passed again, the same contact set and a warm solve on the Newton's direct
/// path, an evaluation without energies allocates nothing (the poses, the search, the compliance
/// and the solver keep their buffers too: verification/unit/dynamics/evaluation_allocations.cpp).
/// Nothing here is a result.
struct EvaluationWorkspace {
  Eigen::VectorXd stage_displacement;  ///< the deviations on the stage model's DOFs
  /// The contact problem's data: the terms' C, δ0 and local terms copied in (same sizes, no
  /// allocation), moved into the problem, released after the solve.
  solvers::ContactProblemData problem;
  solvers::ContactSolution solution;        ///< warm start in, forces out
  std::vector<BodyMotion> body;             ///< per body (kSunBody, kRingBody, PlanetBody(i))
  std::vector<Eigen::Vector2d> body_force;  ///< mesh force per body [N]
  std::vector<double> body_moment;          ///< mesh moment per body about its centre [N·m]
  std::vector<double> mesh_load;            ///< Σ F per mesh (2 per planet) [N]
  /// Per mesh, the tip rounds the search proved out of reach near the last refresh's poses
  /// (geometry::TipRoundReuse): the same contacts with fewer rounds tried.
  std::vector<geometry::TipRoundReuse> tip_rounds;
};

/// What one evaluation of the right-hand side computed (also the outputs of a step).
struct Evaluation {
  bool ok = false;      ///< the poses were evaluated and the contact solve converged
  std::string message;  ///< why not
  /// The stage model's outcome at these poses: not ok for a pose it cannot evaluate (a trial
  /// step past where the meshes have a line of action or the contacts lie on the flank grids);
  /// ok with ok == false: the contact solve failed.
  transmission::StageOutcome geometry;
  transmission::ContactTerms terms;     ///< potential contacts, C, δ0, local terms at the poses
  Eigen::VectorXd force;                ///< elastic contact forces F [N] (the contact problem's)
  Eigen::VectorXd total_force;          ///< F + damping, clipped at 0 [N]
  Eigen::VectorXd friction;             ///< friction force magnitude with sign μ_s F_total [N]
  /// Its direction t_j [-] (unit; on body B along t_j, on A along −t_j), per contact; empty with
  /// friction off, zero where a contact carries no force.
  std::vector<Eigen::Vector2d> friction_tangent;
  Eigen::VectorXd overlap_rate;         ///< δ̇ [m/s]
  Eigen::VectorXd acceleration;         ///< d̈ per DOF [m/s²] or [rad/s²]
  Eigen::VectorXd generalised_force;    ///< Q per DOF (mesh + bearings + external) [N] or [N·m]
  std::vector<double> sun_mesh_torque;  ///< moment on the sun of each planet's mesh [N·m]
  Eigen::Vector2d sun_mesh_force = Eigen::Vector2d::Zero();  ///< net mesh force on the sun [N]
  /// Net force and moment of every planet–ring contact (normal with damping, and friction) on
  /// the ring, in the inertial frame, the moment about the ring's centre [N], [N·m].
  Eigen::Vector2d ring_mesh_force = Eigen::Vector2d::Zero();
  double ring_mesh_torque = 0;
  std::vector<Eigen::Vector2d> planet_bearing_force;         ///< force of the pin on planet i [N]
  Eigen::Vector2d sun_bearing_force = Eigen::Vector2d::Zero();  ///< on the sun [N]
  geometry::StagePoses poses;
  double input_torque = 0;      ///< torque on the sun: T_s, or the drive's reaction [N·m]
  double external_power = 0;    ///< power of the input torque and of the driven carrier [W]
  double dissipated_power = 0;  ///< friction + mesh damping + bearing damping [W], ≥ 0
  double friction_power = 0;    ///< friction alone [W], ≥ 0
  /// Σ_j F_j δ̇_j: the power the elastic contact forces take from the bodies [W] (the contacts'
  /// damping and friction are in dissipated_power). With a compliance C that changes as the
  /// contacts move along the flanks it differs from the rate of the contacts' stored energy by
  /// ½FᵀĊF (docs/dynamic.md, "Energy balance").
  double contact_power = 0;
  double kinetic_energy = 0;    ///< [J] (0 unless asked for: Evaluate's `energies`)
  double elastic_energy = 0;  ///< contacts ½FᵀCF + Σ[F u(F) − ∫u] plus bearings [J] (ditto)
  double contact_energy = 0;  ///< the contacts' part of elastic_energy [J] (ditto)
  solvers::ContactReport report;
  EvaluationWorkspace work;  ///< Evaluate's buffers (no result)
};

/// The start of a run (DynamicModel::SolveQuasiStaticStart): its status, why it failed, and the
/// initial deviations d(0) [m, rad] when it did not.
struct StartOutcome {
  transmission::RunStatus status = transmission::RunStatus::kCompleted;
  std::string message;
  Eigen::VectorXd d;
};

class DynamicModel {
 public:
  /// Keeps a reference to `model` (it must outlive this): the stage model with its supports, the
  /// dynamic settings, the members' masses and inertias, and the input torque.
  /// @throws std::invalid_argument naming the key for a free member without mass or inertia, a
  ///         bad setting, loads that StageModel::CheckLoads refuses, or a support the model
  ///         cannot represent.
  DynamicModel(const transmission::StageModel& model, const transmission::DynamicSettings& settings,
               const transmission::StageInertias& inertias, const transmission::StageLoads& loads);

  const std::vector<MotionDof>& dofs() const { return dofs_; }
  int size() const { return static_cast<int>(dofs_.size()); }
  const Eigen::VectorXd& mass() const { return mass_; }  ///< per DOF [kg] or [kg·m²]
  const transmission::StageModel& stage_model() const { return model_; }
  const transmission::DynamicSettings& settings() const { return settings_; }
  const transmission::StageLoads& loads() const { return loads_; }
  /// The members' masses and inertias the model was built with.
  transmission::StageInertias inertias() const { return {sun_, planet_, ring_, carrier_}; }
  double sun_torque() const { return loads_.sun_torque; }  ///< T_s [N·m]
  double carrier_speed() const { return carrier_speed_; }  ///< ω_c [rad/s] (signed)
  double sun_speed() const { return carrier_speed_ * model_.stage().sun_ratio(); }  ///< ω_s
  double carrier_torque() const { return carrier_torque_; }  ///< output load T_c [N·m] if free
  /// The mesh damping coefficient c_m of the sun meshes and of the ring meshes [N·s/m].
  double sun_mesh_damping() const { return damping_sun_; }
  double ring_mesh_damping() const { return damping_ring_; }
  /// Mean mesh stiffness used for c_m and for the modes [N/m]; set by SetMeshStiffness.
  double sun_mesh_stiffness() const { return k_sun_; }
  double ring_mesh_stiffness() const { return k_ring_; }
  /// Sets the mean mesh stiffnesses (e.g. from transmission::ComputeMeshStiffness) and so c_m.
  void SetMeshStiffness(double sun_mesh, double ring_mesh);

  /// Carrier angle of the reference motion at time t [rad]: φ_0 + ω_c t.
  double CarrierAngle(double t) const { return start_angle_ + carrier_speed_ * t; }
  void SetStartAngle(double carrier_angle) { start_angle_ = carrier_angle; }

  /// The poses at time t with deviations d.
  geometry::StagePoses Poses(double t, const Eigen::VectorXd& d) const;

  /// One evaluation: contact search, compliance, contact solve (warm-started from `warm`, forces
  /// matched by contact label), damping, friction, bearings → accelerations. A pose the stage
  /// model cannot evaluate (Evaluation::geometry) or a failed contact solve gives ok = false
  /// (recoverable: the integrator retries with a smaller step).
  /// `energies` = false leaves kinetic_energy and elastic_energy at 0: the right-hand side needs
  /// only the powers, and the stored energy of the local terms costs a closed-form integral per
  /// loaded contact (outputs and balances ask for them). `out` (its results and its work space)
  /// is reused: passing the same Evaluation again saves the allocations; `warm` must be another.
  void Evaluate(double t, const Eigen::VectorXd& d, const Eigen::VectorXd& v,
                solvers::ContactSolver& solver, const solvers::ContactOptions& contact,
                const Evaluation* warm, Evaluation* out, bool energies = true) const;

  /// ∂d̈/∂d and ∂d̈/∂ḋ at an evaluation: the contact part from the contact solution's sensitivity,
  /// −M⁻¹ G_A (C_AA + diag u'_local(F_A))⁻¹ G_Aᵀ and −M⁻¹ G diag(c) Gᵀ (frozen contact geometry),
  /// friction's part through the same forces and the surface velocities (its law's dependence on
  /// the load and on the sliding and rolling speeds), the bearing part by finite differences of
  /// the (cheap) bearing forces.
  void Jacobian(double t, const Eigen::VectorXd& d, const Eigen::VectorXd& v, const Evaluation& at,
                Eigen::MatrixXd* dd, Eigen::MatrixXd* dv) const;

  /// The initial deviations: the quasi-static solution of the stage model at carrier angle
  /// CarrierAngle(0) (its rotations and translations), zero deviation velocities.
  /// @throws std::runtime_error if that quasi-static solve fails.
  Eigen::VectorXd QuasiStaticStart(const solvers::ContactOptions& contact,
                                   solvers::Backend backend) const;
  /// The same as an outcome: kCompleted with `d`, or kGeometry (a planet separated from a
  /// member at the start) or kContactFailure (the solve did not converge) with the message.
  StartOutcome SolveQuasiStaticStart(const solvers::ContactOptions& contact,
                                     solvers::Backend backend) const;

  /// Linearised mass and stiffness about the reference configuration at carrier angle φ: mean
  /// mesh stiffness along each mesh's line of action (k_m g gᵀ, g the involute contact's
  /// sensitivity), bearings; M diagonal. `c` (optional): the viscous damping of the same
  /// linearisation, M q̈ + C q̇ + K q = f: each mesh's c_m g gᵀ (sun_mesh_damping,
  /// ring_mesh_damping) and the bearings' dampers c JᵀJ on the springs' deflections.
  void Linearise(double carrier_angle, Eigen::MatrixXd* m, Eigen::MatrixXd* k,
                 Eigen::MatrixXd* c = nullptr) const;

  /// The members and their DOF indices, for SolveModes (sun, ring, carrier central; planets).
  std::vector<MemberDofs> ModeLayout() const;

  /// Index of a DOF in dofs(), or −1.
  int Find(MotionDof::Member member, MotionDof::Axis axis, int planet = 0) const;

 private:
  // Evaluate's steps, in order: the poses, the contact terms and the contact solve (false, with
  // out->message, for a pose the stage model cannot evaluate or a failed solve); the contacts'
  // damped and rubbing forces per body; the generalised forces and accelerations; the powers and,
  // with `energies`, the energies.
  bool SolveContacts(double t, const Eigen::VectorXd& d, solvers::ContactSolver& solver,
                     const solvers::ContactOptions& contact, const Evaluation* warm,
                     Evaluation* out) const;
  void ContactForces(double t, const Eigen::VectorXd& d, const Eigen::VectorXd& v,
                     Evaluation* out) const;
  void Accelerations(double t, const Eigen::VectorXd& d, const Eigen::VectorXd& v,
                     Evaluation* out) const;
  void PowersAndEnergies(double t, const Eigen::VectorXd& d, const Eigen::VectorXd& v,
                         bool energies, Evaluation* out) const;
  void BearingForces(double t, const Eigen::VectorXd& d, const Eigen::VectorXd& v,
                     Eigen::VectorXd* q, Evaluation* out) const;
  Eigen::Vector2d PinReference(int planet, double t) const;  // pin position, nominal carrier
  Eigen::Vector2d Pin(int planet, double t, const Eigen::VectorXd& d) const;
  Eigen::Vector2d CarrierCentre(const Eigen::VectorXd& d) const;  // or its velocity, from v
  Eigen::Vector2d PinVelocity(int planet, double t, const Eigen::VectorXd& d,
                              const Eigen::VectorXd& v) const;
  void BodyVelocities(double t, const Eigen::VectorXd& d, const Eigen::VectorXd& v,
                      std::vector<BodyMotion>* out) const;
  // Poses(t, d) into `poses`, with `q` the work space for the stage DOFs' deviations.
  void Poses(double t, const Eigen::VectorXd& d, Eigen::VectorXd* q,
             geometry::StagePoses* poses) const;
  double ReferenceVelocity(int k, double t) const;
  // Q_k += the generalised force of a force f on body B at p and −f on body A (per DOF).
  void AddPairForce(const transmission::StageContact& s, const geometry::StagePoses& poses,
                    const Eigen::Vector2d& f, Eigen::Ref<Eigen::VectorXd> q) const;
  // Friction's terms of ∂d̈/∂d and ∂d̈/∂ḋ (before the division by the masses): `active` the
  // loaded contacts, `force_by_d` their ∂F_A/∂d (one row each), `damping` their c_j.
  void AddFrictionJacobian(double t, const Eigen::VectorXd& d, const Eigen::VectorXd& v,
                           const Evaluation& at, const std::vector<int>& active,
                           const Eigen::MatrixXd& force_by_d, const Eigen::VectorXd& damping,
                           Eigen::MatrixXd* dd, Eigen::MatrixXd* dv) const;
  // Contact j's face width, reduced radius and contact modulus (FrictionForce sets the rest).
  transmission::FrictionContact FrictionState(const transmission::ContactTerms& terms, int j) const;

  const transmission::StageModel& model_;
  transmission::DynamicSettings settings_;
  std::vector<MotionDof> dofs_;
  std::vector<int> dof_index_;  // Find's answer per DofSlot (member, axis), −1 if absent
  static std::size_t DofSlot(const MotionDof& f);
  std::vector<int> stage_dof_;  // per DOF: index into stage_dofs_, or −1 (carrier)
  std::vector<transmission::StageDof> stage_dofs_;
  Eigen::VectorXd mass_;
  transmission::Inertia sun_, planet_, ring_, carrier_;
  transmission::StageLoads loads_;
  double carrier_speed_ = 0, carrier_torque_ = 0, start_angle_ = 0;
  double k_sun_ = 0, k_ring_ = 0, damping_sun_ = 0, damping_ring_ = 0;
  double contact_modulus_ = 0;
  transmission::FrictionModel
      friction_;  // settings_.friction with its constant factors evaluated once
};

/// A stage scene's dynamic model with everything it refers to, built in order: the scene, its
/// stage, the FE compliance (tables through `fe`'s cache), the stage model of the scene's
/// supports, and the dynamic model of its settings with the mean mesh stiffnesses set (for the
/// damping and the modes). Not copyable or movable (the members refer to each other).
/// A helical stage (fe.helical_slices true: the caller's driver resolves it in slices, after
/// transmission::RequireHelicalSlices) takes its mesh stiffnesses from its own quasi-static
/// solutions over a mesh cycle (transmission::ComputeStageMeshStiffness, docs/model.md §10); a
/// spur stage from the mesh-stiffness driver on planet 1's meshes with the stage's own tables
/// (transmission::StageMeshPairs, MeanMeshStiffness). With fe.helical_slices false a
/// helical scene is refused (transmission::RequireSpur).
struct StageDynamics {
  transmission::Scene scene;
  transmission::RatingInputs rating;  ///< what its ratings take (RateRun), resolved from `scene`
  geometry::Stage stage;
  transmission::FeComplianceOptions fe;
  transmission::FeStageCompliance compliance;
  transmission::StageModel stage_model;
  DynamicModel model;
  /// A helical stage's mesh stiffnesses (secant: the model's; tangent: the modes'); zero for a
  /// spur stage.
  transmission::StageMeshStiffness sliced_stiffness;
  /// A spur stage's modal meshes on the stage's own tables (the secant mesh stiffness of the
  /// model, the tangent of the modes and the speed sweep); none for a helical stage.
  std::optional<transmission::StageMeshPairs> modal_pairs;
  /// The tangent mesh stiffnesses {sun–planet, planet–ring} [N/m] of the modes and the speed
  /// sweep's coincidences: a helical stage's sliced_stiffness.tangent, a spur stage's
  /// MeanTangentMeshStiffness of modal_pairs.
  std::array<double, 2> TangentMeshStiffness() const;
  /// @throws std::invalid_argument as the members' constructors.
  StageDynamics(transmission::Scene scene, const transmission::FeComplianceOptions& fe);
  StageDynamics(const StageDynamics&) = delete;
  StageDynamics& operator=(const StageDynamics&) = delete;
};

/// The mean tangent mesh stiffness dF/dδ [N/m] of the modal meshes `pairs` at their load,
/// {sun mesh, ring mesh}: at each of `positions` samples of a mesh cycle, the mesh-stiffness
/// driver (transmission::ComputeMeshStiffness) at the load × (1 ± step),
///   k_t = (F₊ − F₋)/(δ₊ − δ₋)   (F the mesh's total force, δ its deflection along the line of
///                                action), averaged over the samples.
/// Why: transmission::MeanMeshStiffness is the secant F/δ; the local contact term's deflection
/// grows less than linearly with the load (docs/model.md §4), so small vibrations about the
/// operating point see the tangent, which is higher (about 6 % on the paper's stage). The
/// resonances of the speed sweep sit at the tangent stiffness' coincidences (docs/speed_sweeps.md).
/// @throws std::invalid_argument for step outside (0, 0.5) or positions < 2;
///         std::runtime_error if a sample fails at either load.
std::array<double, 2> MeanTangentMeshStiffness(const transmission::StageMeshPairs& pairs,
                                               int positions = 24, double step = 0.05);

/// The natural modes of a stage about its operating point (`epicycle modes`, docs/dynamic.md
/// "Natural modes"): `rig`'s model with the tangent mesh stiffnesses (MeanTangentMeshStiffness, a
/// helical stage's StageDynamics::sliced_stiffness:
/// where the speed sweep's resonances sit; the secant, which sets the mesh damping of a run, is
/// softer), linearised at carrier angle 0 (DynamicModel::Linearise) and solved by SolveModes.
struct OperatingPointModes {
  std::array<double, 2> mesh_stiffness{};  ///< tangent dF/dδ {sun–planet, planet–ring} [N/m]
  std::vector<Mode> modes;                 ///< SolveModes of the linearisation
};
/// @throws as MeanTangentMeshStiffness and SolveModes.
OperatingPointModes StageModes(const StageDynamics& rig);

}  // namespace epicycle::dynamics
