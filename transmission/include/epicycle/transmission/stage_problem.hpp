// From a posed stage to the contact problem of docs/model.md §5: the potential contacts of every
// mesh, their compliance (from the compliance layer, through StageCompliance), the local terms, the
// overlaps, and the equilibrium equalities of the members whose position is set by equilibrium.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "epicycle/compliance/compliance_operator.hpp"
#include "epicycle/geometry/stage.hpp"
#include "epicycle/solvers/contact_problem.hpp"
#include "epicycle/transmission/scene.hpp"

namespace epicycle::transmission {

/// What became of a stage computation at given poses. Bad input throws std::invalid_argument;
/// these are the expected outcomes of a legal scene at an extreme pose (a trial step of an
/// integrator, a large error, a large load), reported as statuses so that a driver can react: the
/// dynamic right-hand side asks the integrator for a smaller step, a quasi-static position is
/// reported failed and the sweep goes on.
enum class StageStatus {
  kOk,
  kNoLineOfAction,    ///< a mesh's centres so placed that its base circles admit no line of action
  kOffFlankGrid,      ///< a contact point outside its body's influence-table flank grid
  kNoReducedRadius,   ///< a contact's curvature radii give no positive reduced radius
  kNoContact,         ///< quasi-static: no potential contact within the gap window
  kContactSolveFailed,  ///< the contact problem's solve did not converge
  kNotSettled,        ///< quasi-static: the geometric iterations did not settle
  /// quasi-static with friction: the fixed point on the contact forces (the friction loads of
  /// the previous solve's forces) did not settle within the iterations (docs/model.md §9)
  kFrictionNotSettled,
  /// quasi-static with pins of finite stiffness: the fixed point on the planets' tilts (the
  /// pins' deflections under the previous solve's forces, pin.hpp) did not settle within the
  /// iterations (docs/model.md §10)
  kTiltNotSettled,
};
/// "ok", "no line of action", "off the flank grid", ... (for messages and files).
std::string StatusName(StageStatus status);

/// A status with the reason (empty when ok), naming the mesh or contact.
struct StageOutcome {
  StageStatus status = StageStatus::kOk;
  std::string message;
  bool ok() const { return status == StageStatus::kOk; }
};

/// Bodies of a stage: 0 the sun, 1 the ring, 2 + i planet i.
inline constexpr int kSunBody = 0;
inline constexpr int kRingBody = 1;
inline int PlanetBody(int planet) { return 2 + planet; }
/// "sun", "ring", "planet1", ...: a body's name in messages and output columns.
std::string BodyName(int body);
/// BodyName(b) of the bodies b = 0 … bodies − 1 (a stage's: bodies = PlanetBody(planets)).
std::vector<std::string> BodyNames(int bodies);

/// One potential contact of the stage with the bodies it joins (A and B of its mesh).
struct StageContact {
  geometry::PotentialContact contact;
  int planet = 0;
  geometry::MeshKind mesh = geometry::MeshKind::kSunPlanet;
  int body_a = kSunBody, body_b = kRingBody;
  bool loaded = true;  ///< on the flanks that carry the scene's torque (drive side)
  /// A contact on a pitted flank is split into strips of the face width (damage.hpp): this
  /// strip's share of the face width [-] (1: the whole contact), the depth [m] by which its gap
  /// has grown (already in contact.overlap) and its index among its contact's strips.
  double width_fraction = 1;
  double pit_depth = 0;
  int part = 0;
  /// A slice of the face width (face_width.hpp): its index s among the mesh's S slices (0 and 1:
  /// the plane model's whole face).
  int slice = 0;
  int slices = 1;
  /// A slice of a helical mesh (helical_slices.hpp): the turns [rad] of body A's and body B's
  /// transverse sections at the slice's z from the sections the poses describe (the contact was
  /// searched with each body turned by them); 0 for a spur mesh.
  double section_turn_a = 0, section_turn_b = 0;
  /// "sun-planet1 involute drive teeth 3/5", a pitted strip with " pitted <part>" appended, a
  /// slice with " slice <s+1>/<S>".
  std::string Label() const;
  /// "drive" or "coast" (the flank column of the output files), a pitted strip's with
  /// " pitted <part>" appended, a slice's with " slice <s+1>/<S>".
  std::string FlankName() const;
  /// The same tooth pair's flanks as `other`, whatever the contact's kind (involute or tip
  /// round): planet, mesh, flank side, teeth, pitted strip and slice of the face width.
  bool SameToothPair(const StageContact& other) const {
    return planet == other.planet && mesh == other.mesh && loaded == other.loaded &&
           contact.tooth_a == other.contact.tooth_a && contact.tooth_b == other.contact.tooth_b &&
           part == other.part && slice == other.slice;
  }
  /// The same potential contact as `other` (what Label() names: mesh, planet, kind, flank side,
  /// teeth, strip, slice), compared without building the labels.
  bool SameAs(const StageContact& other) const {
    return SameToothPair(other) && contact.kind == other.contact.kind;
  }
};

/// Warm start of a contact solve from an earlier state (the last accepted step of a motion, the
/// neighbouring position of a sweep): `force` [N] of the contacts `from`, carried over to the same
/// potential contacts (SameAs) in `to`; a contact of `to` that `from` does not have gets 0.
/// @return how many contacts of `to` were matched.
/// @throws std::invalid_argument if `force` does not have one entry per contact of `from`.
int CarryForces(const std::vector<StageContact>& from, const Eigen::VectorXd& force,
                const std::vector<StageContact>& to, Eigen::VectorXd* out);

/// Every potential contact of every mesh at the given poses (both flanks, within the window).
/// @throws std::runtime_error with the outcome's message if a mesh has no line of action.
std::vector<StageContact> SearchStage(const geometry::Stage& stage,
                                      const geometry::StagePoses& poses, double gap_window);
/// The same into `out` (cleared first; its capacity is reused); kNoLineOfAction (naming the mesh)
/// if the poses place a mesh's base circles so that it has no line of action. With `reuse`, each
/// mesh's tip rounds are reused under a pose bound (geometry::TipRoundReuse, one per mesh in the
/// order of geometry::MeshIndex; sized here): the same contacts.
StageOutcome SearchStage(const geometry::Stage& stage, const geometry::StagePoses& poses,
                         double gap_window, std::vector<StageContact>* out,
                         std::vector<geometry::TipRoundReuse>* reuse = nullptr);

/// Friction forces of a state's contacts for the root stresses: φ_j [N] on body B along the unit
/// tangent t_j (inertial frame), on body A along −t_j (contact_kinematics.hpp, FrictionForce),
/// one entry each per contact.
struct TangentialLoads {
  Eigen::VectorXd force;                 ///< φ_j [N], signed
  std::vector<Eigen::Vector2d> tangent;  ///< t_j [-]
};

/// The structural compliance of the stage's bodies (built by the compliance layer):
/// C_jk [m/N] of contacts j, k, coupling every pair of contacts that share a body.
class StageCompliance {
 public:
  virtual ~StageCompliance() = default;
  /// @return N×N symmetric positive definite [m/N].
  virtual Eigen::MatrixXd Matrix(const geometry::Stage& stage, const geometry::StagePoses& poses,
                                 const std::vector<StageContact>& contacts) const = 0;
  /// The same into `out`, or kOffFlankGrid (naming the contact) for a contact point that the
  /// compliance cannot represent at these poses. The default calls Matrix.
  virtual StageOutcome TryMatrix(const geometry::Stage& stage, const geometry::StagePoses& poses,
                                 const std::vector<StageContact>& contacts,
                                 Eigen::MatrixXd* out) const {
    *out = Matrix(stage, poses, contacts);
    return {};
  }
  /// Depth h [m] at which the body's structural and local terms are joined.
  virtual double JoiningDepth(int body) const = 0;
  /// The bodies' material and plane assumption, the same in the structural term and in the
  /// local contact terms that the stage model adds (one home: what the compliance was built
  /// with).
  virtual const Material& material() const = 0;
  virtual solvers::PlaneAssumption plane() const = 0;
  /// True when FilletStresses can answer (FE tables built with their fillet stresses).
  virtual bool has_root_stress() const { return false; }
  /// The root stresses (docs/model.md §9) of the state with contact forces `force` [N] at these
  /// poses: both fillets of the loaded teeth and their neighbours, per body (body index as in
  /// StageContact); with `friction` also those of the contacts' friction forces.
  /// @throws std::logic_error unless has_root_stress().
  virtual std::vector<compliance::FilletStress> FilletStresses(
      const geometry::Stage& stage, const geometry::StagePoses& poses,
      const std::vector<StageContact>& contacts, const Eigen::VectorXd& force,
      const TangentialLoads* friction = nullptr) const;
};

/// A rigid degree of freedom of a gear body: in a quasi-static problem one set by equilibrium (a
/// multiplier of the contact problem), in the dynamic model a coordinate of the motion.
struct StageDof {
  enum Kind {
    kSunRotation,
    kSunX,
    kSunY,
    kPlanetRotation,
    kPlanetX,
    kPlanetY,
    kRingRotation,
    kRingX,
    kRingY
  } kind = kSunRotation;
  int planet = 0;
  std::string Label() const;  ///< with its unit: "sun rotation [rad]"
};

struct StageProblem {
  std::vector<StageContact> contacts;
  std::vector<StageDof> dofs;
  solvers::ContactProblemData data;  ///< ready for solvers::ContactProblem
};

/// The local contact term of a potential contact between gears a and b (docs/model.md §4) into
/// `out`: face width the narrower one, R_eq from the two signed curvature radii (1/R = 1/ρ_a +
/// 1/ρ_b; a concave ring flank has ρ < 0), both bodies of `material`, joined at depths h_a and
/// h_b [m]; or kNoReducedRadius naming `label` if the radii give no positive reduced radius.
StageOutcome ContactLocalTerm(const geometry::PotentialContact& contact, const geometry::Gear& a,
                              const geometry::Gear& b, const Material& material,
                              solvers::PlaneAssumption plane, double depth_a, double depth_b,
                              const std::string& label, solvers::LocalTermParameters* out);
/// The same for a stage contact, named by its label (built only for the message), with the face
/// width of its strip (width_fraction of the narrower gear's).
StageOutcome ContactLocalTerm(const StageContact& contact, const geometry::Gear& a,
                              const geometry::Gear& b, const Material& material,
                              solvers::PlaneAssumption plane, double depth_a, double depth_b,
                              solvers::LocalTermParameters* out);

}  // namespace epicycle::transmission
