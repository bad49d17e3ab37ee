// From a posed stage to the contact problem of MODEL.md §5: the potential contacts of every mesh,
// their compliance (from the compliance layer, through StageCompliance), the local terms, the
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
};

/// Every potential contact of every mesh at the given poses (both flanks, within the window).
std::vector<StageContact> SearchStage(const geometry::Stage& stage,
                                      const geometry::StagePoses& poses, double gap_window);

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

struct QuasiStaticSetup {
  SunSupport sun = SunSupport::kFixed;  ///< constrained (paper), floating or elastic sun
  double sun_stiffness = 0;     ///< k_s [N/m], SunSupport::kElastic: isotropic bearing stiffness
  double planet_stiffness = 0;  ///< k_p [N/m]: > 0 elastic planet bearings, 0 rigid pins
  solvers::PlaneAssumption plane = solvers::PlaneAssumption::kPlaneStrain;
  bool local_terms = true;  ///< false: structural compliance only (linear studies)
};

/// The scene's supports and model settings as a setup.
QuasiStaticSetup SetupFromScene(const Scene& scene);

/// A rigid degree of freedom set by equilibrium (a multiplier of the contact problem).
struct StageDof {
  enum Kind { kSunRotation, kSunX, kSunY, kPlanetRotation, kPlanetX, kPlanetY } kind = kSunRotation;
  int planet = 0;
  std::string Label() const;  ///< with its unit: "sun rotation [rad]"
};

struct StageProblem {
  std::vector<StageContact> contacts;
  std::vector<StageDof> dofs;
  solvers::ContactProblemData data;  ///< ready for solvers::ContactProblem
};

/// The local contact term of a potential contact between gears a and b (MODEL.md §4): face width
/// the narrower one, R_eq from the two signed curvature radii (1/R = 1/ρ_a + 1/ρ_b; a concave ring
/// flank has ρ < 0), both bodies of `material`, joined at depths h_a and h_b [m].
/// @throws std::invalid_argument naming `label` if the radii give no positive reduced radius.
solvers::LocalTermParameters ContactLocalTerm(const geometry::PotentialContact& contact,
                                              const geometry::Gear& a, const geometry::Gear& b,
                                              const Material& material,
                                              solvers::PlaneAssumption plane, double depth_a,
                                              double depth_b, const std::string& label);

/// G_kj = ∂δ_j/∂q_k (rigid sensitivity of overlap j to DOF k), W_k the external load on DOF k
/// (the sun torque on the sun's rotation, zero elsewhere), so that G F = W is equilibrium and the
/// multipliers λ are the DOFs' rigid displacements [rad] or [m]. Elastic supports (sun or planet
/// bearings) give their translation rows the bearing stiffness k: G F + k λ = W replaces the
/// equality (the potential gains ½(GF − W)ᵀk⁻¹(GF − W)), and λ is the bearing's deflection.
/// @throws std::invalid_argument if a contact has no valid local-term geometry.
StageProblem BuildStageProblem(const Scene& scene, const geometry::Stage& stage,
                               const geometry::StagePoses& poses, const StageCompliance& compliance,
                               const QuasiStaticSetup& setup);

/// The poses moved by rigid displacements λ of the DOFs (rotations about rotation centres; the
/// geometric centre turns with the gear).
geometry::StagePoses Displace(const geometry::StagePoses& poses, const std::vector<StageDof>& dofs,
                              const Eigen::VectorXd& lambda);

}  // namespace epicycle::transmission
