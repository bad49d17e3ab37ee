// One mesh-stiffness run of a gear pair, as every front end asks for it (docs/model.md §4): a
// request (the scene, the mesh of a stage and typed overrides, every default resolved here), a run
// that builds the pair, its tables and the sweep once and streams each sample to a sink, and one
// record of what the run found. The program (`epicycle stiffness`) and Python's `mesh_stiffness`
// parse their options into a request and format the record; report/ writes the record's one
// serialisation (report::StiffnessRecordJson), whose keys are the fields VisitRecord names.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/mesh_stiffness.hpp"
#include "epicycle/transmission/record.hpp"
#include "epicycle/transmission/run_arguments.hpp"
#include "epicycle/transmission/scene.hpp"

namespace epicycle::transmission {

/// Samples per mesh cycle when a front end does not say [-].
inline constexpr int kDefaultStiffnessPositions = 60;

/// What a mesh-stiffness run is asked for. The `*_option` fields name the front end's option in
/// messages (the program: "--mesh"; Python: "mesh").
struct StiffnessRequest {
  Scene scene;       ///< read and validated (ReadScene): a gear pair or a stage
  std::string mesh;  ///< a stage's mesh ("sun-planet1", "planet2-ring"); "" for a pair scene
  int positions = kDefaultStiffnessPositions;  ///< samples per mesh cycle [-]
  int cycle = -1;   ///< this one mesh cycle of gear 1; < 0: the cycles a damaged tooth meshes in
  int threads = 0;  ///< worker threads [-]; 0: one per core
  std::string backend = "newton";  ///< contact back end (solvers::BackendFromName)
  bool local_terms = true;         ///< false: the structural compliance only
  bool tooth_coupling = true;      ///< MeshStiffnessOptions::tooth_coupling
  bool stresses = false;           ///< root stresses too (also when the scene asks for them)
  /// The healthy teeth over the same cycles beside a run of more than the first cycle (a damaged
  /// pair's); false: not computed.
  bool healthy = true;
  FeComplianceOptions tables;  ///< the influence tables' cache
  std::string mesh_option = StiffnessArguments::kMesh.keyword,
              positions_option = StiffnessArguments::kPositions.keyword,
              threads_option = StiffnessArguments::kThreads.keyword;
};

/// What the run has built before its first sample (for a front end's header and files).
struct StiffnessPlan {
  const Scene* scene = nullptr;  ///< as run (stresses overridden)
  const MeshPairSetup* setup = nullptr;
  const geometry::GearPair* pair = nullptr;
  const FePairCompliance* compliance = nullptr;  ///< null before the tables are built
  int positions_per_cycle = 0;                   ///< [-]
  int first_cycle = 0, cycles = 1;
  double face_width = 0;  ///< b [m], the narrower gear's
};

/// Where a run streams what it computes, in order.
class StiffnessSink {
 public:
  virtual ~StiffnessSink() = default;
  /// Once, when the pair and its cycles are known, before its tables are built (`compliance` is
  /// null then).
  virtual void Pair(const StiffnessPlan& /*plan*/) {}
  /// Once, after the pair and its tables are built and before the first sample.
  virtual void Start(const StiffnessPlan& /*plan*/) {}
  /// Each sample in the order of the positions, as soon as it and every earlier one are computed.
  virtual void Sample(const MeshSample& /*sample*/) {}
};

/// What a mesh-stiffness run found. Every field is in the record's one serialisation
/// (VisitRecord), named with its unit there.
struct StiffnessRecord {
  std::string scene;  ///< the scene's name
  std::string plane;  ///< "strain" or "stress" (the scene's [model] plane)
  bool local_terms = true;
  MeshStiffnessResult result;  ///< the samples and their statistics
  double contact_ratio = 0;    ///< ε_α from the tip circles [-]
  /// A helical pair's β [rad] and ε_β = b sin β/(π m_n) [-] (in the record when β > 0).
  double helix_angle = 0, overlap_ratio = 0;
  double iso6336_c_prime = 0, iso6336_c_gamma_alpha = 0;  ///< ISO 6336-1 method B [N/(mm·µm)]
  std::array<double, 2> join_depth{};                     ///< each gear's joining depth [m]
  std::optional<MeshStiffnessResult> healthy;  ///< the healthy teeth over the same cycles
  std::vector<std::string> warnings;           ///< the scene's and the validity checks'
};

/// Builds the pair and its tables once, sweeps the cycles (each sample to `sink`) and returns the
/// record. A failed sample is in the record (result.failed), not an exception.
/// @throws std::invalid_argument for a request that breaks a rule (named by its option)
StiffnessRecord RunStiffness(const StiffnessRequest& request, StiffnessSink& sink);

/// The record's fields, each once with its name and unit (its serialisation's keys).
void VisitRecord(const StiffnessRecord& record, RecordVisitor& visit);

}  // namespace epicycle::transmission
