// The hybrid compliance of a scene's bodies (docs/model.md §4): one FE influence table per distinct
// gear body (built, or loaded from the disk cache), assembled into the contact compliance of a
// stage or of a gear pair by compliance::AssembleCompliance.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "epicycle/compliance/compliance_operator.hpp"
#include "epicycle/compliance/damaged_influence.hpp"
#include "epicycle/compliance/influence_table.hpp"
#include "epicycle/geometry/pair.hpp"
#include "epicycle/transmission/scene.hpp"
#include "epicycle/transmission/stage_problem.hpp"

namespace epicycle::transmission {

struct FeComplianceOptions {
  /// Table options; the scene's [model] settings (join depth, refinement) are applied on top.
  compliance::InfluenceTableOptions table;
  /// Disk cache of the tables; empty: build in memory, write nothing.
  std::string cache_directory;
  /// True for a run whose stage model resolves helical meshes in slices (StageRig:
  /// helical_slices.hpp): a helical scene is taken; false refuses it (RequireSpur).
  bool helical_slices = false;
};

/// The default cache directory: $EPICYCLE_CACHE_DIR, else $XDG_CACHE_HOME/epicycle, else
/// $HOME/.cache/epicycle, else ".epicycle-cache".
std::string DefaultCacheDirectory();

/// The influence tables of a set of gears: one per distinct body (gears with identical specs, such
/// as error-free planets, share one table), and the damaged rows of a gear with a root crack
/// (the scene's [[damage.crack]], docs/model.md §9 "Root crack"; each healthy gear keeps the
/// shared table, the cracked one gets compliance::DamagedInfluence beside it, cached like the
/// tables).
class GearTables {
 public:
  /// `names[i]` is gear i's name in the scene's damage (a stage's BodyName, "gear1"/"gear2" of a
  /// pair, or the stage's names of a mesh studied as a pair: MeshPairSetup::gears).
  /// @throws std::invalid_argument for a table that cannot be built, a crack that cannot be
  ///         meshed or placed (naming the scene's [[damage.crack]] table), or a crack with root
  ///         stresses asked (none are tabulated on a cracked body).
  GearTables(const Scene& scene, const std::vector<const geometry::Gear*>& gears,
             const std::vector<std::string>& names, const FeComplianceOptions& options);
  const compliance::InfluenceTable& Table(int gear) const { return *tables_.at(gear); }
  /// Gear `gear`'s damaged rows (its root crack, placed), or null for a healthy gear.
  const compliance::DamagedInfluence* Damaged(int gear) const { return damaged_.at(gear).get(); }
  int size() const { return static_cast<int>(tables_.size()); }  ///< gears (one table each)
  /// What the cache did, one line per distinct table.
  const std::vector<std::string>& messages() const { return messages_; }
  compliance::PlaneAssumption plane() const { return plane_; }
  /// Gears `gears` (indices here, in their order) of these tables, shared (not copied, not built
  /// or read from the cache again) and healthy: a crack's damaged rows are left out, so that the
  /// selection is the bodies' undamaged compliance. No messages (nothing was built).
  /// @throws std::invalid_argument naming an index outside [0, size()).
  GearTables Healthy(const std::vector<int>& gears) const;

 private:
  GearTables() = default;
  std::vector<std::shared_ptr<const compliance::InfluenceTable>> tables_;
  std::vector<std::shared_ptr<const compliance::DamagedInfluence>> damaged_;
  std::vector<std::string> messages_;
  compliance::PlaneAssumption plane_ = compliance::PlaneAssumption::kPlaneStrain;
};

/// The stage's contact compliance from the FE tables of the sun, every planet and the ring.
class FeStageCompliance final : public StageCompliance {
 public:
  /// @throws std::invalid_argument for a table that cannot be built (message from the mesher or
  ///         the table's rules).
  FeStageCompliance(const Scene& scene, const geometry::Stage& stage,
                    const FeComplianceOptions& options);
  /// @throws std::invalid_argument naming the contacts for a point off its flank grid.
  Eigen::MatrixXd Matrix(const geometry::Stage& stage, const geometry::StagePoses& poses,
                         const std::vector<StageContact>& contacts) const override;
  StageOutcome TryMatrix(const geometry::Stage& stage, const geometry::StagePoses& poses,
                         const std::vector<StageContact>& contacts,
                         Eigen::MatrixXd* out) const override;
  double JoiningDepth(int body) const override;
  const Material& material() const override { return material_; }
  solvers::PlaneAssumption plane() const override { return plane_; }
  const GearTables& tables() const { return tables_; }
  bool has_root_stress() const override;
  /// The normal forces' and (with `friction`) the friction forces' fillet stresses in one
  /// superposition: a friction force is one more load at its contact, along ±t_j.
  std::vector<compliance::FilletStress> FilletStresses(
      const geometry::Stage& stage, const geometry::StagePoses& poses,
      const std::vector<StageContact>& contacts, const Eigen::VectorXd& force,
      const TangentialLoads* friction = nullptr) const override;

 private:
  // The operator's bodies (sun, ring, planets at their poses) and contact sides.
  void Operator(const geometry::Stage& stage, const geometry::StagePoses& poses,
                const std::vector<StageContact>& contacts,
                std::vector<compliance::OperatorBody>* bodies,
                std::vector<compliance::OperatorContact>* oc) const;
  // C into *out; a point off its flank grid: the message in *off_flank (non-null) or thrown.
  void Assemble(const geometry::Stage& stage, const geometry::StagePoses& poses,
                const std::vector<StageContact>& contacts, Eigen::MatrixXd* out,
                std::string* off_flank) const;
  GearTables tables_;               // gear index = body index (0 sun, 1 ring, 2 + i planet i)
  std::vector<std::string> names_;  // per body, for messages
  Material material_;               // the scene's, as the tables were built with it
  solvers::PlaneAssumption plane_;  // the scene's [model] plane
};

/// The contact compliance of a single gear pair (gear 1 body 0, gear 2 body 1).
class FePairCompliance {
 public:
  /// `gears`: the two gears' names in the scene's damage (MeshPairSetup::gears: a stage mesh
  /// studied as a pair keeps the stage's names, so that a crack on its gears is found).
  FePairCompliance(const Scene& scene, const geometry::GearPair& pair,
                   const FeComplianceOptions& options,
                   const std::vector<std::string>& gears = {"gear1", "gear2"});
  /// Bodies `body1` and `body2` of a built stage compliance (kSunBody, kRingBody, PlanetBody(i))
  /// as gear 1 and gear 2 of a pair (a mesh of the stage studied as a pair, MakeMeshPair): their
  /// tables shared with `stage` (GearTables::Healthy: not rebuilt, without a crack's rows), its
  /// material and plane. The pair's gears must be those bodies' gears (the same specs).
  /// @throws std::invalid_argument naming a body outside the stage's.
  FePairCompliance(const FeStageCompliance& stage, int body1, int body2);
  /// `section_turns` (empty, or one per contact): each contact's sides searched on sections of
  /// gear 1 and gear 2 turned by their leads, Δθ_1 and Δθ_2 [rad] (a helical pair's slices,
  /// helical_slices.hpp), carried back by −Δθ onto the section `poses` describe.
  Eigen::MatrixXd Matrix(const geometry::GearPair& pair, const geometry::PairPoses& poses,
                         const std::vector<geometry::PotentialContact>& contacts,
                         const std::vector<std::array<double, 2>>& section_turns = {}) const;
  /// True when FilletStresses can answer: both tables built with their fillet stresses (the
  /// scene's [model] stresses or FeComplianceOptions::table.fillet_stress).
  bool has_root_stress() const;
  /// The root stresses (docs/model.md §9) of the state with contact forces `force` [N] at these
  /// poses: both fillets of the loaded teeth and their neighbours, body 0 gear 1, body 1 gear 2
  /// (compliance::FilletStresses on the bodies and contact sides Matrix assembles).
  /// @throws std::invalid_argument unless has_root_stress(), or as compliance::FilletStresses.
  std::vector<compliance::FilletStress> FilletStresses(
      const geometry::GearPair& pair, const geometry::PairPoses& poses,
      const std::vector<geometry::PotentialContact>& contacts, const Eigen::VectorXd& force,
      const std::vector<std::array<double, 2>>& section_turns = {}) const;
  double JoiningDepth(int gear) const { return tables_.Table(gear).join_depth(); }
  /// The material and plane assumption the tables were built with (the local terms use them).
  const Material& material() const { return material_; }
  solvers::PlaneAssumption plane() const { return plane_; }
  const GearTables& tables() const { return tables_; }

 private:
  // The operator's bodies (gear 1, gear 2 at their poses) and contact sides.
  void Operator(const geometry::GearPair& pair, const geometry::PairPoses& poses,
                const std::vector<geometry::PotentialContact>& contacts,
                const std::vector<std::array<double, 2>>& section_turns,
                std::vector<compliance::OperatorBody>* bodies,
                std::vector<compliance::OperatorContact>* oc) const;
  GearTables tables_;
  Material material_;
  solvers::PlaneAssumption plane_;
};

/// φ [-], the gear bodies' share of the structural compliance of `contact` (FaceCoupling::
/// kToothBody, docs/model.md §10): on each body B, the displacement that a unit force at the
/// contact causes at the same flank point of the neighbouring teeth k ± 1, along their own
/// normals (the mean of the two), is what the rim, web and hub carry under the loaded tooth;
/// summed over both bodies and divided by the contact's structural compliance C_jj (the depth-h
/// self terms):
///   φ = Σ_B ½ [Λ_B(k → k+1) + Λ_B(k → k−1)] / Σ_B Λ_B(k → k).
/// The healthy tables are read (a crack's rows are not).
/// @throws std::invalid_argument for a contact point off its flank grid, or a φ outside [0, 1).
double ContactBodyShare(const FePairCompliance& compliance, const geometry::GearPair& pair,
                        const geometry::PairPoses& poses,
                        const geometry::PotentialContact& contact);

}  // namespace epicycle::transmission
