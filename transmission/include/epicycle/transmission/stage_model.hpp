// One stage model for every driver (quasi-static, mesh stiffness of a stage's mesh, dynamics):
// built once from (stage, compliance, setup), it owns the list of rigid degrees of freedom and
// offers, at any poses of the members, the contact terms of docs/model.md §4–5 (potential
// contacts, compliance C, overlaps δ0, local terms), the rigid sensitivities G = ∂δ/∂q, the
// displacement of poses by q, and named read-outs (load-sharing ratios, sun-mesh torques). Loads
// are passed in; nothing is read from the scene after construction.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "epicycle/geometry/stage.hpp"
#include "epicycle/solvers/contact_problem.hpp"
#include "epicycle/transmission/damage.hpp"
#include "epicycle/transmission/face_width.hpp"
#include "epicycle/transmission/scene.hpp"
#include "epicycle/transmission/stage_problem.hpp"

namespace epicycle::transmission {

/// The model choices of a stage model besides its geometry and compliance, read once from the
/// scene (SetupFromScene) or set by a study or a command: how the members are held, the contact
/// search's gap window, whether the local contact terms are added. The material and the plane
/// assumption are the compliance's (StageCompliance::material, plane); the loads are passed to
/// each computation (StageLoads).
struct StageSetup {
  std::string name;                     ///< the scene's, for problem names and messages
  SunSupport sun = SunSupport::kFixed;  ///< constrained (paper), floating or elastic sun
  double sun_stiffness = 0;     ///< k_s [N/m], SunSupport::kElastic: isotropic bearing stiffness
  double planet_stiffness = 0;  ///< k_p [N/m]: > 0 elastic planet bearings, 0 rigid pins
  double gap_window = 100e-6;   ///< contact-search gap window [m], > 0
  bool local_terms = true;      ///< false: structural compliance only (linear studies)
  /// Pits and spalls on the teeth (the scene's [[damage.pit]]): the contacts on a pitted flank
  /// are split into strips of the face width (damage.hpp) wherever Terms builds them.
  Damage damage;
  /// Slices across the face width and what varies along it (face_width.hpp; one slice: the
  /// plane model, nothing of it runs).
  FaceWidthSpec face_width;
  /// The sun torque [N·m] at which the carrier's wind-up tilts the pins (the scene's; the
  /// wind-up is taken at this nominal load in every computation of the model).
  double wind_up_sun_torque = 0;
  /// @throws std::invalid_argument naming the field (negative or non-finite stiffness, an
  ///         elastic sun without stiffness, a gap window not > 0).
  void Validate() const;
};

/// The scene's supports, gap window, damage and name as a setup.
StageSetup SetupFromScene(const Scene& scene);

/// The contact terms at given poses: everything the contact problem needs except the DOFs.
/// An empty contact set (gears separated beyond the gap window) is a valid state.
struct ContactTerms {
  std::vector<StageContact> contacts;
  Eigen::MatrixXd compliance;                       ///< C [m/N], N×N
  Eigen::VectorXd overlap;                          ///< δ0 [m], N
  std::vector<solvers::LocalTermParameters> local;  ///< N entries, or empty without local terms
  /// Empty, or the structure of `compliance` over the face-width slices, C = Σ source ⊗ kernel
  /// (solvers::KroneckerTerm; FaceWidthModel::Expand), handed to the contact problem.
  std::vector<solvers::KroneckerTerm> compliance_terms;
  /// With slices: the searched contacts and their compliance [m/N] before Expand splits them
  /// (kept here so that an evaluation reusing these terms allocates nothing).
  std::vector<StageContact> plane_contacts;
  Eigen::MatrixXd plane_compliance;
  int size() const { return static_cast<int>(contacts.size()); }
};

class StageModel {
 public:
  /// Keeps references to `stage` and `compliance` (they must outlive the model).
  /// @throws std::invalid_argument for a setup that fails Validate().
  StageModel(const geometry::Stage& stage, const StageCompliance& compliance,
             const StageSetup& setup);

  const geometry::Stage& stage() const { return stage_; }
  const StageCompliance& compliance() const { return compliance_; }
  const StageSetup& setup() const { return setup_; }
  /// The face-width model (inactive with one slice).
  const FaceWidthModel& face_width() const { return faces_; }
  const Material& material() const { return compliance_.material(); }
  const std::string& name() const { return setup_.name; }
  int planets() const { return stage_.planets(); }
  /// A helical stage, resolved in slices at their own sections' poses (helical_slices.hpp).
  bool helical() const { return helical_; }

  /// @throws std::invalid_argument naming sun_torque_Nm if the torque is zero or not finite, or
  ///         if its sign is not the one the stage's loaded flanks were built for
  ///         (geometry::StageSpec::load_sign).
  void CheckLoads(const StageLoads& loads) const;

  /// The DOFs set by quasi-static equilibrium: sun rotation, sun x and y (floating or elastic),
  /// every planet's rotation, planet x and y (elastic pins).
  const std::vector<StageDof>& dofs() const { return dofs_; }
  /// Support stiffness of each DOF of dofs() [N/m] (0: held only by the contacts).
  const std::vector<double>& support_stiffness() const { return support_; }

  /// Rigid kinematic poses at carrier angle φ_c [rad], with the scene's errors.
  geometry::StagePoses KinematicPoses(double carrier_angle) const {
    return stage_.Poses(carrier_angle);
  }
  /// The same into `out`, reusing its storage (the dynamic model's hot path).
  void KinematicPoses(double carrier_angle, geometry::StagePoses* out) const {
    stage_.Poses(carrier_angle, out);
  }

  /// The contact terms at `poses` into `terms`, reusing its buffers (but C, which the compliance
  /// returns anew), with every contact on a pitted flank split into its strips (its rows of C
  /// repeated, its gap grown by the depth, its local term of the strip's width: docs/model.md §9,
  /// "Pitting and spalls"), or with slices of the face width every contact split into its slices
  /// (face_width.hpp, docs/model.md §10; the pits lower the slices they cover), or the geometric
  /// outcome that prevents them (kNoLineOfAction, kOffFlankGrid, kNoReducedRadius, naming the mesh
  /// or contact; `terms` is then incomplete). With `reuse` (kept by the caller between calls, e.g.
  /// a right-hand side's work space), the search reuses each mesh's tip rounds under a pose bound
  /// (SearchStage): the same terms.
  [[nodiscard]] StageOutcome Terms(const geometry::StagePoses& poses, ContactTerms* terms,
                                   std::vector<geometry::TipRoundReuse>* reuse = nullptr) const;
  /// The same as a value, for poses that must work (the reference configuration).
  /// @throws std::runtime_error with the outcome's message if they do not.
  ContactTerms Terms(const geometry::StagePoses& poses) const;

  /// G_kj = ∂δ_j/∂q_k [-] or [m] for the given DOFs (any StageDof, not only dofs()).
  Eigen::MatrixXd Sensitivity(const ContactTerms& terms, const std::vector<StageDof>& dofs) const;

  /// The quasi-static contact problem at `poses` (docs/model.md §5): G F + K λ = W over dofs(),
  /// with W the loads on the DOFs; or the outcome that prevents it: those of Terms, and
  /// kNoContact if no potential contact lies within the gap window (equilibrium under load is
  /// then impossible).
  [[nodiscard]] StageOutcome Problem(const geometry::StagePoses& poses, const StageLoads& loads,
                                     StageProblem* problem) const;

  /// W: the loads on the DOFs (the sun torque on the sun's rotation) [N·m] or [N].
  /// @throws std::invalid_argument as CheckLoads.
  Eigen::VectorXd LoadVector(const std::vector<StageDof>& dofs, const StageLoads& loads) const;

  /// The poses moved by rigid displacements q of the DOFs (rotations about rotation centres; the
  /// geometric centre turns with the gear).
  static geometry::StagePoses Displace(const geometry::StagePoses& poses,
                                       const std::vector<StageDof>& dofs, const Eigen::VectorXd& q);
  /// The same in place.
  static void Displace(const std::vector<StageDof>& dofs, const Eigen::VectorXd& q,
                       geometry::StagePoses* poses);

  /// Largest rigid displacement in q [m], rotations measured at the base circles.
  double DisplacementSize(const std::vector<StageDof>& dofs, const Eigen::VectorXd& q) const;

  /// Moment on the sun of each planet's sun-mesh normal forces F [N·m], per planet.
  std::vector<double> SunMeshTorques(const std::vector<StageContact>& contacts,
                                     const Eigen::VectorXd& force) const;
  /// LSR_i = T_mesh(P_i–S) / T_input (paper eq. 4) [-], per planet; T_mesh the moment on the sun
  /// of planet i's mesh, which balances the input torque (hence the sign).
  std::vector<double> LoadSharing(const std::vector<StageContact>& contacts,
                                  const Eigen::VectorXd& force, double sun_torque) const;

  /// The gear of a body index (kSunBody, kRingBody, PlanetBody(i)).
  const geometry::Gear& BodyGear(int body) const;

 private:
  const geometry::Stage& stage_;
  const StageCompliance& compliance_;
  StageSetup setup_;
  std::vector<StageDof> dofs_;
  std::vector<double> support_;
  DamageModel damage_;
  FaceWidthModel faces_;
  bool helical_ = false;  // every slice at its own section's poses (helical_slices.hpp)
  void SplitDamaged(ContactTerms* terms) const;
  StageOutcome HelicalTerms(const geometry::StagePoses& poses, ContactTerms* terms) const;
  StageOutcome LocalTerms(ContactTerms* terms) const;
};

}  // namespace epicycle::transmission
