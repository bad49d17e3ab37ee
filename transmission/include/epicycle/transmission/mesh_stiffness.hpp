// Mesh stiffness of one gear pair over a mesh cycle at a given load (the hybrid model: FE
// structural term + local contact term, docs/model.md §4), with each tooth pair's stiffness and
// load share: the quantity ISO 6336-1 (c′, c_γα) and the potential-energy method are compared with.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "epicycle/compliance/iso6336.hpp"
#include "epicycle/geometry/pair.hpp"
#include "epicycle/solvers/contact_solver.hpp"
#include "epicycle/transmission/damage.hpp"
#include "epicycle/transmission/face_width.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/root_stress.hpp"
#include "epicycle/transmission/scene.hpp"

namespace epicycle::transmission {

/// A scene's gear pair for a stiffness study: a pair scene itself, or one mesh of a stage scene.
struct MeshPairSetup {
  std::string mesh;  ///< "gear1-gear2", "sun-planet<i>" or "planet<i>-ring"
  /// Gear 1's and gear 2's names, the parts of `mesh`: "gear1", "gear2" of a pair scene, a
  /// stage's BodyName ("sun", "planet<i>", "ring").
  std::vector<std::string> gears{"gear1", "gear2"};
  geometry::PairSpec spec;
  double torque = 0;  ///< on gear 1 [N·m] (ccw +): the pair's, or the stage's per-planet share
  double gap_window = 100e-6;  ///< contact-search gap window [m] (the scene's)
  /// The scene's pits (those on `gears`): the contacts on a pitted flank are split into strips
  /// of the face width as in the stage model (damage.hpp).
  Damage damage;
  /// Slices of the face width with the leads of gear1 and gear2 (a pair scene's [face_width],
  /// pair_face_width.hpp); one slice for a stage's mesh (the plane pair).
  FaceWidthSpec face_width;
};

/// For a pair scene, `mesh` may be empty or "gear1-gear2". For a stage scene it names a mesh of
/// the stage ("sun-planet1", "planet2-ring"): the pair is that mesh at the carrier radius, without
/// errors, loaded by the sun torque's share T/n (sun–planet) or the same tooth force on the planet
/// (planet–ring: T_p = T/n · r_bp/r_bs).
/// @throws std::invalid_argument naming the mesh and the names allowed.
MeshPairSetup MakeMeshPair(const Scene& scene, const geometry::Stage* stage,
                           const std::string& mesh);

struct MeshStiffnessOptions {
  int positions = 60;  ///< samples over the sweep (all its cycles) [-], ≥ 2
  /// The sweep covers gear-1 rotations [first_cycle, first_cycle + cycles) mesh cycles [-]
  /// (DamagedToothCycles: the cycles a damaged tooth meshes in); cycles ≥ 1, first_cycle ≥ 0.
  int first_cycle = 0;
  int cycles = 1;
  solvers::Backend backend = solvers::Backend::kActiveSetNewton;
  solvers::ContactOptions contact;
  bool local_terms = true;  ///< add the nonlinear local term (false: structural only)
  /// false: every contact's compliance alone (the off-diagonal C_jk dropped), so that the pairs in
  /// contact act as independent springs, the assumption of the potential-energy method; true (the
  /// model): the bodies couple the teeth.
  bool tooth_coupling = true;
  int max_geometric_iterations = 20;   ///< [-]
  double geometric_tolerance = 1e-11;  ///< largest rotation increment × base radius [m]
  /// Worker threads [-]; 0: one per core. The positions are split into contiguous chunks, one per
  /// thread (each position is solved from the kinematic pose, so the result does not depend on
  /// the thread count).
  int threads = 0;
  void Validate() const;  ///< @throws std::invalid_argument naming the field
};

/// One tooth pair in contact at one position.
struct ToothPairLoad {
  int tooth1 = 0, tooth2 = 0;  ///< tooth indices (body frames)
  geometry::ContactKind kind = geometry::ContactKind::kInvolute;
  double force = 0;      ///< F [N], normal
  double stiffness = 0;  ///< F / δ_LOA [N/m]: the pair's share of the mesh stiffness
  double share = 0;      ///< F / ΣF [-]
  double roll1 = 0;      ///< involute roll angle of gear 1 at the contact [rad] (r_b1·roll1 is
                         ///< the distance along the line of action from gear 1's base circle)
};

struct MeshSample {
  double angle = 0;  ///< gear-1 rotation from the cycle start [rad]
  bool converged = false;
  std::string message;        ///< why not, when not converged
  double rotation = 0;        ///< loaded static transmission error: gear-1 rotation [rad]
  double approach = 0;        ///< δ_LOA = |rotation| r_b1, the mesh deflection along the LOA [m]
  double total_force = 0;     ///< Σ F [N]
  double mesh_stiffness = 0;  ///< k = (|T|/r_b1)/δ_LOA [N/m]
  std::vector<ToothPairLoad> pairs;  ///< pairs carrying load (F > 0)
  /// max over the loaded contacts of F / ValidityLimitForce (solvers/local_term.hpp) [-]: above 1
  /// the Hertz half-width exceeds the joining depth, outside the local term's validity; 0 without
  /// local terms.
  double local_validity_ratio = 0;
  solvers::ContactReport report;
  /// The converged state: the poses and potential contacts of the last contact problem and
  /// their forces F_j [N] (empty when not converged).
  geometry::PairPoses poses;
  std::vector<geometry::PotentialContact> contacts;
  Eigen::VectorXd force;
  /// The root stresses of the converged state (docs/model.md §9: both fillets of the loaded teeth
  /// and their neighbours, body 0 gear 1, body 1 gear 2) when the compliance has them (the
  /// scene's [model] stresses), else empty.
  std::vector<compliance::FilletStress> fillet_stress;
  /// Each gear's extremes of fillet_stress (SummariseRootStress, body order; empty with it).
  std::vector<GearRootStress> root_stress;
  /// With slices of the face width (MeshPairSetup::face_width): the load per unit width across
  /// the face, K_Hβ and where the largest sits; else empty line loads.
  MeshFaceLoad face_load;
  /// A helical pair's (else 0): the largest stiffness per unit face width of one tooth pair in
  /// one slice, F_pair,s/(δ_LOA Δz) [N/m²] (Δz = b/S): the section's single-pair stiffness, the
  /// quantity ISO 6336-1's c′ (with cos β) stands for.
  double peak_slice_pair_stiffness = 0;
};

struct MeshStiffnessResult {
  std::string mesh;
  double torque = 0;      ///< on gear 1 [N·m]
  double face_width = 0;  ///< b [m] (the narrower gear)
  std::vector<MeshSample> samples;
  int failed = 0;                  ///< samples that did not converge
  double mean_stiffness = 0;       ///< mean of k over the converged samples [N/m]
  double peak_pair_stiffness = 0;  ///< max over samples and pairs of a single pair's k [N/m]
  double min_stiffness = 0, max_stiffness = 0;  ///< [N/m]
  /// Per gear (gear 1, gear 2, named by MeshPairSetup::gears) over the converged samples with root
  /// stresses (else empty): the extremes with the gear-1 rotation where they occur
  /// (RootStressSummary's x [rad]) and the largest range at one fillet point.
  std::vector<RootStressSummary> root_stress;
  /// With slices of the face width (else slices = 1 and the rest unset): K_Hβ's largest and mean
  /// over the converged samples, the gear-1 rotation [rad] and z [m] of the largest.
  int slices = 1;
  double k_h_beta_max = 0, k_h_beta_mean = 0, k_h_beta_angle = 0, largest_z = 0;
  /// A helical pair (resolved in slices, helical_slices.hpp): its largest
  /// MeshSample::peak_slice_pair_stiffness over the converged samples [N/m²].
  bool helical = false;
  double peak_slice_pair_stiffness = 0;
  /// Per unit face width in N/(mm·µm) (= 1e9 N/m²): mean (c_γα-like) and peak single pair (c′).
  double mean_per_width() const { return mean_stiffness / face_width / 1e9; }
  double peak_pair_per_width() const { return peak_pair_stiffness / face_width / 1e9; }
  /// A helical pair's peak_slice_pair_stiffness in N/(mm·µm).
  double peak_slice_pair_per_width() const { return peak_slice_pair_stiffness / 1e9; }
};

/// The mesh cycles [first, first + count) of gear 1's rotation (as MeshStiffnessOptions) in which
/// a tooth of `setup`'s damage (a pit or a root crack on gear 1 or gear 2) comes within the gap
/// window of its mate, found by the rigid contact search at 8 angles per cycle over the pair's
/// period for that tooth (z of its gear cycles); with one cycle of margin each side. {0, 1} for a
/// pair without damage on its gears. Several damaged teeth: the cycles from the first to the last
/// of them (at most z1 z2 / gcd cycles).
std::array<int, 2> DamagedToothCycles(const MeshPairSetup& setup, const geometry::GearPair& pair);

/// Sweeps options.cycles mesh cycles of gear 1 from options.first_cycle: at every position, contact
/// search → FE compliance → contact problem with the moment equilibrium of gear 1 (gear 2 held) →
/// back end, repeated at the moved position until the rotation settles. A position that fails is
/// reported in its sample and the sweep goes on. With a compliance that has root stresses
/// (FePairCompliance::has_root_stress) every converged sample carries its fillet stresses and the
/// result their summary; without, no stress is computed. The positions run on options.threads
/// workers; `on_sample` (if given) sees each sample in the order of the positions as soon as it and
/// every earlier one are computed (under a lock, from any worker).
MeshStiffnessResult ComputeMeshStiffness(
    const MeshPairSetup& setup, const geometry::GearPair& pair, const FePairCompliance& compliance,
    const MeshStiffnessOptions& options,
    const std::function<void(const MeshSample&)>& on_sample = {});

/// The pair's data for ISO 6336-1 method B (c′, c_γα): tooth counts, shifts, the basic-rack
/// dedendum h_fP/m of each gear (the rack's addendum, or for a directly defined ring its root
/// depth below the shifted reference circle), tool pressure angle, C_R = 1 (solid bodies) and
/// ε_α from the tip circles.
/// ComputeMeshStiffness of the same pair and options with the scene's damage left out: the healthy
/// teeth beside a damaged run (`epicycle stiffness` of a damaged pair). Its own tables (`fe`).
MeshStiffnessResult ComputeHealthyMeshStiffness(const Scene& scene, const MeshPairSetup& setup,
                                                const geometry::GearPair& pair,
                                                const FeComplianceOptions& fe,
                                                const MeshStiffnessOptions& options);

compliance::iso6336::PairData IsoPairData(const geometry::GearPair& pair);

/// Planet 1's sun–planet and planet–ring meshes of a built stage as gear pairs for the
/// mesh-stiffness driver (ComputeMeshStiffness), of the healthy teeth: the scene's damage is left
/// out (a damaged tooth meshes once in many cycles; the modes, the mesh damping and method C's c_γ
/// take the stage's healthy mean, docs/model.md §9). Each mesh holds its setup (MakeMeshPair of
/// `scene`, the scene the stage was built from with the run's load, without its damage), the pair
/// of the stage's own gear specs at the carrier radius, and the FE compliance of the stage's two
/// bodies sharing `compliance`'s tables (FePairCompliance(compliance, body1, body2): no table is
/// built or read from the cache again). Refers to none of its arguments after construction. Not
/// copyable or movable.
class StageMeshPairs {
 public:
  struct Mesh {
    /// `kind`: planet 1's sun mesh or ring mesh.
    Mesh(const Scene& scene, const geometry::Stage& stage, const FeStageCompliance& compliance,
         geometry::MeshKind kind);
    Mesh(const Mesh&) = delete;
    Mesh& operator=(const Mesh&) = delete;
    std::string name;  ///< "sun-planet1" or "planet1-ring"
    MeshPairSetup setup;
    geometry::GearPair pair;
    FePairCompliance compliance;
  };
  /// @throws std::invalid_argument as MakeMeshPair.
  StageMeshPairs(const Scene& scene, const geometry::Stage& stage,
                 const FeStageCompliance& compliance);
  /// {sun–planet, planet–ring}.
  const std::array<std::unique_ptr<const Mesh>, 2>& meshes() const { return meshes_; }

 private:
  std::array<std::unique_ptr<const Mesh>, 2> meshes_;
};

/// The mean mesh stiffness [N/m] of the meshes `pairs` at their load, from the mesh-stiffness
/// driver (ComputeMeshStiffness) over `positions` samples of a mesh cycle (the secant F/δ of each
/// sample, averaged over the converged ones): {sun mesh, ring mesh}.
/// @throws std::runtime_error if every sample of a mesh fails.
std::array<double, 2> MeanMeshStiffness(const StageMeshPairs& pairs, int positions = 24);

/// c_γα [N/m²]: MeanMeshStiffness of `pairs` divided by each pair's face width
/// (geometry::ContactFaceWidth), {sun mesh, ring mesh}: the model's c_γ that ISO 6336-1 method C
/// takes (rating.hpp).
/// @throws std::runtime_error if every sample of a mesh fails.
std::array<double, 2> MeanMeshStiffnessPerWidth(const StageMeshPairs& pairs, int positions = 24);

}  // namespace epicycle::transmission
