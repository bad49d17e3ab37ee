// From a posed stage to the contact problem of docs/model.md §5: the potential contacts of every
// mesh, their compliance (from the compliance layer, through StageCompliance), the local terms, the
// overlaps, and the equilibrium equalities of the members whose position is set by equilibrium.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "epicycle/geometry/stage.hpp"
#include "epicycle/solvers/contact_problem.hpp"
#include "epicycle/transmission/scene.hpp"

namespace epicycle::transmission {

/// Bodies of a stage: 0 the sun, 1 the ring, 2 + i planet i.
inline constexpr int kSunBody = 0;
inline constexpr int kRingBody = 1;
inline int PlanetBody(int planet) { return 2 + planet; }

/// One potential contact of the stage with the bodies it joins (A and B of its mesh).
struct StageContact {
  geometry::PotentialContact contact;
  int planet = 0;
  geometry::MeshKind mesh = geometry::MeshKind::kSunPlanet;
  int body_a = kSunBody, body_b = kRingBody;
  bool loaded = true;  ///< on the flanks that carry the scene's torque (drive side)
  std::string Label() const;
  /// The same potential contact as `other` (what Label() names: mesh, planet, kind, flank side,
  /// teeth), compared without building the labels.
  bool SameAs(const StageContact& other) const {
    return planet == other.planet && mesh == other.mesh && loaded == other.loaded &&
           contact.kind == other.contact.kind && contact.tooth_a == other.contact.tooth_a &&
           contact.tooth_b == other.contact.tooth_b;
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
std::vector<StageContact> SearchStage(const geometry::Stage& stage,
                                      const geometry::StagePoses& poses, double gap_window);
/// The same into `out` (cleared first; its capacity is reused).
void SearchStage(const geometry::Stage& stage, const geometry::StagePoses& poses, double gap_window,
                 std::vector<StageContact>* out);

/// The structural compliance of the stage's bodies (built by the compliance layer):
/// C_jk [m/N] of contacts j, k, coupling every pair of contacts that share a body.
class StageCompliance {
 public:
  virtual ~StageCompliance() = default;
  /// @return N×N symmetric positive definite [m/N].
  virtual Eigen::MatrixXd Matrix(const geometry::Stage& stage, const geometry::StagePoses& poses,
                                 const std::vector<StageContact>& contacts) const = 0;
  /// Depth h [m] at which the body's structural and local terms are joined.
  virtual double JoiningDepth(int body) const = 0;
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

/// The local contact term of a potential contact between gears a and b (docs/model.md §4): face
/// width the narrower one, R_eq from the two signed curvature radii (1/R = 1/ρ_a + 1/ρ_b; a concave
/// ring flank has ρ < 0), both bodies of `material`, joined at depths h_a and h_b [m].
/// @throws std::invalid_argument naming `label` if the radii give no positive reduced radius.
solvers::LocalTermParameters ContactLocalTerm(const geometry::PotentialContact& contact,
                                              const geometry::Gear& a, const geometry::Gear& b,
                                              const Material& material,
                                              solvers::PlaneAssumption plane, double depth_a,
                                              double depth_b, const std::string& label);
/// The same for a stage contact, named by its label (built only for the message).
solvers::LocalTermParameters ContactLocalTerm(const StageContact& contact, const geometry::Gear& a,
                                              const geometry::Gear& b, const Material& material,
                                              solvers::PlaneAssumption plane, double depth_a,
                                              double depth_b);

}  // namespace epicycle::transmission
