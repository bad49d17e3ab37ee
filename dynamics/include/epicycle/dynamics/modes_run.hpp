// The natural modes of a stage about its operating point, as every front end asks for them
// (docs/dynamic.md "Natural modes"): a request (the scene, the sun support and the speeds of the
// coincidences, every default resolved here), a run that builds the rig once (or takes a front
// end's prebuilt one) and one record of the modes and coincidences. The program (`epicycle
// modes`) and Python's `modes` parse their options into a request and format the record; report/
// writes its one serialisation (report::ModesRecordJson), whose keys the fields VisitRecord names.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "epicycle/dynamics/dynamic_model.hpp"
#include "epicycle/dynamics/modes.hpp"
#include "epicycle/dynamics/speed_sweep.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/record.hpp"
#include "epicycle/transmission/scene.hpp"

namespace epicycle::dynamics {

/// What a modes run is asked for.
struct ModesRequest {
  transmission::Scene scene;                    ///< read and validated (ReadScene): a stage
  std::optional<transmission::SunSupport> sun;  ///< overrides [supports] sun when given
  /// The sun speeds [rpm] {LO, HI} whose mesh harmonics meet a mode; not given: the scene's
  /// speed / 2 .. × 2.
  std::optional<std::array<double, 2>> speed_range_rpm;
  transmission::FeComplianceOptions tables;  ///< the influence tables' cache
  /// A rig built from `scene` as run (a front end's cache); null: the run builds its own.
  std::shared_ptr<const StageDynamics> rig;
  std::string speed_range_option = "speed_range_rpm";  ///< its name in messages
};

/// What the run has built before the modes are solved (for a front end's header).
struct ModesPlan {
  const StageDynamics* rig = nullptr;
};

/// Where a run says what it has built.
class ModesSink {
 public:
  virtual ~ModesSink() = default;
  /// Once, after the rig is built.
  virtual void Start(const ModesPlan& /*plan*/) {}
};

/// What a modes run found. Every field is in the record's one serialisation (VisitRecord).
struct ModesRecord {
  std::string scene;  ///< the scene's name
  /// The tangent dF/dδ {sun–planet, planet–ring} [N/m] the modes use (MeanTangentMeshStiffness).
  std::array<double, 2> mesh_stiffness{};
  /// The secant F/δ {sun–planet, planet–ring} [N/m] (sets the mesh damping of a run).
  std::array<double, 2> secant_mesh_stiffness{};
  /// A helical stage: both stiffnesses from the stage's own quasi-static solutions of its sliced
  /// meshes (transmission::ComputeStageMeshStiffness), not the gear-pair driver's.
  bool sliced_meshes = false;
  double mesh_hz_per_sun_rpm = 0;  ///< f_m / n_s [Hz/rpm]
  std::vector<Mode> modes;
  std::array<double, 2> coincidence_range_rpm{};  ///< {LO, HI} [rpm]
  std::vector<Coincidence> coincidences;          ///< every h f_m = f_j in the range
  std::vector<std::string> warnings;              ///< the scene's
};

/// Builds the rig once (unless given), linearises it about its operating point with the tangent
/// mesh stiffness (StageModes) and finds the coincidences.
/// @throws std::invalid_argument for a request that breaks a rule (named by its option);
///         as StageModes for a failed operating point.
ModesRecord RunModes(const ModesRequest& request, ModesSink& sink);

/// The record's fields, each once with its name and unit (its serialisation's keys).
void VisitRecord(const ModesRecord& record, transmission::RecordVisitor& visit);

/// The coincidences as the list "coincidences" (mode numbers from 1), the modes record's and the
/// speed sweep's.
void VisitCoincidences(const std::vector<Coincidence>& coincidences,
                       transmission::RecordVisitor& visit);

}  // namespace epicycle::dynamics
